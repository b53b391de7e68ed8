/* SPDX-License-Identifier: GPL-3.0-or-later
 * lsolve_krylov.c -- preconditioned BiCGSTAB (van der Vorst, SIAM J. Sci.
 * Stat. Comput. 13, 1992) with Jacobi or ILU(0) preconditioning.
 *
 * Workload: the implicit particle predictor (Eq. 14) gives a new matrix,
 * with a new pattern, every time step, warm-started from the previous
 * velocities: a few tens of iterations per solve. The workspace (8 vectors
 * of n, the diagonal pointers and the ILU(0) values) is allocated once; the
 * ILU value array grows only when a matrix has more entries than any before,
 * so in steady state no solve allocates.
 *
 * Preconditioning is on the right (A M^-1 y = b, x = M^-1 y), so the
 * residual the iteration tracks is the true residual b - A x of the
 * unpreconditioned system; at the end it is recomputed explicitly, and if
 * the recursively updated residual has drifted from it the iteration is
 * restarted from the current x.
 *
 * ILU(0) on compressed columns: the CSC arrays of A are the CSR arrays of
 * B = A^T. The row-wise IKJ ILU(0) of B, B ~ L U (L unit lower, U upper,
 * both with the pattern of B), gives A ~ U^T L^T, applied as a forward
 * column sweep with U^T followed by a backward column sweep with L^T.
 */
#include "umppm/lsolve.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define ALLOC(p, n) ((p) = ump_alloc_array((size_t)(n), sizeof *(p)))

/* Restarts allowed after a breakdown or residual drift, per solve. */
#define KRYLOV_MAX_RESTARTS 5

struct lsolve_krylov {
    ump_idx n;
    double *r, *rh, *p, *v, *ph, *s, *sh, *t; /* [n] BiCGSTAB vectors */
    double *dinv;                             /* [n] Jacobi: 1 / a_ii */
    ump_idx *dptr;                            /* [n] ILU: position of a_ii */
    ump_idx *iw;                              /* [n] ILU: column marker, -1 */
    double *lu;                               /* [cap] ILU(0) factor values */
    size_t cap;
    ump_idx pc_n;                             /* order the preconditioner was built for, -1 none */
    int pc_kind;                              /* its lsolve_pc */
    lsolve_pc_fn add;                         /* of this solve: adds its correction (lsolve_bicgstab_pc) */
    void *add_ctx;
};

void lsolve_krylov_free(lsolve_krylov **pk)
{
    if (!pk || !*pk)
        return;
    lsolve_krylov *k = *pk;
    double *vec[] = {k->r, k->rh, k->p, k->v, k->ph, k->s, k->sh, k->t, k->dinv, k->lu};
    for (size_t i = 0; i < sizeof vec / sizeof vec[0]; i++)
        free(vec[i]);
    free(k->dptr);
    free(k->iw);
    free(k);
    *pk = NULL;
}

ump_status lsolve_krylov_create(ump_idx n, lsolve_krylov **out, ump_err *err)
{
    *out = NULL;
    UMP_CHECK(n > 0, err, UMP_ERR_INPUT, "BiCGSTAB: %d unknowns", (int)n);
    lsolve_krylov *k = ump_alloc_array(1, sizeof *k);
    UMP_CHECK(k, err, UMP_ERR_NOMEM, "BiCGSTAB: out of memory");
    k->n = n;
    k->pc_n = -1;
    ALLOC(k->r, n);
    ALLOC(k->rh, n);
    ALLOC(k->p, n);
    ALLOC(k->v, n);
    ALLOC(k->ph, n);
    ALLOC(k->s, n);
    ALLOC(k->sh, n);
    ALLOC(k->t, n);
    ALLOC(k->dinv, n);
    ALLOC(k->dptr, n);
    ALLOC(k->iw, n);
    if (!k->r || !k->rh || !k->p || !k->v || !k->ph || !k->s || !k->sh || !k->t || !k->dinv ||
        !k->dptr || !k->iw) {
        lsolve_krylov_free(&k);
        return UMP_FAIL(err, UMP_ERR_NOMEM, "BiCGSTAB: out of memory for %d unknowns", (int)n);
    }
    for (ump_idx i = 0; i < n; i++)
        k->iw[i] = -1;
    *out = k;
    return UMP_OK;
}

static double dot(ump_idx n, const double *restrict a, const double *restrict b)
{
    double s = 0.0;
    for (ump_idx i = 0; i < n; i++)
        s += a[i] * b[i];
    return s;
}

/* Position of a_jj in column j (rows sorted), -1 if absent. */
static ump_idx diag_pos(const lsolve_mat *A, ump_idx j)
{
    for (ump_idx p = A->Ap[j]; p < A->Ap[j + 1]; p++)
        if (A->Ai[p] >= j)
            return A->Ai[p] == j ? p : -1;
    return -1;
}

static ump_status setup_jacobi(lsolve_krylov *k, const lsolve_mat *A, ump_err *err)
{
    for (ump_idx j = 0; j < A->n; j++) {
        ump_idx p = diag_pos(A, j);
        double d = p >= 0 ? A->Ax[p] : 0.0;
        UMP_CHECK(d != 0.0 && isfinite(d), err, UMP_ERR_SINGULAR,
                  "BiCGSTAB/Jacobi: zero or non-finite diagonal in row %d", (int)j);
        k->dinv[j] = 1.0 / d;
    }
    return UMP_OK;
}

/* IKJ ILU(0) of B = A^T, B's rows being A's columns (see top of file). */
static ump_status setup_ilu0(lsolve_krylov *k, const lsolve_mat *A, ump_err *err)
{
    const ump_idx n = A->n, *Ap = A->Ap, *Ai = A->Ai;
    size_t nnz = (size_t)Ap[n];
    if (nnz > k->cap) {
        /* by half again at least: a pattern that grows by a few entries
         * per step (the meshless solvers' moving particles) reallocates
         * only every few steps */
        size_t nc = UMP_MAX(nnz, k->cap + k->cap / 2);
        double *lu = ump_realloc_array(k->lu, nc, sizeof *lu);
        UMP_CHECK(lu, err, UMP_ERR_NOMEM, "BiCGSTAB/ILU(0): out of memory for %zu entries", nc);
        k->lu = lu;
        k->cap = nc;
    }
    double *lu = k->lu;
    memcpy(lu, A->Ax, sizeof *lu * nnz);
    for (ump_idx i = 0; i < n; i++) {
        k->dptr[i] = diag_pos(A, i);
        UMP_CHECK(k->dptr[i] >= 0, err, UMP_ERR_SINGULAR,
                  "BiCGSTAB/ILU(0): no diagonal entry in row %d", (int)i);
    }
    ump_idx *iw = k->iw;
    for (ump_idx i = 0; i < n; i++) {
        for (ump_idx p = Ap[i]; p < Ap[i + 1]; p++)
            iw[Ai[p]] = p;
        for (ump_idx p = Ap[i]; p < k->dptr[i]; p++) {
            ump_idx c = Ai[p];                 /* c < i: eliminate with row c */
            lu[p] /= lu[k->dptr[c]];           /* l_ic = b_ic / u_cc */
            for (ump_idx q = k->dptr[c] + 1; q < Ap[c + 1]; q++) {
                ump_idx w = iw[Ai[q]];
                if (w >= 0)
                    lu[w] -= lu[p] * lu[q];    /* b_ij <- b_ij - l_ic u_cj, within pattern */
            }
        }
        for (ump_idx p = Ap[i]; p < Ap[i + 1]; p++)
            iw[Ai[p]] = -1;
        double d = lu[k->dptr[i]];
        UMP_CHECK(d != 0.0 && isfinite(d), err, UMP_ERR_SINGULAR,
                  "BiCGSTAB/ILU(0): zero or non-finite pivot in row %d", (int)i);
    }
    return UMP_OK;
}

/* z <- M^-1 r (z and r may alias for PC_NONE only through the copy). */
static void apply_pc(const lsolve_krylov *k, const lsolve_mat *A, lsolve_pc pc, const double *restrict r,
                     double *restrict z)
{
    const ump_idx n = A->n, *Ap = A->Ap, *Ai = A->Ai;
    switch (pc) {
    case LSOLVE_PC_NONE:
        memcpy(z, r, sizeof *z * (size_t)n);
        return;
    case LSOLVE_PC_JACOBI:
        for (ump_idx i = 0; i < n; i++)
            z[i] = k->dinv[i] * r[i];
        return;
    case LSOLVE_PC_ILU0: {
        const double *lu = k->lu;
        memcpy(z, r, sizeof *z * (size_t)n);
        /* U^T y = r: column i of U^T is row i of U (entries right of the diagonal) */
        for (ump_idx i = 0; i < n; i++) {
            z[i] /= lu[k->dptr[i]];
            for (ump_idx q = k->dptr[i] + 1; q < Ap[i + 1]; q++)
                z[Ai[q]] -= lu[q] * z[i];
        }
        /* L^T z = y: column i of L^T is row i of L (entries left of the diagonal) */
        for (ump_idx i = n - 1; i >= 0; i--)
            for (ump_idx q = Ap[i]; q < k->dptr[i]; q++)
                z[Ai[q]] -= lu[q] * z[i];
        return;
    }
    }
}

static ump_status bicgstab(lsolve_krylov *k, const lsolve_mat *A, lsolve_pc pc, int setup,
                           const double *b, double *x, double tol, int maxit, lsolve_stats *st,
                           ump_err *err);

ump_status lsolve_bicgstab(lsolve_krylov *k, const lsolve_mat *A, lsolve_pc pc, const double *b,
                           double *x, double tol, int maxit, lsolve_stats *st, ump_err *err)
{
    k->add = NULL;
    return bicgstab(k, A, pc, 1, b, x, tol, maxit, st, err);
}

ump_status lsolve_bicgstab_pc(lsolve_krylov *k, const lsolve_mat *A, lsolve_pc pc, lsolve_pc_fn add, void *ctx,
                              const double *b, double *x, double tol, int maxit, lsolve_stats *st, ump_err *err)
{
    k->add = add;
    k->add_ctx = ctx;
    ump_status rc = bicgstab(k, A, pc, 1, b, x, tol, maxit, st, err);
    k->add = NULL;
    return rc;
}

ump_status lsolve_bicgstab_again(lsolve_krylov *k, const lsolve_mat *A, lsolve_pc pc, const double *b,
                                 double *x, double tol, int maxit, lsolve_stats *st, ump_err *err)
{
    UMP_CHECK(k->pc_n == A->n && k->pc_kind == (int)pc, err, UMP_ERR_INPUT,
              "BiCGSTAB: no preconditioner of this kind was built for a matrix of order %d", (int)A->n);
    k->add = NULL;
    return bicgstab(k, A, pc, 0, b, x, tol, maxit, st, err);
}

static ump_status bicgstab(lsolve_krylov *k, const lsolve_mat *A, lsolve_pc pc, int setup,
                           const double *b, double *x, double tol, int maxit, lsolve_stats *st,
                           ump_err *err)
{
    /* the workspace may be larger than A: the particle count varies per step */
    const ump_idx n = A->n;
    memset(st, 0, sizeof *st);
    UMP_CHECK(A->n <= k->n, err, UMP_ERR_INPUT, "BiCGSTAB: matrix of order %d, workspace for %d",
              (int)A->n, (int)k->n);
    UMP_CHECK(tol > 0 && maxit >= 0, err, UMP_ERR_INPUT, "BiCGSTAB: tolerance %g, %d iterations",
              tol, maxit);
    if (setup) {
        k->pc_n = -1;
        if (pc == LSOLVE_PC_JACOBI)
            UMP_CALL(setup_jacobi(k, A, err));
        else if (pc == LSOLVE_PC_ILU0)
            UMP_CALL(setup_ilu0(k, A, err));
        k->pc_n = A->n; /* remembered for lsolve_bicgstab_again */
        k->pc_kind = (int)pc;
    }

    double *r = k->r, *rh = k->rh, *p = k->p, *v = k->v, *ph = k->ph, *s = k->s, *sh = k->sh,
           *t = k->t;
    double bnorm = sqrt(dot(n, b, b));
    UMP_CHECK(isfinite(bnorm), err, UMP_ERR_INPUT, "BiCGSTAB: right-hand side has NaN or inf");
    if (bnorm == 0.0) {
        memset(x, 0, sizeof *x * (size_t)n); /* the exact solution */
        st->converged = 1;
        return UMP_OK;
    }
    lsolve_mat_mult(A, x, r);
    for (ump_idx i = 0; i < n; i++)
        r[i] = b[i] - r[i];                 /* r <- b - A x */
    double res = sqrt(dot(n, r, r)) / bnorm;
    st->res0 = res;
    int it = 0, restarts = 0;
    int reason = res <= tol ? 1 : 0;

    while (reason == 0 && it < maxit) {
        /* (re)start: shadow residual rh = r */
        memcpy(rh, r, sizeof *rh * (size_t)n);
        double rho_old = 1.0, alpha = 1.0, omega = 1.0;
        int broke = 0, first = 1;
        while (it < maxit) {
            double rho = dot(n, rh, r);     /* rho <- (rh, r) */
            if (rho == 0.0 || !isfinite(rho)) {
                broke = 1;
                break;
            }
            if (first) {
                memcpy(p, r, sizeof *p * (size_t)n);
                first = 0;
            } else {
                double beta = (rho / rho_old) * (alpha / omega);
                for (ump_idx i = 0; i < n; i++)
                    p[i] = r[i] + beta * (p[i] - omega * v[i]); /* p <- r + b (p - w v) */
            }
            apply_pc(k, A, pc, p, ph);      /* ph <- M^-1 p */
            if (k->add)
                k->add(k->add_ctx, p, ph);
            lsolve_mat_mult(A, ph, v);      /* v <- A ph */
            double sigma = dot(n, rh, v);
            if (sigma == 0.0 || !isfinite(sigma)) {
                broke = 1;
                break;
            }
            alpha = rho / sigma;            /* alpha <- rho / (rh, v) */
            for (ump_idx i = 0; i < n; i++)
                s[i] = r[i] - alpha * v[i]; /* s <- r - a v */
            it++;
            double snorm = sqrt(dot(n, s, s)) / bnorm;
            if (snorm <= tol) {
                for (ump_idx i = 0; i < n; i++)
                    x[i] += alpha * ph[i];  /* x <- x + a ph */
                memcpy(r, s, sizeof *r * (size_t)n);
                res = snorm;
                break;
            }
            apply_pc(k, A, pc, s, sh);      /* sh <- M^-1 s */
            if (k->add)
                k->add(k->add_ctx, s, sh);
            lsolve_mat_mult(A, sh, t);      /* t <- A sh */
            double tt = dot(n, t, t);
            omega = tt > 0.0 ? dot(n, t, s) / tt : 0.0; /* w <- (t, s) / (t, t) */
            for (ump_idx i = 0; i < n; i++) {
                x[i] += alpha * ph[i] + omega * sh[i]; /* x <- x + a ph + w sh */
                r[i] = s[i] - omega * t[i];            /* r <- s - w t */
            }
            res = sqrt(dot(n, r, r)) / bnorm;
            if (!isfinite(res)) {
                broke = 1;
                break;
            }
            if (res <= tol)
                break;
            if (omega == 0.0) {
                broke = 1;
                break;
            }
            rho_old = rho;
        }
        /* true residual: the recursive one may drift */
        lsolve_mat_mult(A, x, r);
        for (ump_idx i = 0; i < n; i++)
            r[i] = b[i] - r[i];
        res = sqrt(dot(n, r, r)) / bnorm;
        if (res <= tol)
            reason = 1;
        else if (!isfinite(res) || (broke && restarts >= KRYLOV_MAX_RESTARTS))
            reason = -1;
        else if (restarts++ >= KRYLOV_MAX_RESTARTS)
            reason = broke ? -1 : 0;
    }
    st->iterations = it;
    st->res = res;
    st->converged = reason;
    return UMP_OK;
}
