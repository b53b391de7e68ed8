/* SPDX-License-Identifier: GPL-3.0-or-later
 * lsolve.c -- triplet assembly, compressed-column matrices and the direct
 * solvers (UMFPACK, KLU, CHOLMOD) behind lsolve.h.
 *
 * Workload (docs/METHOD.md section 5, Step 9): the PPE matrix depends only on
 * the mesh, so it is analysed and factorized once and then solved once per time
 * step, for thousands of steps. Everything a solve needs (UMFPACK's wsolve
 * workspace, CHOLMOD's solve2 dense blocks) is allocated at factorization
 * time, so lsolve_solve allocates nothing after its first call.
 *
 * This file is the only code that touches SuiteSparse. Each SuiteSparse
 * status is mapped to a ump_status with one line naming the solver and,
 * for a singular matrix, the column SuiteSparse reports (UMFPACK: the
 * original column of the smallest pivot; KLU: Common.singular_col;
 * CHOLMOD: L->minor). Exact zero pivots are not the only failure: a matrix
 * that is singular in exact arithmetic (a pure-Neumann Laplacian with no
 * reference value, a PPE region without a reference) usually factorizes with
 * a round-off pivot whose size grows with n, so pivot ratios cannot tell it
 * from an ill-conditioned matrix. After every numeric factorization the
 * 1-norm condition number is estimated (Hager 1984 / Higham 1988, a few
 * solves with A and A^T) and a matrix with cond_1(A) > LSOLVE_COND_MAX is
 * refused as numerically singular.
 */
#include "umppm/lsolve.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cholmod.h>
#include <klu.h>
#include <umfpack.h>

/* SuiteSparse's int interfaces (umfpack_di_*, klu_*, cholmod_*) take int. */
_Static_assert(sizeof(ump_idx) == sizeof(int), "lsolve uses the int SuiteSparse interfaces");

/* Condition number above which a factorization is declared numerically
 * singular: the solution would keep fewer than ~5 significant digits
 * (cond * DBL_EPSILON > 2e-5). Measured: 5-point pure-Neumann Laplacians
 * (singular in exact arithmetic) estimate at 5e16..6e17 for n = 25..1e5,
 * the same with one cell pinned at 2e2..3e6. */
#define LSOLVE_COND_MAX 1e11

/* CHOLMOD's flops / nnz(L) above which the factorization is supernodal */
#define LSOLVE_SUPERNODAL_SWITCH 120.0

#define ALLOC(p, n) ((p) = ump_alloc_array((size_t)(n), sizeof *(p)))

/* ---- triplets ------------------------------------------------------------ */

ump_status lsolve_trip_init(lsolve_trip *t, ump_idx n, size_t cap_hint, ump_err *err)
{
    memset(t, 0, sizeof *t);
    UMP_CHECK(n >= 0, err, UMP_ERR_INPUT, "lsolve: matrix order %d is negative", (int)n);
    t->n = n;
    if (cap_hint < 16)
        cap_hint = 16;
    ALLOC(t->Ti, cap_hint);
    ALLOC(t->Tj, cap_hint);
    ALLOC(t->Tx, cap_hint);
    if (!t->Ti || !t->Tj || !t->Tx) {
        lsolve_trip_free(t);
        return UMP_FAIL(err, UMP_ERR_NOMEM, "lsolve: out of memory for %zu triplets", cap_hint);
    }
    t->cap = cap_hint;
    return UMP_OK;
}

ump_status lsolve_trip_add(lsolve_trip *t, ump_idx i, ump_idx j, double x, ump_err *err)
{
    UMP_CHECK(i >= 0 && i < t->n && j >= 0 && j < t->n, err, UMP_ERR_INPUT,
              "lsolve: entry (%d, %d) outside a %d x %d matrix", (int)i, (int)j, (int)t->n,
              (int)t->n);
    if (t->nz == t->cap) {
        /* doubling keeps the appends amortised O(1) */
        size_t cap = t->cap ? 2 * t->cap : 16;
        ump_idx *Ti = ump_realloc_array(t->Ti, cap, sizeof *Ti);
        if (Ti)
            t->Ti = Ti;
        ump_idx *Tj = ump_realloc_array(t->Tj, cap, sizeof *Tj);
        if (Tj)
            t->Tj = Tj;
        double *Tx = ump_realloc_array(t->Tx, cap, sizeof *Tx);
        if (Tx)
            t->Tx = Tx;
        if (!Ti || !Tj || !Tx)
            return UMP_FAIL(err, UMP_ERR_NOMEM, "lsolve: out of memory for %zu triplets", cap);
        t->cap = cap;
    }
    t->Ti[t->nz] = i;
    t->Tj[t->nz] = j;
    t->Tx[t->nz] = x;
    t->nz++;
    return UMP_OK;
}

void lsolve_trip_clear(lsolve_trip *t)
{
    t->nz = 0;
}

void lsolve_trip_free(lsolve_trip *t)
{
    if (!t)
        return;
    free(t->Ti);
    free(t->Tj);
    free(t->Tx);
    t->Ti = t->Tj = NULL;
    t->Tx = NULL;
    t->nz = t->cap = 0;
}

void lsolve_mat_free(lsolve_mat **A)
{
    if (!A || !*A)
        return;
    free((*A)->Ap);
    free((*A)->Ai);
    free((*A)->Ax);
    free(*A);
    *A = NULL;
}

static lsolve_mat *mat_alloc(ump_idx n, size_t nnz)
{
    lsolve_mat *A = ump_alloc_array(1, sizeof *A);
    if (!A)
        return NULL;
    A->n = n;
    ALLOC(A->Ap, (size_t)n + 1);
    ALLOC(A->Ai, nnz);
    ALLOC(A->Ax, nnz);
    if (!A->Ap || !A->Ai || !A->Ax)
        lsolve_mat_free(&A);
    return A;
}

/* Triplets -> CSC in O(nz + n), as cs_compress + cs_dupl do: bucket by row,
 * sum duplicates within each row, then transpose, which leaves the row
 * indices of every column sorted. Explicit zeros are kept: the pattern is
 * what a later refactor must match. */
ump_status lsolve_trip_to_mat(const lsolve_trip *t, lsolve_mat **out, ump_err *err)
{
    *out = NULL;
    ump_idx n = t->n;
    UMP_CHECK(t->nz <= (size_t)UMP_IDX_MAX, err, UMP_ERR_NOMEM,
              "lsolve: %zu triplets exceed the index range", t->nz);
    ump_idx *Rp = NULL, *Rj = NULL, *w = NULL;
    double *Rx = NULL;
    ALLOC(Rp, (size_t)n + 1);
    ALLOC(Rj, t->nz);
    ALLOC(Rx, t->nz);
    ALLOC(w, (size_t)n + 1);
    lsolve_mat *A = NULL;
    ump_status rc = UMP_OK;
    if (!Rp || !Rj || !Rx || !w) {
        rc = UMP_FAIL(err, UMP_ERR_NOMEM, "lsolve: out of memory converting %zu triplets", t->nz);
        goto done;
    }
    /* row buckets */
    for (size_t k = 0; k < t->nz; k++)
        Rp[t->Ti[k] + 1]++;
    for (ump_idx i = 0; i < n; i++)
        Rp[i + 1] += Rp[i];
    memcpy(w, Rp, sizeof *w * (size_t)n);
    for (size_t k = 0; k < t->nz; k++) {
        ump_idx p = w[t->Ti[k]]++;
        Rj[p] = t->Tj[k];
        Rx[p] = t->Tx[k];
    }
    /* sum duplicates in each row: w[j] = where column j sits in the current row */
    for (ump_idx j = 0; j < n; j++)
        w[j] = -1;
    ump_idx nz = 0;
    for (ump_idx i = 0; i < n; i++) {
        ump_idx start = nz;
        for (ump_idx p = Rp[i]; p < Rp[i + 1]; p++) {
            ump_idx j = Rj[p];
            if (w[j] >= start) {
                Rx[w[j]] += Rx[p];
            } else {
                w[j] = nz;
                Rj[nz] = j;
                Rx[nz] = Rx[p];
                nz++;
            }
        }
        Rp[i] = start;
    }
    Rp[n] = nz;
    /* transpose into CSC: rows are visited in order, so columns come out sorted */
    A = mat_alloc(n, (size_t)nz);
    if (!A) {
        rc = UMP_FAIL(err, UMP_ERR_NOMEM, "lsolve: out of memory for a %d x %d matrix with %d entries",
                      (int)n, (int)n, (int)nz);
        goto done;
    }
    for (ump_idx p = 0; p < nz; p++)
        A->Ap[Rj[p] + 1]++;
    for (ump_idx j = 0; j < n; j++)
        A->Ap[j + 1] += A->Ap[j];
    memcpy(w, A->Ap, sizeof *w * (size_t)n);
    for (ump_idx i = 0; i < n; i++)
        for (ump_idx p = Rp[i]; p < Rp[i + 1]; p++) {
            ump_idx q = w[Rj[p]]++;
            A->Ai[q] = i;
            A->Ax[q] = Rx[p];
        }
    *out = A;
done:
    free(Rp);
    free(Rj);
    free(Rx);
    free(w);
    return rc;
}

void lsolve_mat_mult(const lsolve_mat *A, const double *restrict x, double *restrict y)
{
    ump_idx n = A->n;
    for (ump_idx i = 0; i < n; i++)
        y[i] = 0.0;
    for (ump_idx j = 0; j < n; j++) {
        double xj = x[j];
        for (ump_idx p = A->Ap[j]; p < A->Ap[j + 1]; p++)
            y[A->Ai[p]] += A->Ax[p] * xj; /* y <- y + A(:,j) x_j */
    }
}

void lsolve_mat_mult_sym(const lsolve_mat *A, const double *restrict x, double *restrict y)
{
    ump_idx n = A->n;
#pragma omp parallel for schedule(static) if (n > 4096)
    for (ump_idx i = 0; i < n; i++) {
        double s = 0.0; /* rows of column i ascending: lsolve_mat_mult's order */
        for (ump_idx p = A->Ap[i]; p < A->Ap[i + 1]; p++)
            s += A->Ax[p] * x[A->Ai[p]];
        y[i] = s;
    }
}

/* Position of row i in column j (rows sorted), -1 if absent. */
static ump_idx find_entry(const lsolve_mat *A, ump_idx i, ump_idx j)
{
    ump_idx lo = A->Ap[j], hi = A->Ap[j + 1];
    while (lo < hi) {
        ump_idx mid = lo + (hi - lo) / 2;
        if (A->Ai[mid] < i)
            lo = mid + 1;
        else
            hi = mid;
    }
    return (lo < A->Ap[j + 1] && A->Ai[lo] == i) ? lo : -1;
}

int lsolve_mat_is_symmetric(const lsolve_mat *A, double tol)
{
    double amax = 0.0;
    ump_idx nnz = A->Ap[A->n];
    for (ump_idx p = 0; p < nnz; p++)
        amax = fmax(amax, fabs(A->Ax[p]));
    double lim = tol * amax;
    for (ump_idx j = 0; j < A->n; j++)
        for (ump_idx p = A->Ap[j]; p < A->Ap[j + 1]; p++) {
            ump_idx i = A->Ai[p];
            if (i == j)
                continue;
            ump_idx q = find_entry(A, j, i);
            double aji = q >= 0 ? A->Ax[q] : 0.0;
            if (!(fabs(A->Ax[p] - aji) <= lim))
                return 0;
        }
    return 1;
}

/* ---- direct solvers ------------------------------------------------------ */

struct lsolve {
    lsolve_kind kind;      /* the solver actually used (never LSOLVE_AUTO) */
    lsolve_mat *A;         /* own copy: pattern check on refactor, UMFPACK refinement */
    /* UMFPACK */
    void *sym, *num;
    double control[UMFPACK_CONTROL], info[UMFPACK_INFO];
    int *Wi;               /* [n] wsolve workspace */
    double *W;             /* [5n] wsolve workspace (iterative refinement) */
    /* KLU */
    klu_symbolic *ks;
    klu_numeric *kn;
    klu_common kc;
    /* CHOLMOD: factors sign * A, sign = +1 or -1 so that sign * A is positive definite */
    int cholmod_started;
    cholmod_common cc;
    cholmod_sparse *cA;
    cholmod_factor *L;
    cholmod_dense *B, *X, *Y, *E;
    double sign;
    lsolve_lanes *lanes;   /* the solves on the simplicial factor, or NULL: cholmod_solve2 */
    double *ly;            /* [n] permuted right-hand side of the lane solves */
    double cond;           /* 1-norm condition estimate of the last factorization */
    int valid;             /* factors usable by lsolve_solve */
    int serial;            /* lsolve_factor_serial: no lanes (a refactor allocates nothing) */
    int *sperm;            /* [n] serial CHOLMOD: the fill-reducing order (cA = its P A P^T) */
    ump_idx *amap;         /* [nnz(A)] serial CHOLMOD: entry of cA of each entry of A, or -1 */
    double *sy;            /* [n] serial CHOLMOD: the permuted solution */
    double *cw;            /* [3n] the condition estimate's vectors, kept for refactors */
};

const char *lsolve_name(const lsolve *s)
{
    switch (s->kind) {
    case LSOLVE_UMFPACK: return "UMFPACK";
    case LSOLVE_KLU: return "KLU";
    case LSOLVE_CHOLMOD: return "CHOLMOD";
    case LSOLVE_AUTO: break;
    }
    return "?";
}

static void release_factors(lsolve *s)
{
    if (s->num)
        umfpack_di_free_numeric(&s->num);
    if (s->sym)
        umfpack_di_free_symbolic(&s->sym);
    if (s->kn)
        klu_free_numeric(&s->kn, &s->kc);
    if (s->ks)
        klu_free_symbolic(&s->ks, &s->kc);
    lsolve_lanes_free(&s->lanes);
    free(s->ly);
    free(s->sperm);
    free(s->amap);
    free(s->sy);
    s->ly = s->sy = NULL;
    s->sperm = NULL;
    s->amap = NULL;
    if (s->cholmod_started) {
        cholmod_free_factor(&s->L, &s->cc);
        cholmod_free_sparse(&s->cA, &s->cc);
        cholmod_free_dense(&s->B, &s->cc);
        cholmod_free_dense(&s->X, &s->cc);
        cholmod_free_dense(&s->Y, &s->cc);
        cholmod_free_dense(&s->E, &s->cc);
        cholmod_finish(&s->cc);
        s->cholmod_started = 0;
    }
    free(s->Wi);
    free(s->W);
    s->Wi = NULL;
    s->W = NULL;
}

void lsolve_free(lsolve **ps)
{
    if (!ps || !*ps)
        return;
    release_factors(*ps);
    lsolve_mat_free(&(*ps)->A);
    free((*ps)->cw);
    free(*ps);
    *ps = NULL;
}

static ump_status copy_mat(const lsolve_mat *A, lsolve_mat **out, ump_err *err)
{
    size_t nnz = (size_t)A->Ap[A->n];
    lsolve_mat *C = mat_alloc(A->n, nnz);
    if (!C)
        return UMP_FAIL(err, UMP_ERR_NOMEM, "lsolve: out of memory copying a %d x %d matrix",
                        (int)A->n, (int)A->n);
    memcpy(C->Ap, A->Ap, sizeof *C->Ap * ((size_t)A->n + 1));
    memcpy(C->Ai, A->Ai, sizeof *C->Ai * nnz);
    memcpy(C->Ax, A->Ax, sizeof *C->Ax * nnz);
    *out = C;
    return UMP_OK;
}

static int same_pattern(const lsolve_mat *A, const lsolve_mat *B)
{
    if (A->n != B->n)
        return 0;
    if (memcmp(A->Ap, B->Ap, sizeof *A->Ap * ((size_t)A->n + 1)) != 0)
        return 0;
    return memcmp(A->Ai, B->Ai, sizeof *A->Ai * (size_t)A->Ap[A->n]) == 0;
}

static int all_finite(const lsolve_mat *A)
{
    for (ump_idx p = 0; p < A->Ap[A->n]; p++)
        if (!isfinite(A->Ax[p]))
            return 0;
    return 1;
}

/* UMFPACK: original column of the smallest |U_kk| (called on failure only). */
static int umfpack_worst_column(const lsolve *s, double *piv)
{
    ump_idx n = s->A->n;
    double *Dx = NULL;
    int *Q = NULL;
    int col = -1;
    ALLOC(Dx, n);
    ALLOC(Q, n);
    if (Dx && Q &&
        umfpack_di_get_numeric(NULL, NULL, NULL, NULL, NULL, NULL, NULL, Q, Dx, NULL, NULL,
                               s->num) == UMFPACK_OK) {
        double best = INFINITY;
        for (ump_idx k = 0; k < n; k++)
            if (fabs(Dx[k]) < best) {
                best = fabs(Dx[k]);
                col = Q[k];
            }
        *piv = best;
    }
    free(Dx);
    free(Q);
    return col;
}

static ump_status umfpack_status(int st, const char *what, ump_err *err)
{
    switch (st) {
    case UMFPACK_ERROR_out_of_memory:
        return UMP_FAIL(err, UMP_ERR_NOMEM, "UMFPACK: out of memory in %s", what);
    case UMFPACK_ERROR_invalid_matrix:
        return UMP_FAIL(err, UMP_ERR_INPUT, "UMFPACK: invalid matrix in %s", what);
    case UMFPACK_ERROR_different_pattern:
        return UMP_FAIL(err, UMP_ERR_INPUT, "UMFPACK: pattern differs from the analysed one in %s", what);
    default:
        return UMP_FAIL(err, UMP_ERR_INPUT, "UMFPACK: %s failed with status %d", what, st);
    }
}

static ump_status umfpack_numeric_step(lsolve *s, ump_err *err)
{
    const lsolve_mat *A = s->A;
    if (s->num)
        umfpack_di_free_numeric(&s->num);
    int st = umfpack_di_numeric(A->Ap, A->Ai, A->Ax, s->sym, &s->num, s->control, s->info);
    if (st == UMFPACK_WARNING_singular_matrix) {
        double piv = 0;
        int col = umfpack_worst_column(s, &piv);
        umfpack_di_free_numeric(&s->num);
        return UMP_FAIL(err, UMP_ERR_SINGULAR,
                        "UMFPACK: matrix (n = %d) is singular: zero pivot in column %d", (int)A->n, col);
    }
    if (st != UMFPACK_OK) {
        s->num = NULL;
        return umfpack_status(st, "numeric factorization", err);
    }
    return UMP_OK;
}

static ump_status umfpack_setup(lsolve *s, ump_err *err)
{
    const lsolve_mat *A = s->A;
    ump_idx n = A->n;
    umfpack_di_defaults(s->control);
    s->control[UMFPACK_PRL] = 0; /* silent: we report */
    /* AMD and METIS, the better of the two: on the PPE of an 80k-cell
     * triangle mesh (~25 entries a row) METIS cuts the LU fill by ~20% */
    s->control[UMFPACK_ORDERING] = UMFPACK_ORDERING_CHOLMOD;
    /* No iterative refinement: LU with partial pivoting is backward stable,
     * the PPE is well conditioned and the continuity errors after the
     * correction stay at round-off (test_solver_*: < 1e-12); the default
     * two refinement steps cost a matrix product and a further solve each,
     * about 40 % of the step's PPE time on triangle meshes. */
    s->control[UMFPACK_IRSTEP] = 0;
    int st = umfpack_di_symbolic(n, n, A->Ap, A->Ai, A->Ax, &s->sym, s->control, s->info);
    if (st != UMFPACK_OK) {
        s->sym = NULL;
        return umfpack_status(st, "symbolic analysis", err);
    }
    ALLOC(s->Wi, n);
    ALLOC(s->W, 5 * (size_t)n);
    if (!s->Wi || !s->W)
        return UMP_FAIL(err, UMP_ERR_NOMEM, "UMFPACK: out of memory for the solve workspace (n = %d)",
                        (int)n);
    return umfpack_numeric_step(s, err);
}

static ump_status klu_status(const lsolve *s, const char *what, ump_err *err)
{
    switch (s->kc.status) {
    case KLU_SINGULAR:
        return UMP_FAIL(err, UMP_ERR_SINGULAR, "KLU: matrix (n = %d) is singular: zero pivot in column %d",
                        (int)s->A->n, s->kc.singular_col);
    case KLU_OUT_OF_MEMORY:
        return UMP_FAIL(err, UMP_ERR_NOMEM, "KLU: out of memory in %s", what);
    case KLU_TOO_LARGE:
        return UMP_FAIL(err, UMP_ERR_NOMEM, "KLU: integer overflow in %s", what);
    case KLU_INVALID:
        return UMP_FAIL(err, UMP_ERR_INPUT, "KLU: invalid input to %s", what);
    default:
        return UMP_FAIL(err, UMP_ERR_INPUT, "KLU: %s failed with status %d", what, s->kc.status);
    }
}

/* KLU: original column of the smallest |U_kk| (Udiag is in pivotal order,
 * the symbolic Q maps it to columns). */
static int klu_worst_column(const lsolve *s, double *piv)
{
    const double *Ud = (const double *)s->kn->Udiag;
    int col = -1;
    double best = INFINITY;
    for (ump_idx k = 0; k < s->A->n; k++)
        if (fabs(Ud[k]) < best) {
            best = fabs(Ud[k]);
            col = s->ks->Q[k];
        }
    *piv = best;
    return col;
}

static ump_status klu_setup(lsolve *s, ump_err *err)
{
    lsolve_mat *A = s->A;
    klu_defaults(&s->kc);
    s->ks = klu_analyze(A->n, A->Ap, A->Ai, &s->kc);
    if (!s->ks)
        return klu_status(s, "klu_analyze", err);
    s->kn = klu_factor(A->Ap, A->Ai, A->Ax, s->ks, &s->kc);
    if (!s->kn || s->kc.status != KLU_OK) {
        if (s->kn)
            klu_free_numeric(&s->kn, &s->kc);
        if (s->kc.status == KLU_OK)
            s->kc.status = KLU_INVALID;
        return klu_status(s, "klu_factor", err);
    }
    return UMP_OK;
}

static ump_status cholmod_status(const lsolve *s, const char *what, ump_err *err)
{
    switch (s->cc.status) {
    case CHOLMOD_NOT_POSDEF:
        return UMP_FAIL(err, UMP_ERR_SINGULAR,
                        "CHOLMOD: matrix (n = %d) is not %s definite: failed at column %d",
                        (int)s->A->n, s->sign > 0 ? "positive" : "negative",
                        s->L ? (int)s->L->minor : -1);
    case CHOLMOD_DSMALL:
        return UMP_FAIL(err, UMP_ERR_SINGULAR,
                        "CHOLMOD: matrix (n = %d) is numerically singular: tiny pivot in %s",
                        (int)s->A->n, what);
    case CHOLMOD_OUT_OF_MEMORY:
        return UMP_FAIL(err, UMP_ERR_NOMEM, "CHOLMOD: out of memory in %s", what);
    case CHOLMOD_TOO_LARGE:
        return UMP_FAIL(err, UMP_ERR_NOMEM, "CHOLMOD: integer overflow in %s", what);
    case CHOLMOD_INVALID:
        return UMP_FAIL(err, UMP_ERR_INPUT, "CHOLMOD: invalid input to %s", what);
    default:
        return UMP_FAIL(err, UMP_ERR_INPUT, "CHOLMOD: %s failed with status %d", what, s->cc.status);
    }
}

/* cA <- sign * A (CHOLMOD reads its upper triangle, stype = 1). */
static void cholmod_load_values(lsolve *s)
{
    double *x = s->cA->x;
    ump_idx nnz = s->A->Ap[s->A->n];
    if (s->amap) {
        for (ump_idx p = 0; p < nnz; p++)
            if (s->amap[p] >= 0)
                x[s->amap[p]] = s->sign * s->A->Ax[p];
        return;
    }
    for (ump_idx p = 0; p < nnz; p++)
        x[p] = s->sign * s->A->Ax[p];
}

/* lsolve_factor_serial with CHOLMOD. cholmod_factorize allocates a
 * permuted copy of the matrix at every call unless the order is the
 * natural one, and cholmod_solve2 reallocates its work between solves. So
 * the fill-reducing order is found once (cholmod_analyze's choice), the
 * matrix is stored already permuted, B = P A P^T (upper triangle, amap
 * taking A's entries there), and analysed in its natural order; a
 * refactor only moves values into B, and the solves with the simplicial
 * LL' factor are the loops of serial_solve. */
static ump_status cholmod_numeric_step(lsolve *s, ump_err *err);

static ump_status cholmod_serial_setup(lsolve *s, ump_err *err)
{
    const lsolve_mat *A = s->A;
    ump_idx n = A->n;
    size_t nnz = (size_t)A->Ap[n];
    s->cc.supernodal = CHOLMOD_SIMPLICIAL;
    cholmod_sparse *P = cholmod_allocate_sparse((size_t)n, (size_t)n, nnz, 1, 1, 1, CHOLMOD_PATTERN, &s->cc);
    if (!P)
        return cholmod_status(s, "cholmod_allocate_sparse", err);
    memcpy(P->p, A->Ap, sizeof(int) * ((size_t)n + 1));
    memcpy(P->i, A->Ai, sizeof(int) * nnz);
    cholmod_factor *L0 = cholmod_analyze(P, &s->cc);
    cholmod_free_sparse(&P, &s->cc);
    if (!L0)
        return cholmod_status(s, "cholmod_analyze", err);
    int *iperm = NULL, *cnt = NULL;
    ALLOC(s->sperm, n);
    ALLOC(s->amap, nnz + 1);
    ALLOC(s->sy, n);
    ALLOC(iperm, n);
    ALLOC(cnt, (size_t)n + 1);
    ump_status rc = UMP_OK;
    if (!s->sperm || !s->amap || !s->sy || !iperm || !cnt) {
        rc = UMP_FAIL(err, UMP_ERR_NOMEM, "CHOLMOD: out of memory (n = %d)", (int)n);
        goto done;
    }
    memcpy(s->sperm, L0->Perm, sizeof(int) * (size_t)n);
    for (ump_idx k = 0; k < n; k++)
        iperm[s->sperm[k]] = (int)k;
    /* B's columns: the entries (i, j) of A with iperm[i] <= iperm[j] */
    for (ump_idx j = 0; j < n; j++)
        for (ump_idx q = A->Ap[j]; q < A->Ap[j + 1]; q++)
            if (iperm[A->Ai[q]] <= iperm[j])
                cnt[iperm[j] + 1]++;
    for (ump_idx k = 0; k < n; k++)
        cnt[k + 1] += cnt[k];
    s->cA = cholmod_allocate_sparse((size_t)n, (size_t)n, (size_t)cnt[n], 1, 1, 1, CHOLMOD_REAL, &s->cc);
    s->B = cholmod_allocate_dense((size_t)n, 1, (size_t)n, CHOLMOD_REAL, &s->cc);
    if (!s->cA || !s->B) {
        rc = cholmod_status(s, "cholmod_allocate", err);
        goto done;
    }
    int *Bp = s->cA->p, *Bi = s->cA->i;
    memcpy(Bp, cnt, sizeof(int) * ((size_t)n + 1));
    for (ump_idx j = 0; j < n; j++)
        for (ump_idx q = A->Ap[j]; q < A->Ap[j + 1]; q++) {
            int r = iperm[A->Ai[q]], c = iperm[j];
            s->amap[q] = -1;
            if (r > c)
                continue;
            /* insertion in row order (a column has a few tens of entries) */
            int p = cnt[c]++;
            while (p > Bp[c] && Bi[p - 1] > r) {
                Bi[p] = Bi[p - 1];
                p--;
            }
            Bi[p] = r;
        }
    /* amap from B's sorted rows (an insertion moves the entries after it) */
    for (ump_idx j = 0; j < n; j++)
        for (ump_idx q = A->Ap[j]; q < A->Ap[j + 1]; q++) {
            int r = iperm[A->Ai[q]], c = iperm[j];
            if (r > c)
                continue;
            int lo = Bp[c], hi = Bp[c + 1] - 1;
            while (lo < hi) {
                int mid = (lo + hi) / 2;
                if (Bi[mid] < r)
                    lo = mid + 1;
                else
                    hi = mid;
            }
            s->amap[q] = lo;
        }
    cholmod_load_values(s);
    s->cc.nmethods = 1;
    s->cc.method[0].ordering = CHOLMOD_NATURAL;
    s->cc.postorder = 0;
    s->L = cholmod_analyze(s->cA, &s->cc);
    if (!s->L) {
        rc = cholmod_status(s, "cholmod_analyze", err);
        goto done;
    }
    rc = cholmod_numeric_step(s, err);
    if (rc == UMP_OK && (s->L->is_super || !s->L->is_ll))
        rc = UMP_FAIL(err, UMP_ERR_INPUT, "CHOLMOD: expected a simplicial LL' factor (n = %d)", (int)n);
done:
    cholmod_free_factor(&L0, &s->cc);
    free(iperm);
    free(cnt);
    return rc;
}

/* x = A^-1 b with serial_setup's factor: sign b permuted, L L^T y = that,
 * permuted back. */
static void serial_solve(lsolve *s, const double *b, double *x)
{
    const cholmod_factor *L = s->L;
    const int *Lp = L->p, *Li = L->i, *Lnz = L->nz, *perm = s->sperm;
    const double *Lx = L->x;
    double *y = s->sy;
    ump_idx n = s->A->n;
    for (ump_idx k = 0; k < n; k++)
        y[k] = s->sign * b[perm[k]];
    for (ump_idx j = 0; j < n; j++) { /* L y = b: the diagonal first in each column */
        double yj = y[j] /= Lx[Lp[j]];
        for (int q = Lp[j] + 1; q < Lp[j] + Lnz[j]; q++)
            y[Li[q]] -= Lx[q] * yj;
    }
    for (ump_idx j = n - 1; j >= 0; j--) { /* L^T x = y */
        double t = y[j];
        for (int q = Lp[j] + 1; q < Lp[j] + Lnz[j]; q++)
            t -= Lx[q] * y[Li[q]];
        y[j] = t / Lx[Lp[j]];
    }
    for (ump_idx k = 0; k < n; k++)
        x[perm[k]] = y[k];
}

/* The factor made simplicial (LL', packed, diagonal first) and split into
 * two lanes for the solves (lsolve_lanes.c). If the split cannot be made,
 * the solves stay with cholmod_solve2. */
static ump_status cholmod_lanes(lsolve *s, ump_err *err)
{
    lsolve_lanes_free(&s->lanes);
    int was_super = s->L->is_super;
    if (!cholmod_change_factor(CHOLMOD_REAL, 1, 0, 1, 1, s->L, &s->cc) || s->cc.status != CHOLMOD_OK)
        return cholmod_status(s, "cholmod_change_factor", err);
    /* the explicit zeros of relaxed supernodes out of the pattern */
    if (was_super && (!cholmod_resymbol(s->cA, NULL, 0, 1, s->L, &s->cc) || s->cc.status != CHOLMOD_OK))
        return cholmod_status(s, "cholmod_resymbol", err);
    ump_idx n = s->A->n;
    if (!s->ly && !(s->ly = ump_alloc_array((size_t)n, sizeof *s->ly)))
        return UMP_FAIL(err, UMP_ERR_NOMEM, "CHOLMOD: out of memory (n = %d)", (int)n);
    ump_err e;
    ump_status rc = lsolve_lanes_build(n, s->L->p, s->L->i, s->L->x, &s->lanes, &e);
    if (rc == UMP_ERR_NOMEM) {
        *err = e;
        return rc;
    }
    return UMP_OK; /* UMP_ERR_INPUT: an unexpected layout, solved by CHOLMOD */
}

static ump_status cholmod_numeric_step(lsolve *s, ump_err *err)
{
    cholmod_load_values(s);
    if (!cholmod_factorize(s->cA, s->L, &s->cc) || s->cc.status != CHOLMOD_OK)
        return cholmod_status(s, "cholmod_factorize", err);
    return s->serial ? UMP_OK : cholmod_lanes(s, err);
}

static ump_status cholmod_setup(lsolve *s, ump_err *err)
{
    const lsolve_mat *A = s->A;
    ump_idx n = A->n;
    UMP_CHECK(lsolve_mat_is_symmetric(A, 1e-12), err, UMP_ERR_INPUT,
              "CHOLMOD: matrix (n = %d) is not symmetric", (int)n);
    /* sign: a definite matrix has a diagonal of one sign (the PPE: negative) */
    int npos = 0, nneg = 0;
    for (ump_idx j = 0; j < n; j++) {
        ump_idx q = find_entry(A, j, j);
        double d = q >= 0 ? A->Ax[q] : 0.0;
        npos += d > 0;
        nneg += d < 0;
    }
    s->sign = nneg == n && n > 0 ? -1.0 : 1.0;
    UMP_CHECK(npos == n || nneg == n, err, UMP_ERR_SINGULAR,
              "CHOLMOD: matrix (n = %d) is not definite: its diagonal has %d positive, %d negative, "
              "%d zero entries", (int)n, npos, nneg, (int)n - npos - nneg);
    cholmod_start(&s->cc);
    s->cholmod_started = 1;
    s->cc.print = 0;    /* silent: we report */
    /* simplicial below a flop density: the lane solves need a simplicial
     * factor, and one made directly has L's exact pattern, while a
     * supernodal factor converted keeps the zeros of relaxed supernodes
     * (resymbol removes them, at a cost). Measured on the cavity: 160^2
     * (flops/nnz(L) = 93) simplicial 0.13 s set-up against 0.20 s
     * supernodal + conversion; 320^2 (162) the simplicial factorization
     * takes 4.4x the instructions of the supernodal one. */
    s->cc.supernodal = CHOLMOD_AUTO;
    s->cc.supernodal_switch = LSOLVE_SUPERNODAL_SWITCH;
    s->cc.final_ll = 1; /* LL' also for simplicial factors: a simplicial LDL' would
                           accept an indefinite matrix without pivoting */
    if (s->serial)
        return cholmod_serial_setup(s, err);
    size_t nnz = (size_t)A->Ap[n];
    s->cA = cholmod_allocate_sparse((size_t)n, (size_t)n, nnz, 1, 1, 1, CHOLMOD_REAL, &s->cc);
    s->B = cholmod_allocate_dense((size_t)n, 1, (size_t)n, CHOLMOD_REAL, &s->cc);
    if (!s->cA || !s->B)
        return cholmod_status(s, "cholmod_allocate", err);
    memcpy(s->cA->p, A->Ap, sizeof(int) * ((size_t)n + 1));
    memcpy(s->cA->i, A->Ai, sizeof(int) * nnz);
    cholmod_load_values(s);
    s->L = cholmod_analyze(s->cA, &s->cc);
    if (!s->L)
        return cholmod_status(s, "cholmod_analyze", err);
    return cholmod_numeric_step(s, err);
}

static ump_status factor_with(lsolve *s, lsolve_kind kind, ump_err *err)
{
    s->kind = kind;
    switch (kind) {
    case LSOLVE_UMFPACK: return umfpack_setup(s, err);
    case LSOLVE_KLU: return klu_setup(s, err);
    case LSOLVE_CHOLMOD: return cholmod_setup(s, err);
    case LSOLVE_AUTO: break;
    }
    return UMP_FAIL(err, UMP_ERR_INPUT, "lsolve: unknown solver kind %d", (int)kind);
}

/* AUTO: CHOLMOD for an exactly symmetric matrix with a one-signed diagonal
 * (it then either succeeds or reports indefiniteness, and we fall back),
 * UMFPACK otherwise. Exact symmetry, because CHOLMOD reads one triangle only:
 * a nearly symmetric matrix would be solved as its upper half. */
static int auto_wants_cholmod(const lsolve_mat *A)
{
    if (!lsolve_mat_is_symmetric(A, 0.0))
        return 0;
    int npos = 0, nneg = 0;
    for (ump_idx j = 0; j < A->n; j++) {
        ump_idx q = find_entry(A, j, j);
        double d = q >= 0 ? A->Ax[q] : 0.0;
        npos += d > 0;
        nneg += d < 0;
    }
    return A->n > 0 && (npos == A->n || nneg == A->n);
}

/* x <- A^-1 b (trans = 0) or A^-T b (trans = 1) with the current factors. */
static ump_status solve_sys(lsolve *s, int trans, const double *b, double *x, ump_err *err)
{
    ump_idx n = s->A->n;
    switch (s->kind) {
    case LSOLVE_UMFPACK: {
        /* wsolve: the workspace (with iterative refinement) was allocated once */
        int st = umfpack_di_wsolve(trans ? UMFPACK_At : UMFPACK_A, s->A->Ap, s->A->Ai, s->A->Ax, x, b,
                                   s->num, s->control, s->info, s->Wi, s->W);
        if (st == UMFPACK_WARNING_singular_matrix)
            return UMP_FAIL(err, UMP_ERR_SINGULAR, "UMFPACK: solve with a singular matrix (n = %d)",
                            (int)n);
        if (st != UMFPACK_OK)
            return umfpack_status(st, "solve", err);
        return UMP_OK;
    }
    case LSOLVE_KLU:
        memcpy(x, b, sizeof *x * (size_t)n); /* klu_solve works in place */
        if (!(trans ? klu_tsolve(s->ks, s->kn, n, 1, x, &s->kc) : klu_solve(s->ks, s->kn, n, 1, x, &s->kc)))
            return klu_status(s, "klu_solve", err);
        return UMP_OK;
    case LSOLVE_CHOLMOD: {
        if (s->amap) {
            serial_solve(s, b, x);
            return UMP_OK;
        }
        if (s->lanes) { /* x = P^T L^-T L^-1 P (sign b) */
            const int *perm = s->L->Perm;
            double *y = s->ly;
            for (ump_idx k = 0; k < n; k++)
                y[k] = s->sign * b[perm[k]];
            lsolve_lanes_solve(s->lanes, y);
            for (ump_idx k = 0; k < n; k++)
                x[perm[k]] = y[k];
            return UMP_OK;
        }
        double *bx = s->B->x;
        for (ump_idx i = 0; i < n; i++)
            bx[i] = s->sign * b[i]; /* (sign A) x = sign b; A^T = A */
        /* solve2 allocates X, Y, E on the first call only and reuses them */
        if (!cholmod_solve2(CHOLMOD_A, s->L, s->B, NULL, &s->X, NULL, &s->Y, &s->E, &s->cc))
            return cholmod_status(s, "cholmod_solve2", err);
        memcpy(x, s->X->x, sizeof *x * (size_t)n);
        return UMP_OK;
    }
    case LSOLVE_AUTO: break;
    }
    return UMP_FAIL(err, UMP_ERR_INPUT, "lsolve: bad solver object");
}

static double norm1(ump_idx n, const double *x)
{
    double s = 0.0;
    for (ump_idx i = 0; i < n; i++)
        s += fabs(x[i]);
    return s;
}

/* Estimate ||A^-1||_1 by Hager's method (Hager 1984, with Higham's 1988
 * safeguards as in LAPACK's xLACON): at most 5 pairs of solves with A and
 * A^T, plus one extra solve with an alternating vector. Non-finite -> inf. */
static ump_status estimate_inverse_norm(lsolve *s, double *est, ump_err *err)
{
    ump_idx n = s->A->n;
    if (!s->cw && !ALLOC(s->cw, 3 * (size_t)n))
        return UMP_FAIL(err, UMP_ERR_NOMEM, "%s: out of memory estimating the condition number",
                        lsolve_name(s));
    double *x = s->cw, *y = x + n, *z = y + n;
    ump_status rc = UMP_OK;
    *est = 0.0;
    for (ump_idx i = 0; i < n; i++)
        x[i] = 1.0 / n;
    ump_idx jold = -1;
    for (int it = 0; it < 5; it++) {
        if ((rc = solve_sys(s, 0, x, y, err)) != UMP_OK)
            goto done;                          /* y <- A^-1 x */
        double e = norm1(n, y);
        if (!isfinite(e)) {
            *est = INFINITY;
            goto done;
        }
        if (it > 0 && e <= *est)
            break;                              /* no progress */
        *est = e;
        for (ump_idx i = 0; i < n; i++)
            x[i] = y[i] >= 0 ? 1.0 : -1.0;      /* xi <- sign(y) */
        if ((rc = solve_sys(s, 1, x, z, err)) != UMP_OK)
            goto done;                          /* z <- A^-T xi */
        ump_idx j = 0;
        for (ump_idx i = 1; i < n; i++)
            if (fabs(z[i]) > fabs(z[j]))
                j = i;
        if (j == jold)
            break;
        jold = j;
        for (ump_idx i = 0; i < n; i++)
            x[i] = 0.0;
        x[j] = 1.0;                             /* x <- e_j */
    }
    /* Higham's alternating vector guards against Hager's worst cases */
    for (ump_idx i = 0; i < n; i++)
        x[i] = (i % 2 ? -1.0 : 1.0) * (1.0 + (n > 1 ? (double)i / (n - 1) : 0.0));
    if ((rc = solve_sys(s, 0, x, y, err)) != UMP_OK)
        goto done;
    double alt = 2.0 * norm1(n, y) / (3.0 * n);
    *est = isfinite(alt) ? fmax(*est, alt) : INFINITY;
done:
    return rc;
}

/* After every numeric factorization: refuse a numerically singular matrix. */
static ump_status check_condition(lsolve *s, ump_err *err)
{
    const lsolve_mat *A = s->A;
    double anorm = 0.0;
    for (ump_idx j = 0; j < A->n; j++) {
        double c = 0.0;
        for (ump_idx p = A->Ap[j]; p < A->Ap[j + 1]; p++)
            c += fabs(A->Ax[p]);
        anorm = fmax(anorm, c);                 /* ||A||_1 = max column sum */
    }
    double ainv = 0.0;
    UMP_CALL(estimate_inverse_norm(s, &ainv, err));
    s->cond = anorm * ainv;
    if (s->cond <= LSOLVE_COND_MAX)
        return UMP_OK;
    double piv = 0.0;
    int col = -1;
    if (s->kind == LSOLVE_UMFPACK)
        col = umfpack_worst_column(s, &piv);
    else if (s->kind == LSOLVE_KLU)
        col = klu_worst_column(s, &piv);
    if (col >= 0)
        return UMP_FAIL(err, UMP_ERR_SINGULAR,
                        "%s: matrix (n = %d) is numerically singular: condition number ~%.2g > %g, "
                        "smallest pivot %.3g in column %d",
                        lsolve_name(s), (int)A->n, s->cond, LSOLVE_COND_MAX, piv, col);
    return UMP_FAIL(err, UMP_ERR_SINGULAR,
                    "%s: matrix (n = %d) is numerically singular: condition number ~%.2g > %g",
                    lsolve_name(s), (int)A->n, s->cond, LSOLVE_COND_MAX);
}

static ump_status factor(const lsolve_mat *A, lsolve_kind kind, int serial, lsolve **out, ump_err *err)
{
    *out = NULL;
    UMP_CHECK(A && A->n > 0, err, UMP_ERR_INPUT, "lsolve: empty matrix");
    UMP_CHECK(all_finite(A), err, UMP_ERR_INPUT, "lsolve: matrix (n = %d) has NaN or infinite entries",
              (int)A->n);
    lsolve *s = ump_alloc_array(1, sizeof *s);
    UMP_CHECK(s, err, UMP_ERR_NOMEM, "lsolve: out of memory");
    s->serial = serial;
    ump_status rc = copy_mat(A, &s->A, err);
    if (rc == UMP_OK) {
        if (kind == LSOLVE_AUTO && auto_wants_cholmod(A)) {
            rc = factor_with(s, LSOLVE_CHOLMOD, err);
            if (rc == UMP_ERR_SINGULAR && s->cc.status == CHOLMOD_NOT_POSDEF) {
                release_factors(s);
                rc = factor_with(s, LSOLVE_UMFPACK, err); /* symmetric indefinite */
            }
        } else {
            rc = factor_with(s, kind == LSOLVE_AUTO ? LSOLVE_UMFPACK : kind, err);
        }
    }
    if (rc == UMP_OK)
        rc = check_condition(s, err);
    if (rc != UMP_OK) {
        lsolve_free(&s);
        return rc;
    }
    s->valid = 1;
    *out = s;
    return UMP_OK;
}

ump_status lsolve_factor(const lsolve_mat *A, lsolve_kind kind, lsolve **out, ump_err *err)
{
    return factor(A, kind, 0, out, err);
}

ump_status lsolve_factor_serial(const lsolve_mat *A, lsolve_kind kind, lsolve **out, ump_err *err)
{
    return factor(A, kind, 1, out, err);
}

static ump_status refactor_values(lsolve *s, ump_err *err)
{
    switch (s->kind) {
    case LSOLVE_UMFPACK:
        return umfpack_numeric_step(s, err);
    case LSOLVE_KLU:
        /* klu_refactor keeps the pivot order of klu_factor: fast, but it may
         * lose stability if the values change much (the condition check then
         * usually catches it) */
        if (!klu_refactor(s->A->Ap, s->A->Ai, s->A->Ax, s->ks, s->kn, &s->kc) ||
            s->kc.status != KLU_OK) {
            if (s->kc.status == KLU_OK)
                s->kc.status = KLU_INVALID;
            return klu_status(s, "klu_refactor", err);
        }
        return UMP_OK;
    case LSOLVE_CHOLMOD:
        return cholmod_numeric_step(s, err); /* the sign is kept from lsolve_factor */
    case LSOLVE_AUTO: break;
    }
    return UMP_FAIL(err, UMP_ERR_INPUT, "lsolve: bad solver object");
}

ump_status lsolve_refactor(lsolve *s, const lsolve_mat *A, ump_err *err)
{
    UMP_CHECK(same_pattern(s->A, A), err, UMP_ERR_INPUT,
              "%s: refactor needs the pattern of the factorized matrix", lsolve_name(s));
    UMP_CHECK(all_finite(A), err, UMP_ERR_INPUT, "%s: matrix (n = %d) has NaN or infinite entries",
              lsolve_name(s), (int)A->n);
    memcpy(s->A->Ax, A->Ax, sizeof *A->Ax * (size_t)A->Ap[A->n]);
    /* a failed refactor leaves no usable factors until a successful one */
    s->valid = 0;
    UMP_CALL(refactor_values(s, err));
    UMP_CALL(check_condition(s, err));
    s->valid = 1;
    return UMP_OK;
}

ump_status lsolve_solve(lsolve *s, const double *b, double *x, ump_err *err)
{
    UMP_CHECK(s->valid, err, UMP_ERR_SINGULAR, "%s: no valid factorization (a refactor failed)",
              lsolve_name(s));
    return solve_sys(s, 0, b, x, err);
}

int lsolve_lane_work(const lsolve *s, size_t work[3])
{
    if (s->kind != LSOLVE_CHOLMOD || !s->lanes)
        return 0;
    lsolve_lanes_work(s->lanes, work);
    return 1;
}

double lsolve_condest(const lsolve *s)
{
    return s->cond;
}

size_t lsolve_factor_nnz(const lsolve *s)
{
    switch (s->kind) {
    case LSOLVE_UMFPACK: {
        int lnz = 0, unz = 0, nr = 0, nc = 0, nzud = 0;
        if (s->num && umfpack_di_get_lunz(&lnz, &unz, &nr, &nc, &nzud, s->num) == UMFPACK_OK)
            return (size_t)lnz + (size_t)unz - (size_t)s->A->n; /* unit diagonal of L not stored */
        return 0;
    }
    case LSOLVE_KLU:
        if (s->kn)
            return (size_t)s->kn->lnz + (size_t)s->kn->unz - (size_t)s->A->n + (size_t)s->kn->nzoff;
        return 0;
    case LSOLVE_CHOLMOD:
        return (size_t)s->cc.lnz;
    case LSOLVE_AUTO: break;
    }
    return 0;
}
