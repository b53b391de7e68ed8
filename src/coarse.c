/* SPDX-License-Identifier: GPL-3.0-or-later
 * coarse.c -- the aggregation coarse level of the particle pressure
 * solves (see coarse.h).
 */
#include "umppm/coarse.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* The aggregates are the squares of a lattice of side H anchored at the
 * origin (bin (ix, iy) holds x in [ix H, (ix+1) H)), so an aggregate is the
 * same square from one step to the next. Ac's pattern is that of a set S
 * of bins: every bin the liquid has occupied, with a ring of one bin around
 * it, coupled to the bins of S within `reach` bins in x and y. Each build
 * fills the values (P^T A P on the occupied bins, an identity row on the
 * others) and refactorizes with that pattern: no allocation. Only when the
 * liquid reaches a bin outside S, or couples bins further apart than
 * `reach`, are S, the pattern and the symbolic analysis made anew (the
 * first build, and in a dam break a few times while the liquid spreads). */
struct coarse {
    size_t nu, ucap;     /* unknowns of the last build; capacity of agg, lx, ly */
    ump_idx *agg;        /* [ucap] coarse unknown of each fine unknown */
    long *lx, *ly;       /* [ucap] its bin on the lattice */
    long gx0, gy0, gnx, gny; /* the grid holding S: bins gx0 .. gx0 + gnx - 1, ... */
    int reach;           /* couplings within reach bins */
    unsigned char *inset; /* [gnx gny] bin in S */
    ump_idx *cidx;       /* [gnx gny] coarse unknown of a bin of S, else -1 */
    ump_idx nc;          /* coarse unknowns (the bins of S) */
    ump_idx *cbin;       /* [nc] grid index of each coarse unknown */
    ump_idx *slot;       /* [nc (2 reach + 1)^2] entry of Ac of (column, offset), or -1 */
    unsigned char *occ;  /* [nc] occupied in this build */
    double *rc, *zc;     /* [nc] restricted residual, coarse solution */
    lsolve_mat *Ac;
    lsolve *fac;
    size_t rebuilds;     /* pattern (and analysis) made anew */
    int ok;
};

#define GROW_TO(ptr, n)                                                                                 \
    do {                                                                                                \
        void *q_ = ump_realloc_array((ptr), (n), sizeof *(ptr));                                        \
        if (!q_)                                                                                        \
            return UMP_FAIL(err, UMP_ERR_NOMEM, "pressure coarse level: out of memory for %zu", (size_t)(n)); \
        (ptr) = q_;                                                                                     \
    } while (0)

ump_status coarse_create(coarse **out, ump_err *err)
{
    *out = ump_alloc_array(1, sizeof **out);
    UMP_CHECK(*out, err, UMP_ERR_NOMEM, "pressure coarse level: out of memory");
    return UMP_OK;
}

static void free_pattern(coarse *c)
{
    free(c->inset);
    free(c->cidx);
    free(c->cbin);
    free(c->slot);
    free(c->occ);
    free(c->rc);
    free(c->zc);
    c->inset = c->occ = NULL;
    c->cidx = c->cbin = c->slot = NULL;
    c->rc = c->zc = NULL;
    lsolve_mat_free(&c->Ac);
    lsolve_free(&c->fac);
    c->nc = 0;
    c->gnx = c->gny = 0;
}

void coarse_free(coarse **pc)
{
    if (!pc || !*pc)
        return;
    coarse *c = *pc;
    free(c->agg);
    free(c->lx);
    free(c->ly);
    free_pattern(c);
    free(c);
    *pc = NULL;
}

size_t coarse_rebuilds(const coarse *c)
{
    return c->rebuilds;
}

static ump_status pattern_arrays(coarse *c, size_t nb, int reach, ump_err *err);

/* S, the grid and Ac's pattern anew: the old S, the bins of the nu
 * unknowns (lx, ly) and a ring around them, couplings within reach. */
static ump_status new_pattern(coarse *c, size_t nu, int reach, ump_err *err)
{
    long x0 = LONG_MAX, y0 = LONG_MAX, x1 = LONG_MIN, y1 = LONG_MIN;
    for (size_t k = 0; k < nu; k++) {
        x0 = c->lx[k] < x0 ? c->lx[k] : x0, x1 = c->lx[k] > x1 ? c->lx[k] : x1;
        y0 = c->ly[k] < y0 ? c->ly[k] : y0, y1 = c->ly[k] > y1 ? c->ly[k] : y1;
    }
    if (c->gnx > 0) { /* keep the old S */
        x0 = c->gx0 < x0 ? c->gx0 : x0, x1 = c->gx0 + c->gnx - 1 > x1 ? c->gx0 + c->gnx - 1 : x1;
        y0 = c->gy0 < y0 ? c->gy0 : y0, y1 = c->gy0 + c->gny - 1 > y1 ? c->gy0 + c->gny - 1 : y1;
    }
    x0--, y0--, x1++, y1++; /* the ring */
    long nx = x1 - x0 + 1, ny = y1 - y0 + 1;
    size_t nb = (size_t)nx * (size_t)ny;
    unsigned char *in = ump_alloc_array(nb, 1);
    UMP_CHECK(in, err, UMP_ERR_NOMEM, "pressure coarse level: out of memory for %zu bins", nb);
    if (c->gnx > 0)
        for (long iy = 0; iy < c->gny; iy++)
            for (long ix = 0; ix < c->gnx; ix++)
                if (c->inset[iy * c->gnx + ix])
                    in[(iy + c->gy0 - y0) * nx + ix + c->gx0 - x0] = 1;
    for (size_t k = 0; k < nu; k++)
        for (long dy = -1; dy <= 1; dy++)
            for (long dx = -1; dx <= 1; dx++)
                in[(c->ly[k] + dy - y0) * nx + c->lx[k] + dx - x0] = 1;
    free_pattern(c);
    c->inset = in;
    c->gx0 = x0, c->gy0 = y0, c->gnx = nx, c->gny = ny;
    c->reach = reach;
    ump_status rc = pattern_arrays(c, nb, reach, err);
    if (rc != UMP_OK)
        free_pattern(c); /* gnx = 0: the next build starts again */
    return rc;
}

/* new_pattern's arrays and Ac's pattern for S = c->inset */
static ump_status pattern_arrays(coarse *c, size_t nb, int reach, ump_err *err)
{
    const unsigned char *in = c->inset;
    long nx = c->gnx, ny = c->gny;
    GROW_TO(c->cidx, nb);
    ump_idx nc = 0;
    for (size_t b = 0; b < nb; b++)
        c->cidx[b] = in[b] ? nc++ : -1;
    c->nc = nc;
    size_t w = (size_t)(2 * reach + 1);
    GROW_TO(c->cbin, (size_t)nc + 1);
    GROW_TO(c->slot, (size_t)nc * w * w + 1);
    GROW_TO(c->occ, (size_t)nc + 1);
    GROW_TO(c->rc, (size_t)nc + 1);
    GROW_TO(c->zc, (size_t)nc + 1);
    for (size_t b = 0; b < nb; b++)
        if (in[b])
            c->cbin[c->cidx[b]] = (ump_idx)b;
    /* columns in order; the rows of a column by dy, then dx: increasing */
    size_t nnz = 0;
    for (ump_idx j = 0; j < nc; j++) {
        long bx = c->cbin[j] % nx, by = c->cbin[j] / nx;
        for (long dy = -reach; dy <= reach; dy++)
            for (long dx = -reach; dx <= reach; dx++) {
                long ix = bx + dx, iy = by + dy;
                nnz += ix >= 0 && ix < nx && iy >= 0 && iy < ny && in[iy * nx + ix];
            }
    }
    lsolve_mat *A = ump_alloc_array(1, sizeof *A);
    if (A) {
        A->n = nc;
        A->Ap = ump_alloc_array((size_t)nc + 1, sizeof *A->Ap);
        A->Ai = ump_alloc_array(nnz + 1, sizeof *A->Ai);
        A->Ax = ump_alloc_array(nnz + 1, sizeof *A->Ax);
    }
    c->Ac = A;
    UMP_CHECK(A && A->Ap && A->Ai && A->Ax, err, UMP_ERR_NOMEM,
              "pressure coarse level: out of memory for %zu entries", nnz);
    ump_idx q = 0;
    for (ump_idx j = 0; j < nc; j++) {
        long bx = c->cbin[j] % nx, by = c->cbin[j] / nx;
        A->Ap[j] = q;
        for (long dy = -reach; dy <= reach; dy++)
            for (long dx = -reach; dx <= reach; dx++) {
                long ix = bx + dx, iy = by + dy;
                ump_idx *sl = &c->slot[(size_t)j * w * w + (size_t)(dy + reach) * w + (size_t)(dx + reach)];
                *sl = -1;
                if (ix >= 0 && ix < nx && iy >= 0 && iy < ny && in[iy * nx + ix]) {
                    A->Ai[q] = c->cidx[iy * nx + ix];
                    *sl = q++;
                }
            }
    }
    A->Ap[nc] = q;
    c->rebuilds++;
    return UMP_OK;
}

ump_status coarse_build(coarse *c, size_t nu, const double *px, const double *py, const size_t *map, double H,
                        const ump_idx *rp, const ump_idx *ci, const double *av, lsolve_kind kind, int *ok,
                        ump_err *err)
{
    *ok = c->ok = 0;
    c->nu = nu;
    if (nu < 64)
        return UMP_OK;
    if (nu > c->ucap) {
        size_t n = nu + nu / 2 + 16;
        GROW_TO(c->agg, n);
        GROW_TO(c->lx, n);
        GROW_TO(c->ly, n);
        c->ucap = n;
    }
    long x0 = LONG_MAX, y0 = LONG_MAX, x1 = LONG_MIN, y1 = LONG_MIN;
    for (size_t k = 0; k < nu; k++) {
        size_t i = map[k];
        c->lx[k] = (long)floor(px[i] / H);
        c->ly[k] = (long)floor(py[i] / H);
        x0 = c->lx[k] < x0 ? c->lx[k] : x0, x1 = c->lx[k] > x1 ? c->lx[k] : x1;
        y0 = c->ly[k] < y0 ? c->ly[k] : y0, y1 = c->ly[k] > y1 ? c->ly[k] : y1;
    }
    if ((double)(x1 - x0 + 1) * (double)(y1 - y0 + 1) > 4.0 * (double)nu + 1024)
        return UMP_OK; /* scattered liquid: not worth it */
    /* does the pattern hold this build? */
    int reach = 1, fits = c->gnx > 0;
    for (size_t k = 0; k < nu; k++)
        for (ump_idx q = rp[k]; q < rp[k + 1]; q++) {
            long dx = labs(c->lx[k] - c->lx[ci[q]]), dy = labs(c->ly[k] - c->ly[ci[q]]);
            reach = dx > reach ? (int)dx : reach;
            reach = dy > reach ? (int)dy : reach;
        }
    fits = fits && reach <= c->reach;
    for (size_t k = 0; k < nu && fits; k++) {
        long ix = c->lx[k] - c->gx0, iy = c->ly[k] - c->gy0;
        fits = ix >= 0 && ix < c->gnx && iy >= 0 && iy < c->gny && c->inset[iy * c->gnx + ix];
    }
    if (!fits)
        UMP_CALL(new_pattern(c, nu, reach > c->reach ? reach : c->reach, err));
    lsolve_mat *A = c->Ac;
    long nx = c->gnx, r = c->reach, w = 2 * r + 1;
    memset(c->occ, 0, (size_t)c->nc);
    for (size_t k = 0; k < nu; k++) {
        c->agg[k] = c->cidx[(c->ly[k] - c->gy0) * nx + c->lx[k] - c->gx0];
        c->occ[c->agg[k]] = 1;
    }
    /* Ac = P^T A P, summed in the order of A's rows: deterministic */
    memset(A->Ax, 0, sizeof *A->Ax * (size_t)A->Ap[A->n]);
    double dsum = 0;
    for (size_t k = 0; k < nu; k++)
        for (ump_idx q = rp[k]; q < rp[k + 1]; q++) {
            size_t j = (size_t)ci[q];
            long dx = c->lx[k] - c->lx[j], dy = c->ly[k] - c->ly[j];
            A->Ax[c->slot[(size_t)c->agg[j] * (size_t)(w * w) + (size_t)((dy + r) * w + dx + r)]] += av[q];
            dsum += k == j ? av[q] : 0;
        }
    /* the bins of S without unknowns: an identity row scaled like A's
     * diagonal, of its sign (CHOLMOD keeps the sign of the first factor) */
    double dfill = dsum / (double)nu;
    for (ump_idx j = 0; j < c->nc; j++)
        if (!c->occ[j])
            A->Ax[c->slot[(size_t)j * (size_t)(w * w) + (size_t)(r * w + r)]] = dfill;
    ump_err ignored;
    if (c->fac && lsolve_refactor(c->fac, A, &ignored) == UMP_OK) {
        *ok = c->ok = 1;
        return UMP_OK;
    }
    /* the first build with this pattern, or a refactor that failed (KLU's
     * pivot order from another step): a factorization anew */
    lsolve_free(&c->fac);
    *ok = c->ok = lsolve_factor_serial(A, kind, &c->fac, &ignored) == UMP_OK;
    return UMP_OK;
}

void coarse_add(coarse *c, const double *r, double *z)
{
    if (!c->ok)
        return;
    size_t nu = c->nu;
    memset(c->rc, 0, sizeof *c->rc * (size_t)c->nc);
    for (size_t k = 0; k < nu; k++)
        c->rc[c->agg[k]] += r[k];
    ump_err ignored;
    if (lsolve_solve(c->fac, c->rc, c->zc, &ignored) != UMP_OK)
        return;
#pragma omp parallel for schedule(static)
    for (size_t k = 0; k < nu; k++)
        z[k] += c->zc[c->agg[k]];
}
