/* SPDX-License-Identifier: GPL-3.0-or-later
 * lsq.c -- least-squares cell gradient, Eq. (26) of Ng, Sheu & Hwang (2016)
 * [NSH16], Section 3.2.2.1, Fig. 3 (docs/METHOD.md section 3.2).
 *
 *   grad phi_P = M_P^-1 sum_j w_j d_j (phi_j - phi_P),  M_P = sum_j w_j d_j d_j^T,
 *   d_j = (x_j + s_j) - x_P over the first neighbours j in N1(P),
 * s_j the cyclic shift of the stencil entry (zero without cyclics), and
 * w_j = 1 (Eq. 26, lsq_build) or, with lsq_build_weighted, the weights
 * w_j = 1/|d_j|^2 of OpenFOAM's leastSquares gradient (umppmFoam's
 * anisotropicCells; docs/METHOD.md section 8, "Anisotropic cells"): on a
 * cell stretched 199:1 the unweighted fit turns the curvature of p along
 * the long side into a gradient across the short one, of order
 * h_long^2 / h_short (a pressure uniform along a row gave dp/dx = -564);
 * weighted, that error is of order h_short. lsq_build_walls also takes
 * the boundary faces it is given as samples at their centres that carry
 * the owner's value (a zeroGradient face in OpenFOAM's leastSquares; for
 * the mesh velocity of Eq. 36 with anisotropicCells, docs/METHOD.md
 * section 8, "Walls in the correction"): such a gradient is exact for
 * linear fields along the walls, not across them.
 * M_P depends only on the mesh (Step 3 of the algorithm): lsq_build stores
 * g_j = M_P^-1 d_j per stencil entry once, and lsq_gradient is then one
 * pass over the stencil, allocation-free. The gradient is exact for fields
 * linear in x (and periodic fields' linear parts on cyclic meshes).
 *
 * Distances are taken relative to the cell size d_c before M_P is formed
 * and inverted, so the singularity test is scale-free: M_P is refused when
 * det(M) <= LSQ_DET_MIN * trace(M)^2 (all neighbours on one line through
 * P, e.g. a cell in a one-cell-wide channel).
 */
#include "umppm/lsq.h"

#include <math.h>
#include <stdlib.h>

#define LSQ_DET_MIN 1e-10

void lsq_free(lsq_grad **pg)
{
    if (!pg || !*pg)
        return;
    free((*pg)->wx);
    free((*pg)->wy);
    free(*pg);
    *pg = NULL;
}

ump_status lsq_build(const mesh2d *m, lsq_grad **out, ump_err *err)
{
    return lsq_build_weighted(m, 0, out, err);
}

ump_status lsq_build_weighted(const mesh2d *m, int weighted, lsq_grad **out, ump_err *err)
{
    return lsq_build_walls(m, weighted, NULL, out, err);
}

ump_status lsq_build_walls(const mesh2d *m, int weighted, const unsigned char *walls, lsq_grad **out,
                           ump_err *err)
{
    *out = NULL;
    lsq_grad *g = ump_alloc_array(1, sizeof *g);
    UMP_CHECK(g, err, UMP_ERR_NOMEM, "lsq: out of memory");
    size_t nst = (size_t)m->n1_off[m->ncells];
    g->m = m;
    g->wx = ump_alloc_array(nst, sizeof *g->wx);
    g->wy = ump_alloc_array(nst, sizeof *g->wy);
    if (!g->wx || !g->wy) {
        lsq_free(&g);
        return UMP_FAIL(err, UMP_ERR_NOMEM, "lsq: out of memory for %zu stencil weights", nst);
    }
    for (ump_idx c = 0; c < m->ncells; c++) {
        double h = m->dc[c] > 0 ? m->dc[c] : 1.0; /* scale: distances in units of d_c */
        double mxx = 0, mxy = 0, myy = 0;
        for (ump_idx k = m->n1_off[c]; k < m->n1_off[c + 1]; k++) {
            ump_idx j = m->n1[k];
            double dx = (m->cx[j] + (m->n1_sx ? m->n1_sx[k] : 0.0) - m->cx[c]) / h;
            double dy = (m->cy[j] + (m->n1_sy ? m->n1_sy[k] : 0.0) - m->cy[c]) / h;
            double r2 = dx * dx + dy * dy;
            if (!(r2 > 0)) {
                lsq_free(&g);
                return UMP_FAIL(err, UMP_ERR_INPUT,
                                "%s: cells %d and %d have the same centroid (%g, %g): no least-squares "
                                "gradient (Eq. 26)",
                                m->pm && m->pm->dir ? m->pm->dir : "mesh", (int)c, (int)j, m->cx[c], m->cy[c]);
            }
            double w = weighted ? 1 / r2 : 1.0; /* w_j = 1/|d_j|^2 or 1 */
            mxx += w * dx * dx;                 /* M_P = sum_j w_j d_j d_j^T, Eq. 26 */
            mxy += w * dx * dy;
            myy += w * dy * dy;
        }
        /* walls: boundary faces where phi has the owner's value (zero normal
         * gradient), as OpenFOAM's leastSquares takes a zeroGradient face:
         * d_f = x_f - x_P with phi_f - phi_P = 0, so the face adds to M_P
         * and nothing to the sum (lsq_gradient is unchanged) */
        for (ump_idx a = walls ? m->cell_face_off[c] : 0; walls && a < m->cell_face_off[c + 1]; a++) {
            ump_idx f = m->cell_faces[a];
            if (f < m->ninternal || !walls[f - m->ninternal])
                continue;
            double dx = (m->fx[f] - m->cx[c]) / h, dy = (m->fy[f] - m->cy[c]) / h;
            double w = weighted ? 1 / (dx * dx + dy * dy) : 1.0;
            mxx += w * dx * dx;
            mxy += w * dx * dy;
            myy += w * dy * dy;
        }
        double det = mxx * myy - mxy * mxy, tr = mxx + myy;
        if (!(tr > 0) || !(det > LSQ_DET_MIN * tr * tr)) {
            ump_idx nn = m->n1_off[c + 1] - m->n1_off[c];
            lsq_free(&g);
            return UMP_FAIL(err, UMP_ERR_INPUT,
                            "%s: least-squares gradient (Eq. 26) of cell %d at (%g, %g) is singular: "
                            "its %d vertex neighbours lie on one line",
                            m->pm && m->pm->dir ? m->pm->dir : "mesh", (int)c, m->cx[c], m->cy[c],
                            (int)nn);
        }
        double ixx = myy / det, ixy = -mxy / det, iyy = mxx / det; /* M_P^-1 */
        for (ump_idx k = m->n1_off[c]; k < m->n1_off[c + 1]; k++) {
            ump_idx j = m->n1[k];
            double dx = (m->cx[j] + (m->n1_sx ? m->n1_sx[k] : 0.0) - m->cx[c]) / h;
            double dy = (m->cy[j] + (m->n1_sy ? m->n1_sy[k] : 0.0) - m->cy[c]) / h;
            /* g_k = w_k M_P^-1 d_k, back in physical units: 1/h from w d/h
             * (w in units of 1/h^2, M dimensionless) */
            double w = weighted ? 1 / (dx * dx + dy * dy) : 1.0;
            g->wx[k] = w * (ixx * dx + ixy * dy) / h;
            g->wy[k] = w * (ixy * dx + iyy * dy) / h;
        }
    }
    *out = g;
    return UMP_OK;
}

void lsq_gradient(const lsq_grad *g, const double *restrict phi, double *restrict gx,
                  double *restrict gy)
{
    const mesh2d *m = g->m;
    for (ump_idx c = 0; c < m->ncells; c++) {
        double sx = 0, sy = 0, pc = phi[c];
        for (ump_idx k = m->n1_off[c]; k < m->n1_off[c + 1]; k++) {
            double d = phi[m->n1[k]] - pc;  /* phi_j - phi_P */
            sx += g->wx[k] * d;             /* grad phi_P = sum_k g_k (phi_j - phi_P) */
            sy += g->wy[k] * d;
        }
        gx[c] = sx;
        gy[c] = sy;
    }
}
