/* SPDX-License-Identifier: GPL-3.0-or-later
 * laplacian.c -- Laplacian models on scattered particles in 1-3 D: Section
 * 3.2.1 of [NSH16] (Ng, Sheu & Hwang 2016) and [HNS16] (Hwang, Ng &
 * Sheu 2016).
 *
 * Every model returns the implicit row lap(phi)_i = sum_j a_j (phi_j - phi_i)
 * (Eq. 14 of [NSH16] is solved implicitly), so the explicit value and the
 * matrix row come from the same numbers.
 *
 * CPM (Koh et al.; [NSH16] Eqs. 16-17). Taylor expansion to second order,
 *   phi_j - phi_i ~ p_j . D,  p_j = [x_d ..., x_d^2/2 or x_d x_e ...],
 * (2-D: p_j = [h, k, h^2/2, hk, k^2/2], D = [phi_x, phi_y, phi_xx, phi_xy,
 * phi_yy]) fitted by weighted least squares with weights w_j^2, w_j = 1/r^3:
 *   D = M^{-1} sum_j w_j^2 p_j (phi_j - phi_i),  M = sum_j w_j^2 p_j p_j^T,
 * and lap = sum of the x_d^2/2 components of D, hence
 * a_j = w_j^2 (sum of those rows of M^{-1}) . p_j.
 * Exact for quadratic fields on any cloud where M is non-singular.
 * Conditioning: offsets are divided by a local length L (the largest
 * neighbour distance). With hat quantities X = x/L, p_hat = D_L p,
 * w_hat = L^3 w, one finds M_hat = L^6 D_L M D_L and a_hat_j = L^2 a_j, so
 * a_j = a_hat_j / L^2. M_hat is then equilibrated (spd_small.h) and its
 * condition number decides singularity.
 *
 * Kernel models, w = max(r_e/r - 1, 0) ([HNS16] Eq. 3), d = dimension:
 *   MPS (Koshizuka; [NSH16] Eq. 15): a_j = 2d w_j / sum_j w_j r_j^2.
 *   PS  (Zhang; [HNS16] Eq. 2):      a_j = 2d (w_j / r_j^2) / Omega_0,
 *       Omega_0 = sum_j w_j (Eq. 5 with p = q = r = 0).
 * Both are exact for quadratics on symmetric lattices only. On an irregular
 * cloud the first moment Omega_2^(1,0) = sum_j w_j h_j / r_j^2 does not
 * vanish, so PS adds the artificial convection u_N phi_x (Eqs. 10, 13) of
 * size O(1/l0): the error grows as the cloud is refined.
 *   IPS ([HNS16] Eq. 15): subtract that term with a gradient that is exact
 *       for linear fields, from G <grad phi> = Phi_2^(1) (Eq. 18; 2-D Eq. 19,
 *       3-D Eq. 27), G_de = sum_j w_j x_d x_e / r_j^2:
 *   lap = 2d/Omega_0 [Phi_2^(0) - Omega_2^(1) . G^{-1} Phi_2^(1)]  (Eq. 20,
 *       1-D Eq. 24, 3-D Eq. 26), i.e. with c = G^{-1} Omega_2^(1),
 *   a_j = 2d (w_j / r_j^2) (1 - c . x_j) / Omega_0.
 * IPS is exact for linear fields; for quadratics it leaves the effective
 * diffusivity tau of Eq. (22) instead of the identity.
 */
#include "umppm/laplacian.h"

#include "spd_small.h"

#include <math.h>
#include <string.h>

/* Neighbours closer than this fraction of L coincide with particle i: their
 * p_j is zero, so they carry no information (and w_j = 1/r^3 would be
 * infinite). They get a_j = 0. */
#define CPM_COINCIDENT 1e-12

/* Second-order Taylor basis in dim dimensions: the dim linear terms, then
 * for d <= e: x_d^2/2 (d == e) or x_d x_e. Its size; the positions of the
 * x_d^2/2 terms go to diag[dim] when diag is not NULL. */
static int taylor_basis(int dim, const double *x, double *p, int *diag)
{
    int m = 0;
    for (int d = 0; d < dim; d++)
        p[m++] = x[d];
    for (int d = 0; d < dim; d++)
        for (int e = d; e < dim; e++) {
            if (d == e && diag)
                diag[d] = m;
            p[m++] = d == e ? 0.5 * x[d] * x[d] : x[d] * x[e];
        }
    return m;
}

static double dist2(int dim, const double *const *off, int j)
{
    double r2 = 0;
    for (int d = 0; d < dim; d++)
        r2 += off[d][j] * off[d][j];
    return r2;
}

static ump_status cpm_coeffs(int dim, const double *const *off, int n, double *a, ump_err *err)
{
    double r2max = 0;
    for (int j = 0; j < n; j++)
        r2max = fmax(r2max, dist2(dim, off, j));
    if (!(r2max > 0) || !isfinite(r2max))
        return UMP_FAIL(err, UMP_ERR_SINGULAR,
                        "CPM Laplacian: %d neighbours, none at a finite non-zero distance", n);
    double L = sqrt(r2max);
    double rmin2 = CPM_COINCIDENT * CPM_COINCIDENT;
    int need = dim + dim * (dim + 1) / 2, diag[LAP_MAX_DIM];

    /* CPM moment matrix, Eq. 17: M = sum_j w_j^2 p_j p_j^T (hat units). */
    double m[SPD_MAX][SPD_MAX] = {{0}};
    int nused = 0;
    for (int j = 0; j < n; j++) {
        double X[LAP_MAX_DIM], p[SPD_MAX], r2 = 0;
        for (int d = 0; d < dim; d++) {
            X[d] = off[d][j] / L;
            r2 += X[d] * X[d];
        }
        if (r2 < rmin2)
            continue;
        double w2 = 1 / (r2 * r2 * r2); /* w_j^2 = 1/r^6 */
        taylor_basis(dim, X, p, NULL);
        for (int r = 0; r < need; r++) {
            double wp = w2 * p[r];
            for (int c = r; c < need; c++)
                m[r][c] += wp * p[c];
        }
        nused++;
    }
    if (nused < need)
        return UMP_FAIL(err, UMP_ERR_SINGULAR,
                        "CPM Laplacian: %d distinct neighbours, at least %d needed in %d-D", nused,
                        need, dim);
    spd_small f;
    double rc = spd_factor_invert(&f, need, m);
    if (rc < LAP_RCOND_MIN)
        return UMP_FAIL(err, UMP_ERR_SINGULAR,
                        "CPM Laplacian: moment matrix singular (rcond %.3g, %d neighbours "
                        "not spread in %d-D)", rc, nused, dim);

    /* q = M^{-1} sum_d e_{x_d^2/2}: the rows of the second derivatives, Eq. 16. */
    double q[SPD_MAX] = {0}, col[SPD_MAX], p[SPD_MAX];
    taylor_basis(dim, (double[LAP_MAX_DIM]){0}, p, diag);
    for (int d = 0; d < dim; d++) {
        spd_inv_column(&f, diag[d], col);
        for (int r = 0; r < need; r++)
            q[r] += col[r];
    }
    double il2 = 1 / r2max; /* a_j = a_hat_j / L^2 */
    for (int j = 0; j < n; j++) {
        double X[LAP_MAX_DIM], r2 = 0;
        for (int d = 0; d < dim; d++) {
            X[d] = off[d][j] / L;
            r2 += X[d] * X[d];
        }
        if (r2 < rmin2) {
            a[j] = 0;
            continue;
        }
        double w2 = 1 / (r2 * r2 * r2), s = 0;
        taylor_basis(dim, X, p, NULL);
        for (int r = 0; r < need; r++)
            s += q[r] * p[r];
        a[j] = w2 * s * il2;
    }
    return UMP_OK;
}

/* cpm_coeffs for 2-D, the solver's case, written out: the moment matrix of
 * p = [h, k, h^2/2, hk, k^2/2] (hat units) is assembled from the 12
 * weighted moments S_ab = sum_j w_j^2 h^a k^b, 2 <= a + b <= 4, and only
 * the one combined column q = M^{-1} (e_hh + e_kk) is applied (Eq. 16:
 * lap = phi_xx + phi_yy). Same numbers as the generic loop up to rounding.
 * Metric (sx, sy): the fit is made in the coordinates (sx h, sy k), so the
 * weights w_j = 1/r_j^3 measure distance in that metric, and the Laplacian
 * is sx^2 phi_XX + sy^2 phi_YY there (q = M^{-1} (sx^2 e_hh + sy^2 e_kk));
 * with sx = sy = 1 it is the plain fit. Still exact for quadratics. */
static inline __attribute__((always_inline)) ump_status cpm_coeffs2(const double *restrict h, const double *restrict k, int n,
                                                                    double sx, double sy, double *restrict a,
                                                                    ump_err *err)
{
    double r2max = 0, r2min = INFINITY;
#pragma omp simd reduction(max : r2max) reduction(min : r2min)
    for (int j = 0; j < n; j++) {
        double hs = sx * h[j], ks = sy * k[j], r2 = hs * hs + ks * ks;
        r2max = r2 > r2max ? r2 : r2max;
        r2min = r2 < r2min ? r2 : r2min;
    }
    if (!(r2max > 0) || !(r2max < INFINITY))
        return UMP_FAIL(err, UMP_ERR_SINGULAR,
                        "CPM Laplacian: %d neighbours, none at a finite non-zero distance", n);
    double iL = 1 / sqrt(r2max), rmin2 = CPM_COINCIDENT * CPM_COINCIDENT;
    if (r2min * (iL * iL) < rmin2) { /* a coincident neighbour: the general loop handles it
                                        (isotropic weights: exact for quadratics too) */
        const double *off[2] = {h, k};
        return cpm_coeffs(2, off, n, a, err);
    }
    enum { S20, S11, S02, S30, S21, S12, S03, S40, S31, S22, S13, S04, NS };
    double S[NS];
    int nused = 0;
    double s20 = 0, s11 = 0, s02 = 0, s30 = 0, s21 = 0, s12 = 0, s03 = 0, s40 = 0, s31 = 0, s22 = 0, s13 = 0,
           s04 = 0;
    /* branch-free, so that it vectorises (omp simd; a fixed summation
     * order, the same bits for any thread count); coincident neighbours
     * went to the general loop above */
#pragma omp simd reduction(+ : s20, s11, s02, s30, s21, s12, s03, s40, s31, s22, s13, s04)
    for (int j = 0; j < n; j++) {
        double X = sx * h[j] * iL, Y = sy * k[j] * iL, r2 = X * X + Y * Y;
        double w2 = 1 / (r2 * r2 * r2); /* w_j^2 = 1/r^6 */
        double wx = w2 * X, wy = w2 * Y;
        double wxx = wx * X, wxy = wx * Y, wyy = wy * Y;
        double wxxx = wxx * X, wxxy = wxx * Y, wxyy = wxy * Y, wyyy = wyy * Y;
        s20 += wxx;
        s11 += wxy;
        s02 += wyy;
        s30 += wxxx;
        s21 += wxxy;
        s12 += wxyy;
        s03 += wyyy;
        s40 += wxxx * X;
        s31 += wxxx * Y;
        s22 += wxxy * Y;
        s13 += wxyy * Y;
        s04 += wyyy * Y;
        a[j] = w2; /* parked until q is known */
    }
    nused = n; /* no coincident neighbour here */
    S[S20] = s20, S[S11] = s11, S[S02] = s02, S[S30] = s30, S[S21] = s21, S[S12] = s12, S[S03] = s03;
    S[S40] = s40, S[S31] = s31, S[S22] = s22, S[S13] = s13, S[S04] = s04;
    if (nused < 5)
        return UMP_FAIL(err, UMP_ERR_SINGULAR,
                        "CPM Laplacian: %d distinct neighbours, at least 5 needed in 2-D", nused);
    /* M = sum_j w_j^2 p_j p_j^T, Eq. 17 (upper triangle) */
    double m[SPD_MAX][SPD_MAX];
    m[0][0] = S[S20];       m[0][1] = S[S11];       m[0][2] = 0.5 * S[S30];
    m[0][3] = S[S21];       m[0][4] = 0.5 * S[S12];
    m[1][1] = S[S02];       m[1][2] = 0.5 * S[S21]; m[1][3] = S[S12];
    m[1][4] = 0.5 * S[S03];
    m[2][2] = 0.25 * S[S40]; m[2][3] = 0.5 * S[S31]; m[2][4] = 0.25 * S[S22];
    m[3][3] = S[S22];        m[3][4] = 0.5 * S[S13];
    m[4][4] = 0.25 * S[S04];
    spd_small f;
    double rc = spd_factor_invert_fixed(&f, 5, m);
    if (rc < LAP_RCOND_MIN)
        return UMP_FAIL(err, UMP_ERR_SINGULAR,
                        "CPM Laplacian: moment matrix singular (rcond %.3g, %d neighbours "
                        "not spread in 2-D)", rc, nused);
    /* q = M^{-1} (sx^2 e_2 + sy^2 e_4): the rows of phi_xx and phi_yy, Eq. 16 */
    double q[5], c2[5], c4[5];
    spd_inv_column(&f, 2, c2);
    spd_inv_column(&f, 4, c4);
    for (int r = 0; r < 5; r++)
        q[r] = sx * sx * c2[r] + sy * sy * c4[r];
    double il2 = 1 / r2max; /* a_j = a_hat_j / L^2 */
#pragma omp simd
    for (int j = 0; j < n; j++) {
        double X = sx * h[j] * iL, Y = sy * k[j] * iL;
        double s = q[0] * X + q[1] * Y + q[2] * 0.5 * X * X + q[3] * X * Y + q[4] * 0.5 * Y * Y;
        a[j] *= s * il2;
    }
    return UMP_OK;
}

/* ---- Zero normal gradients in the fit -------------------------------------
 * A zero-gradient boundary (an adiabatic wall for T) has no value of its
 * own: the solver gave its boundary particle T_P + grad T_P . d_t from the
 * previous step, a Dirichlet value in the implicit row. Next to such a
 * wall on a thin cell that value carries almost the whole row (dt kappa
 * a_b ~ 1 600 on the wall cells of a box graded 200:1, against 7.5 for the
 * particles along the wall), so the particle was held at the lagged
 * value and the diffusion along the wall all but stopped (README,
 * "Zero-gradient walls in the Laplacian"). Here such a sample is a
 * derivative row of the fit instead, d phi/dn (x_b) = 0 in the same Taylor
 * basis: q_b = nu_X [1, 0, X, Y, 0] + nu_Y [0, 1, 0, X, Y], nu the normal
 * in the hat metric (unit), weighted w_b^2 r_b^2 = 1/r_b^4 (a derivative
 * row times a length, so that it weighs like a value row). It enters M
 * (Eq. 17) and not the right-hand side, so its coefficient is 0 and the
 * row is implicit in the particles alone: exact for quadratics whose
 * normal derivative vanishes at the Neumann samples. */
static void neumann_q(double X, double Y, double nX, double nY, double *q)
{
    q[0] = nX;
    q[1] = nY;
    q[2] = nX * X;
    q[3] = nX * Y + nY * X;
    q[4] = nY * Y;
}

/* the normal (nx, ny) in the hat metric of (sx, sy), unit; 0 if none */
static int hat_normal(double nx, double ny, double sx, double sy, double *nX, double *nY)
{
    /* d/dn = nx d/dx + ny d/dy = (nx sx) d/dX + (ny sy) d/dY (times 1/L) */
    double a = nx * sx, b = ny * sy, r = hypot(a, b);
    if (!(r > 0))
        return 0;
    *nX = a / r;
    *nY = b / r;
    return 1;
}

ump_status lap_cpm_neumann(const double *h, const double *k, const double *nx, const double *ny, int n,
                           double sx, double sy, double *a, ump_err *err)
{
    UMP_CHECK(sx > 0 && sy > 0 && isfinite(sx) && isfinite(sy), err, UMP_ERR_INPUT,
              "Laplacian: metric (%g, %g), expected finite and > 0", sx, sy);
    double r2max = 0;
    for (int j = 0; j < n; j++) {
        double X = sx * h[j], Y = sy * k[j];
        r2max = fmax(r2max, X * X + Y * Y);
    }
    if (!(r2max > 0) || !isfinite(r2max))
        return UMP_FAIL(err, UMP_ERR_SINGULAR,
                        "CPM Laplacian: %d neighbours, none at a finite non-zero distance", n);
    double iL = 1 / sqrt(r2max), rmin2 = CPM_COINCIDENT * CPM_COINCIDENT;
    double m[SPD_MAX][SPD_MAX] = {{0}};
    int nval = 0, nneu = 0;
    for (int j = 0; j < n; j++) {
        double X = sx * h[j] * iL, Y = sy * k[j] * iL, r2 = X * X + Y * Y, p[5], nX, nY, w2;
        if (r2 < rmin2)
            continue;
        if (nx && hat_normal(nx[j], ny[j], sx, sy, &nX, &nY)) {
            neumann_q(X, Y, nX, nY, p);
            w2 = 1 / (r2 * r2); /* w^2 r^2 */
            nneu++;
        } else {
            p[0] = X, p[1] = Y, p[2] = 0.5 * X * X, p[3] = X * Y, p[4] = 0.5 * Y * Y;
            w2 = 1 / (r2 * r2 * r2); /* w_j^2 = 1/r^6 */
            nval++;
        }
        for (int r = 0; r < 5; r++)
            for (int c = r; c < 5; c++)
                m[r][c] += w2 * p[r] * p[c];
    }
    if (nval + nneu < 5 || nval < 1)
        return UMP_FAIL(err, UMP_ERR_SINGULAR,
                        "CPM Laplacian: %d neighbours and %d zero-gradient samples, at least 5 needed "
                        "in 2-D", nval, nneu);
    spd_small f;
    double rc = spd_factor_invert_fixed(&f, 5, m);
    if (rc < LAP_RCOND_MIN)
        return UMP_FAIL(err, UMP_ERR_SINGULAR,
                        "CPM Laplacian: moment matrix singular (rcond %.3g, %d neighbours and %d "
                        "zero-gradient samples not spread in 2-D)", rc, nval, nneu);
    double q[5], c2[5], c4[5]; /* M^{-1} (sx^2 e_2 + sy^2 e_4), Eq. 16 */
    spd_inv_column(&f, 2, c2);
    spd_inv_column(&f, 4, c4);
    for (int r = 0; r < 5; r++)
        q[r] = sx * sx * c2[r] + sy * sy * c4[r];
    for (int j = 0; j < n; j++) {
        double X = sx * h[j] * iL, Y = sy * k[j] * iL, r2 = X * X + Y * Y, nX, nY;
        if (r2 < rmin2 || (nx && hat_normal(nx[j], ny[j], sx, sy, &nX, &nY))) {
            a[j] = 0; /* d phi/dn = 0 there: nothing on the right-hand side */
            continue;
        }
        double s = q[0] * X + q[1] * Y + q[2] * 0.5 * X * X + q[3] * X * Y + q[4] * 0.5 * Y * Y;
        a[j] = s / (r2 * r2 * r2) / r2max; /* a_j = w_j^2 p_j . q / L^2 */
    }
    return UMP_OK;
}

/* ---- Positive rows -------------------------------------------------------
 * A CPM row (Eqs. 16-17) is exact for quadratics, but its coefficients a_j
 * may be negative, and then the implicit predictor (Eq. 14) is not an
 * M-matrix: no maximum principle, and the viscous step can create velocity
 * where there is none. On uniform lattices the negative part is below 1e-3
 * of the positive one; on graded meshes (cells stretched 100:1 and more,
 * one-sided stencils) it reaches the positive part, and u* overshoots the
 * lid speed from rest. The positive row replaces such a row by the
 * non-negative coefficients that come closest to the same consistency
 * conditions, sum_j a_j p_j = (0, 0, 1, 0, 1) (p_j = [h, k, h^2/2, hk,
 * k^2/2]), in the least-squares sense with a small penalty on far
 * neighbours (the idea of Seibold's minimal positive stencils, B. Seibold,
 * "Minimal positive stencils in meshfree finite difference methods for the
 * Poisson equation", Comput. Methods Appl. Mech. Engrg. 198 (2008)
 * 592-601, solved here as a non-negative least-squares problem rather than
 * a linear programme):
 *   min ||C a - b||^2 + lam^2 sum_j (r_j^3 a_j)^2   subject to a >= 0,
 * C the 5 x n matrix of the p_j in the row's metric, hat units (offsets
 * divided by the largest, like CPM). Where a positive stencil consistent
 * to second order exists it is found (to lam); where none exists (a
 * particle at a wall with every neighbour on one side) the row keeps the
 * consistency it can with positive weights. Between tau and 2 tau the
 * row is the blend (1 - w) CPM + w positive, w = share/tau - 1, so the
 * row is continuous in the offsets. Lawson-Hanson's active-set
 * algorithm (C. L. Lawson, R. J. Hanson, Solving Least Squares Problems,
 * 1974, Ch. 23); each passive-set solve is 5 x 5 by the Woodbury identity
 * (D + C^T C)^{-1} C^T b = D^{-1} C^T (I + C D^{-1} C^T)^{-1} b with D =
 * lam^2 diag(r^6), r_j^2 floored at LAP_POS_RMIN^2 (below). No
 * allocation; rows with more than LAP_POS_MAX neighbours are left as they
 * are. */
#define LAP_POS_MAX 256
#define LAP_POS_LAM 1e-3
/* The penalty's distance floor, in hat units (the stencil's radius is 1).
 * With d_j = lam^2 r_j^6 unfloored, a neighbour at 4e-4 of the radius
 * (2e-6 from the particle whose row it is, in a cell 1.5e-5 thin: the
 * 8 x 8 cavity graded 3 000:1 toward its walls) put entries of 4e19 beside
 * the identity of I + C D^-1 C^T; its Cholesky factor failed, the row was
 * left as CPM's, whose negatives cost the implicit row all diagonal
 * dominance (2 dt nu sum max(-a_j, 0) up to 2e7), and the predictor turned
 * velocities within [-0.4, 1] into u* = 5.2 x the lid speed in one step
 * (README, "Positive rows that failed"). Floored at 1 % of the radius the
 * entries stay below about 1e10 and no solve failed on those meshes; the
 * neighbours nearer than that are equally cheap. */
#define LAP_POS_RMIN 1e-2

/* the passive-set solve: z_j = (C^T y)_j / d_j on the passive set,
 * y = (I + C_P D_P^{-1} C_P^T)^{-1} b; z_j = 0 elsewhere */
static int pos_solve(int n, const double (*p)[5], const double *d, const unsigned char *pas, const double *b,
                     double *z)
{
    double m[SPD_MAX][SPD_MAX] = {{0}};
    for (int r = 0; r < 5; r++)
        m[r][r] = 1;
    for (int j = 0; j < n; j++) {
        if (!pas[j])
            continue;
        double id = 1 / d[j];
        for (int r = 0; r < 5; r++)
            for (int c = r; c < 5; c++)
                m[r][c] += p[j][r] * p[j][c] * id;
    }
    spd_small f;
    if (!(spd_factor_invert_fixed(&f, 5, m) > 0))
        return -1;
    double y[5], col[5];
    for (int r = 0; r < 5; r++)
        y[r] = 0;
    for (int c = 0; c < 5; c++) {
        spd_inv_column(&f, c, col);
        for (int r = 0; r < 5; r++)
            y[r] += col[r] * b[c];
    }
    for (int j = 0; j < n; j++) {
        z[j] = 0;
        if (pas[j])
            z[j] = (p[j][0] * y[0] + p[j][1] * y[1] + p[j][2] * y[2] + p[j][3] * y[3] + p[j][4] * y[4]) / d[j];
    }
    return 0;
}

static int positive_row(const double *h, const double *k, const double *nx, const double *ny, int n, double sx,
                        double sy, double tau, double *a)
{
    if (n <= 0 || n > LAP_POS_MAX)
        return 0;
    double sp = 0, sn = 0;
    for (int j = 0; j < n; j++) {
        if (a[j] > 0)
            sp += a[j];
        else
            sn -= a[j];
    }
    if (!(sn > tau * sp))
        return 0;
    double p[LAP_POS_MAX][5], d[LAP_POS_MAX], z[LAP_POS_MAX], x[LAP_POS_MAX], g[LAP_POS_MAX];
    unsigned char pas[LAP_POS_MAX], fre[LAP_POS_MAX];
    double r2max = 0;
    for (int j = 0; j < n; j++) {
        double X = sx * h[j], Y = sy * k[j];
        r2max = fmax(r2max, X * X + Y * Y);
    }
    if (!(r2max > 0) || !isfinite(r2max))
        return 0;
    double iL = 1 / sqrt(r2max);
    /* targets in hat units: lap = sx^2 phi_XX + sy^2 phi_YY in the metric,
     * scaled by s2 so that the larger is 1 */
    double s2 = fmax(sx * sx, sy * sy), b[5] = {0, 0, sx * sx / s2, 0, sy * sy / s2};
    int nfree = 0;
    for (int j = 0; j < n; j++) {
        double X = sx * h[j] * iL, Y = sy * k[j] * iL, r2 = X * X + Y * Y, nX, nY;
        p[j][0] = X, p[j][1] = Y, p[j][2] = 0.5 * X * X, p[j][3] = X * Y, p[j][4] = 0.5 * Y * Y;
        double r2f = fmax(r2, LAP_POS_RMIN * LAP_POS_RMIN);
        d[j] = LAP_POS_LAM * LAP_POS_LAM * (r2 > 0 ? r2f * r2f * r2f : 1e300);
        x[j] = 0;
        pas[j] = 0;
        fre[j] = 0;
        if (nx && r2 > 0 && hat_normal(nx[j], ny[j], sx, sy, &nX, &nY)) {
            /* a zero-gradient sample (lap_cpm_neumann): its multiplier
             * of q_b r_b has either sign and multiplies a zero */
            double r = sqrt(r2);
            neumann_q(X, Y, nX, nY, p[j]);
            for (int c = 0; c < 5; c++)
                p[j][c] *= r;
            pas[j] = fre[j] = 1;
            nfree++;
        }
    }
    if (nfree > 0) { /* start from the best fit by the free multipliers alone */
        if (pos_solve(n, (const double (*)[5])p, d, pas, b, z))
            return 0;
        for (int j = 0; j < n; j++)
            x[j] = fre[j] ? z[j] : 0;
    }
    /* Lawson-Hanson */
    for (int it = 0; it < 3 * n; it++) {
        double res[5];
        for (int r = 0; r < 5; r++)
            res[r] = b[r];
        for (int j = 0; j < n; j++)
            for (int r = 0; r < 5; r++)
                res[r] -= p[j][r] * x[j];
        int jmax = -1;
        double gmax = 1e-12;
        for (int j = 0; j < n; j++) {
            g[j] = p[j][0] * res[0] + p[j][1] * res[1] + p[j][2] * res[2] + p[j][3] * res[3] + p[j][4] * res[4] -
                   d[j] * x[j];
            if (!pas[j] && g[j] > gmax)
                gmax = g[j], jmax = j;
        }
        if (jmax < 0)
            break;
        pas[jmax] = 1;
        for (int inner = 0; inner < n; inner++) {
            if (pos_solve(n, (const double (*)[5])p, d, pas, b, z))
                return 0;
            double alpha = 1;
            int jb = -1; /* the passive coefficient that reaches 0 first */
            for (int j = 0; j < n; j++)
                if (pas[j] && !fre[j] && z[j] <= 0) {
                    double t = x[j] - z[j] > 0 ? x[j] / (x[j] - z[j]) : 0;
                    if (t < alpha || jb < 0)
                        alpha = t, jb = j;
                }
            if (jb < 0) {
                for (int j = 0; j < n; j++)
                    x[j] = z[j];
                break;
            }
            for (int j = 0; j < n; j++) {
                x[j] += alpha * (z[j] - x[j]);
                if (pas[j] && !fre[j] && (j == jb || x[j] <= 0))
                    pas[j] = 0, x[j] = 0;
            }
        }
    }
    /* a_j = s2 a_hat_j / L^2 (CPM's hat units); between tau and 2 tau the
     * row is blended from CPM's to the positive one, so that the operator
     * stays continuous in the particle positions (a switch at one share
     * made the graded cavities' answer depend on rounding at O(0.2)) */
    double wb = tau > 0 ? fmin(1, (sn / sp - tau) / tau) : 1;
    for (int j = 0; j < n; j++)
        a[j] = fre[j] ? 0 : (1 - wb) * a[j] + wb * s2 * x[j] * (iL * iL);
    return 1;
}

int lap_positive_row(const double *h, const double *k, int n, double sx, double sy, double tau, double *a)
{
    return positive_row(h, k, NULL, NULL, n, sx, sy, tau, a);
}

int lap_positive_row_neumann(const double *h, const double *k, const double *nx, const double *ny, int n,
                             double sx, double sy, double tau, double *a)
{
    return positive_row(h, k, nx, ny, n, sx, sy, tau, a);
}

/* CPM4: the CPM fit of Eqs. 16-17 over the fourth-order Taylor basis in
 * 2-D (14 terms: the 5 of CPM, then h^3/6, h^2k/2, hk^2/2, k^3/6, h^4/24,
 * h^3k/6, h^2k^2/4, hk^3/6, k^4/24), same weights w_j^2 = 1/r^6 and the
 * same metric (sx, sy). The quadratic fit of CPM leaves the quartic terms
 * of phi in its second derivatives: an error (r k)^2 / 12 relative for a
 * Fourier mode of wavenumber k over a stencil of radius r, which does not
 * depend on the particles' order and is the Laplacian's whole O(h^2) error
 * on a lattice. With the quartic terms in the basis the row is exact for
 * quartics (docs/METHOD.md section 8, "CPM4"). Needs 14 distinct
 * neighbours spread in 2-D; UMP_ERR_SINGULAR otherwise. The solver uses
 * it only for stencils without boundary particles (solver.c, Step 6). */
enum { CPM4_N = 14, CPM4_NS = 42 };
#define CPM4_PIVOT_MIN 1e-11
/* the 14 x 14 factorisation and solves fully unrolled (gcc): straight-line
 * code, 40 % of the row's instructions before (callgrind) */
#if defined(__GNUC__) && !defined(__clang__)
#define CPM4_UNROLL _Pragma("GCC unroll 14")
#else
#define CPM4_UNROLL
#endif
/* The moments S_ab (2 <= a + b <= 8) are kept by degree d = a + b, then
 * by a: index d (d + 1) / 2 - 3 + a. cpm4_m holds, row by row of the lower
 * triangle (r >= c), the index of S_(a_r + a_c)(b_r + b_c), the moment of
 * M_rc (Eq. 17); cpm4_d the index of S_(2 a_r)(2 b_r), of M_rr. A wrong
 * entry breaks test_cpm4's exactness for quartics. */
static const unsigned char cpm4_m[CPM4_N * (CPM4_N + 1) / 2] = {
    2,
    1,  0,
    6,  5,  11,
    5,  4,  10, 9,
    4,  3,  9,  8,  7,
    11, 10, 17, 16, 15, 24,
    10, 9,  16, 15, 14, 23, 22,
    9,  8,  15, 14, 13, 22, 21, 20,
    8,  7,  14, 13, 12, 21, 20, 19, 18,
    17, 16, 24, 23, 22, 32, 31, 30, 29, 41,
    16, 15, 23, 22, 21, 31, 30, 29, 28, 40, 39,
    15, 14, 22, 21, 20, 30, 29, 28, 27, 39, 38, 37,
    14, 13, 21, 20, 19, 29, 28, 27, 26, 38, 37, 36, 35,
    13, 12, 20, 19, 18, 28, 27, 26, 25, 37, 36, 35, 34, 33};
static const unsigned char cpm4_d[CPM4_N] = {2, 0, 11, 9, 7, 24, 22, 20, 18, 41, 39, 37, 35, 33};

static inline __attribute__((always_inline)) ump_status cpm4_coeffs2(const double *restrict h,
                                                                     const double *restrict k, int n,
                                                                     double sx, double sy,
                                                                     double *restrict a, ump_err *err)
{
    double r2max = 0;
#pragma omp simd reduction(max : r2max)
    for (int j = 0; j < n; j++) {
        double hs = sx * h[j], ks = sy * k[j], r2 = hs * hs + ks * ks;
        r2max = r2 > r2max ? r2 : r2max;
    }
    if (!(r2max > 0) || !(r2max < INFINITY))
        return UMP_FAIL(err, UMP_ERR_SINGULAR,
                        "CPM4 Laplacian: %d neighbours, none at a finite non-zero distance", n);
    double iL = 1 / sqrt(r2max), rmin2 = CPM_COINCIDENT * CPM_COINCIDENT;
    /* weighted moments S_ab = sum_j w_j^2 X^a Y^b, 2 <= a + b <= 8 (hat
     * units), Eq. 17: one pass, branch-free, so that it vectorises (omp
     * simd; a fixed summation order, the same bits for any thread count).
     * A coincident neighbour gets weight 0. x_e = w_j^2 X^e, y_e = Y^e. */
    double s0 = 0, s1 = 0, s2 = 0, s3 = 0, s4 = 0, s5 = 0, s6 = 0, s7 = 0, s8 = 0, s9 = 0, s10 = 0, s11 = 0,
           s12 = 0, s13 = 0, s14 = 0, s15 = 0, s16 = 0, s17 = 0, s18 = 0, s19 = 0, s20 = 0, s21 = 0,
           s22 = 0, s23 = 0, s24 = 0, s25 = 0, s26 = 0, s27 = 0, s28 = 0, s29 = 0, s30 = 0, s31 = 0,
           s32 = 0, s33 = 0, s34 = 0, s35 = 0, s36 = 0, s37 = 0, s38 = 0, s39 = 0, s40 = 0, s41 = 0;
    double nu = 0;
#pragma omp simd reduction(+ : nu, s0, s1, s2, s3, s4, s5, s6, s7, s8, s9, s10, s11, s12, s13, s14, s15, \
                           s16, s17, s18, s19, s20, s21, s22, s23, s24, s25, s26, s27, s28, s29, s30, s31, \
                           s32, s33, s34, s35, s36, s37, s38, s39, s40, s41)
    for (int j = 0; j < n; j++) {
        double X = sx * h[j] * iL, Y = sy * k[j] * iL, r2 = X * X + Y * Y;
        double far = r2 >= rmin2 ? 1.0 : 0.0, r2s = r2 + (1 - far); /* (a select of r2 stops the
                                                                         vectoriser) */
        double w2 = far / (r2s * r2s * r2s); /* w_j^2 = 1/r^6, as CPM */
        nu += far;
        double X2 = X * X, X4 = X2 * X2, Y2 = Y * Y, Y4 = Y2 * Y2;
        double x1 = w2 * X, x2 = w2 * X2, x3 = x1 * X2, x4 = w2 * X4;
        double x5 = x1 * X4, x6 = x2 * X4, x7 = x3 * X4, x8 = x4 * X4;
        double y3 = Y2 * Y, y5 = Y4 * Y, y6 = Y4 * Y2, y7 = Y4 * y3, y8 = Y4 * Y4;
        s0 += w2 * Y2, s1 += x1 * Y, s2 += x2;                                             /* d = 2 */
        s3 += w2 * y3, s4 += x1 * Y2, s5 += x2 * Y, s6 += x3;                              /* d = 3 */
        s7 += w2 * Y4, s8 += x1 * y3, s9 += x2 * Y2, s10 += x3 * Y, s11 += x4;             /* d = 4 */
        s12 += w2 * y5, s13 += x1 * Y4, s14 += x2 * y3, s15 += x3 * Y2, s16 += x4 * Y;     /* d = 5 */
        s17 += x5;
        s18 += w2 * y6, s19 += x1 * y5, s20 += x2 * Y4, s21 += x3 * y3, s22 += x4 * Y2;   /* d = 6 */
        s23 += x5 * Y, s24 += x6;
        s25 += w2 * y7, s26 += x1 * y6, s27 += x2 * y5, s28 += x3 * Y4, s29 += x4 * y3;   /* d = 7 */
        s30 += x5 * Y2, s31 += x6 * Y, s32 += x7;
        s33 += w2 * y8, s34 += x1 * y7, s35 += x2 * y6, s36 += x3 * y5, s37 += x4 * Y4;   /* d = 8 */
        s38 += x5 * y3, s39 += x6 * Y2, s40 += x7 * Y, s41 += x8;
    }
    int nused = (int)nu;
    if (nused < CPM4_N)
        return UMP_FAIL(err, UMP_ERR_SINGULAR,
                        "CPM4 Laplacian: %d distinct neighbours, at least %d needed", nused, CPM4_N);
    const double S[CPM4_NS] = {s0,  s1,  s2,  s3,  s4,  s5,  s6,  s7,  s8,  s9,  s10, s11, s12, s13,
                               s14, s15, s16, s17, s18, s19, s20, s21, s22, s23, s24, s25, s26, s27,
                               s28, s29, s30, s31, s32, s33, s34, s35, s36, s37, s38, s39, s40, s41};
    /* M equilibrated, A = D M D with D = diag(1/sqrt(M_rr)) (unit
     * diagonal), into the lower triangle of l; Cholesky A = L L^T in place.
     * Only the column q = M^{-1} (sx^2 e_hh + sy^2 e_kk) is needed, so no
     * inverse: two triangular solves. Singularity is judged by the
     * smallest pivot of A (a pivot is the squared distance of a basis
     * column from the span of the ones before it, in the weighted norm; it
     * is >= the smallest eigenvalue of A, so this under-estimates the
     * condition number -- CPM4_PIVOT_MIN is set far above round-off).
     * M_rc = c_r c_c S_(a_r + a_c)(b_r + b_c) (Eq. 17), so the factors c_r
     * cancel in A: A_rc = S_m / sqrt(S_rr S_cc), with e_r = 1/sqrt(S_rr). */
    double e[CPM4_N], l[CPM4_N][CPM4_N];
    for (int r = 0; r < CPM4_N; r++) {
        double srr = S[cpm4_d[r]];
        if (!(srr > 0) || !(srr < INFINITY))
            return UMP_FAIL(err, UMP_ERR_SINGULAR,
                            "CPM4 Laplacian: moment matrix singular (%d neighbours)", nused);
        e[r] = 1 / sqrt(srr);
    }
    CPM4_UNROLL
    for (int r = 0, m = 0; r < CPM4_N; r++) {
        CPM4_UNROLL
        for (int c = 0; c <= r; c++, m++)
            l[r][c] = e[r] * e[c] * S[cpm4_m[m]];
    }
    CPM4_UNROLL
    for (int c = 0; c < CPM4_N; c++) {
        double piv = l[c][c];
        CPM4_UNROLL
        for (int t = 0; t < c; t++)
            piv -= l[c][t] * l[c][t];
        if (!(piv > CPM4_PIVOT_MIN))
            return UMP_FAIL(err, UMP_ERR_SINGULAR,
                            "CPM4 Laplacian: moment matrix singular (pivot %.3g, %d neighbours)", piv, nused);
        double lc = sqrt(piv), il = 1 / lc;
        l[c][c] = lc;
        CPM4_UNROLL
        for (int r = c + 1; r < CPM4_N; r++) {
            double v = l[r][c];
            CPM4_UNROLL
            for (int t = 0; t < c; t++)
                v -= l[r][t] * l[c][t];
            l[r][c] = v * il;
        }
    }
    /* q = D A^{-1} D (sx^2 e_hh + sy^2 e_kk), Eq. 16's rows of phi_xx,
     * phi_yy, with D = diag(e_r / c_r): the right-hand side takes
     * c_2 = c_4 = 1/2, and the c_r of the result cancel against the
     * monomials' below */
    double q[CPM4_N] = {0};
    q[2] = 2 * sx * sx * e[2], q[4] = 2 * sy * sy * e[4];
    CPM4_UNROLL
    for (int r = 0; r < CPM4_N; r++) { /* L y = b */
        double v = q[r];
        CPM4_UNROLL
        for (int t = 0; t < r; t++)
            v -= l[r][t] * q[t];
        q[r] = v / l[r][r];
    }
    CPM4_UNROLL
    for (int r = CPM4_N - 1; r >= 0; r--) { /* L^T z = y */
        double v = q[r];
        CPM4_UNROLL
        for (int t = r + 1; t < CPM4_N; t++)
            v -= l[t][r] * q[t];
        q[r] = v / l[r][r];
    }
    CPM4_UNROLL
    for (int r = 0; r < CPM4_N; r++)
        q[r] *= e[r]; /* a_j = w_j^2 q . X^a Y^b below (the c_r folded in) */
    double il2 = 1 / r2max;
#pragma omp simd
    for (int j = 0; j < n; j++) {
        double X = sx * h[j] * iL, Y = sy * k[j] * iL, r2 = X * X + Y * Y;
        double far = r2 >= rmin2 ? 1.0 : 0.0, r2s = r2 + (1 - far), w2 = far / (r2s * r2s * r2s);
        double X2 = X * X, Y2 = Y * Y, XY = X * Y;
        double s = q[0] * X + q[1] * Y + q[2] * X2 + q[3] * XY + q[4] * Y2 +
                   X2 * (q[5] * X + q[6] * Y) + Y2 * (q[7] * X + q[8] * Y) +
                   X2 * (q[9] * X2 + q[10] * XY + q[11] * Y2) + Y2 * (q[12] * XY + q[13] * Y2);
        a[j] = s * il2 * w2;
    }
    return UMP_OK;
}

/* The kernel of MPS, PS and IPS, [HNS16] Eq. 3: w = max(r_e/r - 1, 0),
 * and 0 on the particle itself. */
static double kernel(double r, double re)
{
    return (r > 0 && r < re) ? re / r - 1 : 0;
}

static ump_status kernel_coeffs(const lap_params *p, int dim, const double *const *off, int n,
                                double l0, double *a, ump_err *err)
{
    const char *name = lap_name(p->model);
    double ref = lap_re_factor(p);
    UMP_CHECK(l0 > 0 && isfinite(l0), err, UMP_ERR_INPUT,
              "%s Laplacian: particle spacing l0 = %g, expected > 0", name, l0);
    UMP_CHECK(ref > 0 && isfinite(ref), err, UMP_ERR_INPUT,
              "%s Laplacian: re_factor = %g, expected > 0", name, ref);
    double re = ref * l0, den = 0;
    int ips = p->model == LAP_IPS;
    /* Omega sums of [HNS16] Eq. 5 (IPS): g = Omega_2^(1), G = Omega_2^(2). */
    double g[LAP_MAX_DIM] = {0}, G[SPD_MAX][SPD_MAX] = {{0}};
    for (int j = 0; j < n; j++) {
        double r2 = dist2(dim, off, j), r = sqrt(r2), w = kernel(r, re);
        switch (p->model) {
        case LAP_MPS: /* [NSH16] Eq. 15: weights w, normalised by sum w r^2 */
            a[j] = w;
            den += w * r2;
            break;
        default: /* PS ([HNS16] Eq. 2) and IPS: weights w / r^2, normalised by Omega_0 */
            a[j] = w > 0 ? w / r2 : 0;
            den += w;
            for (int d = 0; ips && d < dim; d++) {
                g[d] += off[d][j] * a[j];
                for (int e = d; e < dim; e++)
                    G[d][e] += off[d][j] * off[e][j] * a[j];
            }
            break;
        }
    }
    if (!(den > 0) || !isfinite(den))
        return UMP_FAIL(err, UMP_ERR_SINGULAR, "%s Laplacian: no neighbour within r_e = %g (of %d)",
                        name, re, n);
    double c[LAP_MAX_DIM] = {0};
    if (ips) {
        /* Eq. 18/27: G <grad phi> = Phi_2^(1); c = G^{-1} Omega_2^(1) (G symmetric). */
        spd_small f;
        double rc = spd_factor_invert(&f, dim, G);
        if (rc < LAP_RCOND_MIN)
            return UMP_FAIL(err, UMP_ERR_SINGULAR,
                            "IPS Laplacian: gradient matrix singular (rcond %.3g, neighbours "
                            "within r_e = %g not spread in %d-D)", rc, re, dim);
        for (int d = 0; d < dim; d++) {
            double col[SPD_MAX];
            spd_inv_column(&f, d, col);
            for (int e = 0; e < dim; e++)
                c[e] += col[e] * g[d];
        }
    }
    double s = 2.0 * dim / den; /* 2d / sum_j w_j r_j^2 (MPS) or 2d / Omega_0 (PS, IPS) */
    for (int j = 0; j < n; j++) {
        double corr = 1;
        for (int d = 0; ips && d < dim; d++)
            corr -= c[d] * off[d][j]; /* Eq. 20: minus the artificial convection */
        a[j] *= s * corr;
    }
    return UMP_OK;
}

/* AVX2 and baseline clones chosen at load time, as mls_weights (mls.c):
 * the inlined 2-D CPM kernel's omp simd loops run 4 wide with AVX2. */
UMP_TARGET_CLONES
ump_status lap_coeffs_d(const lap_params *p, int dim, const double *const *off, int n, double l0,
                        double *a, ump_err *err)
{
    UMP_CHECK(p && dim >= 1 && dim <= LAP_MAX_DIM && n >= 0, err, UMP_ERR_INPUT,
              "Laplacian: invalid arguments (dim = %d, n = %d)", dim, n);
    for (int d = 0; d < dim && n > 0; d++)
        UMP_CHECK(off && off[d] && a, err, UMP_ERR_INPUT, "Laplacian: offsets or coefficients missing");
    switch (p->model) {
    case LAP_CPM:
        return dim == 2 ? cpm_coeffs2(off[0], off[1], n, 1.0, 1.0, a, err) : cpm_coeffs(dim, off, n, a, err);
    case LAP_CPM4:
        if (dim != 2)
            return UMP_FAIL(err, UMP_ERR_INPUT, "CPM4 Laplacian: 2-D only (dim = %d)", dim);
        return cpm4_coeffs2(off[0], off[1], n, 1.0, 1.0, a, err);
    case LAP_MPS:
    case LAP_PS:
    case LAP_IPS:
        return kernel_coeffs(p, dim, off, n, l0, a, err);
    }
    return UMP_FAIL(err, UMP_ERR_INPUT, "Laplacian: unknown model %d", (int)p->model);
}

ump_status lap_coeffs(const lap_params *p, const double *h, const double *k, int n, double l0,
                      double *a, ump_err *err)
{
    const double *off[2] = {h, k};
    return lap_coeffs_d(p, 2, off, n, l0, a, err);
}

UMP_TARGET_CLONES
ump_status lap_coeffs_metric(const lap_params *p, const double *h, const double *k, int n, double l0,
                             double sx, double sy, double *a, ump_err *err)
{
    UMP_CHECK(sx > 0 && sy > 0 && isfinite(sx) && isfinite(sy), err, UMP_ERR_INPUT,
              "Laplacian: metric (%g, %g), expected finite and > 0", sx, sy);
    if (p && (p->model == LAP_CPM || p->model == LAP_CPM4) && n > 0) {
        UMP_CHECK(h && k && a, err, UMP_ERR_INPUT, "Laplacian: offsets or coefficients missing");
        return p->model == LAP_CPM ? cpm_coeffs2(h, k, n, sx, sy, a, err)
                                   : cpm4_coeffs2(h, k, n, sx, sy, a, err);
    }
    return lap_coeffs(p, h, k, n, l0, a, err);
}

double lap_value(const double *a, const double *phij, double phii, int n)
{
    double s = 0;
    for (int j = 0; j < n; j++)
        s += a[j] * (phij[j] - phii);
    return s;
}

void lap_moments(int dim, const double *const *off, int n, const double *a, double first[3],
                 double second[6])
{
    /* symmTensor slot of (d, e), d <= e: xx xy xz yy yz zz */
    static const int slot[3][3] = {{0, 1, 2}, {1, 3, 4}, {2, 4, 5}};
    for (int d = 0; d < 3; d++)
        first[d] = 0;
    for (int s = 0; s < 6; s++)
        second[s] = 0;
    for (int j = 0; j < n; j++)
        for (int d = 0; d < dim; d++) {
            first[d] += a[j] * off[d][j];
            for (int e = d; e < dim; e++)
                second[slot[d][e]] += 0.5 * a[j] * off[d][j] * off[e][j];
        }
}

ump_status lap_quality_d(double re_factor, int dim, const double *const *off, int n, double l0,
                         double *work, lap_quality *q, ump_err *err)
{
    double unused[6];
    lap_params ps = {LAP_PS, re_factor}, ips = {LAP_IPS, re_factor};
    /* Eq. 14: u_N = <lap x>_PS */
    UMP_CALL(lap_coeffs_d(&ps, dim, off, n, l0, work, err));
    lap_moments(dim, off, n, work, q->uN, unused);
    /* Eq. 23: tau_de = <lap (x_d x_e / 2)>_IPS */
    double first[3];
    UMP_CALL(lap_coeffs_d(&ips, dim, off, n, l0, work, err));
    lap_moments(dim, off, n, work, first, q->tau);
    return UMP_OK;
}

double lap_re_factor(const lap_params *p)
{
    if (p->re_factor != 0)
        return p->re_factor;
    return p->model == LAP_MPS ? LAP_RE_FACTOR_DEFAULT : LAP_RE_FACTOR_PS_DEFAULT;
}

static const char *const NAMES[] = {"CPM", "MPS", "IPS", "PS", "CPM4"};

const char *lap_name(lap_model m)
{
    int i = (int)m;
    return (i >= 0 && i < (int)(sizeof NAMES / sizeof NAMES[0])) ? NAMES[i] : "unknown";
}

int lap_parse(const char *word)
{
    if (!word)
        return -1;
    for (int i = 0; i < (int)(sizeof NAMES / sizeof NAMES[0]); i++)
        if (strcmp(word, NAMES[i]) == 0)
            return i;
    return -1;
}
