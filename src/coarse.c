/* SPDX-License-Identifier: GPL-3.0-or-later
 * coarse.c -- the aggregation coarse level of the particle pressure
 * solves (see coarse.h).
 */
#include "umppm/coarse.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

struct coarse {
    size_t nu, ucap;     /* unknowns of the last build; capacity of agg */
    ump_idx *agg;        /* [ucap] aggregate of each unknown */
    long *binmap;        /* [bcap] bin of the grid -> aggregate */
    size_t bcap, nagg;
    double *rc, *zc;     /* [ccap] restricted residual, coarse solution */
    size_t ccap;
    lsolve_trip trip;
    lsolve_mat *Ac;
    lsolve *fac;
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

void coarse_free(coarse **pc)
{
    if (!pc || !*pc)
        return;
    coarse *c = *pc;
    free(c->agg);
    free(c->binmap);
    free(c->rc);
    free(c->zc);
    lsolve_trip_free(&c->trip);
    lsolve_mat_free(&c->Ac);
    lsolve_free(&c->fac);
    free(c);
    *pc = NULL;
}

ump_status coarse_build(coarse *c, size_t nu, const double *px, const double *py, const size_t *map, double H,
                        const ump_idx *rp, const ump_idx *ci, const double *av, lsolve_kind kind, int *ok,
                        ump_err *err)
{
    *ok = c->ok = 0;
    c->nu = nu;
    if (nu < 64)
        return UMP_OK;
    double x0 = HUGE_VAL, y0 = HUGE_VAL, x1 = -HUGE_VAL, y1 = -HUGE_VAL;
    for (size_t k = 0; k < nu; k++) {
        size_t i = map[k];
        x0 = fmin(x0, px[i]), x1 = fmax(x1, px[i]);
        y0 = fmin(y0, py[i]), y1 = fmax(y1, py[i]);
    }
    long nbx = (long)floor((x1 - x0) / H) + 1, nby = (long)floor((y1 - y0) / H) + 1;
    if ((double)nbx * (double)nby > 4.0 * (double)nu + 1024)
        return UMP_OK; /* scattered liquid: not worth it */
    size_t nb = (size_t)nbx * (size_t)nby;
    if (nb > c->bcap) {
        size_t nc = nb + nb / 2 + 16;
        GROW_TO(c->binmap, nc);
        c->bcap = nc;
    }
    if (nu > c->ucap) {
        size_t nc = nu + nu / 2 + 16;
        GROW_TO(c->agg, nc);
        c->ucap = nc;
    }
    for (size_t b = 0; b < nb; b++)
        c->binmap[b] = -1;
    size_t na = 0;
    for (size_t k = 0; k < nu; k++) { /* aggregates numbered by first unknown: deterministic */
        size_t i = map[k];
        long bx = (long)floor((px[i] - x0) / H), by = (long)floor((py[i] - y0) / H);
        size_t b = (size_t)(by * nbx + bx);
        if (c->binmap[b] < 0)
            c->binmap[b] = (long)na++;
        c->agg[k] = (ump_idx)c->binmap[b];
    }
    c->nagg = na;
    if (na + 1 > c->ccap) {
        size_t nc = na + na / 2 + 16;
        GROW_TO(c->rc, nc);
        GROW_TO(c->zc, nc);
        c->ccap = nc;
    }
    /* P^T A P (whole: lsolve_factor checks the symmetry CHOLMOD needs) */
    if (!c->trip.Ti)
        UMP_CALL(lsolve_trip_init(&c->trip, (ump_idx)na, (size_t)rp[nu], err));
    lsolve_trip_clear(&c->trip);
    c->trip.n = (ump_idx)na;
    for (size_t k = 0; k < nu; k++)
        for (ump_idx q = rp[k]; q < rp[k + 1]; q++)
            UMP_CALL(lsolve_trip_add(&c->trip, c->agg[k], c->agg[ci[q]], av[q], err));
    lsolve_mat_free(&c->Ac);
    lsolve_free(&c->fac);
    UMP_CALL(lsolve_trip_to_mat(&c->trip, &c->Ac, err));
    ump_err ignored;
    *ok = c->ok = lsolve_factor(c->Ac, kind, &c->fac, &ignored) == UMP_OK;
    return UMP_OK;
}

void coarse_add(coarse *c, const double *r, double *z)
{
    if (!c->ok)
        return;
    size_t nu = c->nu;
    memset(c->rc, 0, sizeof *c->rc * c->nagg);
    for (size_t k = 0; k < nu; k++)
        c->rc[c->agg[k]] += r[k];
    ump_err ignored;
    if (lsolve_solve(c->fac, c->rc, c->zc, &ignored) != UMP_OK)
        return;
#pragma omp parallel for schedule(static)
    for (size_t k = 0; k < nu; k++)
        z[k] += c->zc[c->agg[k]];
}
