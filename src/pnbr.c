/* SPDX-License-Identifier: GPL-3.0-or-later
 * pnbr.c -- neighbour rows of a particle set (see pnbr.h).
 */
#include "umppm/pnbr.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define PNBR_MAXN 512 /* neighbours of one row */

#define GROW_TO(ptr, n)                                                                                   \
    do {                                                                                                  \
        void *q_ = ump_realloc_array((ptr), (n), sizeof *(ptr));                                          \
        if (!q_)                                                                                          \
            return UMP_FAIL(err, UMP_ERR_NOMEM, "%s: out of memory for %zu particles", who, (size_t)(n)); \
        (ptr) = q_;                                                                                       \
    } while (0)

void pnbr_free(pnbr *nb)
{
    free(nb->off);
    free(nb->j);
    free(nb->dx);
    free(nb->dy);
    free(nb->r);
    free(nb->xb);
    free(nb->yb);
    free(nb->goff);
    free(nb->gcur);
    free(nb->gidx);
    free(nb->gbin);
    memset(nb, 0, sizeof *nb);
}

/* Bin every particle but the hidden ones (need[kind] < 0) on a grid of
 * spacing h over the bounding box of those particles: counting sort,
 * O(N). Particles are clamped into the border
 * bins, which keeps the search exact (a bin may then hold distant
 * particles, which the distance test drops). */
static ump_status grid_build(pnbr *g, const part_set *s, const unsigned char *kind, const int *need, double h,
                             const char *who, ump_err *err)
{
    size_t n = s->n;
    double xmin = HUGE_VAL, ymin = HUGE_VAL, xmax = -HUGE_VAL, ymax = -HUGE_VAL;
    for (size_t i = 0; i < n; i++) {
        if (!isfinite(s->x[i]) || !isfinite(s->y[i]))
            return UMP_FAIL(err, UMP_ERR_INPUT, "%s: particle %zu (id %lld) has a non-finite position", who, i,
                            (long long)s->id[i]);
        if (need[kind[i]] < 0)
            continue;
        xmin = fmin(xmin, s->x[i]);
        xmax = fmax(xmax, s->x[i]);
        ymin = fmin(ymin, s->y[i]);
        ymax = fmax(ymax, s->y[i]);
    }
    if (!(xmin <= xmax))
        xmin = ymin = xmax = ymax = 0; /* none binned */
    g->h = h;
    g->x0 = xmin;
    g->y0 = ymin;
    g->nx = (long)floor((xmax - xmin) / h) + 1;
    g->ny = (long)floor((ymax - ymin) / h) + 1;
    /* a particle flung far away must not make the grid huge: beyond
     * 4 bins per particle the box is cut, and the border bins take the rest */
    while ((double)g->nx * (double)g->ny > 4.0 * (double)n + 1024) {
        if (g->nx >= g->ny)
            g->nx = g->nx / 2 + 1;
        else
            g->ny = g->ny / 2 + 1;
    }
    size_t nbins = (size_t)g->nx * (size_t)g->ny;
    if (nbins + 1 > g->gcap) {
        size_t nc = nbins + 1 + nbins / 2;
        GROW_TO(g->goff, nc);
        GROW_TO(g->gcur, nc);
        g->gcap = nc;
    }
    memset(g->goff, 0, sizeof *g->goff * (nbins + 1));
    for (size_t i = 0; i < n; i++) {
        if (need[kind[i]] < 0) {
            g->gbin[i] = -1;
            continue;
        }
        long bx = (long)floor((s->x[i] - g->x0) / h), by = (long)floor((s->y[i] - g->y0) / h);
        bx = bx < 0 ? 0 : bx >= g->nx ? g->nx - 1 : bx;
        by = by < 0 ? 0 : by >= g->ny ? g->ny - 1 : by;
        g->gbin[i] = by * g->nx + bx;
        g->goff[g->gbin[i] + 1]++;
    }
    for (size_t b = 0; b < nbins; b++)
        g->goff[b + 1] += g->goff[b];
    /* stable: indices increase within a bin */
    memcpy(g->gcur, g->goff, sizeof *g->gcur * nbins);
    for (size_t i = 0; i < n; i++)
        if (g->gbin[i] >= 0)
            g->gidx[g->gcur[g->gbin[i]]++] = i;
    return UMP_OK;
}

/* Neighbours of particle i within radius re (m), any kind but i itself:
 * their number; with jj != NULL also, in increasing index, their indices,
 * offsets and distances (at most max; the count tells whether all fit).
 * Each of the 3 x 3 bins yields its particles in increasing index; the
 * candidates are gathered, then ordered by an insertion sort of their
 * positions (one small array moved instead of four). */
static size_t gather(const pnbr *g, const part_set *s, size_t i, double re, size_t *jj, double *ddx, double *ddy,
                     double *rr, size_t max)
{
    enum { TMAX = PNBR_MAXN };
    long b = g->gbin[i], bx = b % g->nx, by = b / g->nx;
    double xi = s->x[i], yi = s->y[i], re2 = re * re;
    size_t k = 0, tj[TMAX];
    double tx[TMAX], ty[TMAX];
    unsigned short ord[TMAX];
    if (max > TMAX)
        max = TMAX;
    for (long y = by - 1; y <= by + 1; y++) {
        if (y < 0 || y >= g->ny)
            continue;
        for (long x = bx - 1; x <= bx + 1; x++) {
            if (x < 0 || x >= g->nx)
                continue;
            size_t c = (size_t)(y * g->nx + x);
            for (size_t q = g->goff[c]; q < g->goff[c + 1]; q++) {
                size_t j = g->gidx[q];
                if (j == i)
                    continue;
                double dx = s->x[j] - xi, dy = s->y[j] - yi;
                if (dx * dx + dy * dy >= re2)
                    continue;
                if (jj && k < max) {
                    tj[k] = j;
                    tx[k] = dx;
                    ty[k] = dy;
                }
                k++;
            }
        }
    }
    if (!jj)
        return k;
    size_t kk = k < max ? k : max;
    for (size_t t = 0; t < kk; t++) {
        unsigned short v = (unsigned short)t;
        size_t u = t;
        while (u > 0 && tj[ord[u - 1]] > tj[v]) {
            ord[u] = ord[u - 1];
            u--;
        }
        ord[u] = v;
    }
    for (size_t t = 0; t < kk; t++) {
        unsigned short o = ord[t];
        jj[t] = tj[o];
        ddx[t] = tx[o];
        ddy[t] = ty[o];
        rr[t] = sqrt(tx[o] * tx[o] + ty[o] * ty[o]);
    }
    return k;
}

/* Rows within radius re (m) for the particles with need[kind[i]]. Two
 * passes: count, then fill, each parallel over particles. */
static ump_status rows_build(pnbr *R, const part_set *s, const unsigned char *kind, const int *need, double re,
                             const char *who, ump_err *err)
{
    size_t n = s->n;
    size_t *off = R->off;
    int overflow = 0;
#pragma omp parallel
    {
#pragma omp for schedule(static)
        for (size_t i = 0; i < n; i++) {
            size_t cnt = 0;
            if (need[kind[i]] > 0) {
                cnt = gather(R, s, i, re, NULL, NULL, NULL, NULL, PNBR_MAXN); /* count only */
                if (cnt > PNBR_MAXN) {
#pragma omp atomic write
                    overflow = 1;
                }
            }
            off[i + 1] = cnt;
        }
    }
    UMP_CHECK(!overflow, err, UMP_ERR_INPUT,
              "%s: a particle has more than %d neighbours within %g m: particles have collapsed onto each "
              "other (the run has diverged)", who, PNBR_MAXN, re);
    off[0] = 0;
    for (size_t i = 0; i < n; i++)
        off[i + 1] += off[i];
    size_t nz = off[n];
    if (nz > R->rcap) {
        size_t nc = nz + nz / 2 + 64;
        GROW_TO(R->j, nc);
        GROW_TO(R->dx, nc);
        GROW_TO(R->dy, nc);
        GROW_TO(R->r, nc);
        R->rcap = nc;
    }
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; i++)
        if (off[i + 1] > off[i])
            (void)gather(R, s, i, re, R->j + off[i], R->dx + off[i], R->dy + off[i], R->r + off[i],
                         off[i + 1] - off[i]);
    return UMP_OK;
}

ump_status pnbr_update(pnbr *nb, const part_set *s, const unsigned char *kind, const int *need, double radius,
                       double skin, int force, const char *who, ump_err *err)
{
    size_t n = s->n;
    if (n + 1 > nb->cap) {
        size_t nc = n + n / 2 + 16;
        GROW_TO(nb->off, nc + 1);
        GROW_TO(nb->xb, nc);
        GROW_TO(nb->yb, nc);
        GROW_TO(nb->gidx, nc);
        GROW_TO(nb->gbin, nc);
        nb->cap = nc;
    }
    if (!force && nb->nb == n && n > 0) {
        double d2max = 0;
        for (size_t i = 0; i < n; i++) {
            double dx = s->x[i] - nb->xb[i], dy = s->y[i] - nb->yb[i];
            d2max = fmax(d2max, dx * dx + dy * dy);
        }
        double half = 0.5 * skin;
        force = !(d2max <= half * half);
    } else {
        force = 1;
    }
    if (force) {
        double re = radius + skin;
        UMP_CALL(grid_build(nb, s, kind, need, re, who, err));
        UMP_CALL(rows_build(nb, s, kind, need, re, who, err));
        memcpy(nb->xb, s->x, sizeof *nb->xb * n);
        memcpy(nb->yb, s->y, sizeof *nb->yb * n);
        nb->nb = n;
        return UMP_OK;
    }
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; i++)
        for (size_t q = nb->off[i]; q < nb->off[i + 1]; q++) {
            size_t j = nb->j[q];
            double dx = s->x[j] - s->x[i], dy = s->y[j] - s->y[i];
            nb->dx[q] = dx;
            nb->dy[q] = dy;
            nb->r[q] = sqrt(dx * dx + dy * dy);
        }
    return UMP_OK;
}
