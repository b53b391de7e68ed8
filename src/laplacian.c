/* SPDX-License-Identifier: GPL-3.0-or-later
 * laplacian.c -- Laplacian models on scattered particles, Section 3.2.1 of
 * seed 000 (Ng, Sheu & Hwang 2016).
 *
 * Every model returns the implicit row lap(phi)_i = sum_j a_j (phi_j - phi_i)
 * (Eq. 14 is solved implicitly), so the explicit value and the matrix row
 * come from the same numbers.
 *
 * CPM (Koh et al.; Eqs. 16-17). Taylor expansion to second order,
 *   phi_j - phi_i ~ p_j . D,  p_j = [h, k, h^2/2, hk, k^2/2],
 *   D = [phi_x, phi_y, phi_xx, phi_xy, phi_yy],
 * fitted by weighted least squares with weights w_j^2, w_j = 1/r_j^3:
 *   D = M^{-1} sum_j w_j^2 p_j (phi_j - phi_i),  M = sum_j w_j^2 p_j p_j^T,
 * and lap = D_3 + D_5, hence a_j = w_j^2 (row 3 + row 5 of M^{-1}) . p_j.
 * Exact for quadratic fields on any cloud where M is non-singular.
 * Conditioning: h, k are divided by a local length L (the largest neighbour
 * distance). With hat quantities H = h/L, K = k/L, p_hat = D_L p,
 * w_hat = L^3 w, one finds M_hat = L^6 D_L M D_L and a_hat_j = L^2 a_j, so
 * a_j = a_hat_j / L^2. M_hat is then equilibrated (spd_small.h) and its
 * condition number decides singularity.
 *
 * MPS (Koshizuka; Eq. 15), d = 2:
 *   a_j = 2d w_j / sum_j w_j r_j^2,  w = r_e/r - 1 for r < r_e, else 0.
 * Exact for quadratics on symmetric lattices only: on an irregular cloud the
 * first moment sum_j w_j h_j does not vanish, so a linear field gives an
 * O(1/l0) error and the scheme is inconsistent (the paper's motivation for
 * CPM; Ng et al. [27], Souto-Iglesias et al. [43]).
 */
#include "umppm/laplacian.h"

#include "spd_small.h"

#include <math.h>
#include <string.h>

/* Neighbours closer than this fraction of L coincide with particle i: their
 * p_j is zero, so they carry no information (and w_j = 1/r^3 would be
 * infinite). They get a_j = 0. */
#define CPM_COINCIDENT 1e-12

static ump_status cpm_coeffs(const double *h, const double *k, int n, double *a, ump_err *err)
{
    double r2max = 0;
    for (int j = 0; j < n; j++)
        r2max = fmax(r2max, h[j] * h[j] + k[j] * k[j]);
    if (!(r2max > 0) || !isfinite(r2max))
        return UMP_FAIL(err, UMP_ERR_SINGULAR,
                        "CPM Laplacian: %d neighbours, none at a finite non-zero distance", n);
    double L = sqrt(r2max);
    double rmin2 = CPM_COINCIDENT * CPM_COINCIDENT;

    /* CPM moment matrix, Eq. 17: M = sum_j w_j^2 p_j p_j^T (hat units). */
    double m[SPD_MAX][SPD_MAX] = {{0}};
    int nused = 0;
    for (int j = 0; j < n; j++) {
        double H = h[j] / L, K = k[j] / L, r2 = H * H + K * K;
        if (r2 < rmin2)
            continue;
        double w2 = 1 / (r2 * r2 * r2); /* w_j^2 = 1/r^6 */
        double p[5] = {H, K, 0.5 * H * H, H * K, 0.5 * K * K};
        for (int r = 0; r < 5; r++) {
            double wp = w2 * p[r];
            for (int c = r; c < 5; c++)
                m[r][c] += wp * p[c];
        }
        nused++;
    }
    if (nused < 5)
        return UMP_FAIL(err, UMP_ERR_SINGULAR,
                        "CPM Laplacian: %d distinct neighbours, at least 5 needed", nused);
    spd_small f;
    double rc = spd_factor_invert(&f, 5, m);
    if (rc < LAP_RCOND_MIN)
        return UMP_FAIL(err, UMP_ERR_SINGULAR,
                        "CPM Laplacian: moment matrix singular (rcond %.3g, %d neighbours "
                        "not spread in 2-D)", rc, nused);

    /* q = M^{-1} (e_3 + e_5) = (row 3 + row 5 of M^{-1})^T, Eq. 16. */
    double q3[5], q5[5], q[5];
    spd_inv_column(&f, 2, q3);
    spd_inv_column(&f, 4, q5);
    for (int r = 0; r < 5; r++)
        q[r] = q3[r] + q5[r];
    double il2 = 1 / r2max; /* a_j = a_hat_j / L^2 */
    for (int j = 0; j < n; j++) {
        double H = h[j] / L, K = k[j] / L, r2 = H * H + K * K;
        if (r2 < rmin2) {
            a[j] = 0;
            continue;
        }
        double w2 = 1 / (r2 * r2 * r2);
        double s = q[0] * H + q[1] * K + q[2] * 0.5 * H * H + q[3] * H * K + q[4] * 0.5 * K * K;
        a[j] = w2 * s * il2;
    }
    return UMP_OK;
}

static ump_status mps_coeffs(const lap_params *p, const double *h, const double *k, int n,
                             double l0, double *a, ump_err *err)
{
    double ref = p->re_factor == 0 ? LAP_RE_FACTOR_DEFAULT : p->re_factor;
    UMP_CHECK(l0 > 0 && isfinite(l0), err, UMP_ERR_INPUT,
              "MPS Laplacian: particle spacing l0 = %g, expected > 0", l0);
    UMP_CHECK(ref > 0 && isfinite(ref), err, UMP_ERR_INPUT,
              "MPS Laplacian: re_factor = %g, expected > 0", ref);
    double re = ref * l0;
    /* Eq. 15: lambda-like normalisation sum_j w_j r_j^2; kernel w = r_e/r - 1. */
    double den = 0;
    for (int j = 0; j < n; j++) {
        double r = sqrt(h[j] * h[j] + k[j] * k[j]);
        double w = (r > 0 && r < re) ? re / r - 1 : 0;
        a[j] = w;
        den += w * r * r;
    }
    if (!(den > 0) || !isfinite(den))
        return UMP_FAIL(err, UMP_ERR_SINGULAR,
                        "MPS Laplacian: no neighbour within r_e = %g (of %d)", re, n);
    double c = 2.0 * 2 / den; /* 2d / sum_j w_j r_j^2, d = 2 */
    for (int j = 0; j < n; j++)
        a[j] *= c;
    return UMP_OK;
}

ump_status lap_coeffs(const lap_params *p, const double *h, const double *k, int n, double l0,
                      double *a, ump_err *err)
{
    UMP_CHECK(p && n >= 0 && (n == 0 || (h && k && a)), err, UMP_ERR_INPUT,
              "Laplacian: invalid arguments (n = %d)", n);
    switch (p->model) {
    case LAP_CPM:
        return cpm_coeffs(h, k, n, a, err);
    case LAP_MPS:
        return mps_coeffs(p, h, k, n, l0, a, err);
    case LAP_IPS:
        return UMP_FAIL(err, UMP_ERR_UNSUPPORTED,
                        "Laplacian IPS (seed 001 Eq. 20) is not implemented yet");
    }
    return UMP_FAIL(err, UMP_ERR_INPUT, "Laplacian: unknown model %d", (int)p->model);
}

static const char *const NAMES[] = {"CPM", "MPS", "IPS"};

const char *lap_name(lap_model m)
{
    int i = (int)m;
    return (i >= 0 && i <= (int)LAP_IPS) ? NAMES[i] : "unknown";
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
