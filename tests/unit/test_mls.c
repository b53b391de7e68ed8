/* SPDX-License-Identifier: GPL-3.0-or-later
 * test_mls.c -- moving-least-squares weights (mls_weights, Eqs. 27-35).
 *
 * Exactness for quadratics on random clouds and on triangle-mesh vertices
 * and centroids; the linear and Shepard fallbacks; a differential oracle
 * (weighted least squares solved by modified Gram-Schmidt QR on sqrt(w)-
 * scaled rows in physical coordinates, i.e. without normal equations and
 * without the normalisation); scale invariance; a sample on the target;
 * observed order of convergence for a smooth field; cost per call.
 */
#include "testutil.h"
#include "umppm/mls.h"
#include "umppm/ump.h"

#include <time.h>

/* ---- helpers ---------------------------------------------------------- */

/* Quadratic f = q0 + q1 x + q2 y + q3 xy + q4 x^2 + q5 y^2 (absolute coordinates). */
typedef struct { double q[6]; } quad;
static quad rnd_quad(void)
{
    quad f;
    for (int i = 0; i < 6; i++)
        f.q[i] = tu_rnd_in(-1, 1);
    return f;
}
static double qval(const quad *f, double x, double y)
{
    const double *q = f->q;
    return q[0] + q[1] * x + q[2] * y + q[3] * x * y + q[4] * x * x + q[5] * y * y;
}
static double qdx(const quad *f, double x, double y) { return f->q[1] + f->q[3] * y + 2 * f->q[4] * x; }
static double qdy(const quad *f, double x, double y) { return f->q[2] + f->q[3] * x + 2 * f->q[5] * y; }

static double dot(const double *c, const double *u, int n)
{
    double s = 0;
    for (int j = 0; j < n; j++)
        s += c[j] * u[j];
    return s;
}
static double absdot(const double *c, const double *u, int n)
{
    double s = 0;
    for (int j = 0; j < n; j++)
        s += fabs(c[j] * u[j]);
    return s;
}

/* |est - exact| <= tol * scale, scale = max(|exact|, sum |c_j u_j|): the
 * rounding error of sum c_j u_j is relative to the second term. */
static void check_rel(const char *what, double est, double exact, double scale, double tol)
{
    double s = fmax(fabs(exact), scale);
    if (!(fabs(est - exact) <= tol * s))
        fail_msg("%s: estimate %.17g, exact %.17g, rel. error %.3g > %.3g", what, est, exact,
                 fabs(est - exact) / s, tol);
}

#define NMAX 512

/* Check value and both derivatives of quadratic f at (x0, y0) from samples
 * at (x0 + dx, y0 + dy); return the basis. */
static mls_basis check_quad(const quad *f, double x0, double y0, const double *dx,
                            const double *dy, int n, double mdx, double mdy, double tol)
{
    double c0[NMAX], cx[NMAX], cy[NMAX], u[NMAX];
    mls_info info;
    mls_basis b = mls_weights(dx, dy, n, mdx, mdy, c0, cx, cy, &info);
    assert_int_equal(b, info.basis);
    for (int j = 0; j < n; j++)
        u[j] = qval(f, x0 + dx[j], y0 + dy[j]);
    if (b == MLS_QUADRATIC) {
        check_rel("value", dot(c0, u, n), qval(f, x0, y0), absdot(c0, u, n), tol);
        check_rel("d/dx", dot(cx, u, n), qdx(f, x0, y0), absdot(cx, u, n), tol);
        check_rel("d/dy", dot(cy, u, n), qdy(f, x0, y0), absdot(cy, u, n), tol);
    }
    return b;
}

/* ---- exactness -------------------------------------------------------- */

/* n samples uniform in the box |dx| < half h ax, |dy| < half h (cells of
 * size h ax by h) */
static void box_cloud(double *dx, double *dy, int n, double half, double h, double ax)
{
    for (int j = 0; j < n; j++) {
        dx[j] = tu_rnd_in(-half, half) * h * ax;
        dy[j] = tu_rnd_in(-half, half) * h;
    }
}

/* a random quadratic rescaled to vary O(1) over a stencil of size h */
static quad scaled_quad(double h)
{
    quad f = rnd_quad();
    for (int i = 1; i < 6; i++)
        f.q[i] /= (i < 3 ? h : h * h);
    return f;
}


/* A fixed support (mean extents passed negative, mlsSupport of umppmFoam):
 * quadratics are still reproduced on random clouds whose samples fill the
 * support, a sample outside it (rho >= 1) gets practically no weight, and a
 * sample entering the set there changes the fit by the floor's order only
 * (MLS_W_CUT).
 * With Eq. 35's scales (x_m = max |dx_j| + Delta-bar) the same sample
 * changes x_m and enters with an O(1) weight. */
static void test_fixed_support(void **state)
{
    (void)state;
    tu_rng_seed(7);
    double dx[NMAX], dy[NMAX], u[NMAX], c0[NMAX];
    int nquad = 0;
    for (int t = 0; t < 200; t++) {
        int n = 20 + (int)(tu_rnd() * 21);
        double h = pow(10, tu_rnd_in(-3, 2)), ax = tu_rnd_in(0.5, 2);
        box_cloud(dx, dy, n, 1.6, h, ax);
        quad f = scaled_quad(h);
        if (check_quad(&f, 0, 0, dx, dy, n, -2 * h * ax, -2 * h, 1e-11) == MLS_QUADRATIC)
            nquad++;
    }
    print_message("fixed support, random clouds: %d/200 quadratic\n", nquad);
    assert_true(nquad >= 195);

    /* 24 samples inside radius 2 (h = 1); one more appears just outside it,
     * as a particle entering a cell's stencil: the fixed support's value is
     * unchanged to the floor's order; Eq. 35's scales grow with it and the
     * value moves */
    int n = 25;
    for (int j = 0; j < n - 1; j++) {
        double r = 1.7 * sqrt(tu_rnd()), a = 2 * M_PI * tu_rnd();
        dx[j] = r * cos(a);
        dy[j] = r * sin(a);
    }
    dx[n - 1] = 2.05;
    dy[n - 1] = 0.3;
    for (int j = 0; j < n; j++)
        u[j] = sin(dx[j]) * cos(0.7 * dy[j]);
    double v[2][2];
    for (int paper = 0; paper < 2; paper++)
        for (int with = 0; with < 2; with++) {
            double e = paper ? 1 : -2;
            assert_int_equal(mls_weights(dx, dy, n - 1 + with, e, e, c0, NULL, NULL, NULL), MLS_QUADRATIC);
            v[paper][with] = dot(c0, u, n - 1 + with);
        }
    double d_fixed = fabs(v[0][1] - v[0][0]), d_paper = fabs(v[1][1] - v[1][0]);
    print_message("a sample entering at rho 1.03: value changes by %.3g (fixed support), %.3g (Eq. 35's scales)\n",
                  d_fixed, d_paper);
    assert_true(d_fixed < 1e-4);
    assert_true(d_paper > 100 * d_fixed);
}


static void test_quadratic_random_clouds(void **state)
{
    (void)state;
    tu_rng_seed(1);
    double dx[NMAX], dy[NMAX];
    int nquad = 0;
    double worst_rcond = 1;
    for (int t = 0; t < 500; t++) {
        int n = 10 + (int)(tu_rnd() * 31); /* 10..40 */
        double h = pow(10, tu_rnd_in(-3, 2));
        double ax = tu_rnd_in(0.5, 2); /* anisotropic cells */
        double x0 = tu_rnd_in(-5, 5) * h * 10, y0 = tu_rnd_in(-5, 5) * h * 10;
        box_cloud(dx, dy, n, 2.5, h, ax);
        quad f = scaled_quad(h);
        mls_info info;
        double c0[NMAX];
        mls_weights(dx, dy, n, h * ax, h, c0, NULL, NULL, &info);
        if (check_quad(&f, x0, y0, dx, dy, n, h * ax, h, 1e-12) == MLS_QUADRATIC) {
            nquad++;
            worst_rcond = fmin(worst_rcond, info.rcond);
        }
    }
    print_message("random clouds: %d/500 quadratic, worst rcond %.3g\n", nquad, worst_rcond);
    assert_true(nquad >= 495);
}

/* Points at the vertices and centroids of a perturbed triangulated grid;
 * targets are edge midpoints (face centres) and centroids (which are also
 * samples: a sample exactly on the target). */
static void test_quadratic_triangle_mesh(void **state)
{
    (void)state;
    tu_rng_seed(2);
    enum { NV = 8 };
    const double h = 0.01;
    double vx[NV][NV], vy[NV][NV];
    for (int i = 0; i < NV; i++)
        for (int j = 0; j < NV; j++) {
            double jit = (i > 0 && i < NV - 1 && j > 0 && j < NV - 1) ? 0.25 : 0;
            vx[i][j] = (i + jit * tu_rnd_in(-1, 1)) * h;
            vy[i][j] = (j + jit * tu_rnd_in(-1, 1)) * 1.5 * h; /* stretched */
        }
    /* all points: vertices + centroids of the two triangles per quad */
    double px[3 * NV * NV], py[3 * NV * NV];
    int np = 0;
    double tcx[2 * NV * NV], tcy[2 * NV * NV], ex[2 * NV * NV], ey[2 * NV * NV];
    int nt = 0, ne = 0;
    double sdx = 0, sdy = 0;
    for (int i = 0; i < NV; i++)
        for (int j = 0; j < NV; j++) {
            px[np] = vx[i][j];
            py[np++] = vy[i][j];
        }
    for (int i = 0; i + 1 < NV; i++)
        for (int j = 0; j + 1 < NV; j++) {
            int tri[2][3][2] = {{{i, j}, {i + 1, j}, {i + 1, j + 1}}, {{i, j}, {i + 1, j + 1}, {i, j + 1}}};
            for (int t = 0; t < 2; t++) {
                double cxs = 0, cys = 0, xmin = 1e9, xmax = -1e9, ymin = 1e9, ymax = -1e9;
                for (int v = 0; v < 3; v++) {
                    double x = vx[tri[t][v][0]][tri[t][v][1]], y = vy[tri[t][v][0]][tri[t][v][1]];
                    cxs += x / 3;
                    cys += y / 3;
                    xmin = fmin(xmin, x), xmax = fmax(xmax, x);
                    ymin = fmin(ymin, y), ymax = fmax(ymax, y);
                }
                px[np] = cxs;
                py[np++] = cys;
                tcx[nt] = cxs;
                tcy[nt++] = cys;
                sdx += xmax - xmin;
                sdy += ymax - ymin;
            }
            /* the diagonal edge of this quad: a face centre */
            ex[ne] = 0.5 * (vx[i][j] + vx[i + 1][j + 1]);
            ey[ne++] = 0.5 * (vy[i][j] + vy[i + 1][j + 1]);
        }
    double mdx = sdx / nt, mdy = sdy / nt;
    quad f = scaled_quad(h);
    int ntarget = 0;
    for (int pass = 0; pass < 2; pass++) {
        int nn = pass ? nt : ne;
        for (int t = 0; t < nn; t++) {
            double x0 = pass ? tcx[t] : ex[t], y0 = pass ? tcy[t] : ey[t];
            double dx[NMAX], dy[NMAX];
            int n = 0;
            for (int p = 0; p < np; p++) /* about two cell layers around the target */
                if (fabs(px[p] - x0) < 2.2 * mdx && fabs(py[p] - y0) < 2.2 * mdy) {
                    dx[n] = px[p] - x0;
                    dy[n++] = py[p] - y0;
                }
            assert_true(n >= MLS_MIN_QUAD);
            assert_int_equal(check_quad(&f, x0, y0, dx, dy, n, mdx, mdy, 1e-12), MLS_QUADRATIC);
            ntarget++;
        }
    }
    print_message("triangle mesh: %d targets (edge centres, centroids) exact\n", ntarget);
}

/* ---- fallbacks -------------------------------------------------------- */

static void test_linear_fallback(void **state)
{
    (void)state;
    tu_rng_seed(3);
    double dx[NMAX], dy[NMAX], c0[NMAX], cx[NMAX], cy[NMAX], u[NMAX];
    for (int t = 0; t < 100; t++) {
        int n = 5; /* < MLS_MIN_QUAD */
        double h = pow(10, tu_rnd_in(-3, 1));
        for (int j = 0; j < n; j++) {
            dx[j] = tu_rnd_in(-2, 2) * h;
            dy[j] = tu_rnd_in(-2, 2) * h;
        }
        double a = tu_rnd_in(-1, 1), b = tu_rnd_in(-1, 1) / h, c = tu_rnd_in(-1, 1) / h;
        double x0 = 3 * h, y0 = -h;
        for (int j = 0; j < n; j++)
            u[j] = a + b * (x0 + dx[j]) + c * (y0 + dy[j]);
        mls_info info;
        assert_int_equal(mls_weights(dx, dy, n, h, h, c0, cx, cy, &info), MLS_LINEAR);
        assert_int_equal(info.basis, MLS_LINEAR);
        assert_true(info.rcond >= MLS_RCOND_MIN);
        check_rel("linear value", dot(c0, u, n), a + b * x0 + c * y0, absdot(c0, u, n), 1e-12);
        check_rel("linear d/dx", dot(cx, u, n), b, absdot(cx, u, n), 1e-12);
        check_rel("linear d/dy", dot(cy, u, n), c, absdot(cy, u, n), 1e-12);
    }
    /* 12 samples on a circle around the target: x^2 + y^2 = const is in the
     * quadratic basis, so A is singular -> linear fallback (by rcond). */
    int n = 12;
    for (int j = 0; j < n; j++) {
        dx[j] = cos(2 * UMP_PI * j / n);
        dy[j] = sin(2 * UMP_PI * j / n);
    }
    mls_info info;
    assert_int_equal(mls_weights(dx, dy, n, 0.5, 0.5, c0, cx, cy, &info), MLS_LINEAR);
    for (int j = 0; j < n; j++)
        u[j] = 2 + 3 * dx[j] - 4 * dy[j];
    TU_CLOSE(dot(c0, u, n), 2, 1e-13);
    TU_CLOSE(dot(cx, u, n), 3, 1e-13);
    TU_CLOSE(dot(cy, u, n), -4, 1e-13);
    print_message("circle of 12 samples: quadratic rejected, linear used (rcond %.3g)\n",
                  info.rcond);
}

static void test_shepard(void **state)
{
    (void)state;
    double dx[8] = {0.3, -0.1}, dy[8] = {0.1, 0.4}, c0[8], cx[8], cy[8];
    mls_info info;
    assert_int_equal(mls_weights(dx, dy, 2, 0.2, 0.2, c0, cx, cy, &info), MLS_SHEPARD);
    assert_int_equal(info.basis, MLS_SHEPARD);
    TU_CLOSE(c0[0] + c0[1], 1, 1e-15);
    assert_true(c0[0] > 0 && c0[1] > 0);
    assert_true(c0[0] > c0[1]); /* the nearer sample (normalised) weighs more */
    assert_true(cx[0] == 0 && cx[1] == 0 && cy[0] == 0 && cy[1] == 0);
    /* one sample: the value itself */
    assert_int_equal(mls_weights(dx, dy, 1, 0.2, 0.2, c0, NULL, NULL, NULL), MLS_SHEPARD);
    TU_CLOSE(c0[0], 1, 0);
    /* collinear samples: the linear fit is degenerate too -> Shepard */
    for (int j = 0; j < 6; j++) {
        dx[j] = 0.1 * (j - 2.5);
        dy[j] = 0.05 * (j - 2.5);
    }
    assert_int_equal(mls_weights(dx, dy, 6, 0.1, 0.1, c0, cx, cy, &info), MLS_SHEPARD);
    double s = 0;
    for (int j = 0; j < 6; j++)
        s += c0[j];
    TU_CLOSE(s, 1, 1e-14);
    /* none */
    c0[0] = 42;
    assert_int_equal(mls_weights(dx, dy, 0, 0.1, 0.1, c0, cx, cy, &info), MLS_NONE);
    assert_int_equal(info.basis, MLS_NONE);
    TU_CLOSE(c0[0], 42, 0);
}

/* ---- differential oracle ---------------------------------------------- */

/* Weighted least squares min sum_j w_j (R(dx_j, dy_j) . m - u_j)^2 in
 * PHYSICAL coordinates, solved by modified Gram-Schmidt QR (twice, for
 * re-orthogonalisation) of the sqrt(w)-scaled rows; returns m[0..2]. */
static void oracle_wls(const double *dx, const double *dy, const double *u, int n, double mdx,
                       double mdy, double m[3])
{
    double mx = 0, my = 0;
    for (int j = 0; j < n; j++) {
        mx = fmax(mx, fabs(dx[j]));
        my = fmax(my, fabs(dy[j]));
    }
    double xm = mx + mdx, ym = my + mdy;
    static double Q[6][NMAX];
    double b[NMAX];
    for (int j = 0; j < n; j++) {
        double X = dx[j] / xm, Y = dy[j] / ym, rho = sqrt(X * X + Y * Y);
        double w = rho > 0 ? 1 / rho - 1 : MLS_W_MAX; /* Eq. 35 */
        w = fmin(fmax(w, MLS_W_MIN), MLS_W_MAX);
        double sw = sqrt(w);
        double row[6] = {1, dx[j], dy[j], dx[j] * dy[j], dx[j] * dx[j], dy[j] * dy[j]};
        for (int i = 0; i < 6; i++)
            Q[i][j] = sw * row[i];
        b[j] = sw * u[j];
    }
    double x[6];
    tu_lsq_qr(6, n, NMAX, &Q[0][0], b, x);
    m[0] = x[0];
    m[1] = x[1];
    m[2] = x[2];
}

static void test_oracle(void **state)
{
    (void)state;
    tu_rng_seed(4);
    double dx[NMAX], dy[NMAX], c0[NMAX], cx[NMAX], cy[NMAX], u[NMAX];
    double worst = 0;
    for (int t = 0; t < 300; t++) {
        int n = 10 + (int)(tu_rnd() * 31);
        double h = tu_rnd_in(0.3, 3), ax = tu_rnd_in(0.5, 2);
        for (int j = 0; j < n; j++) {
            dx[j] = tu_rnd_in(-2.5, 2.5) * h * ax;
            dy[j] = tu_rnd_in(-2.5, 2.5) * h;
            u[j] = tu_rnd_in(-1, 1); /* arbitrary data: not a polynomial */
        }
        if (t % 10 == 0) { /* a sample on the target */
            dx[0] = 0;
            dy[0] = 0;
        }
        assert_int_equal(mls_weights(dx, dy, n, h * ax, h, c0, cx, cy, NULL), MLS_QUADRATIC);
        double m[3];
        oracle_wls(dx, dy, u, n, h * ax, h, m);
        double e0 = fabs(dot(c0, u, n) - m[0]) / fmax(1, fabs(m[0]));
        double ex = fabs(dot(cx, u, n) - m[1]) * h / fmax(1, fabs(m[1]) * h);
        double ey = fabs(dot(cy, u, n) - m[2]) * h / fmax(1, fabs(m[2]) * h);
        worst = fmax(worst, fmax(e0, fmax(ex, ey)));
        /* mls_gradient (B summed with the moments) gives the same derivative */
        double gx, gy;
        assert_int_equal(mls_gradient(dx, dy, u, n, h * ax, h, &gx, &gy, NULL), MLS_QUADRATIC);
        double gxe = fabs(gx - m[1]) * h / fmax(1, fabs(m[1]) * h);
        double gye = fabs(gy - m[2]) * h / fmax(1, fabs(m[2]) * h);
        worst = fmax(worst, fmax(gxe, gye));
    }
    print_message("oracle (MGS-QR, physical coords): worst rel. difference %.3g (mls_weights and "
                  "mls_gradient)\n", worst);
    assert_true(worst < 1e-10);
}

/* ---- scale invariance, sample on target ------------------------------- */

static void test_scale_invariance(void **state)
{
    (void)state;
    tu_rng_seed(5);
    enum { N = 24 };
    double dx[N], dy[N], c0[N], cx[N], cy[N];
    for (int j = 0; j < N; j++) {
        dx[j] = tu_rnd_in(-2.5, 2.5);
        dy[j] = tu_rnd_in(-2.5, 2.5);
    }
    mls_weights(dx, dy, N, 1, 1, c0, cx, cy, NULL);
    const double scales[2] = {1e-4, 1e4};
    for (int s = 0; s < 2; s++) {
        double sx[N], sy[N], d0[N], dxc[N], dyc[N];
        for (int j = 0; j < N; j++) {
            sx[j] = dx[j] * scales[s];
            sy[j] = dy[j] * scales[s];
        }
        assert_int_equal(mls_weights(sx, sy, N, scales[s], scales[s], d0, dxc, dyc, NULL),
                         MLS_QUADRATIC);
        for (int j = 0; j < N; j++) {
            TU_CLOSE(d0[j], c0[j], 1e-13);
            TU_CLOSE(dxc[j] * scales[s], cx[j], 1e-13);
            TU_CLOSE(dyc[j] * scales[s], cy[j], 1e-13);
        }
    }
}

static void test_sample_on_target(void **state)
{
    (void)state;
    tu_rng_seed(6);
    enum { N = 16 };
    double dx[N], dy[N], c0[N], cx[N], cy[N];
    for (int j = 0; j < N; j++) {
        dx[j] = tu_rnd_in(-2, 2) * 0.1;
        dy[j] = tu_rnd_in(-2, 2) * 0.1;
    }
    dx[3] = 0;
    dy[3] = 0;
    dx[7] = 1e-300; /* subnormal-scale offset: also no overflow */
    dy[7] = -1e-300;
    mls_info info;
    assert_int_equal(mls_weights(dx, dy, N, 0.1, 0.1, c0, cx, cy, &info), MLS_QUADRATIC);
    for (int j = 0; j < N; j++)
        assert_true(isfinite(c0[j]) && isfinite(cx[j]) && isfinite(cy[j]));
    /* two samples practically on the target share the value */
    TU_CLOSE(c0[3] + c0[7], 1, 1e-4);
    quad f = rnd_quad();
    assert_int_equal(check_quad(&f, 0.2, 0.3, dx, dy, N, 0.1, 0.1, 1e-11), MLS_QUADRATIC);
    print_message("two samples on the target: c0 = %.9f + %.9f, rcond %.3g\n", c0[3], c0[7],
                  info.rcond);
}

/* ---- convergence ------------------------------------------------------ */

static double fs(double x, double y) { return sin(x) * cos(y); }

/* Max error over ntarget random targets in [0,1]^2 of MLS interpolation of
 * sin(x)cos(y) from a lattice of spacing h jittered by +-0.3h. */
static void conv_errors(double h, double *e0, double *e1)
{
    enum { NT = 200 };
    double dx[NMAX], dy[NMAX], c0[NMAX], cx[NMAX], cy[NMAX], u[NMAX];
    *e0 = *e1 = 0;
    for (int t = 0; t < NT; t++) {
        double x0 = tu_rnd_in(0, 1), y0 = tu_rnd_in(0, 1);
        int i0 = (int)floor(x0 / h), j0 = (int)floor(y0 / h);
        int n = 0;
        /* lattice nodes of the two cell layers around the target's cell;
         * each node's jitter is a hash of (i, j) so it does not depend on t */
        for (int i = i0 - 2; i <= i0 + 3; i++)
            for (int j = j0 - 2; j <= j0 + 3; j++) {
                uint64_t save = tu_rng_state;
                tu_rng_seed((uint64_t)(i * 7919 + j * 104729) ^ 0x1234567ULL);
                double x = (i + 0.3 * tu_rnd_in(-1, 1)) * h, y = (j + 0.3 * tu_rnd_in(-1, 1)) * h;
                tu_rng_state = save;
                dx[n] = x - x0;
                dy[n] = y - y0;
                u[n++] = fs(x, y);
            }
        assert_int_equal(mls_weights(dx, dy, n, h, h, c0, cx, cy, NULL), MLS_QUADRATIC);
        *e0 = fmax(*e0, fabs(dot(c0, u, n) - fs(x0, y0)));
        *e1 = fmax(*e1, fabs(dot(cx, u, n) - cos(x0) * cos(y0)));
        *e1 = fmax(*e1, fabs(dot(cy, u, n) + sin(x0) * sin(y0)));
    }
}

static void test_convergence(void **state)
{
    (void)state;
    tu_rng_seed(7);
    const double hs[5] = {0.1, 0.05, 0.025, 0.0125, 0.00625};
    double e0[5], e1[5];
    for (int k = 0; k < 5; k++) {
        conv_errors(hs[k], &e0[k], &e1[k]);
        if (k == 0)
            print_message("h %-9g value err %.3e  grad err %.3e\n", hs[k], e0[k], e1[k]);
        else
            print_message("h %-9g value err %.3e (order %.2f)  grad err %.3e (order %.2f)\n",
                          hs[k], e0[k], log2(e0[k - 1] / e0[k]), e1[k], log2(e1[k - 1] / e1[k]));
    }
    double p0 = log(e0[0] / e0[4]) / log(hs[0] / hs[4]);
    double p1 = log(e1[0] / e1[4]) / log(hs[0] / hs[4]);
    print_message("observed order over h = 0.1..0.00625: value %.2f, gradient %.2f\n", p0, p1);
    assert_true(p0 >= 2.5);
    assert_true(p1 >= 1.7);
}

/* ---- cost ------------------------------------------------------------- */

static void test_timing(void **state)
{
    (void)state;
    tu_rng_seed(8);
    enum { N = 24, REP = 200000 };
    double dx[N], dy[N], c0[N], cx[N], cy[N];
    for (int j = 0; j < N; j++) {
        dx[j] = tu_rnd_in(-2.5, 2.5);
        dy[j] = tu_rnd_in(-2.5, 2.5);
    }
    struct timespec t0, t1;
    double acc = 0;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    for (int r = 0; r < REP; r++) {
        dx[r % N] += 1e-9; /* defeat hoisting */
        mls_weights(dx, dy, N, 1, 1, c0, cx, cy, NULL);
        acc += c0[0] + cx[1] + cy[2];
    }
    clock_gettime(CLOCK_MONOTONIC, &t1);
    double us = ((double)(t1.tv_sec - t0.tv_sec) * 1e6 + (double)(t1.tv_nsec - t0.tv_nsec) * 1e-3) / REP;
    print_message("mls_weights, n = %d, value + gradient: %.3f us per call\n", N, us);
    assert_true(isfinite(acc));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_quadratic_random_clouds),
        cmocka_unit_test(test_quadratic_triangle_mesh),
        cmocka_unit_test(test_linear_fallback),
        cmocka_unit_test(test_shepard),
        cmocka_unit_test(test_oracle),
        cmocka_unit_test(test_scale_invariance),
        cmocka_unit_test(test_sample_on_target),
        cmocka_unit_test(test_fixed_support),
        cmocka_unit_test(test_convergence),
        cmocka_unit_test(test_timing),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
