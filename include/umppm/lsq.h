/* SPDX-License-Identifier: GPL-3.0-or-later
 * lsq.h -- least-squares cell gradient on the pressure mesh, Eq. (26) of
 * Ng, Sheu & Hwang (2016) [NSH16] (module prefix lsq_).
 *
 *   grad phi_P = M_P^{-1} sum_j w_j (x_j - x_P)(phi_j - phi_P),
 *   M_P = sum_j w_j (x_j - x_P)(x_j - x_P)^T,
 * w_j = 1 as Eq. 26, or 1/|x_j - x_P|^2 (OpenFOAM's leastSquares weights,
 * for stretched cells; lsq.c),
 * over the first-neighbour stencil N1(P) of mesh2d (cells sharing a vertex,
 * Fig. 3), with cyclic shifts. M_P^{-1} depends only on the mesh (Step 3):
 * lsq_build stores, per stencil entry k of cell P, the weight vector
 * g_k = w_k M_P^{-1} (x_j - x_P), so grad phi_P = sum_k g_k (phi_j - phi_P):
 * a linear operator the PPE assembly can expand (Eq. 25).
 */
#ifndef UMPPM_LSQ_H
#define UMPPM_LSQ_H

#include "umppm/mesh2d.h"

typedef struct lsq_grad {
    const mesh2d *m;   /* borrowed */
    double *wx, *wy;   /* [m->n1_off[ncells]], aligned with m->n1 */
} lsq_grad;

/* Fails (UMP_ERR_INPUT) if some M_P is singular (all neighbours collinear). */
ump_status lsq_build(const mesh2d *m, lsq_grad **out, ump_err *err); /* w_j = 1, Eq. 26 */
/* weighted != 0: w_j = 1/|d_j|^2; 0: lsq_build. */
ump_status lsq_build_weighted(const mesh2d *m, int weighted, lsq_grad **out, ump_err *err);
/* The same, with the boundary faces f flagged in walls [nfaces - ninternal]
 * (walls[f - ninternal] != 0) as samples at the face centre that carry the
 * owner's value (zero normal gradient; OpenFOAM's leastSquares at a
 * zeroGradient face): they enter M_P only, so lsq_gradient applies as it
 * is. walls NULL: lsq_build_weighted. */
ump_status lsq_build_walls(const mesh2d *m, int weighted, const unsigned char *walls, lsq_grad **out,
                           ump_err *err);
void lsq_free(lsq_grad **g);
/* gx, gy [ncells] = gradient of phi [ncells] (stride 1). */
void lsq_gradient(const lsq_grad *g, const double *phi, double *gx, double *gy);

#endif
