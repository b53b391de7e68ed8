/* SPDX-License-Identifier: GPL-3.0-or-later
 * laplacian.h -- particle Laplacians on scattered points (module prefix lap_).
 *
 * Every model gives the implicit row of particle i as coefficients a_j over
 * its neighbours:  lap(phi)_i = sum_j a_j (phi_j - phi_i),
 * so the explicit value and the implicit matrix row (diagonal -sum_j a_j)
 * come from the same numbers.
 *   LAP_CPM  consistent particle method, Eqs. (16)-(17) of seed 000: 5x5
 *            weighted least squares with p_j = [h, k, h^2/2, hk, k^2/2],
 *            w_j = 1/r^3; a_j = w_j^2 (row 3 + row 5 of M^{-1}) . p_j.
 *            Exact for quadratic fields on any non-degenerate cloud.
 *   LAP_MPS  Koshizuka's model, Eq. (15): a_j = 2d w_j / sum_j w_j r_j^2,
 *            w = r_e/r - 1 for r < r_e (r_e = re_factor * l0).
 *   LAP_IPS  improved particle smoothing, seed 001 Eq. (20): reserved for
 *            issue 6 (lap_coeffs returns UMP_ERR_UNSUPPORTED until then).
 */
#ifndef UMPPM_LAPLACIAN_H
#define UMPPM_LAPLACIAN_H

#include "umppm/ump.h"

typedef enum { LAP_CPM, LAP_MPS, LAP_IPS } lap_model;

#define LAP_RE_FACTOR_DEFAULT 2.1
/* CPM: UMP_ERR_SINGULAR when the reciprocal 1-norm condition number of the
 * equilibrated, length-normalised moment matrix is below this. */
#define LAP_RCOND_MIN 1.0e-12

typedef struct lap_params {
    lap_model model;
    double re_factor;   /* MPS: influence radius r_e = re_factor * l0; 0 means
                           LAP_RE_FACTOR_DEFAULT (2.1), < 0 is UMP_ERR_INPUT */
} lap_params;

/* Coefficients a [n] for particle i with neighbour offsets h = x_j - x_i,
 * k = y_j - y_i [n]. l0: local particle spacing (MPS only; > 0). Fails with
 * UMP_ERR_SINGULAR when the CPM matrix is singular (fewer than 5
 * independent neighbours) or, for MPS, when no neighbour lies within r_e --
 * the caller decides the fallback. A neighbour at the position of i (CPM:
 * closer than 1e-12 of the stencil radius) gets a_j = 0. No allocation. */
ump_status lap_coeffs(const lap_params *p, const double *h, const double *k, int n, double l0,
                      double *a, ump_err *err);
/* Name of the model ("CPM", "MPS", "IPS"; "unknown" otherwise) and parse
 * (exact, case-sensitive word; -1 if unknown). */
const char *lap_name(lap_model m);
int lap_parse(const char *word);

#endif
