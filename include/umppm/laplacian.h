/* SPDX-License-Identifier: GPL-3.0-or-later
 * laplacian.h -- particle Laplacians on scattered points in 1, 2 and 3
 * dimensions (module prefix lap_).
 *
 * Every model gives the implicit row of particle i as coefficients a_j over
 * its neighbours:  lap(phi)_i = sum_j a_j (phi_j - phi_i),
 * so the explicit value and the implicit matrix row (diagonal -sum_j a_j)
 * come from the same numbers. Offsets x_j - x_i are given per dimension.
 *   LAP_CPM  consistent particle method, Eqs. (16)-(17) of Ng, Sheu & Hwang (2016) [NSH16]:
 *            weighted least squares over the second-order Taylor basis
 *            (2, 5, 9 terms in 1-, 2-, 3-D), w_j = 1/r^3. Exact for
 *            quadratic fields on any non-degenerate cloud.
 *   LAP_CPM4 the same fit over the fourth-order Taylor basis (2-D only,
 *            14 terms), same weights: exact for quartic fields, so the
 *            quadratic fit's O(h^2) truncation error (the quartic terms it
 *            leaves in the second derivatives) is gone. Needs 14 distinct
 *            neighbours spread in 2-D; not in the papers (docs/METHOD.md
 *            section 8, "CPM4").
 *   LAP_MPS  Koshizuka's model, [NSH16] Eq. (15):
 *            a_j = 2d w_j / sum_j w_j r_j^2.
 *   LAP_PS   particle smoothing, Hwang, Ng & Sheu (2016) [HNS16] Eq. (2):
 *            a_j = 2d (w_j / r_j^2) / sum_j w_j.
 *   LAP_IPS  improved particle smoothing, [HNS16] Eqs. (15)-(20), (24),
 *            (26)-(27): PS minus its artificial convection, with the
 *            gradient from the d x d system of Eq. (18). Exact for linear
 *            fields; quadratics see the effective diffusivity of Eq. (22).
 * MPS, PS and IPS use the kernel w = max(r_e/r - 1, 0) ([HNS16] Eq. 3)
 * with r_e = re_factor * l0. MPS and PS differ only in the weighting
 * (PS is MPS with the kernel w/r^2), and both are inconsistent on irregular
 * clouds: the first moment makes a linear field's Laplacian O(1/l0).
 */
#ifndef UMPPM_LAPLACIAN_H
#define UMPPM_LAPLACIAN_H

#include "umppm/ump.h"

typedef enum { LAP_CPM, LAP_MPS, LAP_IPS, LAP_PS, LAP_CPM4 } lap_model;

#define LAP_MAX_DIM 3
/* Default r_e / l0: 2.1 for MPS (Koshizuka), 2.0 for PS and IPS ([HNS16],
 * "r_e = 2 delta"). */
#define LAP_RE_FACTOR_DEFAULT 2.1
#define LAP_RE_FACTOR_PS_DEFAULT 2.0
/* CPM and IPS: UMP_ERR_SINGULAR when the reciprocal 1-norm condition number
 * of the equilibrated, length-normalised moment matrix is below this. */
#define LAP_RCOND_MIN 1.0e-12

typedef struct lap_params {
    lap_model model;
    double re_factor;   /* MPS, PS, IPS: influence radius r_e = re_factor *
                           l0; 0 means the model's default, < 0 is
                           UMP_ERR_INPUT; CPM ignores it */
} lap_params;

/* Coefficients a [n] for particle i in dim dimensions (1..3); off[d][j] is
 * the offset x_j - x_i along axis d. l0: local particle spacing (MPS, PS,
 * IPS; > 0). Fails with UMP_ERR_SINGULAR when the CPM or IPS moment matrix
 * is singular (too few neighbours or all on a line/plane) or, for the
 * kernel models, when no neighbour lies within r_e -- the caller decides
 * the fallback. A neighbour at the position of i gets a_j = 0.
 * No allocation. */
ump_status lap_coeffs_d(const lap_params *p, int dim, const double *const *off, int n, double l0,
                        double *a, ump_err *err);
/* The 2-D form: offsets h = x_j - x_i, k = y_j - y_i. */
ump_status lap_coeffs(const lap_params *p, const double *h, const double *k, int n, double l0,
                      double *a, ump_err *err);

/* The 2-D form with a metric for anisotropic stencils: CPM fits in the
 * coordinates (sx h, sy k), so its weights 1/r^3 measure distance in units
 * of the local cell extents when sx, sy are their inverses (any common
 * factor cancels); the row is still the physical phi_xx + phi_yy, exact
 * for quadratics. sx = sy gives lap_coeffs' CPM row (up to rounding). The
 * kernel models ignore the metric. */
ump_status lap_coeffs_metric(const lap_params *p, const double *h, const double *k, int n, double l0,
                             double sx, double sy, double *a, ump_err *err);

/* Positive rows (docs/METHOD.md section 8, "Anisotropic cells", "Positive
 * rows"): when the negative coefficients of the row a [n] (from
 * lap_coeffs_metric, offsets h, k, metric sx, sy) add up to more than tau
 * times the positive ones,
 * a is replaced by the non-negative row closest to CPM's consistency
 * conditions (exact for quadratics where a positive such row exists), so
 * the implicit predictor keeps a maximum principle; between tau and
 * 2 tau the row is blended from a to that row (continuous in the
 * offsets; tau <= 0: always the positive row). Returns 1 if a was
 * replaced, 0 if kept (also for n > 256 or no finite offsets). No
 * allocation. */
int lap_positive_row(const double *h, const double *k, int n, double sx, double sy, double tau, double *a);

/* CPM (2-D, metric sx, sy as lap_coeffs_metric) with zero-gradient samples
 * (docs/METHOD.md section 8, "Zero-gradient walls in the Laplacian"):
 * sample j with (nx[j], ny[j]) != 0 is a point of a zero-gradient boundary
 * with that unit normal; it enters the fit as the row d phi/dn = 0 and
 * gets a_j = 0, so the row is implicit in the other samples only. nx, ny
 * NULL: lap_coeffs_metric's CPM row (up to rounding; a neighbour at the
 * particle's own position is left out here, where lap_coeffs_metric falls
 * back to its isotropic general loop). UMP_ERR_SINGULAR if
 * the samples do not determine the five derivatives. */
ump_status lap_cpm_neumann(const double *h, const double *k, const double *nx, const double *ny, int n,
                           double sx, double sy, double *a, ump_err *err);

/* lap_positive_row for a row of lap_cpm_neumann: the zero-gradient
 * samples' multipliers are free in sign and their a_j stay 0. */
int lap_positive_row_neumann(const double *h, const double *k, const double *nx, const double *ny, int n,
                             double sx, double sy, double tau, double *a);

/* The explicit value: sum_j a_j (phi_j - phi_i) over a row a [n] from
 * lap_coeffs_d / lap_coeffs, neighbour values phij [n]. */
double lap_value(const double *a, const double *phij, double phii, int n);

/* Modified-equation moments of a Laplacian row a [n]: what it gives for the
 * fields x_d and x_d x_e / 2, i.e. lap(phi) = first . grad phi +
 * second : grad grad phi + ...
 *   first[d] = sum_j a_j off_d,  second = sum_j a_j off_d off_e / 2 stored
 *   as a symmetric tensor xx xy xz yy yz zz (OpenFOAM's order; unused
 *   components 0). A consistent Laplacian has first = 0, second = I. */
void lap_moments(int dim, const double *const *off, int n, const double *a, double first[3],
                 double second[6]);

/* Particle-distribution quality of [HNS16], independent of the model used
 * in the flow: the artificial velocity u_N of PS (Eqs. 13-14: PS applied to
 * x, y, z) and the effective diffusivity tau of IPS (Eqs. 22-23: IPS
 * applied to x_d x_e / 2), both with r_e = re_factor * l0 (re_factor 0:
 * 2.0). work [n] is scratch. Same failures as lap_coeffs_d for PS / IPS. */
typedef struct lap_quality {
    double uN[3];       /* artificial velocity, Eq. 13 */
    double tau[6];      /* effective diffusivity xx xy xz yy yz zz, Eq. 22 */
} lap_quality;
ump_status lap_quality_d(double re_factor, int dim, const double *const *off, int n, double l0,
                         double *work, lap_quality *q, ump_err *err);

/* The influence-radius factor a model uses (its default when p->re_factor
 * is 0). */
double lap_re_factor(const lap_params *p);
/* Name of the model ("CPM", "MPS", "IPS", "PS"; "unknown" otherwise) and
 * parse (exact, case-sensitive word; -1 if unknown). */
const char *lap_name(lap_model m);
int lap_parse(const char *word);

#endif
