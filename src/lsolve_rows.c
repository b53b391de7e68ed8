/* SPDX-License-Identifier: GPL-3.0-or-later
 * lsolve_rows.c -- BiCGSTAB (van der Vorst, SIAM J. Sci. Stat. Comput. 13,
 * 1992) on row-compressed matrices, several right-hand sides in lockstep,
 * OpenMP-parallel and deterministic.
 *
 * Workload: the implicit particle predictor (Eq. 14) builds a new matrix
 * every step, row by row, one row per particle; u and v (and T when its
 * diffusivity equals nu) are solved with the same matrix. In lockstep,
 * every sweep over the matrix (product, preconditioner) serves all systems
 * at once, while each system keeps its own scalars, so the iterates are
 * exactly those of separate solves.
 *
 * Threads: row loops are split statically over threads; every reduction
 * (dot products, norms) sums fixed blocks of LSOLVE_DOT_BLOCK rows, each
 * block in row order, then the block sums in block order -- the same
 * additions in the same order whatever the number of threads, so 1 and N
 * threads give bit-identical results.
 *
 * Preconditioner: ILU(0) of A restricted to diagonal blocks of
 * LSOLVE_ILU_BLOCK consecutive rows (block Jacobi with ILU(0) blocks). The
 * block size is a constant, not the thread count, so the preconditioner --
 * and every iterate -- is the same for any number of threads, and the
 * blocks factor and sweep in parallel. Particles are kept sorted by cell,
 * so a block is a compact strip of the mesh and the couplings it drops are
 * few: on the predictor matrices (I + dt nu L, strongly diagonally
 * dominant) the iteration counts are those of global ILU(0). Jacobi and no
 * preconditioner are also available. Right preconditioning: the residual
 * tracked is the true one, recomputed at the end of every solve.
 *
 * Memory: 8 vectors per right-hand side, the ILU values, the diagonal
 * pointers; grown (x1.5) only when a system is larger than any before.
 */
#include "umppm/lsolve.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define KRYLOV_MAX_RESTARTS 5

struct lsolve_rows {
    size_t ncap;       /* rows the vectors hold */
    size_t zcap;       /* entries lu holds */
    double *vec[LSOLVE_MAX_RHS][8];
    double *dinv, *lu;
    ump_idx *dptr, *iw;
    double *part;      /* block partial sums [LSOLVE_MAX_RHS][nblocks] */
    double *pair;      /* [2 ncap]: two right-hand sides interleaved for spmv */
    lsolve_pc pc;
    ump_idx pc_n;      /* order the preconditioner was built for (-1: none) */
};

enum { V_R, V_RH, V_P, V_V, V_PH, V_S, V_SH, V_T };

void lsolve_rows_free(lsolve_rows **pk)
{
    if (!pk || !*pk)
        return;
    lsolve_rows *k = *pk;
    for (int r = 0; r < LSOLVE_MAX_RHS; r++)
        for (int q = 0; q < 8; q++)
            free(k->vec[r][q]);
    free(k->dinv);
    free(k->lu);
    free(k->dptr);
    free(k->iw);
    free(k->part);
    free(k->pair);
    free(k);
    *pk = NULL;
}

ump_status lsolve_rows_create(lsolve_rows **out, ump_err *err)
{
    *out = ump_alloc_array(1, sizeof **out);
    UMP_CHECK(*out, err, UMP_ERR_NOMEM, "BiCGSTAB: out of memory");
    (*out)->pc_n = -1;
    return UMP_OK;
}

static size_t nblocks(ump_idx n, size_t b) { return ((size_t)n + b - 1) / b; }

/* Vectors for n rows (all LSOLVE_MAX_RHS systems, allocated on first use of
 * each: most runs solve two). */
static ump_status reserve_rows(lsolve_rows *k, ump_idx n, int nrhs, ump_err *err)
{
    size_t need = n > 16 ? (size_t)n : 16;
    int grow = need > k->ncap;
    size_t nc = grow ? need + need / 2 + 16 : k->ncap;
    for (int r = 0; r < LSOLVE_MAX_RHS; r++)
        for (int q = 0; q < 8; q++) {
            if (k->vec[r][q] && !grow)
                continue;
            if (!k->vec[r][q] && r >= nrhs)
                continue;
            double *v = ump_realloc_array(k->vec[r][q], nc, sizeof *v);
            UMP_CHECK(v, err, UMP_ERR_NOMEM, "BiCGSTAB: out of memory for %zu unknowns", nc);
            k->vec[r][q] = v;
        }
    if (grow || !k->dinv) {
        double *z = ump_realloc_array(k->pair, 2 * nc, sizeof *z);
        UMP_CHECK(z, err, UMP_ERR_NOMEM, "BiCGSTAB: out of memory for %zu unknowns", nc);
        k->pair = z;
        double *d = ump_realloc_array(k->dinv, nc, sizeof *d);
        UMP_CHECK(d, err, UMP_ERR_NOMEM, "BiCGSTAB: out of memory for %zu unknowns", nc);
        k->dinv = d;
        ump_idx *p = ump_realloc_array(k->dptr, nc, sizeof *p);
        UMP_CHECK(p, err, UMP_ERR_NOMEM, "BiCGSTAB: out of memory for %zu unknowns", nc);
        k->dptr = p;
        ump_idx *w = ump_realloc_array(k->iw, nc, sizeof *w);
        UMP_CHECK(w, err, UMP_ERR_NOMEM, "BiCGSTAB: out of memory for %zu unknowns", nc);
        k->iw = w;
        for (size_t i = k->ncap; i < nc; i++)
            k->iw[i] = -1; /* rows set their marks and clear them again */
        double *pt = ump_realloc_array(k->part, 2 * LSOLVE_MAX_RHS * nblocks((ump_idx)nc, LSOLVE_DOT_BLOCK) + 2,
                                       sizeof *pt);
        UMP_CHECK(pt, err, UMP_ERR_NOMEM, "BiCGSTAB: out of memory for %zu unknowns", nc);
        k->part = pt;
        k->ncap = nc;
    }
    return UMP_OK;
}

/* ---- deterministic kernels ---------------------------------------------- */

/* d[r] = (a[r], b[r]) for r < m, by fixed blocks (see the top). */
static void dots(lsolve_rows *k, ump_idx n, int m, double *const *a, double *const *b, double *d)
{
    ump_idx nb = (ump_idx)nblocks(n, LSOLVE_DOT_BLOCK);
    double *part = k->part;
#pragma omp parallel for schedule(static)
    for (ump_idx q = 0; q < nb; q++) {
        ump_idx i0 = q * LSOLVE_DOT_BLOCK, i1 = i0 + LSOLVE_DOT_BLOCK < n ? i0 + LSOLVE_DOT_BLOCK : n;
        for (int r = 0; r < m; r++) {
            const double *x = a[r], *y = b[r];
            double s = 0;
            for (ump_idx i = i0; i < i1; i++)
                s += x[i] * y[i];
            part[(size_t)r * nb + q] = s;
        }
    }
    for (int r = 0; r < m; r++) {
        double s = 0;
        for (ump_idx q = 0; q < nb; q++)
            s += part[(size_t)r * nb + q];
        d[r] = s;
    }
}

/* Fused passes (one sweep instead of two; the same arithmetic and block
 * order as the separate loops, so the same bits): */

/* s = r - al v, returns (s, s). */
static double sub_norm(lsolve_rows *k, ump_idx n, const double *restrict r, double al,
                       const double *restrict v, double *restrict s)
{
    ump_idx nb = (ump_idx)nblocks(n, LSOLVE_DOT_BLOCK);
    double *part = k->part, sum = 0;
#pragma omp parallel for schedule(static)
    for (ump_idx q = 0; q < nb; q++) {
        ump_idx i0 = q * LSOLVE_DOT_BLOCK, i1 = i0 + LSOLVE_DOT_BLOCK < n ? i0 + LSOLVE_DOT_BLOCK : n;
        double acc = 0;
        for (ump_idx i = i0; i < i1; i++) {
            s[i] = r[i] - al * v[i];
            acc += s[i] * s[i];
        }
        part[q] = acc;
    }
    for (ump_idx q = 0; q < nb; q++)
        sum += part[q];
    return sum;
}

/* x += al ph + om sh, r = s - om t, returns (r, r). */
static double update_norm(lsolve_rows *k, ump_idx n, double al, double om, double *restrict x,
                          const double *restrict ph, const double *restrict sh, const double *restrict s,
                          const double *restrict t, double *restrict r)
{
    ump_idx nb = (ump_idx)nblocks(n, LSOLVE_DOT_BLOCK);
    double *part = k->part, sum = 0;
#pragma omp parallel for schedule(static)
    for (ump_idx q = 0; q < nb; q++) {
        ump_idx i0 = q * LSOLVE_DOT_BLOCK, i1 = i0 + LSOLVE_DOT_BLOCK < n ? i0 + LSOLVE_DOT_BLOCK : n;
        double acc = 0;
        for (ump_idx i = i0; i < i1; i++) {
            x[i] += al * ph[i] + om * sh[i];
            r[i] = s[i] - om * t[i];
            acc += r[i] * r[i];
        }
        part[q] = acc;
    }
    for (ump_idx q = 0; q < nb; q++)
        sum += part[q];
    return sum;
}

/* (t, t) and (t, s) in one pass. */
static void dots_ts(lsolve_rows *k, ump_idx n, const double *restrict t, const double *restrict s,
                    double *tt, double *ts)
{
    ump_idx nb = (ump_idx)nblocks(n, LSOLVE_DOT_BLOCK);
    double *part = k->part;
#pragma omp parallel for schedule(static)
    for (ump_idx q = 0; q < nb; q++) {
        ump_idx i0 = q * LSOLVE_DOT_BLOCK, i1 = i0 + LSOLVE_DOT_BLOCK < n ? i0 + LSOLVE_DOT_BLOCK : n;
        double a = 0, b = 0;
        for (ump_idx i = i0; i < i1; i++) {
            a += t[i] * t[i];
            b += t[i] * s[i];
        }
        part[2 * q] = a;
        part[2 * q + 1] = b;
    }
    double a = 0, b = 0;
    for (ump_idx q = 0; q < nb; q++) {
        a += part[2 * q];
        b += part[2 * q + 1];
    }
    *tt = a;
    *ts = b;
}

/* y[r] = A x[r], r < m, one sweep over A for all systems. Each row's products are summed in four partial
 * sums (entry p goes to sum p mod 4, combined as (s0 + s1) + (s2 + s3)):
 * four independent addition chains instead of one, which bound the loop
 * by the adder's latency (a row has ~25 entries on quads, ~56 on
 * triangles). The order is the same for every m, so systems solved in
 * lockstep keep exactly the iterates of separate solves, and it depends
 * on the row only, so any thread count gives the same bits. */
static inline __attribute__((always_inline)) void row_sum4(const lsolve_csr *A, ump_idx i, int nr,
                                                          const double *const *x, double s[][4])
{
    const ump_idx *restrict ci = A->ci;
    const double *restrict v = A->v;
    ump_idx p = A->rp[i], e = A->rp[i + 1];
    for (; p + 4 <= e; p += 4) {
        ump_idx c0 = ci[p], c1 = ci[p + 1], c2 = ci[p + 2], c3 = ci[p + 3];
        for (int r = 0; r < nr; r++) {
            s[r][0] += v[p] * x[r][c0];
            s[r][1] += v[p + 1] * x[r][c1];
            s[r][2] += v[p + 2] * x[r][c2];
            s[r][3] += v[p + 3] * x[r][c3];
        }
    }
    for (int q = 0; p < e; p++, q++)
        for (int r = 0; r < nr; r++)
            s[r][q] += v[p] * x[r][ci[p]];
}

/* Two systems: x[0] and x[1] interleaved in z, so one 16-byte load fetches
 * both values of a column and one vector multiply-add serves both sums
 * (half the loads and arithmetic instructions of two scalar sums). Lane r
 * of sum q is exactly s[r][q] of row_sum4: the same bits. */
typedef double lsolve_v2d __attribute__((vector_size(16)));

static void spmv2(const lsolve_csr *A, double *restrict zbuf, double *const *x, double *const *y)
{
    const ump_idx n = A->n;
    lsolve_v2d *restrict z = (lsolve_v2d *)zbuf;
    const double *restrict x0 = x[0], *restrict x1 = x[1];
    double *restrict y0 = y[0], *restrict y1 = y[1];
    const ump_idx *restrict rp = A->rp, *restrict ci = A->ci;
    const double *restrict v = A->v;
#pragma omp parallel
    {
#pragma omp for schedule(static)
        for (ump_idx i = 0; i < n; i++)
            z[i] = (lsolve_v2d){x0[i], x1[i]};
#pragma omp for schedule(static)
        for (ump_idx i = 0; i < n; i++) {
            lsolve_v2d s0 = {0, 0}, s1 = {0, 0}, s2 = {0, 0}, s3 = {0, 0};
            ump_idx p = rp[i], e = rp[i + 1];
            for (; p + 4 <= e; p += 4) {
                s0 += v[p] * z[ci[p]];
                s1 += v[p + 1] * z[ci[p + 1]];
                s2 += v[p + 2] * z[ci[p + 2]];
                s3 += v[p + 3] * z[ci[p + 3]];
            }
            if (p < e)
                s0 += v[p] * z[ci[p]];
            if (p + 1 < e)
                s1 += v[p + 1] * z[ci[p + 1]];
            if (p + 2 < e)
                s2 += v[p + 2] * z[ci[p + 2]];
            lsolve_v2d t = (s0 + s1) + (s2 + s3);
            y0[i] = t[0];
            y1[i] = t[1];
        }
    }
}

static void spmv(const lsolve_rows *k, const lsolve_csr *A, int m, double *const *x, double *const *y)
{
    const ump_idx n = A->n;
    if (m == 1) {
        const double *xr[1] = {x[0]};
#pragma omp parallel for schedule(static)
        for (ump_idx i = 0; i < n; i++) {
            double s[1][4] = {{0, 0, 0, 0}};
            row_sum4(A, i, 1, xr, s);
            y[0][i] = (s[0][0] + s[0][1]) + (s[0][2] + s[0][3]);
        }
        return;
    }
    if (m == 2) {
        spmv2(A, k->pair, x, y);
        return;
    }
#pragma omp parallel for schedule(static)
    for (ump_idx i = 0; i < n; i++) {
        double s[LSOLVE_MAX_RHS][4] = {{0}};
        row_sum4(A, i, m, (const double *const *)x, s);
        for (int r = 0; r < m; r++)
            y[r][i] = (s[r][0] + s[r][1]) + (s[r][2] + s[r][3]);
    }
}

/* z[r] = M^-1 q[r] for r < m. */
static void apply_pc(const lsolve_rows *k, const lsolve_csr *A, int m, double *const *q, double *const *z)
{
    const ump_idx n = A->n, *rp = A->rp, *ci = A->ci, *dp = k->dptr;
    switch (k->pc) {
    case LSOLVE_PC_NONE:
        for (int r = 0; r < m; r++)
            memcpy(z[r], q[r], sizeof(double) * (size_t)n);
        return;
    case LSOLVE_PC_JACOBI:
#pragma omp parallel for schedule(static)
        for (ump_idx i = 0; i < n; i++)
            for (int r = 0; r < m; r++)
                z[r][i] = k->dinv[i] * q[r][i];
        return;
    case LSOLVE_PC_ILU0: {
        const double *lu = k->lu;
        ump_idx nb = (ump_idx)nblocks(n, LSOLVE_ILU_BLOCK);
#pragma omp parallel for schedule(static)
        for (ump_idx b = 0; b < nb; b++) {
            ump_idx lo = b * LSOLVE_ILU_BLOCK, hi = lo + LSOLVE_ILU_BLOCK < n ? lo + LSOLVE_ILU_BLOCK : n;
            /* L y = q (unit lower), within the block */
            for (ump_idx i = lo; i < hi; i++) {
                double s[LSOLVE_MAX_RHS];
                for (int r = 0; r < m; r++)
                    s[r] = q[r][i];
                for (ump_idx p = rp[i]; p < dp[i]; p++) {
                    ump_idx c = ci[p];
                    if (c < lo)
                        continue;
                    for (int r = 0; r < m; r++)
                        s[r] -= lu[p] * z[r][c];
                }
                for (int r = 0; r < m; r++)
                    z[r][i] = s[r];
            }
            /* U z = y, within the block */
            for (ump_idx i = hi - 1; i >= lo; i--) {
                double s[LSOLVE_MAX_RHS];
                for (int r = 0; r < m; r++)
                    s[r] = z[r][i];
                for (ump_idx p = dp[i] + 1; p < rp[i + 1]; p++) {
                    ump_idx c = ci[p];
                    if (c >= hi)
                        break;
                    for (int r = 0; r < m; r++)
                        s[r] -= lu[p] * z[r][c];
                }
                double d = 1 / lu[dp[i]];
                for (int r = 0; r < m; r++)
                    z[r][i] = s[r] * d;
            }
        }
        return;
    }
    }
}

/* ---- preconditioner ------------------------------------------------------ */

ump_status lsolve_rows_setup(lsolve_rows *k, const lsolve_csr *A, lsolve_pc pc, ump_err *err)
{
    const ump_idx n = A->n, *rp = A->rp, *ci = A->ci;
    k->pc_n = -1;
    UMP_CALL(reserve_rows(k, n, 1, err));
    /* diagonal positions (columns sorted in each row) */
    ump_idx bad = -1;
#pragma omp parallel for schedule(static)
    for (ump_idx i = 0; i < n; i++) {
        ump_idx d = -1;
        for (ump_idx p = rp[i]; p < rp[i + 1]; p++) {
            if (p > rp[i] && ci[p] <= ci[p - 1]) {
                d = -1; /* unsorted or duplicated columns */
                break;
            }
            if (ci[p] == i)
                d = p;
        }
        k->dptr[i] = d;
        if (d < 0) {
#pragma omp critical(lsolve_rows_bad)
            if (bad < 0 || i < bad)
                bad = i;
        }
    }
    UMP_CHECK(bad < 0, err, UMP_ERR_INPUT,
              "BiCGSTAB: row %ld has no diagonal entry or unsorted/duplicate columns", (long)bad);
    if (pc == LSOLVE_PC_JACOBI) {
        for (ump_idx i = 0; i < n; i++) {
            double d = A->v[k->dptr[i]];
            UMP_CHECK(d != 0.0 && isfinite(d), err, UMP_ERR_SINGULAR,
                      "BiCGSTAB/Jacobi: zero or non-finite diagonal in row %ld", (long)i);
            k->dinv[i] = 1 / d;
        }
    } else if (pc == LSOLVE_PC_ILU0) {
        size_t nnz = (size_t)rp[n];
        if (nnz > k->zcap || !k->lu) {
            size_t nc = nnz + nnz / 2 + 16;
            double *lu = ump_realloc_array(k->lu, nc, sizeof *lu);
            UMP_CHECK(lu, err, UMP_ERR_NOMEM, "BiCGSTAB/ILU(0): out of memory for %zu entries", nc);
            k->lu = lu;
            k->zcap = nc;
        }
        double *lu = k->lu;
        const ump_idx *dp = k->dptr;
        ump_idx *iw = k->iw;
        memcpy(lu, A->v, sizeof *lu * nnz);
        ump_idx nb = (ump_idx)nblocks(n, LSOLVE_ILU_BLOCK);
        bad = -1;
        /* IKJ ILU(0) of each diagonal block; a block marks only its own
         * columns in iw, so blocks run in parallel on one marker array. */
#pragma omp parallel for schedule(static)
        for (ump_idx b = 0; b < nb; b++) {
            ump_idx lo = b * LSOLVE_ILU_BLOCK, hi = lo + LSOLVE_ILU_BLOCK < n ? lo + LSOLVE_ILU_BLOCK : n;
            for (ump_idx i = lo; i < hi; i++) {
                for (ump_idx p = rp[i]; p < rp[i + 1]; p++)
                    if (ci[p] >= lo && ci[p] < hi)
                        iw[ci[p]] = p;
                for (ump_idx p = rp[i]; p < dp[i]; p++) {
                    ump_idx c = ci[p];
                    if (c < lo)
                        continue;
                    lu[p] /= lu[dp[c]]; /* l_ic = a_ic / u_cc */
                    for (ump_idx q = dp[c] + 1; q < rp[c + 1]; q++) {
                        ump_idx j = ci[q];
                        if (j >= hi)
                            break;
                        ump_idx w = iw[j];
                        if (w >= 0)
                            lu[w] -= lu[p] * lu[q]; /* a_ij -= l_ic u_cj, within the pattern */
                    }
                }
                for (ump_idx p = rp[i]; p < rp[i + 1]; p++)
                    if (ci[p] >= lo && ci[p] < hi)
                        iw[ci[p]] = -1;
                double d = lu[dp[i]];
                if (!(d != 0.0 && isfinite(d))) {
#pragma omp critical(lsolve_rows_bad)
                    if (bad < 0 || i < bad)
                        bad = i;
                    break;
                }
            }
        }
        UMP_CHECK(bad < 0, err, UMP_ERR_SINGULAR, "BiCGSTAB/ILU(0): zero or non-finite pivot in row %ld",
                  (long)bad);
    }
    k->pc = pc;
    k->pc_n = n;
    return UMP_OK;
}

/* ---- BiCGSTAB in lockstep ------------------------------------------------ */

typedef struct sysstate {
    double bnorm, rho, rho_old, alpha, omega, res, snorm2;
    int first, restarts, it, done; /* done: 1 converged, 0 running/maxit, -1 breakdown */
    int active;
} sysstate;

/* true residual r = b - A x of system r, its relative norm */
static double true_residual(lsolve_rows *k, const lsolve_csr *A, const double *b, double *x, double *r)
{
    double *xs[1] = {x}, *rs[1] = {r}, d;
    spmv(k, A, 1, xs, rs);
    ump_idx n = A->n;
#pragma omp parallel for schedule(static)
    for (ump_idx i = 0; i < n; i++)
        r[i] = b[i] - r[i];
    dots(k, n, 1, rs, rs, &d);
    return sqrt(d);
}

/* A system that claims convergence or broke down: check the true residual,
 * then finish it or restart it from its current x. */
static void settle(lsolve_rows *k, const lsolve_csr *A, sysstate *s, const double *b, double *x, double *r,
                   double *rh, double tol, int maxit, int broke)
{
    s->res = true_residual(k, A, b, x, r) / s->bnorm;
    if (s->res <= tol) {
        s->done = 1;
        s->active = 0;
        return;
    }
    if (!isfinite(s->res) || (broke && s->restarts >= KRYLOV_MAX_RESTARTS)) {
        s->done = -1;
        s->active = 0;
        return;
    }
    if (s->restarts++ >= KRYLOV_MAX_RESTARTS || s->it >= maxit) {
        s->done = broke ? -1 : 0;
        s->active = 0;
        return;
    }
    memcpy(rh, r, sizeof *rh * (size_t)A->n); /* restart: shadow residual rh = r */
    s->rho_old = s->alpha = s->omega = 1;
    s->first = 1;
}

/* Keep the systems at positions live[0..ml-1] of the running list: the
 * system numbers a[] and every per-system pointer list move down together.
 * Returns the new count. */
static int keep_live(int *a, const int *live, int ml, double **const *lists, int nlists)
{
    for (int j = 0; j < ml; j++) { /* live[] ascends: in place is safe */
        a[j] = a[live[j]];
        for (int l = 0; l < nlists; l++)
            lists[l][j] = lists[l][live[j]];
    }
    return ml;
}

ump_status lsolve_rows_bicgstab(lsolve_rows *k, const lsolve_csr *A, int nrhs, const double *const *b,
                                double *const *x, double tol, int maxit, lsolve_stats *st, ump_err *err)
{
    const ump_idx n = A->n;
    UMP_CHECK(nrhs >= 1 && nrhs <= LSOLVE_MAX_RHS, err, UMP_ERR_INPUT, "BiCGSTAB: %d right-hand sides", nrhs);
    UMP_CHECK(tol > 0 && maxit >= 0, err, UMP_ERR_INPUT, "BiCGSTAB: tolerance %g, %d iterations", tol, maxit);
    UMP_CHECK(k->pc_n == n, err, UMP_ERR_INPUT,
              "BiCGSTAB: no preconditioner was built for a matrix of order %ld", (long)n);
    UMP_CALL(reserve_rows(k, n, nrhs, err));
    sysstate s[LSOLVE_MAX_RHS];
    double *R[LSOLVE_MAX_RHS], *RH[LSOLVE_MAX_RHS], *P[LSOLVE_MAX_RHS], *V[LSOLVE_MAX_RHS],
        *PH[LSOLVE_MAX_RHS], *S[LSOLVE_MAX_RHS], *SH[LSOLVE_MAX_RHS], *T[LSOLVE_MAX_RHS],
        *X[LSOLVE_MAX_RHS], *B[LSOLVE_MAX_RHS], d[LSOLVE_MAX_RHS];
    enum { NLISTS = 10 };
    double **const lists[NLISTS] = {R, RH, P, V, PH, S, SH, T, X, B};
    for (int r = 0; r < nrhs; r++) {
        memset(&st[r], 0, sizeof st[r]);
        memset(&s[r], 0, sizeof s[r]);
        B[r] = (double *)b[r];
        X[r] = x[r];
        R[r] = k->vec[r][V_R];
    }
    dots(k, n, nrhs, B, B, d);
    spmv(k, A, nrhs, X, R);
    for (int r = 0; r < nrhs; r++) {
        s[r].bnorm = sqrt(d[r]);
        UMP_CHECK(isfinite(s[r].bnorm), err, UMP_ERR_INPUT, "BiCGSTAB: right-hand side has NaN or inf");
        double *rr = R[r];
        const double *br = b[r];
#pragma omp parallel for schedule(static)
        for (ump_idx i = 0; i < n; i++)
            rr[i] = br[i] - rr[i];
    }
    dots(k, n, nrhs, R, R, d);
    for (int r = 0; r < nrhs; r++) {
        if (s[r].bnorm == 0) {
            memset(x[r], 0, sizeof(double) * (size_t)n); /* the exact solution */
            s[r].done = 1;
            s[r].res = st[r].res0 = 0;
            continue;
        }
        s[r].res = st[r].res0 = sqrt(d[r]) / s[r].bnorm;
        s[r].done = s[r].res <= tol ? 1 : 0;
        s[r].active = !s[r].done && maxit > 0;
        s[r].rho_old = s[r].alpha = s[r].omega = 1;
        s[r].first = 1;
        if (s[r].active)
            memcpy(k->vec[r][V_RH], R[r], sizeof(double) * (size_t)n);
    }
    /* the lockstep iteration: systems still running form the list a[] */
    for (;;) {
        int a[LSOLVE_MAX_RHS], m = 0;
        for (int r = 0; r < nrhs; r++)
            if (s[r].active)
                a[m++] = r;
        if (!m)
            break;
        for (int j = 0; j < m; j++) {
            int r = a[j];
            R[j] = k->vec[r][V_R];
            RH[j] = k->vec[r][V_RH];
            P[j] = k->vec[r][V_P];
            V[j] = k->vec[r][V_V];
            PH[j] = k->vec[r][V_PH];
            S[j] = k->vec[r][V_S];
            SH[j] = k->vec[r][V_SH];
            T[j] = k->vec[r][V_T];
            X[j] = x[r];
            B[j] = (double *)b[r];
        }
        dots(k, n, m, RH, R, d); /* rho = (rh, r) */
        int live[LSOLVE_MAX_RHS], ml = 0;
        for (int j = 0; j < m; j++) {
            sysstate *q = &s[a[j]];
            q->rho = d[j];
            if (q->rho == 0.0 || !isfinite(q->rho)) {
                settle(k, A, q, B[j], X[j], R[j], RH[j], tol, maxit, 1);
                continue;
            }
            live[ml++] = j;
        }
        m = keep_live(a, live, ml, lists, NLISTS);
        if (!m)
            continue;
        for (int j = 0; j < m; j++) {
            sysstate *q = &s[a[j]];
            double *pp = P[j], *rr = R[j], *vv = V[j];
            if (q->first) {
                memcpy(pp, rr, sizeof(double) * (size_t)n);
                q->first = 0;
            } else {
                double beta = (q->rho / q->rho_old) * (q->alpha / q->omega), om = q->omega;
#pragma omp parallel for schedule(static)
                for (ump_idx i = 0; i < n; i++)
                    pp[i] = rr[i] + beta * (pp[i] - om * vv[i]); /* p <- r + b (p - w v) */
            }
        }
        apply_pc(k, A, m, P, PH); /* ph <- M^-1 p */
        spmv(k, A, m, PH, V);        /* v <- A ph */
        dots(k, n, m, RH, V, d);  /* sigma = (rh, v) */
        ml = 0;
        for (int j = 0; j < m; j++) {
            sysstate *q = &s[a[j]];
            if (d[j] == 0.0 || !isfinite(d[j])) {
                settle(k, A, q, B[j], X[j], R[j], RH[j], tol, maxit, 1);
                continue;
            }
            q->alpha = q->rho / d[j];
            q->snorm2 = sub_norm(k, n, R[j], q->alpha, V[j], S[j]); /* s <- r - a v, (s, s) */
            q->it++;
            live[ml++] = j;
        }
        m = keep_live(a, live, ml, lists, NLISTS);
        if (!m)
            continue;
        ml = 0;
        for (int j = 0; j < m; j++) {
            sysstate *q = &s[a[j]];
            if (sqrt(q->snorm2) / q->bnorm <= tol) { /* converged on the half step */
                double al = q->alpha, *xx = X[j], *ph = PH[j];
#pragma omp parallel for schedule(static)
                for (ump_idx i = 0; i < n; i++)
                    xx[i] += al * ph[i]; /* x <- x + a ph */
                settle(k, A, q, B[j], X[j], R[j], RH[j], tol, maxit, 0);
                continue;
            }
            live[ml++] = j;
        }
        m = keep_live(a, live, ml, lists, NLISTS);
        if (!m)
            continue;
        apply_pc(k, A, m, S, SH); /* sh <- M^-1 s */
        spmv(k, A, m, SH, T);        /* t <- A sh */
        for (int j = 0; j < m; j++) {
            sysstate *q = &s[a[j]];
            double tt, ts;
            dots_ts(k, n, T[j], S[j], &tt, &ts);
            q->omega = tt > 0.0 ? ts / tt : 0.0; /* w <- (t, s) / (t, t) */
            /* x <- x + a ph + w sh, r <- s - w t, and (r, r) */
            d[j] = update_norm(k, n, q->alpha, q->omega, X[j], PH[j], SH[j], S[j], T[j], R[j]);
        }
        for (int j = 0; j < m; j++) {
            sysstate *q = &s[a[j]];
            q->res = sqrt(d[j]) / q->bnorm;
            if (!isfinite(q->res) || q->omega == 0.0)
                settle(k, A, q, B[j], X[j], R[j], RH[j], tol, maxit, 1);
            else if (q->res <= tol || q->it >= maxit)
                settle(k, A, q, B[j], X[j], R[j], RH[j], tol, maxit, 0);
            else
                q->rho_old = q->rho;
        }
    }
    for (int r = 0; r < nrhs; r++) {
        st[r].iterations = s[r].it;
        st[r].res = s[r].res;
        st[r].converged = s[r].done;
    }
    return UMP_OK;
}

/* ---- conjugate gradients ------------------------------------------------- */

ump_status lsolve_rows_cg(lsolve_rows *k, const lsolve_csr *A, const double *b, double *x, double tol, int maxit,
                          lsolve_stats *st, ump_err *err)
{
    return lsolve_rows_cg_pc(k, A, b, x, tol, maxit, NULL, NULL, st, err);
}

/* z = M^-1 r: the caller's preconditioner, or the one of lsolve_rows_setup */
static void cg_pc(lsolve_rows *k, const lsolve_csr *A, lsolve_pc_fn fn, void *ctx, double *r, double *z)
{
    if (fn) {
        fn(ctx, r, z);
        return;
    }
    double *R[1] = {r}, *Z[1] = {z};
    apply_pc(k, A, 1, R, Z);
}

ump_status lsolve_rows_cg_pc(lsolve_rows *k, const lsolve_csr *A, const double *b, double *x, double tol, int maxit,
                             lsolve_pc_fn fn, void *ctx, lsolve_stats *st, ump_err *err)
{
    const ump_idx n = A->n;
    memset(st, 0, sizeof *st);
    UMP_CHECK(tol > 0 && maxit >= 0, err, UMP_ERR_INPUT, "CG: tolerance %g, %d iterations", tol, maxit);
    UMP_CHECK(k->pc_n == n, err, UMP_ERR_INPUT, "CG: no preconditioner was built for a matrix of order %ld",
              (long)n);
    /* CG needs a symmetric preconditioner: the block ILU(0) is not one */
    UMP_CHECK(fn || k->pc != LSOLVE_PC_ILU0, err, UMP_ERR_INPUT, "CG: the ILU0 preconditioner is not symmetric; "
              "use Jacobi or none");
    UMP_CALL(reserve_rows(k, n, 1, err));
    double *r = k->vec[0][V_R], *p = k->vec[0][V_P], *q = k->vec[0][V_V], *z = k->vec[0][V_PH];
    double *R[1] = {r}, *P[1] = {p}, *Q[1] = {q}, *Z[1] = {z}, *X[1] = {x}, *B[1] = {(double *)b};
    double bb, rz, pq, rr;
    dots(k, n, 1, B, B, &bb);
    double bnorm = sqrt(bb);
    UMP_CHECK(isfinite(bnorm), err, UMP_ERR_INPUT, "CG: right-hand side has NaN or inf");
    if (bnorm == 0) {
        memset(x, 0, sizeof(double) * (size_t)n); /* the exact solution */
        st->converged = 1;
        return UMP_OK;
    }
    spmv(k, A, 1, X, R);
#pragma omp parallel for schedule(static)
    for (ump_idx i = 0; i < n; i++)
        r[i] = b[i] - r[i];
    dots(k, n, 1, R, R, &rr);
    st->res0 = st->res = sqrt(rr) / bnorm;
    if (st->res <= tol) {
        st->converged = 1;
        return UMP_OK;
    }
    cg_pc(k, A, fn, ctx, r, z);
    memcpy(p, z, sizeof(double) * (size_t)n);
    dots(k, n, 1, R, Z, &rz);
    int it = 0;
    while (it < maxit) {
        spmv(k, A, 1, P, Q);     /* q <- A p */
        dots(k, n, 1, P, Q, &pq);
        if (!(pq > 0) || !isfinite(pq)) {
            st->converged = -1; /* not positive definite, or NaN */
            break;
        }
        double al = rz / pq;
        it++;
        /* x <- x + al p, r <- r - al q, and (r, r) */
        ump_idx nb = (ump_idx)nblocks(n, LSOLVE_DOT_BLOCK);
        double *part = k->part;
#pragma omp parallel for schedule(static)
        for (ump_idx c = 0; c < nb; c++) {
            ump_idx i0 = c * LSOLVE_DOT_BLOCK, i1 = i0 + LSOLVE_DOT_BLOCK < n ? i0 + LSOLVE_DOT_BLOCK : n;
            double acc = 0;
            for (ump_idx i = i0; i < i1; i++) {
                x[i] += al * p[i];
                r[i] -= al * q[i];
                acc += r[i] * r[i];
            }
            part[c] = acc;
        }
        rr = 0;
        for (ump_idx c = 0; c < nb; c++)
            rr += part[c];
        st->res = sqrt(rr) / bnorm;
        if (!isfinite(st->res)) {
            st->converged = -1;
            break;
        }
        if (st->res <= tol) {
            st->converged = 1;
            break;
        }
        cg_pc(k, A, fn, ctx, r, z);
        double rz_new;
        dots(k, n, 1, R, Z, &rz_new);
        double be = rz_new / rz;
        rz = rz_new;
#pragma omp parallel for schedule(static)
        for (ump_idx i = 0; i < n; i++)
            p[i] = z[i] + be * p[i];
    }
    st->iterations = it;
    if (st->converged == 1) {
        /* the recursive residual drifts: report the true one */
        spmv(k, A, 1, X, R);
#pragma omp parallel for schedule(static)
        for (ump_idx i = 0; i < n; i++)
            r[i] = b[i] - r[i];
        dots(k, n, 1, R, R, &rr);
        st->res = sqrt(rr) / bnorm;
    }
    return UMP_OK;
}
