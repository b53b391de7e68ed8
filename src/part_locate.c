/* SPDX-License-Identifier: GPL-3.0-or-later
 * part_locate.c -- point location on the 2-D pressure mesh (docs/METHOD.md
 * section 4: each particle is re-located by walking from its previous cell,
 * with a search over all cells as the fall-back).
 *
 * Workload: after every particle move (Steps 7 and 10) each particle is
 * re-located from its previous cell; with CFL < 1 the point is in that cell
 * or one or two faces away, so the walk costs one or two polygon-face loops.
 *
 * The walk (a "visibility walk"): in the current cell c, the signed distance
 * of the point beyond each face line is d = (x - x_f).n_out with the outward
 * normal n_out = n_f on the owner side and -n_f on the neighbour side (whose
 * copy of a cyclic face lies at x_f + sep). If no d exceeds eps the point is
 * in c (boundary inclusive, exact for convex cells). Otherwise step across
 * the internal face with the largest d; only when the point is beyond
 * boundary faces alone does it leave (PART_LEFT). Preferring internal faces
 * keeps points that are beyond a wall *line* of c but still in the domain
 * (non-convex domains: round obstacles, re-entrant corners) from being
 * reported as left. When the point is beyond walls only (by db), it may
 * still be in the domain round a corner (e.g. just below a re-entrant
 * corner, seen from a triangle beside it): for db <= d_c the cells of N2(c)
 * are tested (point-in-polygon, cyclic shifts applied) before PART_LEFT is
 * returned; for db > d_c the point may lie behind an obstacle the walk did
 * not go round, and the global search decides. The stencil test costs ~20
 * polygon tests, only for particles that leave. Consequence: a particle
 * that jumps across a baffle (zero-thickness wall) into a stencil cell is
 * found there, not reported as left.
 *
 * Cyclic faces: the neighbour seen from the owner is at x_N - sep (mesh2d.h),
 * so a point crossing from the owner into the neighbour gets x += sep, and
 * from the neighbour into the owner x -= sep.
 *
 * Robustness: the face the walk came through is never crossed back unless
 * the point is beyond that face alone and outside the cell by the polygon
 * test (possible only in non-convex cells), so an edge or vertex point
 * cannot ping-pong; any longer cycle is caught by Brent's cycle detection
 * on the walk state and gone round once more with polygon tests (a
 * non-convex cell can hold the point while the point is beyond one of its
 * face lines), and a step budget (ncells + 16) bounds everything else.
 * On failure: point-in-polygon over all cells (O(ncells), bounding boxes
 * first), then -- the point being outside every cell -- the nearest
 * boundary face (PART_LEFT).
 */
#include "part_internal.h"

#include <math.h>

double part_eps(const mesh2d *m, ump_idx c, double x, double y)
{
    return 1e-10 * m->dc[c] + 1e-15 * (fabs(x) + fabs(y));
}

/* Is entry k of c's face list on the neighbour side of its face? A cyclic
 * face whose owner and neighbour are both c (one cell across the period) is
 * listed twice, owner side first (mesh2d build_cell_faces). */
static inline int nb_side(const mesh2d *m, ump_idx c, ump_idx k)
{
    ump_idx f = m->cell_faces[k];
    if (m->owner[f] != c)
        return 1;
    return f < m->ninternal && m->neigh[f] == c && k > m->cell_face_off[c] && m->cell_faces[k - 1] == f;
}

/* Signed distance of (x, y) beyond face f seen from side `side` (0 owner). */
static inline double beyond(const mesh2d *m, ump_idx f, int side, double x, double y)
{
    if (!side)
        return (x - m->fx[f]) * m->nx[f] + (y - m->fy[f]) * m->ny[f];
    double fx = m->fx[f], fy = m->fy[f];
    if (m->sepx) {
        fx += m->sepx[f];
        fy += m->sepy[f];
    }
    return (fx - x) * m->nx[f] + (fy - y) * m->ny[f];
}

int part_in_cell(const mesh2d *m, ump_idx c, double x, double y)
{
    if (c < 0 || c >= m->ncells)
        return 0;
    ump_idx b = m->cell_off[c], e = m->cell_off[c + 1];
    double eps = part_eps(m, c, x, y);
    int in = 0;
    for (ump_idx i = b, j = e - 1; i < e; j = i++) {
        double xi = m->vx[m->cell_verts[i]], yi = m->vy[m->cell_verts[i]];
        double xj = m->vx[m->cell_verts[j]], yj = m->vy[m->cell_verts[j]];
        /* on edge j-i within eps: inside (boundary inclusive) */
        double ex = xi - xj, ey = yi - yj, l2 = ex * ex + ey * ey;
        double t = l2 > 0 ? ((x - xj) * ex + (y - yj) * ey) / l2 : 0;
        t = t < 0 ? 0 : (t > 1 ? 1 : t);
        double qx = xj + t * ex - x, qy = yj + t * ey - y;
        if (qx * qx + qy * qy <= eps * eps)
            return 1;
        /* even-odd crossing of the ray to +x */
        if ((yi > y) != (yj > y) && x < xj + (y - yj) * ex / ey)
            in = !in;
    }
    return in;
}

/* Is (*x, *y) in a cell q of N2(*c)? Then *c = q and the point is moved by
 * -shift_q (the shift brings q next to c: p in q + s <=> p - s in q). */
static int in_stencil(const mesh2d *m, ump_idx *c, double *x, double *y)
{
    for (ump_idx a = m->n2_off[*c]; a < m->n2_off[*c + 1]; a++) {
        double sx = m->n2_sx ? m->n2_sx[a] : 0, sy = m->n2_sy ? m->n2_sy[a] : 0;
        if (part_in_cell(m, m->n2[a], *x - sx, *y - sy)) {
            *c = m->n2[a];
            *x -= sx;
            *y -= sy;
            return 1;
        }
    }
    return 0;
}

/* State of the walk: current cell, face entered through (-1 at the start)
 * and its side as seen from c, and the point (wrapped across cyclics). */
typedef struct walk_state {
    ump_idx c, ef;
    int es;
    double x, y;
} walk_state;

enum { W_MOVED, W_INSIDE, W_LEFT, W_FAR, W_BUDGET };

/* One step of the walk: decide in w->c, or cross one face (if may_move). */
static int walk_step(const mesh2d *m, walk_state *w, ump_idx *face, int may_move)
{
    ump_idx c = w->c;
    double eps = part_eps(m, c, w->x, w->y);
    ump_idx bi = -1, bb = -1; /* best internal / boundary face */
    int si = 0, back = 0;
    double di = eps, db = eps;
    for (ump_idx k = m->cell_face_off[c]; k < m->cell_face_off[c + 1]; k++) {
        ump_idx f = m->cell_faces[k];
        int side = nb_side(m, c, k);
        double d = beyond(m, f, side, w->x, w->y);
        if (!(d > eps))
            continue;
        if (f == w->ef && side == w->es) {
            back = 1;
            continue;
        }
        if (f < m->ninternal) {
            if (d > di) {
                di = d;
                bi = f;
                si = side;
            }
        } else if (d > db) {
            db = d;
            bb = f;
        }
    }
    if (bi < 0) {
        if (bb >= 0) {
            /* beyond walls only. Within d_c: left, unless the point is in a
             * cell of the stencil (round a corner of the domain, cyclic
             * images included). Farther, the point may be in the domain
             * behind an obstacle: global search. */
            if (db > m->dc[c])
                return W_FAR;
            if (in_stencil(m, &w->c, &w->x, &w->y))
                return W_INSIDE;
            *face = bb;
            return W_LEFT;
        }
        if (!back || part_in_cell(m, c, w->x, w->y))
            return W_INSIDE;
        /* non-convex cell: beyond the entry face only and outside */
        bi = w->ef;
        si = w->es;
        back = 2;
    }
    if (!may_move)
        return W_BUDGET;
    if (si == 0) {
        w->c = m->neigh[bi];
        if (m->sepx) {
            w->x += m->sepx[bi];
            w->y += m->sepy[bi];
        }
    } else {
        w->c = m->owner[bi];
        if (m->sepx) {
            w->x -= m->sepx[bi];
            w->y -= m->sepy[bi];
        }
    }
    w->ef = bi;
    w->es = !si;
    /* stepped back into a non-convex cell that holds the point although
     * the point is beyond one of its face lines */
    if (back == 2 && part_in_cell(m, w->c, w->x, w->y))
        return W_INSIDE;
    return W_MOVED;
}

static int same_state(const walk_state *a, const walk_state *b)
{
    return a->c == b->c && a->ef == b->ef && a->es == b->es && a->x == b->x && a->y == b->y;
}

part_where part_walk(const mesh2d *m, ump_idx start, double *x, double *y, ump_idx *cell,
                     ump_idx *face, long budget, long *nsteps)
{
    walk_state w = {start, -1, 0, *x, *y};
    /* Brent's cycle detection: checkpoint state, refreshed at powers of 2 */
    walk_state k = {-1, -1, 0, 0, 0};
    long power = 1, lam = 0, steps = 0;
    int rc;
    *face = -1;
    for (;;) {
        rc = walk_step(m, &w, face, steps < budget);
        if (rc != W_MOVED)
            break;
        steps++;
        lam++;
        if (same_state(&w, &k)) {
            /* the walk is deterministic in its state: a cycle of length
             * lam. Non-convex cells can make the point leave the cell that
             * holds it: go round once more with polygon tests. */
            rc = W_FAR;
            for (long i = 0; i < lam; i++) {
                if (part_in_cell(m, w.c, w.x, w.y)) {
                    rc = W_INSIDE;
                    break;
                }
                if ((rc = walk_step(m, &w, face, 1)) != W_MOVED)
                    break;
                rc = W_FAR;
                steps++;
            }
            break;
        }
        if (lam == power) {
            k = w;
            power *= 2;
            lam = 0;
        }
    }
    *x = w.x;
    *y = w.y;
    *cell = w.c;
    if (nsteps)
        *nsteps = steps;
    return rc == W_INSIDE ? PART_INSIDE : rc == W_LEFT ? PART_LEFT : PART_LOST;
}

/* Global fall-back: the cell containing (x, y), or -1. */
static ump_idx search_all(const mesh2d *m, double x, double y)
{
    for (ump_idx c = 0; c < m->ncells; c++) {
        /* the centroid lies in the bounding box: |x - cx| <= dx inside */
        double eps = part_eps(m, c, x, y);
        if (fabs(x - m->cx[c]) > m->dx[c] + eps || fabs(y - m->cy[c]) > m->dy[c] + eps)
            continue;
        if (part_in_cell(m, c, x, y))
            return c;
    }
    return -1;
}

/* Boundary face nearest to (x, y) (distance to the edge segment), or -1. */
static ump_idx nearest_boundary_face(const mesh2d *m, double x, double y)
{
    ump_idx best = -1;
    double bd = INFINITY;
    for (ump_idx f = m->ninternal; f < m->nfaces; f++) {
        double ax = m->vx[m->fv0[f]], ay = m->vy[m->fv0[f]];
        double ex = m->vx[m->fv1[f]] - ax, ey = m->vy[m->fv1[f]] - ay, l2 = ex * ex + ey * ey;
        double t = l2 > 0 ? ((x - ax) * ex + (y - ay) * ey) / l2 : 0;
        t = t < 0 ? 0 : (t > 1 ? 1 : t);
        double qx = ax + t * ex - x, qy = ay + t * ey - y, d2 = qx * qx + qy * qy;
        if (d2 < bd) {
            bd = d2;
            best = f;
        }
    }
    return best;
}

part_where part_locate(const mesh2d *m, ump_idx start, double *x, double *y, ump_idx *cell,
                       ump_idx *face)
{
    *face = -1;
    *cell = -1;
    if (!isfinite(*x) || !isfinite(*y))
        return PART_LOST;
    double x0 = *x, y0 = *y, wx = x0, wy = y0;
    if (start >= 0 && start < m->ncells) {
        ump_idx c;
        part_where r = part_walk(m, start, &wx, &wy, &c, face, (long)m->ncells + 16, NULL);
        if (r != PART_LOST) {
            *x = wx;
            *y = wy;
            *cell = c;
            return r;
        }
    }
    /* the walk failed: the original point, then its image where the walk
     * ended (cyclic wraps are exact identifications, both are valid) */
    ump_idx c = search_all(m, x0, y0);
    if (c < 0 && (wx != x0 || wy != y0)) {
        c = search_all(m, wx, wy);
        if (c >= 0) {
            x0 = wx;
            y0 = wy;
        }
    }
    if (c >= 0) {
        *x = x0;
        *y = y0;
        *cell = c;
        return PART_INSIDE;
    }
    ump_idx f = nearest_boundary_face(m, x0, y0);
    if (f < 0)
        return PART_LOST;
    *face = f;
    *cell = m->owner[f];
    return PART_LEFT;
}
