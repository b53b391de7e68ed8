/* SPDX-License-Identifier: GPL-3.0-or-later
 * mls.c -- moving-least-squares interpolation weights, Eqs. (27)-(35) of
 * [NSH16] (Ng, Sheu & Hwang 2016; Tabbara, Blacker & Belytschko 1994).
 *
 * Workload: one call per mesh face and per centroid every time step
 * (Step 8), with n ~ 10-40 samples from the N1 u N2 stencil. So: no
 * allocation, no per-sample scratch (the weights are parked in the output
 * array c0 between the two passes), the normal matrix is assembled from
 * the 15 distinct weighted moments sum_j w_j X^a Y^b (a + b <= 4), summed
 * in one unrolled pass (14 products and 15 additions per sample), the 6x6
 * inverse comes from the triangular factor (spd_small.h), and value-only
 * fits (cx == NULL) skip the derivative dot products.
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
#include "umppm/ump.h"

#include "spd_small.h"

#include <math.h>

/* Eq. (35) in normalised coordinates, clamped to [wmin, MLS_W_MAX]
 * (wmin: MLS_W_MIN with Eq. 35's scales, MLS_W_CUT with a fixed support):
 * w = 1/rho - 1, rho = sqrt(X^2 + Y^2). A sample on the target (rho = 0,
 * 1/rho = inf) and every rho <= 1/(1 + w_max) get the cap, so nothing
 * divides by zero; the floor keeps the corner samples (rho >= 1, where
 * Eq. 35 is zero or negative) in the fit with a small positive weight. The
 * clamped weight is continuous in the sample positions. Written with
 * conditional expressions (minsd/maxsd), not fmin/fmax calls. */
static inline double weight(double X, double Y, double wmin)
{
    double w = 1 / sqrt(X * X + Y * Y) - 1;
    w = w < MLS_W_MAX ? w : MLS_W_MAX;
    return w > wmin ? w : wmin;
}

/* The 15 weighted moments sum_j w_j X^a Y^b, a + b <= 4, by degree:
 * m[0] = 1; m[1..2] = X, Y; m[3..5] = XX, XY, YY; m[6..9] = XXX, XXY, XYY,
 * YYY; m[10..14] = X^4, X^3Y, X^2Y^2, XY^3, Y^4. */
enum { M1, MX, MY, MXX, MXY, MYY, MXXX, MXXY, MXYY, MYYY, MX4, MX3Y, MX2Y2, MXY3, MY4, NMOM };

/* Normal matrix of the first nb basis functions R = [1 X Y XY X^2 Y^2]
 * (Eq. 28), A = sum_j w_j R_j R_j^T (Eq. 30), from the moments; its
 * inverse and reciprocal condition number. Returns 1 if usable. */
static inline __attribute__((always_inline)) int factor(int nb, const double *m, spd_small *f, double *rcond)
{
    double a[SPD_MAX][SPD_MAX];
    a[0][0] = m[M1];  a[0][1] = m[MX];  a[0][2] = m[MY];
    a[1][1] = m[MXX]; a[1][2] = m[MXY]; a[2][2] = m[MYY];
    if (nb == 6) {
        a[0][3] = m[MXY];  a[0][4] = m[MXX];  a[0][5] = m[MYY];
        a[1][3] = m[MXXY]; a[1][4] = m[MXXX]; a[1][5] = m[MXYY];
        a[2][3] = m[MXYY]; a[2][4] = m[MXXY]; a[2][5] = m[MYYY];
        a[3][3] = m[MX2Y2]; a[3][4] = m[MX3Y]; a[3][5] = m[MXY3];
        a[4][4] = m[MX4]; a[4][5] = m[MX2Y2]; a[5][5] = m[MY4];
        *rcond = spd_factor_invert_fixed(f, 6, a);
    } else {
        *rcond = spd_factor_invert_fixed(f, 3, a);
    }
    return *rcond >= MLS_RCOND_MIN;
}

/* Per-sample coefficients from the columns q0 (value), qx, qy (derivatives,
 * already divided by x_m, y_m) of A^{-1}: c_j = w_j R_j . q (Eqs. 32-34).
 * The weights are parked in c0 on entry. */
static inline __attribute__((always_inline)) void coeffs6(const double *restrict dx, const double *restrict dy, int n, double ixm, double iym,
                    const double *q0, const double *qx, const double *qy, double *restrict c0,
                    double *restrict cx, double *restrict cy)
{
    if (!cx && !cy) {
#pragma omp simd
        for (int j = 0; j < n; j++) {
            double X = dx[j] * ixm, Y = dy[j] * iym;
            c0[j] *= q0[0] + X * q0[1] + Y * q0[2] + X * Y * q0[3] + X * X * q0[4] + Y * Y * q0[5];
        }
        return;
    }
    if (cx && cy) { /* the usual derivative fit: no branch in the loop */
#pragma omp simd
        for (int j = 0; j < n; j++) {
            double X = dx[j] * ixm, Y = dy[j] * iym, XY = X * Y, XX = X * X, YY = Y * Y, w = c0[j];
            c0[j] = w * (q0[0] + X * q0[1] + Y * q0[2] + XY * q0[3] + XX * q0[4] + YY * q0[5]); /* Eq. 32 */
            cx[j] = w * (qx[0] + X * qx[1] + Y * qx[2] + XY * qx[3] + XX * qx[4] + YY * qx[5]); /* Eq. 33 */
            cy[j] = w * (qy[0] + X * qy[1] + Y * qy[2] + XY * qy[3] + XX * qy[4] + YY * qy[5]); /* Eq. 34 */
        }
        return;
    }
    for (int j = 0; j < n; j++) {
        double X = dx[j] * ixm, Y = dy[j] * iym, XY = X * Y, XX = X * X, YY = Y * Y, w = c0[j];
        c0[j] = w * (q0[0] + X * q0[1] + Y * q0[2] + XY * q0[3] + XX * q0[4] + YY * q0[5]);
        if (cx)
            cx[j] = w * (qx[0] + X * qx[1] + Y * qx[2] + XY * qx[3] + XX * qx[4] + YY * qx[5]);
        if (cy)
            cy[j] = w * (qy[0] + X * qy[1] + Y * qy[2] + XY * qy[3] + XX * qy[4] + YY * qy[5]);
    }
}

static inline __attribute__((always_inline)) void coeffs3(const double *dx, const double *dy, int n, double ixm, double iym,
                    const double *q0, const double *qx, const double *qy, double *c0, double *cx,
                    double *cy)
{
    for (int j = 0; j < n; j++) {
        double X = dx[j] * ixm, Y = dy[j] * iym, w = c0[j];
        c0[j] = w * (q0[0] + X * q0[1] + Y * q0[2]);
        if (cx)
            cx[j] = w * (qx[0] + X * qx[1] + Y * qx[2]);
        if (cy)
            cy[j] = w * (qy[0] + X * qy[1] + Y * qy[2]);
    }
}

/* Columns 0, 1, 2 of A^{-1} (value, d/dX, d/dY), the latter two scaled to
 * physical derivatives (d/dx = (1/x_m) d/dX). */
static inline __attribute__((always_inline)) void columns(const spd_small *f, int nb, double ixm, double iym, double *q0, double *qx,
                    double *qy)
{
    spd_inv_column(f, 0, q0);
    spd_inv_column(f, 1, qx);
    spd_inv_column(f, 2, qy);
    for (int i = 0; i < nb; i++) {
        qx[i] *= ixm;
        qy[i] *= iym;
    }
}

/* Eq. 35's scales 1/x_m, 1/y_m: x_m = max|dx_j| + mean dx, y_m likewise. A
 * non-positive or non-finite mean counts as 0; a zero extent (all samples
 * on one line through the target) borrows the other one, so X, Y stay
 * finite and the degeneracy shows up as a singular normal matrix instead.
 * Both means negative: a fixed support, x_m = -mean_dx, y_m = -mean_dy
 * (docs/METHOD.md section 8, "MLS support"), and the weight floor
 * MLS_W_CUT. Returns the floor. */
static inline __attribute__((always_inline)) double scales(const double *restrict dx, const double *restrict dy,
                                                           int n, double mean_dx, double mean_dy, double *ixm,
                                                           double *iym)
{
    if (mean_dx < 0 && mean_dy < 0 && mean_dx > -INFINITY && mean_dy > -INFINITY) {
        *ixm = -1 / mean_dx;
        *iym = -1 / mean_dy;
        return MLS_W_CUT;
    }
    double mx = 0, my = 0;
#pragma omp simd reduction(max : mx, my)
    for (int j = 0; j < n; j++) {
        double ax = fabs(dx[j]), ay = fabs(dy[j]);
        mx = ax > mx ? ax : mx;
        my = ay > my ? ay : my;
    }
    double xm = mx + (mean_dx > 0 && mean_dx < INFINITY ? mean_dx : 0);
    double ym = my + (mean_dy > 0 && mean_dy < INFINITY ? mean_dy : 0);
    if (!(xm > 0))
        xm = ym > 0 ? ym : 1;
    if (!(ym > 0))
        ym = xm;
    *ixm = 1 / xm;
    *iym = 1 / ym;
    return MLS_W_MIN;
}

/* Eq. 35's scales and pass 1: weights (parked in w) and the 15 moments. */
static inline __attribute__((always_inline)) void prepare(const double *restrict dx, const double *restrict dy, int n, double mean_dx,
                    double mean_dy, double *restrict w, double *m, double *pixm, double *piym)
{
    double ixm, iym;
    double wmin = scales(dx, dy, n, mean_dx, mean_dy, &ixm, &iym);
    /* scalar accumulators: they stay in registers */
    double s1 = 0, sx = 0, sy = 0, sxx = 0, sxy = 0, syy = 0, sxxx = 0, sxxy = 0, sxyy = 0, syyy = 0,
           sx4 = 0, sx3y = 0, sx2y2 = 0, sxy3 = 0, sy4 = 0;
    /* omp simd: two (or more) samples per instruction; the partial sums
     * are combined in an order fixed at compile time, so every run and any
     * thread count gives the same bits */
#pragma omp simd reduction(+ : s1, sx, sy, sxx, sxy, syy, sxxx, sxxy, sxyy, syyy, sx4, sx3y, sx2y2, sxy3, sy4)
    for (int j = 0; j < n; j++) {
        double X = dx[j] * ixm, Y = dy[j] * iym;
        double wj = weight(X, Y, wmin);
        double wx = wj * X, wy = wj * Y;
        double wxx = wx * X, wxy = wx * Y, wyy = wy * Y;
        double wxxx = wxx * X, wxxy = wxx * Y, wxyy = wxy * Y, wyyy = wyy * Y;
        s1 += wj;
        sx += wx;
        sy += wy;
        sxx += wxx;
        sxy += wxy;
        syy += wyy;
        sxxx += wxxx;
        sxxy += wxxy;
        sxyy += wxyy;
        syyy += wyyy;
        sx4 += wxxx * X;
        sx3y += wxxx * Y;
        sx2y2 += wxxy * Y;
        sxy3 += wxyy * Y;
        sy4 += wyyy * Y;
        w[j] = wj;
    }
    m[M1] = s1;
    m[MX] = sx;
    m[MY] = sy;
    m[MXX] = sxx;
    m[MXY] = sxy;
    m[MYY] = syy;
    m[MXXX] = sxxx;
    m[MXXY] = sxxy;
    m[MXYY] = sxyy;
    m[MYYY] = syyy;
    m[MX4] = sx4;
    m[MX3Y] = sx3y;
    m[MX2Y2] = sx2y2;
    m[MXY3] = sxy3;
    m[MY4] = sy4;
    *pixm = ixm;
    *piym = iym;
}

/* Compiled twice, for AVX2 and for baseline x86-64, chosen at load time
 * (target_clones, an ifunc): the omp simd loops of the inlined helpers
 * run 4 samples wide where the CPU has AVX2 (Step 8: 25 % less time).
 * The partial sums then combine in another fixed order, so results
 * differ between the two kinds of CPU by rounding only, and never
 * between runs or thread counts on one machine. */
UMP_TARGET_CLONES
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
    /* Pass 1: weights (parked in c0) and the 15 moments, unrolled. */
    double m[NMOM], ixm, iym;
    prepare(dx, dy, n, mean_dx, mean_dy, c0, m, &ixm, &iym);

    /* Pass 2: quadratic, else linear, else Shepard (Eq. 27). */
    spd_small f;
    double q0[SPD_MAX], qx[SPD_MAX], qy[SPD_MAX];
    if (n >= MLS_MIN_QUAD && factor(6, m, &f, &info->rcond)) {
        columns(&f, 6, ixm, iym, q0, qx, qy);
        coeffs6(dx, dy, n, ixm, iym, q0, qx, qy, c0, cx, cy);
        info->basis = MLS_QUADRATIC;
        return MLS_QUADRATIC;
    }
    if (n >= 3 && factor(3, m, &f, &info->rcond)) {
        columns(&f, 3, ixm, iym, q0, qx, qy);
        coeffs3(dx, dy, n, ixm, iym, q0, qx, qy, c0, cx, cy);
        info->basis = MLS_LINEAR;
        return MLS_LINEAR;
    }
    /* Weighted mean: no derivative information, so cx = cy = 0. */
    double wsum = m[M1];
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

/* AVX2 and baseline clones, as mls_weights. */
UMP_TARGET_CLONES
mls_basis mls_gradient(const double *restrict dx, const double *restrict dy, const double *restrict u, int n,
                       double mean_dx, double mean_dy, double *gx, double *gy, mls_info *info)
{
    mls_info dummy;
    if (!info)
        info = &dummy;
    info->basis = MLS_NONE;
    info->rcond = 0;
    *gx = *gy = 0;
    if (n <= 0)
        return MLS_NONE;
    double ixm, iym;
    double wmin = scales(dx, dy, n, mean_dx, mean_dy, &ixm, &iym);
    /* one pass: the moments of A (Eq. 30) and B = sum_j w_j u_j R_j (Eq. 31) */
    double s1 = 0, sx = 0, sy = 0, sxx = 0, sxy = 0, syy = 0, sxxx = 0, sxxy = 0, sxyy = 0, syyy = 0,
           sx4 = 0, sx3y = 0, sx2y2 = 0, sxy3 = 0, sy4 = 0;
    double b0 = 0, b1 = 0, b2 = 0, b3 = 0, b4 = 0, b5 = 0;
#pragma omp simd reduction(+ : s1, sx, sy, sxx, sxy, syy, sxxx, sxxy, sxyy, syyy, sx4, sx3y, sx2y2, sxy3, sy4, \
                               b0, b1, b2, b3, b4, b5)
    for (int j = 0; j < n; j++) {
        double X = dx[j] * ixm, Y = dy[j] * iym;
        double wj = weight(X, Y, wmin);
        double wx = wj * X, wy = wj * Y;
        double wxx = wx * X, wxy = wx * Y, wyy = wy * Y;
        double wxxx = wxx * X, wxxy = wxx * Y, wxyy = wxy * Y, wyyy = wyy * Y;
        s1 += wj;
        sx += wx;
        sy += wy;
        sxx += wxx;
        sxy += wxy;
        syy += wyy;
        sxxx += wxxx;
        sxxy += wxxy;
        sxyy += wxyy;
        syyy += wyyy;
        sx4 += wxxx * X;
        sx3y += wxxx * Y;
        sx2y2 += wxxy * Y;
        sxy3 += wxyy * Y;
        sy4 += wyyy * Y;
        double uj = u[j];
        b0 += wj * uj;
        b1 += wx * uj;
        b2 += wy * uj;
        b3 += wxy * uj;
        b4 += wxx * uj;
        b5 += wyy * uj;
    }
    double m[NMOM] = {s1, sx, sy, sxx, sxy, syy, sxxx, sxxy, sxyy, syyy, sx4, sx3y, sx2y2, sxy3, sy4};
    double B[6] = {b0, b1, b2, b3, b4, b5};
    spd_small f;
    int nb = 0;
    if (n >= MLS_MIN_QUAD && factor(6, m, &f, &info->rcond))
        nb = 6;
    else if (n >= 3 && factor(3, m, &f, &info->rcond))
        nb = 3;
    if (!nb) { /* Shepard: no derivative information */
        info->basis = MLS_SHEPARD;
        info->rcond = 1;
        return MLS_SHEPARD;
    }
    /* (m2, m3) = rows 1, 2 of A^{-1} B (Eqs. 33-34), A^{-1} = S inv S */
    double q1[SPD_MAX], q2[SPD_MAX];
    spd_inv_column(&f, 1, q1); /* A^{-1} is symmetric: column = row */
    spd_inv_column(&f, 2, q2);
    double m2 = 0, m3 = 0;
    for (int i = 0; i < nb; i++) {
        m2 += q1[i] * B[i];
        m3 += q2[i] * B[i];
    }
    *gx = m2 * ixm;
    *gy = m3 * iym;
    info->basis = nb == 6 ? MLS_QUADRATIC : MLS_LINEAR;
    return info->basis;
}

/* ---- The full derivatives of the fit: [LHC19] Eqs. 1-18 ------------------- */

void mls_wfun_eval(mls_wfun wf, double q, double *w, double *w1, double *wq, double *w2)
{
    *w = *w1 = *wq = *w2 = 0;
    if (!(q < 1))
        return;
    if (wf == MLS_WFUN_SPLINE) {
        /* Eq. 5: w = 1 - 6q^2 + 8q^3 - 3q^4 = (1 - q)^3 (1 + 3q), in the
         * factored form: positive for every q < 1 (the expanded sum
         * cancels to rounding, even to <= 0, near q = 1, where w'' is
         * not negligible); w' = -12 q (1 - q)^2, w'' = -12 (1 - q)(1 - 3q) */
        double r = 1 - q;
        *w = r * r * r * (1 + 3 * q);
        *wq = -12 * r * r;
        *w1 = q * *wq;
        *w2 = -12 * r * (1 - 3 * q);
        return;
    }
    /* Eq. 4 in q: w = exp(-s^-2), s = q^2 - 1 < 0; w' = 4 q w / s^3,
     * w'' = w (4/s^3 + 16 q^2/s^6 - 24 q^2/s^4). Below s^2 = 1e-3, w <
     * e^-1000 = 0 in double precision and its derivatives too. */
    double s = q * q - 1, s2 = s * s;
    if (s2 < 1e-3)
        return;
    double e = exp(-1 / s2), s3 = s2 * s;
    *w = e;
    *wq = 4 * e / s3;
    *w1 = q * *wq;
    *w2 = e * (4 / s3 + 16 * q * q / (s3 * s3) - 24 * q * q / (s2 * s2));
}

/* The weight of sample (X, Y) (normalised offset from the target) and its
 * derivatives with respect to the evaluation point, at the target:
 * d = |x - x_j|, dq/dX = -X/q, so w_X = -w' X/q and
 * w_XY = w'' X Y/q^2 + (w'/q)(delta - X Y/q^2). wd[0..5]: w, w_X, w_Y,
 * w_XX, w_XY, w_YY. */
static inline void wderiv(mls_wfun wf, double X, double Y, double wd[6])
{
    double q = sqrt(X * X + Y * Y), w, w1, wq, w2;
    mls_wfun_eval(wf, q, &w, &w1, &wq, &w2);
    wd[0] = w;
    wd[1] = -wq * X;
    wd[2] = -wq * Y;
    if (q > 0) {
        double a = (w2 - wq) / (q * q); /* w''/q^2 - (w'/q)/q^2 */
        wd[3] = a * X * X + wq;
        wd[4] = a * X * Y;
        wd[5] = a * Y * Y + wq;
    } else { /* w'(0) = 0 for both weights: the limit is w''(0) delta */
        wd[3] = wd[5] = w2;
        wd[4] = 0;
    }
}

/* Basis b = [1 X Y X^2 XY Y^2] (Eq. 2) of a normalised offset. */
static inline void basis(double X, double Y, double b[6])
{
    b[0] = 1;
    b[1] = X;
    b[2] = Y;
    b[3] = X * X;
    b[4] = X * Y;
    b[5] = Y * Y;
}

/* y = A x for the nb x nb symmetric matrix stored as its upper triangle. */
static inline void symv(int nb, double a[6][6], const double *x, double *y)
{
    for (int i = 0; i < nb; i++) {
        double t = 0;
        for (int k = 0; k < nb; k++)
            t += (k >= i ? a[i][k] : a[k][i]) * x[k];
        y[i] = t;
    }
}

static inline double dot(int nb, const double *a, const double *b)
{
    double t = 0;
    for (int k = 0; k < nb; k++)
        t += a[k] * b[k];
    return t;
}

mls_basis mls_full(const double *dx, const double *dy, int n, double h, mls_wfun wf, double *const c[MLS_NOUT],
                   mls_info *info)
{
    if (info) {
        info->basis = MLS_NONE;
        info->rcond = 0;
    }
    if (n <= 0)
        return MLS_NONE;
    const double ih = 1 / h;
    /* S and its derivatives S_a (a = X, Y, XX, XY, YY): S_a = sum w_a b b^T
     * (Eqs. 10, 13, 15), upper triangles of the quadratic basis */
    double S[6][6][6]; /* upper triangles, from mom below */
    int nw = 0;
    double wsum = 0;
    /* the 21 products b_i b_k are 15 monomials X^p Y^q, p + q <= 4: the
     * moments of those (mom[monomial][a]), then S */
    double mom[15][6] = {{0}};
    for (int j = 0; j < n; j++) {
        double X = dx[j] * ih, Y = dy[j] * ih, wd[6];
        if (!(X * X + Y * Y < 1))
            continue; /* beyond the support: no weight (mls_wfun_eval) */
        wderiv(wf, X, Y, wd);
        if (wd[0] <= 0)
            continue;
        nw++;
        wsum += wd[0];
        double X2 = X * X, Y2 = Y * Y, XY = X * Y;
        const double mono[15] = {1, X, Y, X2, XY, Y2, X2 * X, X2 * Y, XY * Y, Y2 * Y,
                                 X2 * X2, X2 * XY, X2 * Y2, XY * Y2, Y2 * Y2};
        for (int m = 0; m < 15; m++)
#pragma omp simd
            for (int a = 0; a < 6; a++)
                mom[m][a] += mono[m] * wd[a];
    }
    /* monomial of b_i b_k, b = [1 X Y X^2 XY Y^2] */
    static const unsigned char mk[6][6] = {{0, 1, 2, 3, 4, 5},     {1, 3, 4, 6, 7, 8},
                                           {2, 4, 5, 7, 8, 9},     {3, 6, 7, 10, 11, 12},
                                           {4, 7, 8, 11, 12, 13},  {5, 8, 9, 12, 13, 14}};
    for (int a = 0; a < 6; a++)
        for (int i = 0; i < 6; i++)
            for (int k = i; k < 6; k++)
                S[a][i][k] = mom[mk[i][k]][a];
    /* the quadratic basis on MLS_MIN_QUAD samples or more, as mls_weights:
     * on 6 or 7 the fit interpolates, and at the thin tip of a jet on a
     * wall its gradient was up to 6.7 m/s per step of pressure correction
     * (a particle ejected from the dam break's front; docs/METHOD.md 11) */
    int nb = nw >= MLS_MIN_QUAD ? 6 : nw >= 3 ? 3 : nw >= 1 ? 1 : 0;
    spd_small f;
    double rcond = 0;
    while (nb > 1) {
        double a[SPD_MAX][SPD_MAX];
        for (int i = 0; i < nb; i++)
            for (int k = i; k < nb; k++)
                a[i][k] = S[0][i][k];
        rcond = spd_factor_invert(&f, nb, a);
        if (rcond >= MLS_RCOND_MIN)
            break;
        nb = nb == 6 ? 3 : 1;
    }
    if (info) {
        info->basis = (mls_basis)nb;
        info->rcond = nb == 1 ? 1 : rcond;
    }
    if (nb <= 1) {
        /* Shepard (Eq. 27 of mls_weights): value only */
        for (int j = 0; j < n; j++) {
            double wd[6];
            wderiv(wf, dx[j] * ih, dy[j] * ih, wd);
            if (c[MLS_C0])
                c[MLS_C0][j] = nw ? wd[0] / wsum : 1.0 / n;
            for (int k = 1; k < MLS_NOUT; k++)
                if (c[k])
                    c[k][j] = 0;
        }
        return nw ? MLS_SHEPARD : MLS_NONE;
    }
    /* M = S^-1 (unscaled); m0 = M e0 (Eq. 12 at the target, b = e0);
     * g_a = M (b_a - S_a m0) (Eq. 14 contracted with b);
     * h_ab = M (b_ab - S_ab m0 - S_b g_a - S_a g_b) (Eq. 16 contracted) */
    double M[6][6] = {{0}};
    for (int i = 0; i < nb; i++)
        for (int k = 0; k < nb; k++)
            M[i][k] = f.s[i] * f.inv[i < k ? i : k][i < k ? k : i] * f.s[k];
    double m0[6], g[2][6], hh[3][6], t[6], t2[6];
    for (int i = 0; i < nb; i++)
        m0[i] = M[i][0];
    for (int a = 0; a < 2; a++) {
        symv(nb, S[1 + a], m0, t);
        for (int i = 0; i < nb; i++)
            t[i] = (i == 1 + a ? 1.0 : 0.0) - t[i];
        for (int i = 0; i < nb; i++)
            g[a][i] = dot(nb, M[i], t);
    }
    /* second derivatives: pairs (a, b) = (X, X), (X, Y), (Y, Y); b_XX = 2 e3,
     * b_XY = e4, b_YY = 2 e5 */
    static const int pa[3] = {0, 0, 1}, pb[3] = {0, 1, 1};
    for (int q = 0; q < 3; q++) {
        for (int i = 0; i < 6; i++)
            hh[q][i] = 0;
        if (nb < 6)
            continue; /* the linear basis has no curvature */
        symv(nb, S[3 + q], m0, t);
        for (int i = 0; i < nb; i++)
            t[i] = (i == 3 + q ? (q == 1 ? 1.0 : 2.0) : 0.0) - t[i];
        symv(nb, S[1 + pb[q]], g[pa[q]], t2);
        for (int i = 0; i < nb; i++)
            t[i] -= t2[i];
        symv(nb, S[1 + pa[q]], g[pb[q]], t2);
        for (int i = 0; i < nb; i++)
            t[i] -= t2[i];
        for (int i = 0; i < nb; i++)
            hh[q][i] = dot(nb, M[i], t);
    }
    /* per sample (Eqs. 17-18): c0 = w m0.b; c_a = w g_a.b + w_a m0.b;
     * c_ab = w h_ab.b + w_a g_b.b + w_b g_a.b + w_ab m0.b; then back to
     * physical units (d/dx = d/dX / h) */
    const double s1 = ih, s2 = ih * ih;
    for (int j = 0; j < n; j++) {
        double X = dx[j] * ih, Y = dy[j] * ih, wd[6] = {0}, b[6];
        if (X * X + Y * Y < 1) /* as in the moments */
            wderiv(wf, X, Y, wd);
        if (wd[0] <= 0) /* as in the moments: no weight, no part in the fit */
            wd[0] = wd[1] = wd[2] = wd[3] = wd[4] = wd[5] = 0;
        basis(X, Y, b);
        double mb = dot(nb, m0, b), gb[2] = {dot(nb, g[0], b), dot(nb, g[1], b)};
        if (c[MLS_C0])
            c[MLS_C0][j] = wd[0] * mb;
        if (c[MLS_CX])
            c[MLS_CX][j] = s1 * (wd[0] * gb[0] + wd[1] * mb);
        if (c[MLS_CY])
            c[MLS_CY][j] = s1 * (wd[0] * gb[1] + wd[2] * mb);
        for (int q = 0; q < 3; q++) {
            double *cq = c[MLS_CXX + q];
            if (!cq)
                continue;
            if (nb < 6) {
                cq[j] = 0;
                continue;
            }
            int a = pa[q], bq = pb[q];
            cq[j] = s2 * (wd[0] * dot(nb, hh[q], b) + wd[1 + a] * gb[bq] + wd[1 + bq] * gb[a] + wd[3 + q] * mb);
        }
    }
    return (mls_basis)nb;
}
