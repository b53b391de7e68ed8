/* SPDX-License-Identifier: GPL-3.0-or-later
 * particles.c -- the particle set (struct of arrays), seeding, compaction,
 * per-cell bins and boundary particles (docs/METHOD.md section 4; Step 2 of
 * Ng, Sheu & Hwang (2016) [NSH16] Section 3.3).
 *
 * Workload: every time step re-locates and re-bins all N particles and the
 * neighbour search reads the bins many times, so the bins are a counting
 * sort (O(N + ncells), two passes, no comparison sort) whose storage is kept
 * between steps; the set grows by doubling and never shrinks, so after the
 * first few steps the time loop allocates nothing here.
 */
#include "umppm/particles.h"

#include <stdlib.h>
#include <string.h>

/* Resize array p of the set to nc entries; on failure p is left untouched
 * (no void ** punning: each array is assigned through its own type). */
#define GROW(p)                                                   \
    do {                                                          \
        void *q_ = ump_realloc_array((p), nc, sizeof *(p));       \
        if (!q_)                                                  \
            goto nomem;                                           \
        (p) = q_;                                                 \
    } while (0)

ump_status part_create(size_t cap, part_set **out, ump_err *err)
{
    *out = NULL;
    part_set *s = ump_alloc_array(1, sizeof *s);
    if (!s)
        return UMP_FAIL(err, UMP_ERR_NOMEM, "particles: out of memory creating the particle set");
    ump_status rc = part_reserve(s, cap, err);
    if (rc != UMP_OK) {
        part_free(&s);
        return rc;
    }
    *out = s;
    return UMP_OK;
}

void part_free(part_set **ps)
{
    if (!ps || !*ps)
        return;
    part_set *s = *ps;
    free(s->x);
    free(s->y);
    free(s->u);
    free(s->v);
    free(s->T);
    free(s->cell);
    free(s->id);
    free(s);
    *ps = NULL;
}

ump_status part_reserve(part_set *s, size_t cap, ump_err *err)
{
    if (cap <= s->cap && s->x)
        return UMP_OK;
    /* amortised doubling: a run of part_add costs O(1) per particle */
    size_t nc = s->cap > SIZE_MAX / 2 ? SIZE_MAX : 2 * s->cap;
    if (nc < cap)
        nc = cap;
    if (nc < 16)
        nc = 16;
    /* each array that grows keeps its content; cap only changes when all did */
    GROW(s->x);
    GROW(s->y);
    GROW(s->u);
    GROW(s->v);
    GROW(s->T);
    GROW(s->cell);
    GROW(s->id);
    s->cap = nc;
    return UMP_OK;
nomem:
    return UMP_FAIL(err, UMP_ERR_NOMEM, "particles: out of memory growing the particle set to %zu", nc);
}

ump_status part_add(part_set *s, double x, double y, double u, double v, double T, ump_idx cell,
                    size_t *idx, ump_err *err)
{
    if (s->n == s->cap || !s->x)
        UMP_CALL(part_reserve(s, s->n + 1, err));
    size_t i = s->n++;
    s->x[i] = x;
    s->y[i] = y;
    s->u[i] = u;
    s->v[i] = v;
    s->T[i] = T;
    s->cell[i] = cell;
    s->id[i] = s->next_id++;
    if (idx)
        *idx = i;
    return UMP_OK;
}

void part_compact(part_set *s, const unsigned char *keep)
{
    size_t k = 0;
    for (size_t i = 0; i < s->n; i++) {
        if (!keep[i])
            continue;
        if (k != i) {
            s->x[k] = s->x[i];
            s->y[k] = s->y[i];
            s->u[k] = s->u[i];
            s->v[k] = s->v[i];
            s->T[k] = s->T[i];
            s->cell[k] = s->cell[i];
            s->id[k] = s->id[i];
        }
        k++;
    }
    s->n = k;
}

ump_status part_seed_centroids(part_set *s, const mesh2d *m, const double *u, const double *v,
                               const double *T, ump_err *err)
{
    UMP_CALL(part_reserve(s, s->n + (size_t)m->ncells, err));
    for (ump_idx c = 0; c < m->ncells; c++)
        UMP_CALL(part_add(s, m->cx[c], m->cy[c], u[c], v[c], T ? T[c] : 0.0, c, NULL, err));
    return UMP_OK;
}

/* Counting sort by cell. off[] first holds counts at c+1, then start
 * offsets used as fill cursors (after the fill off[c] is the end of c), and
 * is shifted back by one: no extra cursor array. Stable: within a cell the
 * particles stay in increasing index order. */
ump_status part_bins_build(part_bins *b, const mesh2d *m, const part_set *s, ump_err *err)
{
    ump_idx nc = m->ncells;
    if (!b->off || b->ncells != nc) {
        ump_idx *o = ump_realloc_array(b->off, (size_t)nc + 1, sizeof *o);
        if (!o)
            return UMP_FAIL(err, UMP_ERR_NOMEM, "particles: out of memory binning %ld cells", (long)nc);
        b->off = o;
        b->ncells = nc;
    }
    if (!b->idx || b->cap < s->n) {
        size_t nc2 = b->cap > SIZE_MAX / 2 ? SIZE_MAX : 2 * b->cap;
        if (nc2 < s->n)
            nc2 = s->n;
        size_t *q = ump_realloc_array(b->idx, nc2, sizeof *q);
        if (!q)
            return UMP_FAIL(err, UMP_ERR_NOMEM, "particles: out of memory binning %zu particles", s->n);
        b->idx = q;
        b->cap = nc2;
    }
    ump_idx *off = b->off;
    size_t n = s->n;
    /* serial: a threaded count (per-thread counts, merged in cell order) was
     * measured slower on 2 threads at 25 600 and 102 400 particles
     * (Steps 7 and 11 of the 160^2 and 320^2 cavities) */
    memset(off, 0, ((size_t)nc + 1) * sizeof *off);
    for (size_t i = 0; i < n; i++) {
        ump_idx c = s->cell[i];
        if (c < 0)
            continue;
        if (c >= nc)
            return UMP_FAIL(err, UMP_ERR_INPUT, "particles: particle %zu (id %lld) in cell %ld, mesh has %ld cells",
                            i, (long long)s->id[i], (long)c, (long)nc);
        off[c + 1]++;
    }
    for (ump_idx c = 0; c < nc; c++)
        off[c + 1] += off[c];
    for (size_t i = 0; i < n; i++) {
        ump_idx c = s->cell[i];
        if (c >= 0)
            b->idx[off[c]++] = i;
    }
    for (ump_idx c = nc; c > 0; c--)
        off[c] = off[c - 1];
    off[0] = 0;
    return UMP_OK;
}

void part_bins_free(part_bins *b)
{
    if (!b)
        return;
    free(b->off);
    free(b->idx);
    free(b->work);
    memset(b, 0, sizeof *b);
}

ump_status part_boundary_create(part_boundary *b, const mesh2d *m, ump_err *err)
{
    memset(b, 0, sizeof *b);
    ump_idx n = m->nfaces - m->ninternal, nc = m->ncells;
    b->n = n;
    b->x = ump_alloc_array((size_t)n, sizeof *b->x);
    b->y = ump_alloc_array((size_t)n, sizeof *b->y);
    b->u = ump_alloc_array((size_t)n, sizeof *b->u);
    b->v = ump_alloc_array((size_t)n, sizeof *b->v);
    b->T = ump_alloc_array((size_t)n, sizeof *b->T);
    b->face = ump_alloc_array((size_t)n, sizeof *b->face);
    b->off = ump_alloc_array((size_t)nc + 1, sizeof *b->off);
    b->idx = ump_alloc_array((size_t)n, sizeof *b->idx);
    if (!b->x || !b->y || !b->u || !b->v || !b->T || !b->face || !b->off || !b->idx) {
        part_boundary_free(b);
        return UMP_FAIL(err, UMP_ERR_NOMEM, "particles: out of memory creating %ld boundary particles",
                        (long)n);
    }
    for (ump_idx k = 0; k < n; k++) {
        ump_idx f = m->ninternal + k;
        b->x[k] = m->fx[f];
        b->y[k] = m->fy[f];
        b->face[k] = f;
        b->off[m->owner[f] + 1]++;
    }
    for (ump_idx c = 0; c < nc; c++)
        b->off[c + 1] += b->off[c];
    /* fill in face order; off[c] as cursor, shifted back afterwards */
    for (ump_idx k = 0; k < n; k++) {
        ump_idx c = m->owner[m->ninternal + k];
        b->idx[b->off[c]++] = k;
    }
    for (ump_idx c = nc; c > 0; c--)
        b->off[c] = b->off[c - 1];
    b->off[0] = 0;
    return UMP_OK;
}

void part_boundary_free(part_boundary *b)
{
    if (!b)
        return;
    free(b->x);
    free(b->y);
    free(b->u);
    free(b->v);
    free(b->T);
    free(b->face);
    free(b->off);
    free(b->idx);
    memset(b, 0, sizeof *b);
}

/* Gather every array of the set through perm (new i <- old perm[i]), with
 * tmp of n * 8 bytes as the staging buffer. */
#define PERMUTE(arr, type)                                  \
    do {                                                    \
        type *t_ = (type *)tmp;                             \
        for (size_t i = 0; i < n; i++)                      \
            t_[i] = (arr)[perm[i]];                         \
        memcpy((arr), t_, n * sizeof(type));                \
    } while (0)

ump_status part_sort_by_cell(part_set *s, part_bins *b, const mesh2d *m, ump_err *err)
{
    UMP_CALL(part_bins_build(b, m, s, err));
    size_t n = (size_t)b->off[m->ncells]; /* binned particles: all with cell >= 0 */
    UMP_CHECK(n == s->n, err, UMP_ERR_INPUT, "particles: %zu of %zu particles have no cell", s->n - n, s->n);
    int sorted = 1;
    for (size_t i = 0; i < n && sorted; i++)
        sorted = b->idx[i] == i;
    if (sorted)
        return UMP_OK;
    size_t need = n * 8;
    if (!b->work || b->work_bytes < need) {
        void *w = ump_realloc_array(b->work, need, 1);
        UMP_CHECK(w, err, UMP_ERR_NOMEM, "particles: out of memory sorting %zu particles", n);
        b->work = w;
        b->work_bytes = need;
    }
    void *tmp = b->work;
    const size_t *perm = b->idx;
    PERMUTE(s->x, double);
    PERMUTE(s->y, double);
    PERMUTE(s->u, double);
    PERMUTE(s->v, double);
    PERMUTE(s->T, double);
    PERMUTE(s->id, int64_t);
    PERMUTE(s->cell, ump_idx);
    for (size_t i = 0; i < n; i++)
        b->idx[i] = i; /* the bins of the sorted set: same offsets, identity order */
    return UMP_OK;
}
