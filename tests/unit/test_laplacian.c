/* SPDX-License-Identifier: GPL-3.0-or-later
 * test_laplacian.c -- particle Laplacians (lap_coeffs): CPM (Eqs. 16-17)
 * and MPS (Eq. 15) of seed 000.
 *
 * CPM: exact for quadratics on irregular 24-neighbour clouds, observed order
 * for a smooth field, singular clouds refused, and the implicit row checked
 * against an explicit CPM evaluation done differently (weighted least
 * squares for all five derivatives by Gram-Schmidt QR, physical units).
 * MPS: exact for quadratics on a regular lattice with r_e = 2.1 l0, and
 * inconsistent on an irregular cloud: its error does not vanish as h -> 0.
 */
#include "testutil.h"
#include "umppm/laplacian.h"

#include <time.h>

/* ---- helpers ---------------------------------------------------------- */

static uint64_t rng_state;
static void rng_seed(uint64_t s) { rng_state = s; }
static double rnd(void) /* [0, 1), splitmix64 */
{
    uint64_t z = (rng_state += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    z ^= z >> 31;
    return (double)(z >> 11) * (1.0 / 9007199254740992.0);
}
static double rnd_in(double a, double b) { return a + (b - a) * rnd(); }

#define NMAX 128

/* The 24 neighbours of a particle in a lattice of spacing h jittered by
 * +-jit*h (two rings of cells, 5x5 minus the centre); the particle itself is
 * jittered too. Offsets h_j, k_j into hh, kk; particle position into xi, yi
 * (the lattice origin is at (ox, oy)). */
static int cloud24(double h, double jit, double ox, double oy, double *xi, double *yi,
                   double *hh, double *kk)
{
    *xi = ox + jit * rnd_in(-1, 1) * h;
    *yi = oy + jit * rnd_in(-1, 1) * h;
    int n = 0;
    for (int i = -2; i <= 2; i++)
        for (int j = -2; j <= 2; j++) {
            if (i == 0 && j == 0)
                continue;
            double x = ox + (i + jit * rnd_in(-1, 1)) * h;
            double y = oy + (j + jit * rnd_in(-1, 1)) * h;
            hh[n] = x - *xi;
            kk[n++] = y - *yi;
        }
    return n;
}

/* lap = sum_j a_j (phi_j - phi_i) and the rounding scale sum_j |a_j (phi_j - phi_i)|. */
static double apply(const double *a, const double *phij, double phii, int n, double *scale)
{
    double s = 0, sa = 0;
    for (int j = 0; j < n; j++) {
        s += a[j] * (phij[j] - phii);
        sa += fabs(a[j] * (phij[j] - phii));
    }
    if (scale)
        *scale = sa;
    return s;
}

typedef struct { double q[6]; } quad;
static double qval(const quad *f, double x, double y)
{
    const double *q = f->q;
    return q[0] + q[1] * x + q[2] * y + q[3] * x * y + q[4] * x * x + q[5] * y * y;
}

static const lap_params CPM = {LAP_CPM, 0};
static const lap_params MPS = {LAP_MPS, 2.1};

/* ---- CPM -------------------------------------------------------------- */

static void test_cpm_quadratic_exact(void **state)
{
    (void)state;
    rng_seed(11);
    double hh[NMAX], kk[NMAX], a[NMAX], phi[NMAX];
    double worst = 0;
    for (int t = 0; t < 500; t++) {
        double h = pow(10, rnd_in(-4, 2));
        double xi, yi;
        int n = cloud24(h, 0.45, rnd_in(-10, 10) * h, rnd_in(-10, 10) * h, &xi, &yi, hh, kk);
        quad f;
        for (int i = 0; i < 6; i++)
            f.q[i] = rnd_in(-1, 1) / (i == 0 ? 1 : i < 3 ? h : h * h);
        ump_err err;
        assert_int_equal(lap_coeffs(&CPM, hh, kk, n, h, a, &err), UMP_OK);
        for (int j = 0; j < n; j++)
            phi[j] = qval(&f, xi + hh[j], yi + kk[j]);
        double sc, lap = apply(a, phi, qval(&f, xi, yi), n, &sc);
        double exact = 2 * f.q[4] + 2 * f.q[5];
        double rel = fabs(lap - exact) / fmax(fabs(exact), sc);
        worst = fmax(worst, rel);
        if (!(rel <= 1e-10))
            fail_msg("trial %d: CPM %.17g, exact %.17g, rel %.3g", t, lap, exact, rel);
    }
    print_message("CPM on 500 irregular 24-neighbour clouds: worst rel. error %.3g\n", worst);
}

static double fsin(double x, double y) { return sin(x + 0.3) * sin(2 * y - 0.1); }
static double lsin(double x, double y) { return -5 * fsin(x, y); }

/* Max error of a model's Laplacian of fsin over NT particles of a lattice
 * of spacing h jittered by +-jit*h, origins spread over [0,1]^2. */
static double lap_error(const lap_params *p, double h, double jit, int nt)
{
    double hh[NMAX], kk[NMAX], a[NMAX], phi[NMAX], e = 0;
    for (int t = 0; t < nt; t++) {
        double xi, yi;
        double ox = h * floor(rnd() / h), oy = h * floor(rnd() / h);
        int n = cloud24(h, jit, ox, oy, &xi, &yi, hh, kk);
        ump_err err;
        assert_int_equal(lap_coeffs(p, hh, kk, n, h, a, &err), UMP_OK);
        for (int j = 0; j < n; j++)
            phi[j] = fsin(xi + hh[j], yi + kk[j]);
        e = fmax(e, fabs(apply(a, phi, fsin(xi, yi), n, NULL) - lsin(xi, yi)));
    }
    return e;
}

static void test_cpm_order(void **state)
{
    (void)state;
    rng_seed(12);
    enum { NH = 5 };
    const double hs[NH] = {0.1, 0.05, 0.025, 0.0125, 0.00625};
    double e[NH];
    for (int k = 0; k < NH; k++) {
        e[k] = lap_error(&CPM, hs[k], 0.3, 400);
        if (k == 0)
            print_message("CPM jittered  h %-8g max err %.3e\n", hs[k], e[k]);
        else
            print_message("CPM jittered  h %-8g max err %.3e (order %.2f)\n", hs[k], e[k],
                          log2(e[k - 1] / e[k]));
    }
    double p = log(e[0] / e[NH - 1]) / log(hs[0] / hs[NH - 1]);
    print_message("CPM observed order (jitter 0.3 h): %.2f\n", p);
    assert_true(p >= 0.9);
    /* regular lattice: symmetric stencil, second order */
    double r0 = lap_error(&CPM, 0.05, 0, 50), r1 = lap_error(&CPM, 0.025, 0, 50);
    print_message("CPM regular lattice: err %.3e -> %.3e (order %.2f)\n", r0, r1, log2(r0 / r1));
    assert_true(log2(r0 / r1) >= 1.8);
}

static void test_cpm_singular(void **state)
{
    (void)state;
    double hh[NMAX], kk[NMAX], a[NMAX];
    ump_err err;
    /* 4 collinear neighbours (also too few) */
    for (int j = 0; j < 4; j++) {
        hh[j] = 0.1 * (j + 1);
        kk[j] = 0.05 * (j + 1);
    }
    assert_int_equal(lap_coeffs(&CPM, hh, kk, 4, 0.1, a, &err), UMP_ERR_SINGULAR);
    assert_int_equal(err.code, UMP_ERR_SINGULAR);
    assert_null(strchr(err.msg, '\n'));
    print_message("4 collinear: %s\n", err.msg);
    /* 12 collinear neighbours on both sides: enough of them, still rank 2 */
    for (int j = 0; j < 12; j++) {
        hh[j] = 0.1 * (j - 5.5);
        kk[j] = -0.03 * (j - 5.5);
    }
    assert_int_equal(lap_coeffs(&CPM, hh, kk, 12, 0.1, a, &err), UMP_ERR_SINGULAR);
    print_message("12 collinear: %s\n", err.msg);
    /* 8 neighbours on a circle through the particle: h^2 + k^2 - 2Rh = 0 is a
     * combination of the columns of p_j */
    for (int j = 0; j < 8; j++) {
        double t = 2 * UMP_PI * (j + 0.5) / 8;
        hh[j] = 0.2 + 0.2 * cos(t);
        kk[j] = 0.2 * sin(t);
    }
    assert_int_equal(lap_coeffs(&CPM, hh, kk, 8, 0.1, a, &err), UMP_ERR_SINGULAR);
    print_message("circle through particle: %s\n", err.msg);
    /* all neighbours coincide with the particle */
    for (int j = 0; j < 6; j++)
        hh[j] = kk[j] = 0;
    assert_int_equal(lap_coeffs(&CPM, hh, kk, 6, 0.1, a, &err), UMP_ERR_SINGULAR);
    assert_int_equal(lap_coeffs(&CPM, hh, kk, 0, 0.1, a, &err), UMP_ERR_SINGULAR);
}

static void test_cpm_coincident_neighbour(void **state)
{
    (void)state;
    rng_seed(13);
    double hh[NMAX], kk[NMAX], a[NMAX], phi[NMAX], xi, yi;
    int n = cloud24(0.1, 0.3, 0, 0, &xi, &yi, hh, kk);
    hh[n] = 0;
    kk[n++] = 0; /* a 25th neighbour at the particle's position */
    ump_err err;
    assert_int_equal(lap_coeffs(&CPM, hh, kk, n, 0.1, a, &err), UMP_OK);
    assert_true(a[n - 1] == 0);
    quad f = {{1, 2, 3, 4, 5, 6}};
    for (int j = 0; j < n; j++) {
        assert_true(isfinite(a[j]));
        phi[j] = qval(&f, xi + hh[j], yi + kk[j]);
    }
    TU_CLOSE(apply(a, phi, qval(&f, xi, yi), n, NULL), 22, 1e-10);
}

/* Explicit CPM done differently: solve min sum_j w_j^2 (p_j . D - dphi_j)^2
 * for D = [phi_x, phi_y, phi_xx, phi_xy, phi_yy] in physical units by
 * modified Gram-Schmidt QR (twice) of the rows w_j p_j; return D_3 + D_5. */
static double explicit_cpm(const double *hh, const double *kk, const double *dphi, int n)
{
    double Q[5][NMAX], b[NMAX], R[5][5] = {{0}};
    for (int j = 0; j < n; j++) {
        double r = sqrt(hh[j] * hh[j] + kk[j] * kk[j]), w = 1 / (r * r * r);
        double p[5] = {hh[j], kk[j], 0.5 * hh[j] * hh[j], hh[j] * kk[j], 0.5 * kk[j] * kk[j]};
        for (int i = 0; i < 5; i++)
            Q[i][j] = w * p[i];
        b[j] = w * dphi[j];
    }
    for (int c = 0; c < 5; c++) {
        for (int pass = 0; pass < 2; pass++)
            for (int i = 0; i < c; i++) {
                double r = 0;
                for (int j = 0; j < n; j++)
                    r += Q[i][j] * Q[c][j];
                R[i][c] += r;
                for (int j = 0; j < n; j++)
                    Q[c][j] -= r * Q[i][j];
            }
        double nr = 0;
        for (int j = 0; j < n; j++)
            nr += Q[c][j] * Q[c][j];
        R[c][c] = sqrt(nr);
        for (int j = 0; j < n; j++)
            Q[c][j] /= R[c][c];
    }
    double z[5], D[5];
    for (int i = 0; i < 5; i++) {
        z[i] = 0;
        for (int j = 0; j < n; j++)
            z[i] += Q[i][j] * b[j];
    }
    for (int i = 4; i >= 0; i--) {
        double v = z[i];
        for (int c = i + 1; c < 5; c++)
            v -= R[i][c] * D[c];
        D[i] = v / R[i][i];
    }
    return D[2] + D[4];
}

/* The implicit row (diagonal -sum a_j, off-diagonal a_j) applied to phi
 * equals sum_j a_j (phi_j - phi_i) and the explicit CPM value. */
static void test_implicit_row(void **state)
{
    (void)state;
    rng_seed(14);
    double hh[NMAX], kk[NMAX], a[NMAX], phi[NMAX], dphi[NMAX];
    double worst = 0;
    for (int t = 0; t < 300; t++) {
        double h = rnd_in(0.2, 2), xi, yi;
        int n = cloud24(h, 0.4, 0, 0, &xi, &yi, hh, kk);
        n -= (int)(rnd() * 12); /* 12..24 neighbours */
        ump_err err;
        assert_int_equal(lap_coeffs(&CPM, hh, kk, n, h, a, &err), UMP_OK);
        double phii = rnd_in(-1, 1), diag = 0, row = 0;
        for (int j = 0; j < n; j++) {
            phi[j] = rnd_in(-1, 1); /* arbitrary data */
            dphi[j] = phi[j] - phii;
            diag -= a[j];
            row += a[j] * phi[j];
        }
        row += diag * phii;
        double sc, lap = apply(a, phi, phii, n, &sc);
        double ex = explicit_cpm(hh, kk, dphi, n);
        TU_CLOSE(row, lap, 1e-12 * fmax(1, sc));
        double rel = fabs(lap - ex) / fmax(fabs(ex), sc);
        worst = fmax(worst, rel);
        assert_true(rel < 1e-10);
        /* a constant field has zero Laplacian: the row sums to zero */
        for (int j = 0; j < n; j++)
            phi[j] = phii;
        TU_CLOSE(apply(a, phi, phii, n, NULL), 0, 0);
    }
    print_message("implicit row vs explicit CPM (MGS-QR): worst rel. difference %.3g\n", worst);
}

/* ---- MPS -------------------------------------------------------------- */

static void test_mps_regular_lattice(void **state)
{
    (void)state;
    rng_seed(15);
    double hh[NMAX], kk[NMAX], a[NMAX], phi[NMAX];
    for (int t = 0; t < 50; t++) {
        double l0 = pow(10, rnd_in(-3, 1)), xi, yi;
        int n = cloud24(l0, 0, rnd_in(-3, 3), rnd_in(-3, 3), &xi, &yi, hh, kk);
        ump_err err;
        assert_int_equal(lap_coeffs(&MPS, hh, kk, n, l0, a, &err), UMP_OK);
        int inside = 0;
        for (int j = 0; j < n; j++)
            inside += a[j] != 0;
        assert_int_equal(inside, 12); /* r in {1, sqrt 2, 2} l0 < 2.1 l0 */
        quad f;
        for (int i = 0; i < 6; i++)
            f.q[i] = rnd_in(-1, 1);
        for (int j = 0; j < n; j++)
            phi[j] = qval(&f, xi + hh[j], yi + kk[j]);
        double sc, lap = apply(a, phi, qval(&f, xi, yi), n, &sc);
        double exact = 2 * f.q[4] + 2 * f.q[5];
        /* symmetric stencil: odd moments and sum w hk vanish, sum w h^2 =
         * sum w k^2 = sum w r^2 / 2, so Eq. 15 is exact for quadratics */
        if (!(fabs(lap - exact) <= 1e-12 * fmax(fabs(exact), sc)))
            fail_msg("MPS regular: %.17g vs %.17g", lap, exact);
    }
    /* ... and second order for a smooth field */
    double e0 = lap_error(&MPS, 0.02, 0, 50), e1 = lap_error(&MPS, 0.01, 0, 50);
    print_message("MPS regular lattice, sin field: err %.3e -> %.3e (order %.2f)\n", e0, e1,
                  log2(e0 / e1));
}

/* MPS on a jittered lattice: the error for x^2 - y^2 (Laplacian 0) is
 * h-independent and that of a smooth field grows; CPM on the same clouds
 * converges. */
static void test_mps_inconsistent(void **state)
{
    (void)state;
    enum { NH = 5, NT = 400 };
    const double hs[NH] = {0.1, 0.05, 0.025, 0.0125, 0.00625};
    double emps[NH], ecpm[NH], equad[NH];
    for (int k = 0; k < NH; k++) {
        rng_seed(16);
        emps[k] = lap_error(&MPS, hs[k], 0.2, NT);
        rng_seed(16);
        ecpm[k] = lap_error(&CPM, hs[k], 0.2, NT);
        /* RMS error for phi = x^2 - y^2 */
        rng_seed(17);
        double hh[NMAX], kk[NMAX], a[NMAX], s2 = 0;
        for (int t = 0; t < NT; t++) {
            double xi, yi;
            int n = cloud24(hs[k], 0.2, 0, 0, &xi, &yi, hh, kk);
            ump_err err;
            assert_int_equal(lap_coeffs(&MPS, hh, kk, n, hs[k], a, &err), UMP_OK);
            double l = 0;
            for (int j = 0; j < n; j++) {
                double xj = xi + hh[j], yj = yi + kk[j];
                l += a[j] * ((xj * xj - yj * yj) - (xi * xi - yi * yi));
            }
            s2 += l * l;
        }
        equad[k] = sqrt(s2 / NT);
        print_message("jitter 0.2h  h %-8g MPS sin err %.3e  MPS x^2-y^2 rms err %.3e  "
                      "CPM sin err %.3e\n", hs[k], emps[k], equad[k], ecpm[k]);
    }
    for (int k = 0; k < NH; k++) {
        assert_true(emps[k] > 0.5);  /* |lap| <= 5: an O(1) error that never goes away */
        assert_true(equad[k] > 0.1); /* exact value 0 */
    }
    assert_true(emps[NH - 1] > emps[0]);    /* the first moment makes it grow like 1/h */
    assert_true(ecpm[NH - 1] < 0.1 * ecpm[0]); /* CPM converges on the same clouds */
}

static void test_mps_params(void **state)
{
    (void)state;
    double hh[4] = {0.1, -0.1, 0, 0.5}, kk[4] = {0, 0, 0.1, 0}, a[4], b[4];
    ump_err err;
    lap_params def = {LAP_MPS, 0};
    assert_int_equal(lap_coeffs(&def, hh, kk, 4, 0.1, a, &err), UMP_OK);
    assert_int_equal(lap_coeffs(&MPS, hh, kk, 4, 0.1, b, &err), UMP_OK);
    for (int j = 0; j < 4; j++)
        TU_CLOSE(a[j], b[j], 0);
    assert_true(a[3] == 0); /* r = 5 l0 > r_e */
    lap_params bad = {LAP_MPS, -1};
    assert_int_equal(lap_coeffs(&bad, hh, kk, 4, 0.1, a, &err), UMP_ERR_INPUT);
    assert_int_equal(lap_coeffs(&MPS, hh, kk, 4, 0, a, &err), UMP_ERR_INPUT);
    assert_int_equal(lap_coeffs(&MPS, hh, kk, 4, 0.01, a, &err), UMP_ERR_SINGULAR);
    print_message("%s\n", err.msg);
    /* a neighbour on the particle contributes nothing */
    hh[0] = kk[0] = 0;
    assert_int_equal(lap_coeffs(&MPS, hh, kk, 4, 0.1, a, &err), UMP_OK);
    assert_true(a[0] == 0 && isfinite(a[1]) && a[1] > 0);
}

static void test_names(void **state)
{
    (void)state;
    double hh[8] = {0}, kk[8] = {0}, a[8];
    ump_err err;
    lap_params ips = {LAP_IPS, 0};
    /* all neighbours on the particle: nothing within r_e */
    assert_int_equal(lap_coeffs(&ips, hh, kk, 8, 0.1, a, &err), UMP_ERR_SINGULAR);
    assert_string_equal(lap_name(LAP_CPM), "CPM");
    assert_string_equal(lap_name(LAP_MPS), "MPS");
    assert_string_equal(lap_name(LAP_IPS), "IPS");
    assert_string_equal(lap_name(LAP_PS), "PS");
    assert_string_equal(lap_name((lap_model)17), "unknown");
    for (int m = LAP_CPM; m <= LAP_PS; m++)
        assert_int_equal(lap_parse(lap_name((lap_model)m)), m);
    assert_int_equal(lap_parse("cpm"), -1);
    assert_int_equal(lap_parse(""), -1);
    assert_int_equal(lap_parse(NULL), -1);
    assert_int_equal(lap_coeffs(NULL, hh, kk, 8, 0.1, a, &err), UMP_ERR_INPUT);
    assert_int_equal(lap_coeffs(&CPM, hh, kk, -1, 0.1, a, &err), UMP_ERR_INPUT);
}

static void test_timing(void **state)
{
    (void)state;
    rng_seed(18);
    enum { REP = 200000 };
    double hh[NMAX], kk[NMAX], a[NMAX], xi, yi;
    int n = cloud24(1, 0.3, 0, 0, &xi, &yi, hh, kk);
    const lap_params *ps[2] = {&CPM, &MPS};
    for (int m = 0; m < 2; m++) {
        struct timespec t0, t1;
        double acc = 0;
        ump_err err;
        clock_gettime(CLOCK_MONOTONIC, &t0);
        for (int r = 0; r < REP; r++) {
            hh[r % n] += 1e-9;
            if (lap_coeffs(ps[m], hh, kk, n, 1, a, &err) != UMP_OK)
                fail_msg("%s", err.msg);
            acc += a[0];
        }
        clock_gettime(CLOCK_MONOTONIC, &t1);
        double us = ((double)(t1.tv_sec - t0.tv_sec) * 1e6 + (double)(t1.tv_nsec - t0.tv_nsec) * 1e-3) / REP;
        print_message("lap_coeffs %s, n = %d: %.3f us per call\n", lap_name(ps[m]->model), n, us);
        assert_true(isfinite(acc));
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_cpm_quadratic_exact),
        cmocka_unit_test(test_cpm_order),
        cmocka_unit_test(test_cpm_singular),
        cmocka_unit_test(test_cpm_coincident_neighbour),
        cmocka_unit_test(test_implicit_row),
        cmocka_unit_test(test_mps_regular_lattice),
        cmocka_unit_test(test_mps_inconsistent),
        cmocka_unit_test(test_mps_params),
        cmocka_unit_test(test_names),
        cmocka_unit_test(test_timing),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
