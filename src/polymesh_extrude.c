/* SPDX-License-Identifier: GPL-3.0-or-later
 * polymesh_extrude.c -- a one-cell-thick polyMesh from 2-D polygons, built in
 * memory (for tests and mesh-making tools; no file I/O).
 *
 * OpenFOAM's conventions are followed so the result passes checkMesh when
 * written out: internal faces first in upper-triangular order, owner <
 * neighbour, right-hand-rule normals from owner to neighbour (outwards on
 * the boundary), boundary faces grouped by patch.
 */
#include "umppm/polymesh.h"

#include <stdlib.h>
#include <string.h>

typedef struct edge_rec {
    ump_idx a, b;      /* vertices, a < b (key) */
    ump_idx c0, c1;    /* cells on each side (-1: none yet) */
    ump_idx from, to;  /* direction as traversed counter-clockwise by c0 */
    int patch;
    double mx, my;
} edge_rec;

static int cmp_edge_key(const void *p, const void *q)
{
    const edge_rec *e = p, *f = q;
    if (e->a != f->a)
        return (e->a > f->a) - (e->a < f->a);
    return (e->b > f->b) - (e->b < f->b);
}

static int cmp_internal(const void *p, const void *q)
{
    const edge_rec *e = p, *f = q;
    if (e->c0 != f->c0)
        return (e->c0 > f->c0) - (e->c0 < f->c0);
    return (e->c1 > f->c1) - (e->c1 < f->c1);
}

static int cmp_boundary(const void *p, const void *q)
{
    const edge_rec *e = p, *f = q;
    if (e->patch != f->patch)
        return (e->patch > f->patch) - (e->patch < f->patch);
    if (e->mx != f->mx)
        return (e->mx > f->mx) - (e->mx < f->mx);
    return (e->my > f->my) - (e->my < f->my);
}

ump_status pmesh_extrude(const double *xy, ump_idx nv, const ump_idx *poly_off,
                         const ump_idx *poly_v, ump_idx npoly, double thickness,
                         int (*patch_of)(double x, double y, void *ctx), void *ctx,
                         const char *const *names, const char *const *types, int npatch,
                         pmesh **out, ump_err *err)
{
    *out = NULL;
    size_t nedge_all = (size_t)poly_off[npoly];
    edge_rec *e = ump_alloc_array(nedge_all, sizeof *e);
    pmesh *m = ump_alloc_array(1, sizeof *m);
    int *ccw = ump_alloc_array((size_t)npoly, sizeof *ccw);
    ump_status rc = UMP_OK;
    if (!e || !m || !ccw)
        goto nomem;
    /* orientation of each polygon */
    for (ump_idx c = 0; c < npoly; c++) {
        double a2 = 0;
        ump_idx b = poly_off[c], n = poly_off[c + 1] - b;
        for (ump_idx i = 0; i < n; i++) {
            const double *p = xy + 2 * (size_t)poly_v[b + i], *q = xy + 2 * (size_t)poly_v[b + (i + 1) % n];
            a2 += p[0] * q[1] - q[0] * p[1];
        }
        ccw[c] = a2 > 0;
    }
    /* every polygon edge, directed counter-clockwise */
    size_t k = 0;
    for (ump_idx c = 0; c < npoly; c++) {
        ump_idx b = poly_off[c], n = poly_off[c + 1] - b;
        for (ump_idx i = 0; i < n; i++, k++) {
            ump_idx u = poly_v[b + i], v = poly_v[b + (i + 1) % n];
            if (!ccw[c]) {
                ump_idx t = u;
                u = v;
                v = t;
            }
            e[k].a = u < v ? u : v;
            e[k].b = u < v ? v : u;
            e[k].c0 = c;
            e[k].c1 = -1;
            e[k].from = u;
            e[k].to = v;
        }
    }
    qsort(e, nedge_all, sizeof *e, cmp_edge_key);
    /* merge duplicates: an interior edge appears twice */
    size_t ne = 0;
    for (size_t i = 0; i < nedge_all; i++) {
        if (ne > 0 && e[ne - 1].a == e[i].a && e[ne - 1].b == e[i].b) {
            if (e[ne - 1].c1 >= 0) {
                rc = UMP_FAIL(err, UMP_ERR_INPUT, "pmesh_extrude: edge %ld-%ld shared by 3 polygons",
                              (long)e[i].a, (long)e[i].b);
                goto done;
            }
            e[ne - 1].c1 = e[i].c0;
            continue;
        }
        e[ne++] = e[i];
    }
    size_t nint = 0;
    for (size_t i = 0; i < ne; i++) {
        e[i].mx = 0.5 * (xy[2 * (size_t)e[i].a] + xy[2 * (size_t)e[i].b]);
        e[i].my = 0.5 * (xy[2 * (size_t)e[i].a + 1] + xy[2 * (size_t)e[i].b + 1]);
        if (e[i].c1 >= 0) {
            /* owner is the lower cell; direction follows the owner's ccw traversal */
            if (e[i].c1 < e[i].c0) {
                ump_idx t = e[i].c0;
                e[i].c0 = e[i].c1;
                e[i].c1 = t;
                t = e[i].from;
                e[i].from = e[i].to;
                e[i].to = t;
            }
            e[i].patch = -1;
            nint++;
        } else {
            e[i].patch = patch_of(e[i].mx, e[i].my, ctx);
            if (e[i].patch < 0 || e[i].patch >= npatch) {
                rc = UMP_FAIL(err, UMP_ERR_INPUT, "pmesh_extrude: no patch for boundary edge at (%g %g)",
                              e[i].mx, e[i].my);
                goto done;
            }
        }
    }
    /* internal edges first (upper-triangular), then boundary by patch */
    for (size_t i = 0, j = ne; i < j;) {
        if (e[i].patch < 0) {
            i++;
        } else {
            edge_rec t = e[--j];
            e[j] = e[i];
            e[i] = t;
        }
    }
    qsort(e, nint, sizeof *e, cmp_internal);
    qsort(e + nint, ne - nint, sizeof *e, cmp_boundary);

    m->npoints = 2 * nv;
    m->ncells = npoly;
    m->ninternal = (ump_idx)nint;
    m->nfaces = (ump_idx)ne + 2 * npoly;
    m->npatches = npatch + 1;
    m->dir = ump_strdup("(extruded mesh)");
    m->points = ump_alloc_array(3 * (size_t)m->npoints, sizeof *m->points);
    m->face_off = ump_alloc_array((size_t)m->nfaces + 1, sizeof *m->face_off);
    m->face_pts = ump_alloc_array(4 * ne + 2 * nedge_all, sizeof *m->face_pts);
    m->owner = ump_alloc_array((size_t)m->nfaces, sizeof *m->owner);
    m->neighbour = ump_alloc_array(nint, sizeof *m->neighbour);
    m->patch = ump_alloc_array((size_t)m->npatches, sizeof *m->patch);
    if (!m->dir || !m->points || !m->face_off || !m->face_pts || !m->owner || !m->neighbour || !m->patch)
        goto nomem;
    for (ump_idx v = 0; v < nv; v++) {
        for (int s = 0; s < 2; s++) {
            double *p = m->points + 3 * (size_t)(v + s * nv);
            p[0] = xy[2 * (size_t)v];
            p[1] = xy[2 * (size_t)v + 1];
            p[2] = s * thickness;
        }
    }
    ump_idx f = 0, w = 0;
    for (size_t i = 0; i < ne; i++, f++) {
        /* quad a0 b0 b1 a1: normal (dy, -dx) points right of from->to, out of c0 */
        ump_idx a = e[i].from, b = e[i].to;
        m->face_pts[w++] = a;
        m->face_pts[w++] = b;
        m->face_pts[w++] = b + nv;
        m->face_pts[w++] = a + nv;
        m->face_off[f + 1] = w;
        m->owner[f] = e[i].c0;
        if (i < nint)
            m->neighbour[f] = e[i].c1;
    }
    for (int p = 0; p < npatch; p++) {
        pmesh_patch *pp = &m->patch[p];
        pp->name = ump_strdup(names[p]);
        pp->type = ump_strdup(types[p]);
        if (!pp->name || !pp->type)
            goto nomem;
        pp->kind = strcmp(types[p], "wall") == 0 ? PMESH_WALL
                 : strcmp(types[p], "symmetryPlane") == 0 ? PMESH_SYMMETRYPLANE
                 : strcmp(types[p], "empty") == 0 ? PMESH_EMPTY : PMESH_PATCH;
        pp->nbr = -1;
        pp->start = (ump_idx)nint;
        for (size_t i = nint; i < ne; i++) {
            if (e[i].patch < p)
                pp->start++;
            else if (e[i].patch == p)
                pp->n++;
        }
    }
    /* back (z = 0, reversed: normal -z) and front (z = t, normal +z) */
    pmesh_patch *fb = &m->patch[npatch];
    fb->name = ump_strdup("frontAndBack");
    fb->type = ump_strdup("empty");
    if (!fb->name || !fb->type)
        goto nomem;
    fb->kind = PMESH_EMPTY;
    fb->nbr = -1;
    fb->start = (ump_idx)ne;
    fb->n = 2 * npoly;
    for (int s = 0; s < 2; s++)
        for (ump_idx c = 0; c < npoly; c++, f++) {
            ump_idx b = poly_off[c], n = poly_off[c + 1] - b;
            for (ump_idx i = 0; i < n; i++) {
                ump_idx j = ccw[c] == (s == 1) ? i : n - 1 - i;
                m->face_pts[w++] = poly_v[b + j] + s * nv;
            }
            m->face_off[f + 1] = w;
            m->owner[f] = c;
        }
    rc = pmesh_check(m, err);
    goto done;
nomem:
    rc = UMP_FAIL(err, UMP_ERR_NOMEM, "pmesh_extrude: out of memory");
done:
    free(e);
    free(ccw);
    if (rc == UMP_OK)
        *out = m;
    else
        pmesh_free(&m);
    return rc;
}
