/* SPDX-License-Identifier: GPL-3.0-or-later
 * mls.h -- moving-least-squares interpolation from scattered samples
 * (module prefix mls_), Eqs. (27)-(35) of Ng, Sheu & Hwang (2016) [NSH16];
 * docs/METHOD.md section 3.4.
 *
 * Quadratic basis R = [1 x y xy x^2 y^2] (Eq. 28) in local coordinates
 * centred at the target point (a face centre, a centroid or a particle);
 * A = sum_j w_j R_j R_j^T (Eq. 30), B = sum_j w_j u_j R_j (Eq. 31);
 * value = m1, d/dx = m2, d/dy = m3 of A^{-1}B (Eqs. 32-34). The fit is linear
 * in the sample values, so mls_weights returns per-sample coefficients
 * (c0, cx, cy) that the caller applies to every component (u, v, T).
 * Weight (Eq. 35): w = 1/sqrt((dx/x_m)^2 + (dy/y_m)^2) - 1 with
 * x_m = max|dx_j| + mean_dx, y_m = max|dy_j| + mean_dy (mean cell extents
 * supplied by the caller). Documented departures, needed for robustness:
 *   - w is clamped to [w_min, w_max]: Eq. 35 goes negative for samples in
 *     the corners of the x_m-by-y_m box and is infinite for a sample on the
 *     target;
 *   - with fewer than MLS_MIN_QUAD samples, or when A is ill-conditioned,
 *     the linear basis [1 x y] is used; with fewer than 3 samples or a
 *     degenerate linear fit, the weighted mean (Shepard, Eq. 27) is used.
 *     mls_info says which basis was used, so the caller can log it once.
 * The scale of coordinates is normalised internally (x/x_m, y/y_m) so the
 * conditioning does not depend on the mesh size.
 */
#ifndef UMPPM_MLS_H
#define UMPPM_MLS_H

#define MLS_MIN_QUAD 8     /* samples needed for the quadratic basis */
#define MLS_MAX_SAMPLES 4096 /* sizing hint for callers' buffers; mls_weights
                                itself keeps no per-sample scratch */

/* Clamp of the Eq. 35 weight (normalised coordinates, rho = |(dx/x_m, dy/y_m)|):
 *   MLS_W_MAX: reached for rho <= 1/(1 + MLS_W_MAX), i.e. only by a sample
 *     practically on the target; the fit then reproduces that sample up to
 *     O(10/MLS_W_MAX), as Eq. 35 intends, without dividing by zero.
 *     After equilibration such a sample feeds only the constant entry of A,
 *     so the cap costs no conditioning.
 *   MLS_W_MIN: floor for rho >= 1/(1 + MLS_W_MIN) (the corners of the
 *     x_m-by-y_m box, where Eq. 35 is zero or negative: a negative weight
 *     makes A indefinite). Corner samples stay in the fit at ~2% of the
 *     weight of an edge-of-stencil sample (w ~ 0.5), which keeps A's rank
 *     when they are the only samples in some direction. The clamped weight
 *     is continuous in the sample positions. */
#define MLS_W_MAX 1.0e6
#define MLS_W_MIN 1.0e-2
/* Floor of the weight with a fixed support (mean extents passed negative):
 * samples at rho >= 1 are practically out of the fit (a sample entering or
 * leaving the caller's stencil there moves the fit by O(1e-4) of the
 * value's variation; Eq. 35's scales: O(1e-2)), yet they still keep the
 * normal matrix away from singular when the support holds few samples.
 * With a floor of 1e-8 such fits passed MLS_RCOND_MIN while resting on
 * 3-5 samples: the stably stratified rest state with `buoyancy source`
 * diverged at t = 810 s. */
#define MLS_W_CUT 1.0e-4
/* Fall back to the next smaller basis when the reciprocal 1-norm condition
 * number of the equilibrated normal matrix is below this. */
#define MLS_RCOND_MIN 1.0e-10

typedef enum { MLS_QUADRATIC = 6, MLS_LINEAR = 3, MLS_SHEPARD = 1, MLS_NONE = 0 } mls_basis;

typedef struct mls_info {
    mls_basis basis;   /* basis actually used */
    double rcond;      /* reciprocal 1-norm condition number of the equilibrated
                          normal matrix of that basis, in normalised
                          coordinates (1 for Shepard, 0 for none) */
} mls_info;

/* Coefficients for n samples at offsets (dx[j], dy[j]) from the target
 * (sample minus target). Outputs c0, cx, cy [n] (cx, cy may be NULL):
 *   value ~ sum_j c0[j] u_j,  du/dx ~ sum_j cx[j] u_j,  du/dy ~ sum_j cy[j] u_j.
 * mean_dx, mean_dy > 0: the Delta-bar of Eq. 35 (x_m = max_j |dx_j| +
 * mean_dx); both < 0: a fixed support x_m = -mean_dx, y_m = -mean_dy, the
 * same weight 1/rho - 1 floored at MLS_W_CUT (continuous in the sample
 * positions; docs/METHOD.md section 8, "MLS support"). Returns the basis used
 * (MLS_NONE only when n <= 0; outputs then untouched). With MLS_SHEPARD,
 * cx and cy are set to 0 (no derivative information). info may be NULL.
 * No allocation; any n works (see MLS_MAX_SAMPLES). */
mls_basis mls_weights(const double *dx, const double *dy, int n, double mean_dx, double mean_dy,
                      double *c0, double *cx, double *cy, mls_info *info);

/* The MLS derivative (Eqs. 33-34) of one quantity u [n] at the target,
 * with the weights, scales and fall-backs of mls_weights (Shepard: 0):
 * B = sum_j w_j u_j R_j (Eq. 31) is summed in the same pass as the
 * moments, so no per-sample coefficients are formed. Same numbers as
 * sum_j cx[j] u_j of mls_weights up to rounding. */
mls_basis mls_gradient(const double *dx, const double *dy, const double *u, int n, double mean_dx,
                       double mean_dy, double *gx, double *gy, mls_info *info);

/* ---- The full MLS derivatives of the finite particle method -----------------
 * Lu, Hu, Chang, Li & Wei, "Grid-free modelling based on the finite particle
 * method for incompressible viscous flow problems", Math. Probl. Eng. 2019
 * [LHC19], Eqs. 1-18 (docs/METHOD.md section 11). The fit at a point x:
 * Pi u(x) = b(x)^T a(x) (Eq. 1), quadratic basis b = [1 x y x^2 xy y^2]
 * (Eq. 2) centred at the target, S a = r with S = V W V^T, r = V W u
 * (Eqs. 7-12). The derivatives are those of the fit itself, with the weights'
 * dependence on x: a' = S^-1 (r' - S' a) (Eq. 14), the second derivatives
 * of Eq. 16 (written for mixed partials), assembled as Eqs. 17-18. Unlike
 * mls_weights (the "diffuse" derivative b'^T a), these are exact for
 * quadratics AND are the true derivatives of a smooth approximant.
 * Weights of the normalised distance q = d / h (h the support radius h_0):
 *   MLS_WFUN_EXP     w = exp(-1 / (q^2 - 1)^2), q < 1        Eq. 4
 *   MLS_WFUN_SPLINE  w = 1 - 6q^2 + 8q^3 - 3q^4, q < 1       Eq. 5
 * Eq. 4 is printed in the paper as exp(-(d^2 - h_0^2)^-2), which is not
 * dimensionless (it underflows to 0 for any h_0 below a metre); it is used
 * in the normalised distance, the form it has for h_0 = 1. */
typedef enum { MLS_WFUN_EXP = 4, MLS_WFUN_SPLINE = 5 } mls_wfun;

/* Outputs of mls_full, per sample: value, d/dx, d/dy, d2/dx2, d2/dxdy, d2/dy2. */
enum { MLS_C0, MLS_CX, MLS_CY, MLS_CXX, MLS_CXY, MLS_CYY, MLS_NOUT };

/* Weight w(q) of the normalised distance q and its first and second
 * derivatives w'(q), w''(q); w'(q)/q in *wq (finite at q = 0). */
void mls_wfun_eval(mls_wfun wf, double q, double *w, double *w1, double *wq, double *w2);

/* Per-sample coefficients at the target for n samples at offsets
 * (dx[j], dy[j]) (sample minus target; the target itself may be one of
 * them, at offset 0), support radius h (samples at d >= h have weight 0):
 *   d^k u / dx^a dy^b (target) ~ sum_j c[k][j] u_j, k = MLS_C0 .. MLS_CYY.
 * Any c[k] may be NULL. Falls back to the linear basis (second derivatives
 * 0) when fewer than MLS_MIN_QUAD samples have weight or the equilibrated S has a
 * reciprocal condition number below MLS_RCOND_MIN, and to Shepard (value
 * only, derivatives 0) below 3. No allocation. */
mls_basis mls_full(const double *dx, const double *dy, int n, double h, mls_wfun wf, double *const c[MLS_NOUT],
                   mls_info *info);

#endif
