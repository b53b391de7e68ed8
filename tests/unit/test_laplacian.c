/* SPDX-License-Identifier: GPL-3.0-or-later
 * test_laplacian.c -- particle Laplacians (lap_coeffs): CPM (Eqs. 16-17)
 * and MPS (Eq. 15) of Ng, Sheu & Hwang (2016) [NSH16], PS and IPS of
 * Hwang, Ng & Sheu (2016) [HNS16].
 *
 * CPM: exact for quadratics on irregular 24-neighbour clouds, observed order
 * for a smooth field, singular clouds refused, and the implicit row checked
 * against an explicit CPM evaluation done differently (weighted least
 * squares for all five derivatives by Gram-Schmidt QR, physical units).
 * MPS: exact for quadratics on a regular lattice with r_e = 2.1 l0, and
 * inconsistent on an irregular cloud: its error does not vanish as h -> 0.
 * PS and IPS ([HNS16]): the 1-D closed forms (Eqs. 30, 32, 33) to
 * round-off, IPS exact for linear and CPM for quadratic fields in 1-3 D,
 * PS's artificial velocity growing as 1/l0, the quality indicators against
 * Eqs. 13 and 22 written out, degenerate 3-D clouds refused.
 */
#include "testutil.h"
#include "umppm/laplacian.h"

#include <time.h>

/* ---- helpers ---------------------------------------------------------- */

#define NMAX 128

/* The 24 neighbours of a particle in a lattice of spacing h jittered by
 * +-jit*h (two rings of cells, 5x5 minus the centre); the particle itself is
 * jittered too. Offsets h_j, k_j into hh, kk; particle position into xi, yi
 * (the lattice origin is at (ox, oy)). */
static int cloud24(double h, double jit, double ox, double oy, double *xi, double *yi,
                   double *hh, double *kk)
{
    *xi = ox + jit * tu_rnd_in(-1, 1) * h;
    *yi = oy + jit * tu_rnd_in(-1, 1) * h;
    int n = 0;
    for (int i = -2; i <= 2; i++)
        for (int j = -2; j <= 2; j++) {
            if (i == 0 && j == 0)
                continue;
            double x = ox + (i + jit * tu_rnd_in(-1, 1)) * h;
            double y = oy + (j + jit * tu_rnd_in(-1, 1)) * h;
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

/* Relative error of the row a [n] on the quadratic f about (xi, yi), the
 * neighbours at offsets hh, kk (phi [n] is scratch): |lap - exact| over the
 * larger of |exact| and the rounding scale of the sum. */
static double quad_rel_error(const double *a, int n, const quad *f, double xi, double yi,
                             const double *hh, const double *kk, double *phi, double *lap, double *exact)
{
    for (int j = 0; j < n; j++)
        phi[j] = qval(f, xi + hh[j], yi + kk[j]);
    double sc;
    *lap = apply(a, phi, qval(f, xi, yi), n, &sc);
    *exact = 2 * f->q[4] + 2 * f->q[5];
    return fabs(*lap - *exact) / fmax(fabs(*exact), sc);
}

/* A quadratic with random coefficients of order 1 at the spacing h; wall
 * != 0: without the y and xy terms (zero y-derivative on y = 0). */
static quad random_quad(double h, int wall)
{
    quad f;
    for (int i = 0; i < 6; i++)
        f.q[i] = wall && (i == 2 || i == 3) ? 0 : tu_rnd_in(-1, 1) / (i == 0 ? 1 : i < 3 ? h : h * h);
    return f;
}

static const lap_params CPM = {LAP_CPM, 0};
static const lap_params MPS = {LAP_MPS, 2.1};

/* ---- CPM -------------------------------------------------------------- */

static void test_cpm_quadratic_exact(void **state)
{
    (void)state;
    tu_rng_seed(11);
    double hh[NMAX], kk[NMAX], a[NMAX], phi[NMAX];
    double worst = 0;
    for (int t = 0; t < 500; t++) {
        double h = pow(10, tu_rnd_in(-4, 2));
        double xi, yi;
        int n = cloud24(h, 0.45, tu_rnd_in(-10, 10) * h, tu_rnd_in(-10, 10) * h, &xi, &yi, hh, kk);
        quad f = random_quad(h, 0);
        ump_err err;
        assert_int_equal(lap_coeffs(&CPM, hh, kk, n, h, a, &err), UMP_OK);
        double lap, exact, rel = quad_rel_error(a, n, &f, xi, yi, hh, kk, phi, &lap, &exact);
        worst = fmax(worst, rel);
        if (!(rel <= 1e-10))
            fail_msg("trial %d: CPM %.17g, exact %.17g, rel %.3g", t, lap, exact, rel);
    }
    print_message("CPM on 500 irregular 24-neighbour clouds: worst rel. error %.3g\n", worst);
}

/* CPM in a cell metric (lap_coeffs_metric): exact for quadratics on clouds
 * stretched by 10^-3 .. 10^3 in x; with sx = sy the plain row; and on a
 * cloud stretched 1000:1 (a lattice of x-spacing 10^-3, y-spacing 1, the
 * stencil of a thin cell) it gives the Laplacian of a field varying on
 * both spacings, f = g(x/ax, y), where the plain fit is refused as
 * singular (the solver then falls back to MPS). */
static double fsin(double x, double y);
static void test_cpm_metric(void **state)
{
    (void)state;
    tu_rng_seed(23);
    double hh[NMAX], kk[NMAX], a[NMAX], b[NMAX], phi[NMAX];
    double worst = 0, worst_eq = 0;
    ump_err err;
    for (int t = 0; t < 200; t++) {
        double ax = pow(10, tu_rnd_in(-3, 3)), xi, yi;
        int n = cloud24(1, 0.45, 0, 0, &xi, &yi, hh, kk);
        /* the same metric in both directions: the plain CPM row */
        assert_int_equal(lap_coeffs_metric(&CPM, hh, kk, n, 1, 3.7, 3.7, a, &err), UMP_OK);
        assert_int_equal(lap_coeffs(&CPM, hh, kk, n, 1, b, &err), UMP_OK);
        double amax = 0, d = 0;
        for (int j = 0; j < n; j++) {
            amax = fmax(amax, fabs(b[j]));
            d = fmax(d, fabs(a[j] - b[j]));
        }
        worst_eq = fmax(worst_eq, d / amax);
        for (int j = 0; j < n; j++)
            hh[j] *= ax;
        xi *= ax;
        quad f;
        for (int i = 0; i < 6; i++)
            f.q[i] = tu_rnd_in(-1, 1) / (i == 1 || i == 3 ? ax : i == 4 ? ax * ax : 1);
        assert_int_equal(lap_coeffs_metric(&CPM, hh, kk, n, 1, 1 / ax, 1, a, &err), UMP_OK);
        double lap, exact, rel = quad_rel_error(a, n, &f, xi, yi, hh, kk, phi, &lap, &exact);
        worst = fmax(worst, rel);
        if (!(rel <= 1e-9))
            fail_msg("trial %d (ax %g): CPM metric %.17g, exact %.17g, rel %.3g", t, ax, lap, exact, rel);
    }
    if (!(worst_eq <= 1e-12))
        fail_msg("sx = sy against plain CPM: %.3g", worst_eq);
    /* thin-cell stencil: f = fsin(x / ax, y), lap f = -(1/ax^2 + 4) f */
    double ax = 1e-3, ep = 0, em = 0;
    for (int t = 0; t < 200; t++) {
        double xi, yi, ox = tu_rnd(), oy = tu_rnd();
        int n = cloud24(0.3, 0.3, ox, oy, &xi, &yi, hh, kk);
        for (int j = 0; j < n; j++)
            hh[j] *= ax;
        xi *= ax;
        double ex = -(1 / (ax * ax) + 4) * fsin(xi / ax, yi);
        for (int j = 0; j < n; j++)
            phi[j] = fsin((xi + hh[j]) / ax, yi + kk[j]);
        assert_int_equal(lap_coeffs_metric(&CPM, hh, kk, n, 1, 1 / ax, 1, a, &err), UMP_OK);
        em = fmax(em, fabs(apply(a, phi, fsin(xi / ax, yi), n, NULL) - ex) * ax * ax);
        if (lap_coeffs(&CPM, hh, kk, n, 1, b, &err) == UMP_OK)
            ep = fmax(ep, fabs(apply(b, phi, fsin(xi / ax, yi), n, NULL) - ex) * ax * ax);
        else
            ep = INFINITY;
    }
    print_message("CPM metric: quadratics worst rel. error %.3g (200 clouds stretched 1e-3..1e3), "
                  "sx = sy against plain %.3g; 1000:1 stencil, sin field: max error / (1/ax^2) "
                  "metric %.3g, plain %.3g\n", worst, worst_eq, em, ep);
    assert_true(em < ep);
}

/* Positive rows (lap_positive_row): on jittered 24-neighbour clouds, where
 * positive stencils exact for quadratics exist, the replaced row is
 * non-negative and within 1e-4 of exact on quadratics (the penalty on far
 * neighbours, 1e-3, is what keeps it from exact); a row without negative
 * coefficients is kept; on the stencil of a wall particle in a graded
 * column (x offsets growing by 2.68 per cell from 10^-4, y spacing 1, the
 * wall particle half a cell to the left) CPM's row in the cell metric is
 * more than 2 % negative and the positive row is non-negative and gives
 * the x-curvature of f = x^2 (which dominates, x-spacing 10^-4) to 1 %;
 * between 1 and 2 % the row is the blend of the two. */
static void test_positive_row(void **state)
{
    (void)state;
    tu_rng_seed(31);
    double hh[NMAX], kk[NMAX], a[NMAX], b[NMAX], phi[NMAX];
    double worst = 0;
    ump_err err;
    for (int t = 0; t < 200; t++) {
        double xi, yi, h = pow(10, tu_rnd_in(-3, 1));
        int n = cloud24(h, 0.3, 0, 0, &xi, &yi, hh, kk);
        assert_int_equal(lap_coeffs(&CPM, hh, kk, n, h, a, &err), UMP_OK);
        assert_int_equal(lap_positive_row(hh, kk, n, 1, 1, -1, a), 1); /* tau < 0: always */
        for (int j = 0; j < n; j++)
            assert_true(a[j] >= 0);
        quad f = random_quad(h, 0);
        double lap, exact, rel = quad_rel_error(a, n, &f, xi, yi, hh, kk, phi, &lap, &exact);
        worst = fmax(worst, rel);
        if (!(rel <= 1e-4))
            fail_msg("trial %d: positive row %.17g, exact %.17g, rel %.3g", t, lap, exact, rel);
        /* a row that is already non-negative is kept */
        for (int j = 0; j < n; j++)
            b[j] = a[j];
        assert_int_equal(lap_positive_row(hh, kk, n, 1, 1, 0.01, b), 0);
        for (int j = 0; j < n; j++)
            assert_true(b[j] == a[j]);
    }
    /* a wall particle of a graded column: cells of width 1e-4 * 2.68^i */
    int n = 0;
    double x0 = 0.5e-4, xc = 0, w = 1e-4;
    hh[n] = -x0, kk[n++] = 0; /* the wall's boundary particle */
    for (int i = 0; i < 3; i++) {
        double c = xc + 0.5 * w; /* centroid of column i */
        for (int j = -1; j <= 1; j++)
            if (i || j) {
                hh[n] = c - x0;
                kk[n++] = j;
            }
        xc += w;
        w *= 2.68;
    }
    hh[n] = -x0, kk[n++] = 1;
    hh[n] = -x0, kk[n++] = -1;
    double sx = 1e4, sy = 1;
    assert_int_equal(lap_coeffs_metric(&CPM, hh, kk, n, 1, sx, sy, a, &err), UMP_OK);
    double sp = 0, sn = 0;
    for (int j = 0; j < n; j++)
        a[j] > 0 ? (sp += a[j]) : (sn -= a[j]);
    /* between tau and 2 tau the blend: with tau = share / 1.5 the mean of
     * CPM's row and the positive row (tau <= 0: the positive row alone) */
    double cpm[NMAX], pos[NMAX], mid[NMAX];
    for (int j = 0; j < n; j++)
        cpm[j] = pos[j] = mid[j] = a[j];
    assert_int_equal(lap_positive_row(hh, kk, n, sx, sy, -1, pos), 1);
    assert_int_equal(lap_positive_row(hh, kk, n, sx, sy, sn / sp / 1.5, mid), 1);
    double dmax = 0, amax = 0;
    for (int j = 0; j < n; j++) {
        dmax = fmax(dmax, fabs(mid[j] - 0.5 * (cpm[j] + pos[j])));
        amax = fmax(amax, fabs(pos[j]) + fabs(cpm[j]));
    }
    assert_true(dmax <= 1e-12 * amax);
    assert_int_equal(lap_positive_row(hh, kk, n, sx, sy, 0.01, a), 1);
    double lx = 0;
    for (int j = 0; j < n; j++) {
        assert_true(a[j] >= 0);
        lx += a[j] * hh[j] * hh[j]; /* lap of x^2 */
    }
    print_message("positive rows: quadratics worst rel. error %.3g (200 jittered clouds); graded wall "
                  "stencil: CPM negative share %.3g, positive row lap(x^2) = %.6g (exact 2)\n",
                  worst, sn / sp, lx);
    assert_true(sn > 0.02 * sp);
    assert_true(fabs(lx - 2) < 0.02);
}

/* A positive row next to a particle 2e-6 away: the stencil of a particle
 * 2e-6 below the lid in the 8 x 8 cavity graded 3 000:1 toward its walls
 * (cells 1.5e-5 to 0.047 across; metric the cell's 1 / extents), as the
 * solver gave it. CPM's row is far from non-negative there; the positive
 * row's passive-set solve failed on the neighbour at 4e-4 of the stencil's
 * radius (its penalty 1e-6 r^6 made the Woodbury system singular), the row
 * came back as CPM's, and the predictor made 5.2 x the lid speed (README,
 * "Positive rows that failed"). Now it is replaced, non-negative, gives
 * lap(y^2) to 1 %, and lap(x^2) to 1 % of lap(y^2) in the metric's units
 * (x weighs (sx / sy)^2 = 2.3e-5 of y there, so the fit spends little on
 * it: measured 49 against 2). */
static void test_positive_row_close(void **state)
{
    (void)state;
    static const double hk[][2] = {
        {-0.065346, -0.00181503},     {-0.0185132, -0.00207769},   {-1.05715e-05, -0.00202135},
        {0.00174123, -0.00186908},    {0.00183934, -0.00186942},   {0.00185431, -0.00185165},
        {-0.0625571, -0.000116328},   {-0.0163962, -0.000174042},  {-3.51629e-06, -0.000133709},
        {0.00173695, -0.000131126},   {0.00184365, -0.000129},     {0.00185431, -0.000126536},
        {-0.0615292, -7.0919e-06},    {-0.0149364, -7.04827e-06},  {0.00172689, -6.70599e-06},
        {0.00184545, -3.29237e-06},   {-0.0714128, 8.31681e-07},   {-0.0248786, 8.31681e-07},
        {1.83446e-06, 8.31681e-07},   {0.00172694, 8.31681e-07},   {0.00184656, 8.31681e-07},
        {0.00185431, -6.92403e-06}};
    int n = (int)(sizeof hk / sizeof hk[0]);
    double hh[NMAX], kk[NMAX], a[NMAX], sx = 309.933, sy = 64468.6;
    for (int j = 0; j < n; j++)
        hh[j] = hk[j][0], kk[j] = hk[j][1];
    ump_err err;
    assert_int_equal(lap_coeffs_metric(&CPM, hh, kk, n, 1, sx, sy, a, &err), UMP_OK);
    double sp = 0, sn = 0;
    for (int j = 0; j < n; j++)
        a[j] > 0 ? (sp += a[j]) : (sn -= a[j]);
    assert_int_equal(lap_positive_row(hh, kk, n, sx, sy, 0.01, a), 1);
    double lx = 0, ly = 0, neg = 0;
    for (int j = 0; j < n; j++) {
        neg = fmin(neg, a[j]);
        lx += a[j] * hh[j] * hh[j];
        ly += a[j] * kk[j] * kk[j];
    }
    print_message("positive row beside a neighbour 2e-6 away: CPM negative share %.3g; positive row "
                  "min a_j %.3g, lap(x^2) %.6g, lap(y^2) %.6g (exact 2)\n", sn / sp, neg, lx, ly);
    assert_true(sn > 0.01 * sp);
    assert_true(neg >= 0);
    assert_true(fabs(ly - 2) < 0.02);
    assert_true(fabs(lx - 2) * (sx / sy) * (sx / sy) < 0.02);
}

/* Zero-gradient samples (lap_cpm_neumann, lap_positive_row_neumann):
 * (1) a particle in the first row above a wall y = 0, jittered lattice
 * neighbours in three rows and five wall samples with d/dy = 0: the row is
 * exact on the quadratics whose y-derivative vanishes on the wall (no y
 * and xy terms), gives the wall samples 0, and its positive form is
 * non-negative and within 1e-3 of them; without normals it is
 * lap_coeffs_metric's row. (2) The wall particle of a cell 0.069 x 0.0011
 * (the stratified box graded 200:1, whose adiabatic walls froze T: README,
 * "Zero-gradient walls in the Laplacian"): x^2 and (y - y_wall)^2 exact,
 * and the positive row keeps lap(x^2) to 1 %. */
static void test_cpm_neumann(void **state)
{
    (void)state;
    tu_rng_seed(47);
    double hh[NMAX], kk[NMAX], nx[NMAX], ny[NMAX], a[NMAX], b[NMAX], phi[NMAX];
    double worst = 0, worstp = 0;
    ump_err err;
    for (int t = 0; t < 200; t++) {
        double h = pow(10, tu_rnd_in(-3, 1)), jit = 0.3;
        double xi = jit * tu_rnd_in(-1, 1) * h, yi = (0.5 + 0.4 * jit * tu_rnd_in(-1, 1)) * h;
        int n = 0;
        for (int i = -2; i <= 2; i++)
            for (int j = 0; j <= 2; j++) {
                if (i == 0 && j == 0)
                    continue;
                hh[n] = (i + jit * tu_rnd_in(-1, 1)) * h - xi;
                kk[n] = (j + 0.5 + 0.4 * jit * tu_rnd_in(-1, 1)) * h - yi;
                nx[n] = ny[n] = 0;
                n++;
            }
        for (int i = -2; i <= 2; i++) { /* the wall's samples */
            hh[n] = i * h - xi;
            kk[n] = -yi;
            nx[n] = 0;
            ny[n++] = t % 2 ? -1 : 1; /* either orientation */
        }
        double sx = (t % 3 ? 1 : tu_rnd_in(0.5, 2)) / h, sy = 1 / h;
        assert_int_equal(lap_cpm_neumann(hh, kk, nx, ny, n, sx, sy, a, &err), UMP_OK);
        for (int j = n - 5; j < n; j++)
            assert_true(a[j] == 0);
        quad f = random_quad(h, 1);
        double lap, exact, rel = quad_rel_error(a, n, &f, xi, yi, hh, kk, phi, &lap, &exact);
        worst = fmax(worst, rel);
        if (!(rel <= 1e-9))
            fail_msg("trial %d: zero-gradient row %.17g, exact %.17g, rel %.3g", t, lap, exact, rel);
        for (int j = 0; j < n; j++)
            b[j] = a[j];
        assert_int_equal(lap_positive_row_neumann(hh, kk, nx, ny, n, sx, sy, -1, b), 1);
        for (int j = 0; j < n; j++)
            assert_true(b[j] >= 0 && (j < n - 5 || b[j] == 0));
        rel = quad_rel_error(b, n, &f, xi, yi, hh, kk, phi, &lap, &exact);
        worstp = fmax(worstp, rel);
        if (!(rel <= 1e-3))
            fail_msg("trial %d: positive zero-gradient row %.17g, exact %.17g, rel %.3g", t, lap, exact, rel);
        /* no normals: CPM's row */
        assert_int_equal(lap_cpm_neumann(hh, kk, NULL, NULL, n, sx, sy, a, &err), UMP_OK);
        assert_int_equal(lap_coeffs_metric(&CPM, hh, kk, n, h, sx, sy, b, &err), UMP_OK);
        double amax = 0, dmax = 0;
        for (int j = 0; j < n; j++) {
            amax = fmax(amax, fabs(b[j]));
            dmax = fmax(dmax, fabs(a[j] - b[j]));
        }
        assert_true(dmax <= 1e-9 * amax);
    }
    /* (2) the thin wall cell: 4 columns x 3 rows of particles, the wall's
     * samples 5.58e-4 below (offsets of the particle at the centroid) */
    static const double xs[5] = {-2.6974e-01, -9.6280e-02, 0, 5.3440e-02, 8.3101e-02};
    static const double ys[3] = {0, 1.5626e-03, 4.3778e-03};
    double yw = -5.5774e-04;
    int n = 0;
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 5; c++)
            if (r || c != 2)
                hh[n] = xs[c], kk[n] = ys[r], nx[n] = ny[n] = 0, n++;
    for (int c = 0; c < 5; c++)
        hh[n] = xs[c], kk[n] = yw, nx[n] = 0, ny[n] = -1, n++;
    double sx = 1 / 0.0687307, sy = 1 / 0.00111548;
    assert_int_equal(lap_cpm_neumann(hh, kk, nx, ny, n, sx, sy, a, &err), UMP_OK);
    double lxx = 0, lyy = 0, pxx = 0;
    for (int j = 0; j < n; j++) {
        lxx += a[j] * hh[j] * hh[j];
        lyy += a[j] * ((kk[j] - yw) * (kk[j] - yw) - yw * yw);
        b[j] = a[j];
    }
    assert_int_equal(lap_positive_row_neumann(hh, kk, nx, ny, n, sx, sy, -1, b), 1);
    for (int j = 0; j < n; j++) {
        assert_true(b[j] >= 0);
        pxx += b[j] * hh[j] * hh[j];
    }
    print_message("zero-gradient rows: quadratics worst rel. error %.3g, positive %.3g (200 clouds); thin wall "
                  "cell: lap(x^2) %.9g, lap((y-yw)^2) %.9g, positive lap(x^2) %.6g (exact 2)\n",
                  worst, worstp, lxx, lyy, pxx);
    assert_true(fabs(lxx - 2) < 1e-8 && fabs(lyy - 2) < 1e-8);
    assert_true(fabs(pxx - 2) < 0.02);
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
        double ox = h * floor(tu_rnd() / h), oy = h * floor(tu_rnd() / h);
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
    tu_rng_seed(12);
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

/* CPM4 (the fourth-order basis): exact for quartics on irregular
 * 24-neighbour clouds of any scale, also in a stretched metric; a jittered
 * cloud's error of a smooth field falls at order >= 2.5 (a quartic fit:
 * the second derivatives' error is O(h^3) on an irregular cloud, O(h^4) on
 * the lattice), where CPM falls at order 1. */
static double quartic(const double *c, double x, double y)
{
    double s = 0;
    int m = 0;
    for (int d = 0; d <= 4; d++)
        for (int e = 0; e <= d; e++)
            s += c[m++] * pow(x, e) * pow(y, d - e);
    return s;
}
static double quartic_lap(const double *c, double x, double y)
{
    double s = 0;
    int m = 0;
    for (int d = 0; d <= 4; d++)
        for (int e = 0; e <= d; e++, m++) {
            int f = d - e;
            if (e >= 2)
                s += c[m] * e * (e - 1) * pow(x, e - 2) * pow(y, f);
            if (f >= 2)
                s += c[m] * f * (f - 1) * pow(x, e) * pow(y, f - 2);
        }
    return s;
}

static void test_cpm4(void **state)
{
    (void)state;
    tu_rng_seed(31);
    const lap_params CPM4 = {LAP_CPM4, 0};
    double hh[NMAX], kk[NMAX], a[NMAX], phi[NMAX], worst = 0, worst_m = 0;
    ump_err err;
    for (int t = 0; t < 400; t++) {
        int metric = t % 2;
        double h = pow(10, tu_rnd_in(-4, 2)), ax = metric ? pow(10, tu_rnd_in(-3, 3)) : 1, xi, yi, c[15];
        int n = cloud24(h, 0.45, tu_rnd_in(-10, 10) * h, tu_rnd_in(-10, 10) * h, &xi, &yi, hh, kk);
        for (int j = 0; j < n; j++)
            hh[j] *= ax;
        xi *= ax;
        int m = 0;
        for (int d = 0; d <= 4; d++)
            for (int e = 0; e <= d; e++) /* each term of size 1 on the cloud */
                c[m++] = tu_rnd_in(-1, 1) / (pow(ax * h, e) * pow(h, d - e));
        assert_int_equal(metric ? lap_coeffs_metric(&CPM4, hh, kk, n, h, 1 / ax, 1, a, &err)
                                : lap_coeffs(&CPM4, hh, kk, n, h, a, &err),
                         UMP_OK);
        for (int j = 0; j < n; j++) /* about (xi, yi): the polynomial in the offsets */
            phi[j] = quartic(c, hh[j], kk[j]);
        double sc, lap = apply(a, phi, quartic(c, 0, 0), n, &sc), ex = quartic_lap(c, 0, 0);
        double rel = fabs(lap - ex) / fmax(fabs(ex), sc);
        if (metric)
            worst_m = fmax(worst_m, rel);
        else
            worst = fmax(worst, rel);
        if (!(rel <= 1e-8))
            fail_msg("trial %d (h %g, ax %g): CPM4 %.17g, exact %.17g, rel %.3g", t, h, ax, lap, ex, rel);
    }
    /* too few neighbours for 14 terms: refused (the solver falls back to CPM) */
    assert_int_equal(lap_coeffs(&CPM4, hh, kk, 13, 1, a, &err), UMP_ERR_SINGULAR);
    print_message("CPM4 quartics: worst rel. error %.3g (200 clouds), %.3g (200 stretched "
                  "1e-3..1e3); 13 neighbours: %s\n", worst, worst_m, err.msg);
    enum { NH = 4 };
    const double hs[NH] = {0.1, 0.05, 0.025, 0.0125};
    double e4[NH], e2[NH];
    for (int k = 0; k < NH; k++) {
        e4[k] = lap_error(&CPM4, hs[k], 0.3, 400);
        e2[k] = lap_error(&CPM, hs[k], 0.3, 400);
        print_message("jitter 0.3 h, h %-7g max err CPM4 %.3e CPM %.3e\n", hs[k], e4[k], e2[k]);
    }
    double p4 = log(e4[0] / e4[NH - 1]) / log(hs[0] / hs[NH - 1]);
    print_message("CPM4 observed order (jitter 0.3 h): %.2f\n", p4);
    assert_true(p4 >= 2.5);
    for (int k = 0; k < NH; k++)
        assert_true(e4[k] < e2[k]);
    double r0 = lap_error(&CPM4, 0.05, 0, 50), r1 = lap_error(&CPM4, 0.025, 0, 50);
    print_message("CPM4 regular lattice: err %.3e -> %.3e (order %.2f)\n", r0, r1, log2(r0 / r1));
    assert_true(log2(r0 / r1) >= 3.8);
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
    tu_rng_seed(13);
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
    double Q[5][NMAX], b[NMAX], D[5];
    for (int j = 0; j < n; j++) {
        double r = sqrt(hh[j] * hh[j] + kk[j] * kk[j]), w = 1 / (r * r * r);
        double p[5] = {hh[j], kk[j], 0.5 * hh[j] * hh[j], hh[j] * kk[j], 0.5 * kk[j] * kk[j]};
        for (int i = 0; i < 5; i++)
            Q[i][j] = w * p[i];
        b[j] = w * dphi[j];
    }
    tu_lsq_qr(5, n, NMAX, &Q[0][0], b, D);
    return D[2] + D[4];
}

/* The implicit row (diagonal -sum a_j, off-diagonal a_j) applied to phi
 * equals sum_j a_j (phi_j - phi_i) and the explicit CPM value. */
static void test_implicit_row(void **state)
{
    (void)state;
    tu_rng_seed(14);
    double hh[NMAX], kk[NMAX], a[NMAX], phi[NMAX], dphi[NMAX];
    double worst = 0;
    for (int t = 0; t < 300; t++) {
        double h = tu_rnd_in(0.2, 2), xi, yi;
        int n = cloud24(h, 0.4, 0, 0, &xi, &yi, hh, kk);
        n -= (int)(tu_rnd() * 12); /* 12..24 neighbours */
        ump_err err;
        assert_int_equal(lap_coeffs(&CPM, hh, kk, n, h, a, &err), UMP_OK);
        double phii = tu_rnd_in(-1, 1), diag = 0, row = 0;
        for (int j = 0; j < n; j++) {
            phi[j] = tu_rnd_in(-1, 1); /* arbitrary data */
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
    tu_rng_seed(15);
    double hh[NMAX], kk[NMAX], a[NMAX], phi[NMAX];
    for (int t = 0; t < 50; t++) {
        double l0 = pow(10, tu_rnd_in(-3, 1)), xi, yi;
        int n = cloud24(l0, 0, tu_rnd_in(-3, 3), tu_rnd_in(-3, 3), &xi, &yi, hh, kk);
        ump_err err;
        assert_int_equal(lap_coeffs(&MPS, hh, kk, n, l0, a, &err), UMP_OK);
        int inside = 0;
        for (int j = 0; j < n; j++)
            inside += a[j] != 0;
        assert_int_equal(inside, 12); /* r in {1, sqrt 2, 2} l0 < 2.1 l0 */
        quad f;
        for (int i = 0; i < 6; i++)
            f.q[i] = tu_rnd_in(-1, 1);
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
        tu_rng_seed(16);
        emps[k] = lap_error(&MPS, hs[k], 0.2, NT);
        tu_rng_seed(16);
        ecpm[k] = lap_error(&CPM, hs[k], 0.2, NT);
        /* RMS error for phi = x^2 - y^2 */
        tu_rng_seed(17);
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

/* ---- [HNS16]: PS, IPS, and the d-dimensional operators ------------------ */

static const lap_params PS = {LAP_PS, 2.0};
static const lap_params IPS = {LAP_IPS, 2.0};

/* A random cloud around the origin in dim dimensions: n neighbours at
 * offsets within (0.3, 1.9) l0 in every direction of a jittered lattice
 * window (so all lie inside r_e = 2 l0). */
static int cloud_d(int dim, double l0, double jit, double *off[3])
{
    int n = 0;
    for (int i = -2; i <= 2; i++)
        for (int j = (dim > 1 ? -2 : 0); j <= (dim > 1 ? 2 : 0); j++)
            for (int k = (dim > 2 ? -1 : 0); k <= (dim > 2 ? 1 : 0); k++) {
                if (!i && !j && !k)
                    continue;
                int o[3] = {i, j, k};
                double r2 = 0, x[3];
                for (int d = 0; d < dim; d++) {
                    x[d] = (o[d] + jit * tu_rnd_in(-1, 1)) * l0;
                    r2 += x[d] * x[d];
                }
                if (r2 >= 1.9 * 1.9 * l0 * l0 || r2 < 0.09 * l0 * l0)
                    continue;
                for (int d = 0; d < dim; d++)
                    off[d][n] = x[d];
                n++;
            }
    return n;
}

/* [HNS16] Eqs. 30a, 30b: PS and IPS of phi = a x + b x^2 on an irregular
 * 1-D cloud, against the closed forms written with the Omega sums (Eq. 25b)
 * computed here independently. */
static void test_ps_ips_1d_closed_forms(void **state)
{
    (void)state;
    tu_rng_seed(21);
    double h[NMAX], c[NMAX], phi[NMAX];
    double worst = 0;
    for (int t = 0; t < 200; t++) {
        double l0 = pow(10, tu_rnd_in(-3, 1)), re = 2 * l0;
        int n = 0;
        for (int j = -2; j <= 2; j++) /* neighbours at (j +- 0.45) l0, j != 0 */
            if (j)
                h[n++] = (j + 0.45 * tu_rnd_in(-1, 1)) * l0;
        double A = tu_rnd_in(-2, 2) / l0, Bq = tu_rnd_in(-2, 2) / (l0 * l0);
        for (int j = 0; j < n; j++)
            phi[j] = A * h[j] + Bq * h[j] * h[j];
        double O0 = 0, O21 = 0, O23 = 0; /* Omega_0^(0), Omega_2^(1), Omega_2^(3) */
        for (int j = 0; j < n; j++) {
            double r = fabs(h[j]), w = r < re ? re / r - 1 : 0;
            O0 += w;
            O21 += w * h[j] / (r * r);
            O23 += w * h[j] * h[j] * h[j] / (r * r);
        }
        const double *off[1] = {h};
        ump_err err;
        assert_int_equal(lap_coeffs_d(&PS, 1, off, n, l0, c, &err), UMP_OK);
        double sc, ps = apply(c, phi, 0, n, &sc);
        assert_true(lap_value(c, phi, 0, n) == ps); /* the explicit value, same sum */
        double e30a = 2 * A * O21 / O0 + 2 * Bq; /* Eq. 30a */
        double rel = fabs(ps - e30a) / fmax(fabs(e30a), sc);
        worst = fmax(worst, rel);
        if (!(rel <= 1e-13))
            fail_msg("PS 1-D: %.17g vs Eq. 30a %.17g", ps, e30a);
        assert_int_equal(lap_coeffs_d(&IPS, 1, off, n, l0, c, &err), UMP_OK);
        double ips = apply(c, phi, 0, n, &sc);
        double e30b = 2 * Bq * (1 - O21 * O23 / (O0 * O0)); /* Eq. 30b */
        rel = fabs(ips - e30b) / fmax(fabs(e30b), sc);
        worst = fmax(worst, rel);
        if (!(rel <= 1e-13))
            fail_msg("IPS 1-D: %.17g vs Eq. 30b %.17g", ips, e30b);
    }
    print_message("Eqs. 30a/30b on 200 irregular 1-D clouds: worst rel. difference %.3g\n", worst);
}

/* [HNS16] Eqs. 31-33: the three-point problem, PS and IPS at x = 0 with
 * neighbours at 1 and -1 + alpha (r_e = 2), against Eqs. 32a, 32b and the
 * reality factor of IPS, Eq. 33b (exact in alpha, not only to O(alpha^3)). */
static void test_three_point(void **state)
{
    (void)state;
    const double stars[4] = {2.0, 0.5, -0.5, -2.0};
    double worst = 0;
    for (int s = 0; s < 4; s++)
        for (int k = 0; k <= 18; k++) {
            double al = 0.05 * k, ps = stars[s];
            double h[2] = {1, -1 + al}, ph[2] = {1, ps}, a[2];
            const double *off[1] = {h};
            ump_err err;
            double ex = 2 * (1 - al + ps) / ((1 - al) * (2 - al)); /* Eq. 31c */
            double ws = (1 + al) / (1 - al);                        /* Eq. 32c */
            double e32a = 2 * ((1 - al) * (1 - al) + ps * ws) / ((1 - al) * (1 - al) * (1 + ws));
            double e32b = ex * (1 - (1 - al - ws) * (1 - (1 - al) * ws) /
                                        ((1 - al) * (1 + ws) * (1 + ws)));
            double e33b = 1 - 0.75 * al * al + 0.25 * al * al * al;
            assert_int_equal(lap_coeffs_d(&PS, 1, off, 2, 1.0, a, &err), UMP_OK);
            double vps = a[0] * ph[0] + a[1] * ph[1];
            assert_int_equal(lap_coeffs_d(&IPS, 1, off, 2, 1.0, a, &err), UMP_OK);
            double vips = a[0] * ph[0] + a[1] * ph[1];
            double d1 = fabs(vps - e32a) / fmax(fabs(e32a), 1), d2 = fabs(vips - e32b) / fmax(fabs(e32b), 1);
            double d3 = fabs(ex) > 1e-9 ? fabs(vips / ex - e33b) : 0;
            worst = fmax(worst, fmax(d1, fmax(d2, d3)));
            if (!(d1 <= 1e-13 && d2 <= 1e-13 && d3 <= 1e-12))
                fail_msg("three-point alpha %g phi* %g: PS %.17g (32a %.17g) IPS %.17g (32b %.17g) "
                         "reality %.17g (33b %.17g)", al, ps, vps, e32a, vips, e32b, vips / ex, e33b);
        }
    print_message("three-point problem, 76 cases: worst rel. difference to Eqs. 32a/32b/33b %.3g\n",
                  worst);
}

/* IPS is exact for linear fields and CPM for quadratics in 1, 2 and 3-D;
 * PS is not exact even for linear fields, and its error there is exactly
 * u_N . grad phi with u_N growing as 1/l0 (Eqs. 10, 12-14). */
static void test_consistency_by_dimension(void **state)
{
    (void)state;
    tu_rng_seed(22);
    double buf[3][NMAX], a[NMAX], phi[NMAX];
    double *off[3] = {buf[0], buf[1], buf[2]};
    for (int dim = 1; dim <= 3; dim++) {
        double wl = 0, wq = 0;
        for (int t = 0; t < 200; t++) {
            double l0 = pow(10, tu_rnd_in(-3, 1));
            int n = cloud_d(dim, l0, 0.3, off);
            double g[3], H[3][3];
            for (int d = 0; d < 3; d++) {
                g[d] = tu_rnd_in(-1, 1) / l0;
                for (int e = 0; e < 3; e++)
                    H[d][e] = tu_rnd_in(-1, 1) / (l0 * l0);
            }
            ump_err err;
            const double *co[3] = {off[0], off[1], off[2]};
            /* linear field, IPS */
            for (int j = 0; j < n; j++) {
                phi[j] = 0;
                for (int d = 0; d < dim; d++)
                    phi[j] += g[d] * off[d][j];
            }
            if (lap_coeffs_d(&IPS, dim, co, n, l0, a, &err) != UMP_OK)
                fail_msg("IPS %d-D: %s", dim, err.msg);
            double sc, v = apply(a, phi, 0, n, &sc);
            wl = fmax(wl, fabs(v) / sc);
            if (!(fabs(v) <= 1e-12 * sc))
                fail_msg("IPS %d-D linear field: %.3g (scale %.3g)", dim, v, sc);
            /* PS on the same linear field: exactly first-moment . g */
            assert_int_equal(lap_coeffs_d(&PS, dim, co, n, l0, a, &err), UMP_OK);
            double first[3], second[6], u = 0;
            lap_moments(dim, co, n, a, first, second);
            for (int d = 0; d < dim; d++)
                u += first[d] * g[d];
            v = apply(a, phi, 0, n, &sc);
            assert_true(fabs(v - u) <= 1e-12 * sc);
            /* quadratic field (symmetric part of H), CPM */
            for (int j = 0; j < n; j++) {
                phi[j] = 0;
                for (int d = 0; d < dim; d++) {
                    phi[j] += g[d] * off[d][j];
                    for (int e = 0; e < dim; e++)
                        phi[j] += 0.5 * 0.5 * (H[d][e] + H[e][d]) * off[d][j] * off[e][j];
                }
            }
            double lapx = 0;
            for (int d = 0; d < dim; d++)
                lapx += H[d][d];
            if (lap_coeffs_d(&CPM, dim, co, n, l0, a, &err) != UMP_OK)
                fail_msg("CPM %d-D: %s", dim, err.msg);
            v = apply(a, phi, 0, n, &sc);
            double rel = fabs(v - lapx) / fmax(fabs(lapx), sc);
            wq = fmax(wq, rel);
            if (!(rel <= 1e-10))
                fail_msg("CPM %d-D quadratic: %.17g vs %.17g", dim, v, lapx);
        }
        print_message("%d-D: IPS on linear fields worst |lap|/scale %.3g, CPM on quadratics worst "
                      "rel. error %.3g (200 clouds each)\n", dim, wl, wq);
    }
    /* u_N of PS scales as 1/l0 on a scaled copy of one cloud (O(1/delta), Eq. 12) */
    tu_rng_seed(23);
    int n = cloud_d(2, 1.0, 0.3, off);
    double base[3][NMAX];
    for (int d = 0; d < 2; d++)
        memcpy(base[d], off[d], (size_t)n * sizeof(double));
    double u1 = 0;
    for (int s = 0; s < 4; s++) {
        double l0 = pow(0.5, s), first[3], second[6];
        for (int d = 0; d < 2; d++)
            for (int j = 0; j < n; j++)
                off[d][j] = base[d][j] * l0;
        const double *co[3] = {off[0], off[1], off[2]};
        ump_err err;
        assert_int_equal(lap_coeffs_d(&PS, 2, co, n, l0, a, &err), UMP_OK);
        lap_moments(2, co, n, a, first, second);
        double u = hypot(first[0], first[1]);
        if (s == 0)
            u1 = u;
        assert_true(u1 > 0.05);
        assert_true(fabs(u * l0 - u1) <= 1e-12 * u1);
    }
}

/* The quality indicators against the sums of [HNS16] written out:
 * u_N = 4 Omega_2^(1,0) / Omega_0^(0,0) (Eq. 13) and tau of Eqs. 22a-c;
 * on a regular lattice u_N = 0, tau = I and PS = IPS. */
static void test_quality_closed_forms(void **state)
{
    (void)state;
    tu_rng_seed(24);
    double buf[3][NMAX], a[NMAX], a2[NMAX], work[NMAX];
    double *off[3] = {buf[0], buf[1], buf[2]};
    for (int t = 0; t < 100; t++) {
        double l0 = pow(10, tu_rnd_in(-2, 1)), re = 2 * l0;
        int n = cloud_d(2, l0, 0.4, off);
        double O[4][4] = {{0}}; /* O[q][r] = Omega_2^(q,r), plus Omega_0^(0,0) */
        double O0 = 0;
        for (int j = 0; j < n; j++) {
            double h = off[0][j], k = off[1][j], r2 = h * h + k * k, r = sqrt(r2);
            double w = r < re ? re / r - 1 : 0;
            O0 += w;
            for (int q = 0; q <= 3; q++)
                for (int r_ = 0; q + r_ <= 3; r_++)
                    O[q][r_] += pow(h, q) * pow(k, r_) * w / r2;
        }
        double det = O[2][0] * O[0][2] - O[1][1] * O[1][1];
        double cx = (O[1][0] * O[0][2] - O[0][1] * O[1][1]) / det;
        double cy = (O[0][1] * O[2][0] - O[1][0] * O[1][1]) / det;
        double txx = 2 / O0 * (O[2][0] - cx * O[3][0] - cy * O[2][1]); /* Eq. 22a */
        double txy = 2 / O0 * (O[1][1] - cx * O[2][1] - cy * O[1][2]); /* Eq. 22b */
        double tyy = 2 / O0 * (O[0][2] - cx * O[1][2] - cy * O[0][3]); /* Eq. 22c */
        double uN = 4 * O[1][0] / O0, vN = 4 * O[0][1] / O0;            /* Eq. 13 */
        const double *co[3] = {off[0], off[1], off[2]};
        lap_quality q;
        ump_err err;
        assert_int_equal(lap_quality_d(2.0, 2, co, n, l0, work, &q, &err), UMP_OK);
        double su = (fabs(uN) + fabs(vN)) + 1 / l0;
        assert_true(fabs(q.uN[0] - uN) <= 1e-12 * su && fabs(q.uN[1] - vN) <= 1e-12 * su);
        assert_true(fabs(q.tau[0] - txx) <= 1e-12 && fabs(q.tau[1] - txy) <= 1e-12 &&
                    fabs(q.tau[3] - tyy) <= 1e-12);
        assert_true(q.uN[2] == 0 && q.tau[2] == 0 && q.tau[4] == 0 && q.tau[5] == 0);
        /* the IPS row with the sums of Eq. 20 */
        assert_int_equal(lap_coeffs_d(&IPS, 2, co, n, l0, a, &err), UMP_OK);
        for (int j = 0; j < n; j++) {
            double h = off[0][j], k = off[1][j], r2 = h * h + k * k, r = sqrt(r2);
            double w = r < re ? re / r - 1 : 0;
            double e = 4 / O0 * w / r2 * (1 - cx * h - cy * k);
            assert_true(fabs(a[j] - e) <= 1e-12 * (fabs(e) + 1 / (l0 * l0)));
        }
    }
    /* regular lattice: PS = IPS, u_N = 0, tau = I (r_e = 2 l0: 8 neighbours) */
    double xi, yi, hh[NMAX], kk[NMAX];
    int n = cloud24(0.1, 0, 0, 0, &xi, &yi, hh, kk);
    assert_int_equal(lap_coeffs(&PS, hh, kk, n, 0.1, a, &(ump_err){0}), UMP_OK);
    assert_int_equal(lap_coeffs(&IPS, hh, kk, n, 0.1, a2, &(ump_err){0}), UMP_OK);
    for (int j = 0; j < n; j++)
        assert_true(fabs(a[j] - a2[j]) <= 1e-12 * fabs(a[j]) + 1e-9);
    const double *co[3] = {hh, kk, NULL};
    lap_quality q;
    assert_int_equal(lap_quality_d(0, 2, co, n, 0.1, work, &q, &(ump_err){0}), UMP_OK);
    assert_true(fabs(q.uN[0]) < 1e-10 && fabs(q.uN[1]) < 1e-10);
    assert_true(fabs(q.tau[0] - 1) < 1e-12 && fabs(q.tau[1]) < 1e-12 && fabs(q.tau[3] - 1) < 1e-12);
}

/* Degenerate clouds in 3-D: all neighbours in a plane make CPM's 9x9 and
 * IPS's 3x3 matrices singular; they are refused, not answered. */
static void test_3d_singular(void **state)
{
    (void)state;
    tu_rng_seed(25);
    double buf[3][NMAX], a[NMAX];
    double *off[3] = {buf[0], buf[1], buf[2]};
    int n = cloud_d(3, 1.0, 0.3, off);
    for (int j = 0; j < n; j++)
        off[2][j] = 0.3 * off[0][j] - 0.2 * off[1][j]; /* a plane through i */
    const double *co[3] = {off[0], off[1], off[2]};
    ump_err err;
    assert_int_equal(lap_coeffs_d(&CPM, 3, co, n, 1.0, a, &err), UMP_ERR_SINGULAR);
    print_message("coplanar, CPM: %s\n", err.msg);
    assert_int_equal(lap_coeffs_d(&IPS, 3, co, n, 1.0, a, &err), UMP_ERR_SINGULAR);
    print_message("coplanar, IPS: %s\n", err.msg);
    assert_int_equal(lap_coeffs_d(&PS, 3, co, n, 1.0, a, &err), UMP_OK); /* PS needs no inverse */
    assert_int_equal(lap_coeffs_d(&CPM, 4, co, n, 1.0, a, &err), UMP_ERR_INPUT);
    assert_int_equal(lap_coeffs_d(&CPM, 0, co, n, 1.0, a, &err), UMP_ERR_INPUT);
    lap_params bad = {LAP_IPS, -1};
    assert_int_equal(lap_coeffs_d(&bad, 3, co, n, 1.0, a, &err), UMP_ERR_INPUT);
    lap_params dflt = {LAP_IPS, 0};
    assert_true(lap_re_factor(&dflt) == 2.0 && lap_re_factor(&(lap_params){LAP_MPS, 0}) == 2.1);
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
    assert_string_equal(lap_name(LAP_CPM4), "CPM4");
    assert_string_equal(lap_name((lap_model)17), "unknown");
    for (int m = LAP_CPM; m <= LAP_CPM4; m++)
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
    tu_rng_seed(18);
    enum { REP = 200000 };
    double hh[NMAX], kk[NMAX], a[NMAX], xi, yi;
    int n = cloud24(1, 0.3, 0, 0, &xi, &yi, hh, kk);
    const lap_params CPM4 = {LAP_CPM4, 0}, *ps[3] = {&CPM, &MPS, &CPM4};
    for (int m = 0; m < 3; m++) {
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
        cmocka_unit_test(test_cpm_metric),
        cmocka_unit_test(test_positive_row),
        cmocka_unit_test(test_positive_row_close),
        cmocka_unit_test(test_cpm_neumann),
        cmocka_unit_test(test_cpm_order),
        cmocka_unit_test(test_cpm4),
        cmocka_unit_test(test_cpm_singular),
        cmocka_unit_test(test_cpm_coincident_neighbour),
        cmocka_unit_test(test_implicit_row),
        cmocka_unit_test(test_mps_regular_lattice),
        cmocka_unit_test(test_mps_inconsistent),
        cmocka_unit_test(test_mps_params),
        cmocka_unit_test(test_ps_ips_1d_closed_forms),
        cmocka_unit_test(test_three_point),
        cmocka_unit_test(test_consistency_by_dimension),
        cmocka_unit_test(test_quality_closed_forms),
        cmocka_unit_test(test_3d_singular),
        cmocka_unit_test(test_names),
        cmocka_unit_test(test_timing),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
