/* SPDX-License-Identifier: GPL-3.0-or-later
 * mlseed.c -- the initial lattice of fluid, wall and dummy particles (see
 * mlseed.h).
 */
#include "umppm/mlseed.h"
#include "umppm/mps.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

double mlseed_default_spacing(const mesh2d *m)
{
    if (m->ncells == 0)
        return 0;
    double *h = ump_alloc_array((size_t)m->ncells, sizeof *h);
    if (!h)
        return 0;
    for (ump_idx c = 0; c < m->ncells; c++)
        h[c] = sqrt(m->area[c]);
    qsort(h, (size_t)m->ncells, sizeof *h, cmp_double);
    double med = h[m->ncells / 2];
    free(h);
    return 0.5 * med;
}

/* Distance from (px, py) to the segment a-b. */
double mlseed_seg_dist(double px, double py, double ax, double ay, double bx, double by)
{
    double ex = bx - ax, ey = by - ay, l2 = ex * ex + ey * ey;
    double t = l2 > 0 ? ((px - ax) * ex + (py - ay) * ey) / l2 : 0;
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    double dx = px - (ax + t * ex), dy = py - (ay + t * ey);
    return sqrt(dx * dx + dy * dy);
}

ump_status mlseed_build(const mesh2d *m, const double *alpha, const double *u, const double *v,
                        const unsigned char *wall_patch, double l0, double wall_depth, double thick, part_set *s,
                        unsigned char **kinds, ump_idx **solid_face, mlseed_stats *st, ump_err *err)
{
    memset(st, 0, sizeof *st);
    *kinds = NULL;
    if (solid_face)
        *solid_face = NULL;
    ump_idx *sface = NULL;
    UMP_CHECK(l0 > 0 && thick >= wall_depth && wall_depth > 0, err, UMP_ERR_INPUT,
              "particle seeding: spacing %g, wall depth %g, solid thickness %g", l0, wall_depth, thick);
    double xmin = HUGE_VAL, ymin = HUGE_VAL, xmax = -HUGE_VAL, ymax = -HUGE_VAL;
    for (ump_idx k = 0; k < m->nverts; k++) {
        xmin = fmin(xmin, m->vx[k]);
        xmax = fmax(xmax, m->vx[k]);
        ymin = fmin(ymin, m->vy[k]);
        ymax = fmax(ymax, m->vy[k]);
    }
    st->x0 = xmin;
    st->y0 = ymin;
    /* lattice indices i in [ia, ib), j in [ja, jb): the box grown by thick */
    long ia = (long)floor((xmin - thick - xmin) / l0) - 1, ib = (long)ceil((xmax + thick - xmin) / l0) + 1;
    long ja = (long)floor((ymin - thick - ymin) / l0) - 1, jb = (long)ceil((ymax + thick - ymin) / l0) + 1;
    double npts = (double)(ib - ia) * (double)(jb - ja);
    UMP_CHECK(npts <= 1e8, err, UMP_ERR_INPUT,
              "particle seeding: spacing %g m makes %.3g lattice points over the %g x %g m container; "
              "choose a larger meshless spacing", l0, npts, xmax - xmin, ymax - ymin);
    size_t nx = (size_t)(ib - ia), ny = (size_t)(jb - ja), np = nx * ny;
    ump_idx *owner = ump_alloc_array(np, sizeof *owner);
    unsigned char *kind = NULL;
    size_t *bin_off = NULL, *bin_face = NULL;
    ump_status rc = UMP_OK;
    if (!owner) {
        rc = UMP_FAIL(err, UMP_ERR_NOMEM, "particle seeding: out of memory for %zu lattice points", np);
        goto done;
    }
    for (size_t q = 0; q < np; q++)
        owner[q] = -1;
#define PX(i) (xmin + ((double)(i) + 0.5) * l0)
#define PY(j) (ymin + ((double)(j) + 0.5) * l0)
    /* 1. rasterise the cells: each claims the lattice points inside it */
    for (ump_idx c = 0; c < m->ncells; c++) {
        double cx0 = HUGE_VAL, cy0 = HUGE_VAL, cx1 = -HUGE_VAL, cy1 = -HUGE_VAL;
        for (ump_idx k = m->cell_off[c]; k < m->cell_off[c + 1]; k++) {
            ump_idx w = m->cell_verts[k];
            cx0 = fmin(cx0, m->vx[w]);
            cx1 = fmax(cx1, m->vx[w]);
            cy0 = fmin(cy0, m->vy[w]);
            cy1 = fmax(cy1, m->vy[w]);
        }
        long i0 = (long)ceil((cx0 - xmin) / l0 - 0.5), i1 = (long)floor((cx1 - xmin) / l0 - 0.5);
        long j0 = (long)ceil((cy0 - ymin) / l0 - 0.5), j1 = (long)floor((cy1 - ymin) / l0 - 0.5);
        for (long j = j0; j <= j1; j++)
            for (long i = i0; i <= i1; i++) {
                if (i < ia || i >= ib || j < ja || j >= jb)
                    continue;
                size_t q = (size_t)(j - ja) * nx + (size_t)(i - ia);
                if (owner[q] < 0 && part_in_cell(m, c, PX(i), PY(j)))
                    owner[q] = c;
            }
    }
    /* 2. bin the boundary faces (grid of spacing thick over the lattice box) */
    double bh = thick, bx0 = PX(ia) - l0, by0 = PY(ja) - l0;
    long bnx = (long)ceil((PX(ib) - bx0) / bh) + 1, bny = (long)ceil((PY(jb) - by0) / bh) + 1;
    size_t nb = (size_t)bnx * (size_t)bny;
    bin_off = ump_alloc_array(nb + 1, sizeof *bin_off);
    if (!bin_off) {
        rc = UMP_FAIL(err, UMP_ERR_NOMEM, "particle seeding: out of memory");
        goto done;
    }
    for (int pass = 0; pass < 2; pass++) {
        for (ump_idx f = m->ninternal; f < m->nfaces; f++) {
            double ax = m->vx[m->fv0[f]], ay = m->vy[m->fv0[f]], cx = m->vx[m->fv1[f]], cy = m->vy[m->fv1[f]];
            long b0 = (long)floor((fmin(ax, cx) - thick - bx0) / bh), b1 = (long)floor((fmax(ax, cx) + thick - bx0) / bh);
            long c0 = (long)floor((fmin(ay, cy) - thick - by0) / bh), c1 = (long)floor((fmax(ay, cy) + thick - by0) / bh);
            for (long b = c0 < 0 ? 0 : c0; b <= c1 && b < bny; b++)
                for (long a = b0 < 0 ? 0 : b0; a <= b1 && a < bnx; a++) {
                    size_t q = (size_t)b * (size_t)bnx + (size_t)a;
                    if (pass == 0)
                        bin_off[q + 1]++;
                    else
                        bin_face[bin_off[q]++] = (size_t)f;
                }
        }
        if (pass == 0) {
            for (size_t q = 0; q < nb; q++)
                bin_off[q + 1] += bin_off[q];
            bin_face = ump_alloc_array(bin_off[nb] + 1, sizeof *bin_face);
            if (!bin_face) {
                rc = UMP_FAIL(err, UMP_ERR_NOMEM, "particle seeding: out of memory");
                goto done;
            }
        } else {
            for (size_t q = nb; q > 0; q--)
                bin_off[q] = bin_off[q - 1];
            bin_off[0] = 0;
        }
    }
    /* 3. classify: solid points (outside, nearest boundary face a wall
     * within thick), fluid points (inside a cell with alpha >= 1/2) */
    kind = ump_alloc_array(np, sizeof *kind);
    sface = ump_alloc_array(np, sizeof *sface);
    if (!kind || !sface) {
        rc = UMP_FAIL(err, UMP_ERR_NOMEM, "particle seeding: out of memory");
        goto done;
    }
    enum { NONE = 255 };
    for (size_t q = 0; q < np; q++) {
        kind[q] = NONE;
        long i = ia + (long)(q % nx), j = ja + (long)(q / nx);
        double x = PX(i), y = PY(j);
        if (owner[q] >= 0) {
            if (alpha[owner[q]] >= 0.5)
                kind[q] = MPS_FLUID;
            continue;
        }
        long a = (long)floor((x - bx0) / bh), b = (long)floor((y - by0) / bh);
        if (a < 0 || a >= bnx || b < 0 || b >= bny)
            continue;
        size_t c = (size_t)b * (size_t)bnx + (size_t)a;
        double best = HUGE_VAL;
        ump_idx bf = -1;
        for (size_t k = bin_off[c]; k < bin_off[c + 1]; k++) {
            ump_idx f = (ump_idx)bin_face[k];
            double d = mlseed_seg_dist(x, y, m->vx[m->fv0[f]], m->vy[m->fv0[f]], m->vx[m->fv1[f]], m->vy[m->fv1[f]]);
            /* ties (a corner shared by a wall and an open patch): the wall */
            if (d < best - 1e-12 * l0 || (fabs(d - best) <= 1e-12 * l0 && bf >= 0 &&
                                           !wall_patch[m->face_patch[bf]] && wall_patch[m->face_patch[f]])) {
                best = d;
                bf = f;
            }
        }
        if (bf < 0 || best > thick || !wall_patch[m->face_patch[bf]])
            continue;
        kind[q] = best < wall_depth ? MPS_WALL : MPS_DUMMY;
        sface[q] = bf;
    }
    /* 4. append: solid first (wall, then dummy), then fluid */
    size_t nsolid = 0;
    for (size_t q = 0; q < np; q++)
        nsolid += kind[q] == MPS_WALL || kind[q] == MPS_DUMMY;
    *kinds = ump_alloc_array(nsolid + 1, sizeof **kinds);
    if (solid_face)
        *solid_face = ump_alloc_array(nsolid + 1, sizeof **solid_face);
    if (!*kinds || (solid_face && !*solid_face)) {
        rc = UMP_FAIL(err, UMP_ERR_NOMEM, "particle seeding: out of memory");
        goto done;
    }
    size_t ks = 0;
    for (int pass = 0; pass < 3 && rc == UMP_OK; pass++) {
        unsigned char want = pass == 0 ? MPS_WALL : pass == 1 ? MPS_DUMMY : MPS_FLUID;
        for (size_t q = 0; q < np && rc == UMP_OK; q++) {
            if (kind[q] != want)
                continue;
            long i = ia + (long)(q % nx), j = ja + (long)(q / nx);
            ump_idx c = want == MPS_FLUID ? owner[q] : -1;
            double uu = c >= 0 && u ? u[c] : 0, vv = c >= 0 && v ? v[c] : 0;
            rc = part_add(s, PX(i), PY(j), uu, vv, 0, c, NULL, err);
            if (want != MPS_FLUID) {
                if (solid_face)
                    (*solid_face)[ks] = sface[q];
                (*kinds)[ks++] = want;
            }
            if (want == MPS_WALL)
                st->nwall++;
            else if (want == MPS_DUMMY)
                st->ndummy++;
            else
                st->nfluid++;
        }
    }
#undef PX
#undef PY
    if (rc == UMP_OK && st->nfluid == 0)
        rc = UMP_FAIL(err, UMP_ERR_INPUT, "particle seeding: no liquid: no cell has a volume fraction >= 0.5 "
                      "at a lattice point of spacing %g m (run setFields, or choose a smaller spacing)", l0);
done:
    if (rc != UMP_OK) {
        free(*kinds);
        *kinds = NULL;
        if (solid_face) {
            free(*solid_face);
            *solid_face = NULL;
        }
    }
    free(sface);
    free(owner);
    free(kind);
    free(bin_off);
    free(bin_face);
    return rc;
}

ump_status mlseed_wall_points(const mesh2d *m, const unsigned char *wall_patch, double l0, part_set *s, double **nx,
                              double **ny, ump_idx **face, size_t *count, ump_err *err)
{
    *nx = *ny = NULL;
    *face = NULL;
    *count = 0;
    UMP_CHECK(l0 > 0, err, UMP_ERR_INPUT, "wall points: spacing %g", l0);
    size_t np = 0;
    for (int pass = 0; pass < 2; pass++) {
        size_t k = 0;
        for (ump_idx f = m->ninternal; f < m->nfaces; f++) {
            if (!wall_patch[m->face_patch[f]])
                continue;
            double ax = m->vx[m->fv0[f]], ay = m->vy[m->fv0[f]], bx = m->vx[m->fv1[f]], by = m->vy[m->fv1[f]];
            double len = hypot(bx - ax, by - ay);
            long nseg = (long)ceil(len / l0 - 1e-9);
            nseg = nseg < 1 ? 1 : nseg;
            if (pass == 0) {
                np += (size_t)nseg;
                continue;
            }
            for (long t = 0; t < nseg; t++) {
                double a = ((double)t + 0.5) / (double)nseg;
                UMP_CALL(part_add(s, ax + a * (bx - ax), ay + a * (by - ay), 0, 0, 0, m->owner[f], NULL, err));
                (*nx)[k] = m->nx[f];
                (*ny)[k] = m->ny[f];
                (*face)[k] = f;
                k++;
            }
        }
        if (pass == 0) {
            *nx = ump_alloc_array(np + 1, sizeof **nx);
            *ny = ump_alloc_array(np + 1, sizeof **ny);
            *face = ump_alloc_array(np + 1, sizeof **face);
            if (!*nx || !*ny || !*face) {
                free(*nx);
                free(*ny);
                free(*face);
                *nx = *ny = NULL;
                *face = NULL;
                return UMP_FAIL(err, UMP_ERR_NOMEM, "wall points: out of memory");
            }
        }
    }
    *count = np;
    return UMP_OK;
}
