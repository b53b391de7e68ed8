/* SPDX-License-Identifier: GPL-3.0-or-later
 * part_search.c -- particle neighbour search through the mesh stencils and
 * particle management ([NSH16] Section 3.2.2.2 and Section 4 intro;
 * docs/METHOD.md section 4 and section 5, Step 11).
 *
 * Neighbour search: the candidates of a point in cell c are the particles
 * binned in c and in N2(c) (mesh2d stencils), plus the boundary particles
 * owned by those cells. Cost O(particles in the stencil); no all-pairs loop.
 * Offsets carry the stencil shift of the cell (cyclic meshes): a particle j
 * of stencil cell q is seen at (x_j + shift_q) - x.
 *
 * Management (Step 11):
 *   UMPPM  -- particles closer than delta < sqrt(alpha) d_c are deleted
 *             ([NSH16]: "particles which are close to each other are simply
 *             deleted"; alpha = 0.09 in MPPM, 0.05 also used). The paper does
 *             not say which of the two goes; we keep the one nearer its own
 *             cell centroid (it is the better observation point of its cell),
 *             greedily: particles are visited in increasing distance to their
 *             centroid (ties: lower index), a visited survivor is kept and
 *             deletes every unvisited survivor of its cell and N1 cells within
 *             sqrt(alpha) d_c of its own cell. Hence no surviving pair is
 *             closer than sqrt(alpha) d_c of the cell of the member nearer
 *             its centroid, and no particle is deleted without a kept partner
 *             nearer its centroid. Cost O(N log N) (one sort of N keys) plus
 *             O(N * particles per N1 stencil).
 *   UMPPM* -- "retaining only the fluid particle that is closest to the mesh
 *             centroid, while deleting the other fluid particles lying on the
 *             same pressure mesh" (Section 4); ties: lower index. O(N).
 *   Both   -- "in the event of detecting an empty pressure mesh, a particle
 *             is added at the mesh centroid" with u = u_P (Eq. 36), T = T_P,
 *             or with the values a caller's refill function sets for the
 *             cells left empty (part_manage_refill).
 * Scratch (sort keys, flags) lives in the bins and is grown amortised.
 */
#include "part_internal.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

size_t part_neighbours(const mesh2d *m, const part_set *s, const part_bins *b,
                       const part_boundary *bp, ump_idx c, double x, double y, size_t exclude,
                       part_nbr *out, size_t max)
{
    size_t cnt = 0;
    ump_idx a0 = m->n2_off[c], a1 = m->n2_off[c + 1];
    /* a = a0 - 1 stands for c itself (zero shift) */
    for (ump_idx a = a0 - 1; a < a1; a++) {
        ump_idx q = a < a0 ? c : m->n2[a];
        double sx = 0, sy = 0;
        if (a >= a0 && m->n2_sx) {
            sx = m->n2_sx[a];
            sy = m->n2_sy[a];
        }
        double ox = sx - x, oy = sy - y;
        for (ump_idx k = b->off[q]; k < b->off[q + 1]; k++) {
            size_t j = b->idx[k];
            if (j == exclude)
                continue;
            if (cnt < max) {
                out[cnt].index = j;
                out[cnt].is_boundary = 0;
                out[cnt].dx = s->x[j] + ox;
                out[cnt].dy = s->y[j] + oy;
            }
            cnt++;
        }
        if (!bp)
            continue;
        for (ump_idx k = bp->off[q]; k < bp->off[q + 1]; k++) {
            ump_idx j = bp->idx[k];
            if (cnt < max) {
                out[cnt].index = (size_t)j;
                out[cnt].is_boundary = 1;
                out[cnt].dx = bp->x[j] + ox;
                out[cnt].dy = bp->y[j] + oy;
            }
            cnt++;
        }
    }
    return cnt;
}

typedef struct key_rec {
    double d2; /* squared distance to the own cell centroid */
    size_t i;
} key_rec;

static int key_less(const key_rec *a, const key_rec *b)
{
    return a->d2 < b->d2 || (a->d2 == b->d2 && a->i < b->i);
}

/* Sorts a[0 .. n) by (d2, i), a total order, bottom-up merging through tmp
 * (n records): qsort would allocate its own buffer at every step. */
static void sort_keys(key_rec *a, key_rec *tmp, size_t n)
{
    key_rec *src = a, *dst = tmp;
    for (size_t w = 1; w < n; w = w > n / 2 ? n : 2 * w) {
        for (size_t lo = 0; lo < n; lo += 2 * w) {
            size_t mid = lo + w < n ? lo + w : n, hi = mid + w < n ? mid + w : n;
            size_t i = lo, j = mid, k = lo;
            while (i < mid && j < hi)
                dst[k++] = key_less(&src[j], &src[i]) ? src[j++] : src[i++];
            while (i < mid)
                dst[k++] = src[i++];
            while (j < hi)
                dst[k++] = src[j++];
        }
        key_rec *t = src;
        src = dst;
        dst = t;
    }
    if (src != a)
        memcpy(a, src, n * sizeof *a);
}

/* Scratch of 2n key records (the keys and the sort's buffer) followed by n
 * flags, in the bins. */
static ump_status work_reserve(part_bins *b, size_t n, key_rec **keys, unsigned char **flag,
                               ump_err *err)
{
    if (n > SIZE_MAX / (2 * sizeof(key_rec) + 1))
        return UMP_FAIL(err, UMP_ERR_NOMEM, "particles: %zu particles overflow the scratch size", n);
    size_t need = n * (2 * sizeof(key_rec) + 1);
    if (!b->work || b->work_bytes < need) {
        size_t nb = b->work_bytes > SIZE_MAX / 2 ? SIZE_MAX : 2 * b->work_bytes;
        if (nb < need)
            nb = need;
        void *w = ump_realloc_array(b->work, nb, 1);
        if (!w)
            return UMP_FAIL(err, UMP_ERR_NOMEM, "particles: out of memory for %zu bytes of scratch", nb);
        b->work = w;
        b->work_bytes = nb;
    }
    *keys = b->work; /* malloc'ed: aligned for key_rec */
    *flag = (unsigned char *)b->work + 2 * n * sizeof(key_rec);
    return UMP_OK;
}

static double dist2_centroid(const mesh2d *m, const part_set *s, size_t i)
{
    double dx = s->x[i] - m->cx[s->cell[i]], dy = s->y[i] - m->cy[s->cell[i]];
    return dx * dx + dy * dy;
}

/* flag: 0 deleted, 1 alive and not yet visited, 2 kept (visited) */
static size_t delete_close(const part_set *s, const part_bins *b, const mesh2d *m, double alpha,
                           key_rec *keys, unsigned char *flag)
{
    size_t nk = 0, ndel = 0;
    for (size_t i = 0; i < s->n; i++)
        if (flag[i]) {
            keys[nk].d2 = dist2_centroid(m, s, i);
            keys[nk].i = i;
            nk++;
        }
    sort_keys(keys, keys + s->n, nk);
    for (size_t r = 0; r < nk; r++) {
        size_t i = keys[r].i;
        if (!flag[i])
            continue;
        flag[i] = 2;
        ump_idx c = s->cell[i];
        double h = sqrt(alpha) * m->dc[c], h2 = h * h;
        ump_idx a0 = m->n1_off[c], a1 = m->n1_off[c + 1];
        for (ump_idx a = a0 - 1; a < a1; a++) {
            ump_idx q = a < a0 ? c : m->n1[a];
            double sx = 0, sy = 0;
            if (a >= a0 && m->n1_sx) {
                sx = m->n1_sx[a];
                sy = m->n1_sy[a];
            }
            double ox = sx - s->x[i], oy = sy - s->y[i];
            for (ump_idx k = b->off[q]; k < b->off[q + 1]; k++) {
                size_t j = b->idx[k];
                if (flag[j] != 1)
                    continue;
                double dx = s->x[j] + ox, dy = s->y[j] + oy;
                if (dx * dx + dy * dy < h2) { /* delta < sqrt(alpha) d_c */
                    flag[j] = 0;
                    ndel++;
                }
            }
        }
    }
    return ndel;
}

static size_t keep_nearest(const part_set *s, const part_bins *b, const mesh2d *m, unsigned char *flag)
{
    size_t ndel = 0;
    for (ump_idx c = 0; c < m->ncells; c++) {
        ump_idx k0 = b->off[c], k1 = b->off[c + 1];
        if (k1 - k0 < 2)
            continue;
        size_t best = b->idx[k0];
        double bd = dist2_centroid(m, s, best);
        for (ump_idx k = k0 + 1; k < k1; k++) { /* bins ascend in index: '<' keeps the lower on ties */
            size_t j = b->idx[k];
            double d = dist2_centroid(m, s, j);
            if (d < bd) {
                bd = d;
                best = j;
            }
        }
        for (ump_idx k = k0; k < k1; k++)
            if (b->idx[k] != best) {
                flag[b->idx[k]] = 0;
                ndel++;
            }
    }
    return ndel;
}

ump_status part_manage(part_set *s, part_bins *b, const mesh2d *m, part_variant variant, double alpha,
                       const double *uc, const double *vc, const double *Tc, part_manage_stats *st,
                       ump_err *err)
{
    return part_manage_refill(s, b, m, variant, alpha, NULL, NULL, uc, vc, Tc, st, err);
}

ump_status part_manage_refill(part_set *s, part_bins *b, const mesh2d *m, part_variant variant, double alpha,
                              part_refill_fn refill, void *ctx, const double *uc, const double *vc,
                              const double *Tc, part_manage_stats *st, ump_err *err)
{
    part_manage_stats z = {0, 0, 0, 0};
    if (st)
        *st = z;
    else
        st = &z;
    if (variant != PART_UMPPM && variant != PART_UMPPM_STAR)
        return UMP_FAIL(err, UMP_ERR_INPUT, "particles: unknown management variant %d", (int)variant);
    if (variant == PART_UMPPM && !(alpha > 0 && alpha < INFINITY))
        return UMP_FAIL(err, UMP_ERR_INPUT, "particles: UMPPM deletion needs alpha > 0, got %g", alpha);
    UMP_CALL(part_bins_build(b, m, s, err));
    key_rec *keys = NULL;
    unsigned char *flag = NULL;
    UMP_CALL(work_reserve(b, s->n, &keys, &flag, err));
    for (size_t i = 0; i < s->n; i++) {
        flag[i] = s->cell[i] >= 0;
        st->removed_left += !flag[i];
    }
    if (variant == PART_UMPPM)
        st->deleted_close = delete_close(s, b, m, alpha, keys, flag);
    else
        st->deleted_extra = keep_nearest(s, b, m, flag);
    /* the refill values, while the bins still hold the deleted particles */
    if (refill)
        UMP_CALL(refill(ctx, flag, err));
    part_compact(s, flag);
    UMP_CALL(part_bins_build(b, m, s, err));
    /* Eq. (36): a new particle at the centroid of every empty cell */
    for (ump_idx c = 0; c < m->ncells; c++)
        if (b->off[c] == b->off[c + 1]) {
            UMP_CALL(part_add(s, m->cx[c], m->cy[c], uc[c], vc[c], Tc ? Tc[c] : 0.0, c, NULL, err));
            st->added++;
        }
    if (st->added)
        UMP_CALL(part_bins_build(b, m, s, err));
    return UMP_OK;
}
