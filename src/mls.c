/* SPDX-License-Identifier: GPL-3.0-or-later
 * mls.c -- moving-least-squares interpolation weights, Eqs. (27)-(35) of
 * seed 000 (Ng, Sheu & Hwang 2016; Tabbara, Blacker & Belytschko 1994).
 *
 * Workload: one call per mesh face, per centroid and per particle, every
 * time step (Steps 8 and 10), with n ~ 10-40 samples from the N1 u N2
 * stencil. So: no allocation, no per-sample scratch (the weights are parked
 * in the output array c0 between the two passes), and the normal matrix is
 * assembled from the 15 distinct weighted moments sum_j w_j X^a Y^b
 * (a + b <= 4) rather than 21 separate products.
 *
 * Scale: coordinates are normalised, X = dx/x_m, Y = dy/y_m (Eq. 35's own
 * scales), so |X|, |Y| < 1 and the normal matrix does not depend on the mesh
 * size. A quadratic in (x, y) is a quadratic in (X, Y), so exactness for
 * quadratics is kept; the derivative coefficients are divided by x_m and y_m
 * on the way out (d/dx = (1/x_m) d/dX).
 *
 * The fit is linear in the data: with q_k = A^{-1} e_k,
 *   m_k = e_k^T A^{-1} B = sum_j w_j (R_j . q_k) u_j,
 * so c0_j = w_j R_j . q_0 (Eq. 32), cx_j = w_j R_j . q_1 / x_m (Eq. 33),
 * cy_j = w_j R_j . q_2 / y_m (Eq. 34).
 */
#include "umppm/mls.h"

#include "spd_small.h"

#include <math.h>

/* Powers 0..4 of X and Y. */
static void powers(double X, double Y, double xp[5], double yp[5])
{
    xp[0] = yp[0] = 1;
    for (int a = 1; a < 5; a++) {
        xp[a] = xp[a - 1] * X;
        yp[a] = yp[a - 1] * Y;
    }
}

/* Exponents (a, b) of the quadratic basis R = [1 x y xy x^2 y^2], Eq. (28);
 * the linear basis is its first three entries. */
static const int EXPX[6] = {0, 1, 0, 1, 2, 0};
static const int EXPY[6] = {0, 0, 1, 1, 0, 2};

/* Eq. (35) in normalised coordinates, clamped to [MLS_W_MIN, MLS_W_MAX]:
 * w = 1/rho - 1, rho = sqrt(X^2 + Y^2). The cap is applied through rho
 * (rho <= 1/(1 + w_max)) so a sample exactly on the target never divides
 * by zero; the floor keeps the corner samples (rho >= 1, where Eq. 35 is
 * zero or negative) in the fit with a small positive weight. The clamped
 * weight is continuous in the sample positions. */
static double weight(double X, double Y)
{
    double rho = sqrt(X * X + Y * Y);
    double w = rho <= 1 / (1 + MLS_W_MAX) ? MLS_W_MAX : 1 / rho - 1;
    return w > MLS_W_MIN ? w : MLS_W_MIN;
}

/* Solve the fit with the first nb (6 or 3) basis functions; on success write
 * the coefficients and return 1. mom[a][b] = sum_j w_j X^a Y^b. */
static int fit(int nb, double mom[5][5], const double *dx, const double *dy, int n,
               double xm, double ym, double *c0, double *cx, double *cy, double *rcond)
{
    double a[SPD_MAX][SPD_MAX];
    for (int i = 0; i < nb; i++) /* A = sum_j w_j R_j R_j^T, Eq. (30) */
        for (int j = i; j < nb; j++)
            a[i][j] = mom[EXPX[i] + EXPX[j]][EXPY[i] + EXPY[j]];
    spd_small f;
    *rcond = spd_factor_invert(&f, nb, a);
    if (*rcond < MLS_RCOND_MIN)
        return 0;
    double q0[SPD_MAX], qx[SPD_MAX], qy[SPD_MAX];
    spd_inv_column(&f, 0, q0);
    spd_inv_column(&f, 1, qx);
    spd_inv_column(&f, 2, qy);
    double ixm = 1 / xm, iym = 1 / ym;
    for (int i = 0; i < nb; i++) { /* back to physical derivatives */
        qx[i] *= ixm;
        qy[i] *= iym;
    }
    for (int j = 0; j < n; j++) {
        double X = dx[j] * ixm, Y = dy[j] * iym, w = c0[j];
        double R[6] = {1, X, Y, X * Y, X * X, Y * Y};
        double s0 = 0, sx = 0, sy = 0;
        for (int i = 0; i < nb; i++) {
            s0 += R[i] * q0[i];
            sx += R[i] * qx[i];
            sy += R[i] * qy[i];
        }
        c0[j] = w * s0; /* Eq. (32): value = m1 */
        if (cx)
            cx[j] = w * sx; /* Eq. (33): d/dx = m2 */
        if (cy)
            cy[j] = w * sy; /* Eq. (34): d/dy = m3 */
    }
    return 1;
}

mls_basis mls_weights(const double *dx, const double *dy, int n, double mean_dx, double mean_dy,
                      double *c0, double *cx, double *cy, mls_info *info)
{
    mls_info dummy;
    if (!info)
        info = &dummy;
    info->basis = MLS_NONE;
    info->rcond = 0;
    if (n <= 0)
        return MLS_NONE;

    /* x_m = max|dx_j| + mean dx, y_m likewise (Eq. 35). A non-positive or
     * non-finite mean counts as 0; a zero extent (all samples on one line
     * through the target) borrows the other one, so X, Y stay finite and the
     * degeneracy shows up as a singular normal matrix instead. */
    double mx = 0, my = 0;
    for (int j = 0; j < n; j++) {
        mx = fmax(mx, fabs(dx[j]));
        my = fmax(my, fabs(dy[j]));
    }
    double xm = mx + (mean_dx > 0 && isfinite(mean_dx) ? mean_dx : 0);
    double ym = my + (mean_dy > 0 && isfinite(mean_dy) ? mean_dy : 0);
    if (!(xm > 0))
        xm = ym > 0 ? ym : 1;
    if (!(ym > 0))
        ym = xm;

    /* Pass 1: weights (parked in c0) and moments mom[a][b], a + b <= 4. */
    double mom[5][5] = {{0}};
    double wsum = 0, ixm = 1 / xm, iym = 1 / ym;
    for (int j = 0; j < n; j++) {
        double X = dx[j] * ixm, Y = dy[j] * iym;
        double w = weight(X, Y);
        double xp[5], yp[5];
        powers(X, Y, xp, yp);
        for (int a = 0; a <= 4; a++) {
            double wx = w * xp[a];
            for (int b = 0; a + b <= 4; b++)
                mom[a][b] += wx * yp[b];
        }
        c0[j] = w;
        wsum += w;
    }

    /* Pass 2: quadratic, else linear, else Shepard (Eq. 27). */
    if (n >= MLS_MIN_QUAD && fit(6, mom, dx, dy, n, xm, ym, c0, cx, cy, &info->rcond)) {
        info->basis = MLS_QUADRATIC;
        return MLS_QUADRATIC;
    }
    if (n >= 3 && fit(3, mom, dx, dy, n, xm, ym, c0, cx, cy, &info->rcond)) {
        info->basis = MLS_LINEAR;
        return MLS_LINEAR;
    }
    /* Weighted mean: no derivative information, so cx = cy = 0. */
    for (int j = 0; j < n; j++) {
        c0[j] /= wsum;
        if (cx)
            cx[j] = 0;
        if (cy)
            cy[j] = 0;
    }
    info->basis = MLS_SHEPARD;
    info->rcond = 1;
    return MLS_SHEPARD;
}
