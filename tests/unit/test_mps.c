/* SPDX-License-Identifier: GPL-3.0-or-later
 * test_mps.c -- the MPS step (src/mps.c) against what is known exactly:
 *   - n0 and lambda of the square lattice (Eqs. 5, 7) against their sums
 *     written out by hand;
 *   - conjugate gradients (lsolve_rows_cg) on a 1-D Laplacian whose
 *     solution is known, and its refusal of the non-symmetric ILU0;
 *   - free flight: a block of particles without walls or gravity, moving
 *     uniformly, keeps its velocity and lattice (Galilean invariance of
 *     Eqs. 4-20: no divergence, p = 0) up to the weak pull of the density
 *     term on the rows under the surface, bounded by gamma (1 - beta) l0
 *     per step;
 *   - free fall: with gravity and nothing else every particle falls with
 *     g, to the same bound;
 *   - a still block of liquid in a tank of wall particles: the pressure of
 *     the PPE rises with depth as rho g (h - l0/2 - y) (within 5 % in the bulk
 *     after 20 steps; the top fifth excluded, where the MPS source is
 *     noisy);
 *   - threads: one step on 1 and 2 threads gives the same bits.
 */
#include "testutil.h"
#include "umppm/lsolve.h"
#include "umppm/mps.h"
#include "umppm/particles.h"

#include <omp.h>

static void test_lattice_sums(void **state)
{
    (void)state;
    double sw, sr;
    /* r_e = 2.1: neighbours at 1 (4), sqrt 2 (4), 2 (4) */
    mps_lattice_sums(2.1, &sw, &sr);
    double w1 = 2.1 - 1, w2 = 2.1 / sqrt(2.0) - 1, w3 = 2.1 / 2 - 1;
    assert_true(fabs(sw - 4 * (w1 + w2 + w3)) < 1e-12);
    assert_true(fabs(sr - 4 * (w1 + 2 * w2 + 4 * w3)) < 1e-12);
    /* the kernel is zero at and beyond r_e */
    assert_true(mps_weight(2.1, 2.1) == 0 && mps_weight(3, 2.1) == 0 && mps_weight(0, 2.1) == 0);
    assert_true(fabs(mps_weight(1, 2.1) - 1.1) < 1e-15);
}

static void test_cg(void **state)
{
    (void)state;
    /* tridiagonal (2, -1) of order n: x = i (1 - ...) from b */
    enum { N = 200 };
    ump_idx rp[N + 1], ci[3 * N];
    double v[3 * N], x[N], b[N], want[N];
    ump_idx k = 0;
    for (int i = 0; i < N; i++) {
        rp[i] = k;
        if (i > 0)
            ci[k] = i - 1, v[k++] = -1;
        ci[k] = i, v[k++] = 2;
        if (i < N - 1)
            ci[k] = i + 1, v[k++] = -1;
        want[i] = sin(0.1 * i) + 0.01 * i;
    }
    rp[N] = k;
    lsolve_csr A = {N, rp, ci, v};
    for (int i = 0; i < N; i++) {
        double s = 2 * want[i];
        if (i > 0)
            s -= want[i - 1];
        if (i < N - 1)
            s -= want[i + 1];
        b[i] = s;
        x[i] = 0;
    }
    lsolve_rows *kr = NULL;
    ump_err err;
    assert_int_equal(lsolve_rows_create(&kr, &err), UMP_OK);
    assert_int_equal(lsolve_rows_setup(kr, &A, LSOLVE_PC_JACOBI, &err), UMP_OK);
    lsolve_stats st;
    assert_int_equal(lsolve_rows_cg(kr, &A, b, x, 1e-12, 1000, &st, &err), UMP_OK);
    assert_int_equal(st.converged, 1);
    assert_true(st.iterations <= N); /* CG: at most n steps in exact arithmetic */
    for (int i = 0; i < N; i++)
        assert_true(fabs(x[i] - want[i]) < 1e-8);
    /* ILU0 is not symmetric: refused */
    assert_int_equal(lsolve_rows_setup(kr, &A, LSOLVE_PC_ILU0, &err), UMP_OK);
    assert_int_equal(lsolve_rows_cg(kr, &A, b, x, 1e-12, 1000, &st, &err), UMP_ERR_INPUT);
    assert_non_null(strstr(err.msg, "ILU0"));
    lsolve_rows_free(&kr);
}

static mps_params params(double l0)
{
    mps_params P;
    memset(&P, 0, sizeof P);
    P.l0 = l0;
    P.re_n = 3.1;
    P.re_lap = 3.1;
    P.beta = 0.98;
    P.rho = 1000;
    P.nu = 1e-3;
    P.source = MPS_SOURCE_MIXED;
    P.gamma = 0.01;
    P.collision = 0.5;
    P.restitution = 0.2;
    P.p_tol = 1e-10;
    P.u_tol = 1e-12;
    P.maxit = 5000;
    return P;
}

/* nx x ny fluid particles at (i + 1/2, j + 1/2) l0 above nbed rows of
 * solid particles (the first three rows wall, the rest dummy), between
 * side walls of xpad columns (none when xpad is 0); velocity (u0, v0). */
static part_set *block(int nx, int ny, int nbed, int xpad, double l0, double u0, double v0, size_t *nsolid,
                       unsigned char **kinds)
{
    part_set *s = NULL;
    ump_err err;
    assert_int_equal(part_create(64, &s, &err), UMP_OK);
    *kinds = malloc((size_t)(nbed * (nx + 2 * xpad)) + (size_t)(2 * xpad * (ny + 2)) + 1);
    size_t k = 0;
    for (int r = 0; r < nbed; r++)
        for (int i = -xpad; i < nx + xpad; i++) {
            assert_int_equal(part_add(s, (i + 0.5) * l0, -(r + 0.5) * l0, 0, 0, 0, -1, NULL, &err), UMP_OK);
            (*kinds)[k++] = r < 3 ? MPS_WALL : MPS_DUMMY;
        }
    /* side walls: xpad columns on each side, up to two rows above the liquid */
    for (int j = 0; j < (xpad ? ny + 2 : 0); j++)
        for (int c = 0; c < xpad; c++)
            for (int side = 0; side < 2; side++) {
                int i = side ? nx + c : -1 - c;
                assert_int_equal(part_add(s, (i + 0.5) * l0, (j + 0.5) * l0, 0, 0, 0, -1, NULL, &err), UMP_OK);
                (*kinds)[k++] = c < 3 ? MPS_WALL : MPS_DUMMY;
            }
    *nsolid = k;
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++)
            assert_int_equal(part_add(s, (i + 0.5) * l0, (j + 0.5) * l0, u0, v0, 0, -1, NULL, &err), UMP_OK);
    return s;
}

static void test_free_flight(void **state)
{
    (void)state;
    double l0 = 0.01, dt = 1e-3, u0 = 0.3, v0 = -0.2;
    size_t ns;
    unsigned char *kinds;
    part_set *s = block(20, 15, 0, 0, l0, u0, v0, &ns, &kinds);
    mps_params P = params(l0);
    mps *m = NULL;
    ump_err err;
    assert_int_equal(mps_create(&P, s, ns, kinds, &m, &err), UMP_OK);
    for (int step = 0; step < 5; step++) {
        mps_stats st;
        assert_int_equal(mps_step(m, dt, &st, &err), UMP_OK);
        assert_true(st.collisions == 0);
    }
    double du = 0, dx = 0;
    for (size_t i = 0; i < s->n; i++) {
        int ii = (int)(i % 20), jj = (int)(i / 20);
        du = fmax(du, hypot(s->u[i] - u0, s->v[i] - v0));
        dx = fmax(dx, hypot(s->x[i] - ((ii + 0.5) * l0 + 5 * dt * u0), s->y[i] - ((jj + 0.5) * l0 + 5 * dt * v0)));
    }
    printf("    free flight: largest velocity change %.3g m/s, displacement from the lattice %.3g l0\n", du, dx / l0);
    /* the block's first rows under its surfaces have n* < n0 (the lattice is
     * cut there): the mixed source's density term (weight gamma) moves
     * them inwards by at most gamma (1 - beta) l0 per step, a velocity of
     * gamma (1 - beta) l0 / dt; nothing else may change */
    double bound = P.gamma * (1 - P.beta) * l0;
    assert_true(du < bound / dt);
    assert_true(dx < 5 * bound);
    mps_free(&m);
    part_free(&s);
    free(kinds);
}

static void test_free_fall(void **state)
{
    (void)state;
    double l0 = 0.01, dt = 1e-3;
    size_t ns;
    unsigned char *kinds;
    part_set *s = block(12, 10, 0, 0, l0, 0, 0, &ns, &kinds);
    mps_params P = params(l0);
    P.g[1] = -9.81;
    mps *m = NULL;
    ump_err err;
    assert_int_equal(mps_create(&P, s, ns, kinds, &m, &err), UMP_OK);
    for (int step = 0; step < 4; step++) {
        mps_stats st;
        assert_int_equal(mps_step(m, dt, &st, &err), UMP_OK);
    }
    double bound = P.gamma * (1 - P.beta) * l0 / dt; /* as in free flight */
    for (size_t i = 0; i < s->n; i++) {
        assert_true(fabs(s->v[i] + 9.81 * 4 * dt) < bound);
        assert_true(fabs(s->u[i]) < bound);
    }
    mps_free(&m);
    part_free(&s);
    free(kinds);
}

/* Liquid at rest in a tank: after some steps the pressure is hydrostatic
 * (the rows next to the free surface excepted, where the MPS source is
 * noisy). */
static void hydrostatic(int threads, double *out_p, size_t *out_n)
{
    omp_set_num_threads(threads);
    double l0 = 0.01, dt = 5e-4, g = 9.81;
    int nx = 40, ny = 20;
    size_t ns;
    unsigned char *kinds;
    part_set *s = block(nx, ny, 6, 6, l0, 0, 0, &ns, &kinds);
    mps_params P = params(l0);
    P.g[1] = -g;
    mps *m = NULL;
    ump_err err;
    assert_int_equal(mps_create(&P, s, ns, kinds, &m, &err), UMP_OK);
    for (int step = 0; step < 20; step++) {
        mps_stats st;
        assert_int_equal(mps_step(m, dt, &st, &err), UMP_OK);
    }
    const double *p = mps_pressure(m);
    for (size_t i = 0; i < s->n; i++)
        out_p[i] = p[i] + s->x[i] + s->y[i] + s->u[i] + s->v[i]; /* a digest of the state */
    *out_n = s->n;
    if (threads == 1) {
        double h = ny * l0, err_max = 0;
        for (size_t i = ns; i < s->n; i++) {
            double x = s->x[i], y = s->y[i];
            /* the two bottom corner particles (6 % high: both walls push)
             * are not the bulk */
            if (y > 0.8 * h || (y < l0 && (x < l0 || x > (nx - 1) * l0)))
                continue;
            /* p = 0 at the centres of the top row: the surface is h - l0/2 */
            double want = 1000 * g * (h - 0.5 * l0 - y);
            err_max = fmax(err_max, fabs(p[i] - want) / want);
        }
        printf("    hydrostatic block: largest relative pressure error in the bulk %.4f\n", err_max);
        assert_true(err_max < 0.05);
    }
    mps_free(&m);
    part_free(&s);
    free(kinds);
    omp_set_num_threads(2);
}

static void test_hydrostatic_threads(void **state)
{
    (void)state;
    double a[4000], b[4000];
    size_t na, nb;
    hydrostatic(1, a, &na);
    hydrostatic(2, b, &nb);
    assert_int_equal(na, nb);
    assert_memory_equal(a, b, na * sizeof a[0]);
}

static void test_bad_params(void **state)
{
    (void)state;
    size_t ns;
    unsigned char *kinds;
    part_set *s = block(3, 3, 0, 0, 0.01, 0, 0, &ns, &kinds);
    mps *m = NULL;
    ump_err err;
    mps_params P = params(0.01);
    P.re_lap = 2.0; /* < re_n */
    assert_int_equal(mps_create(&P, s, ns, kinds, &m, &err), UMP_ERR_INPUT);
    P = params(-1);
    assert_int_equal(mps_create(&P, s, ns, kinds, &m, &err), UMP_ERR_INPUT);
    P = params(0.01);
    P.beta = 1.5;
    assert_int_equal(mps_create(&P, s, ns, kinds, &m, &err), UMP_ERR_INPUT);
    assert_null(m);
    part_free(&s);
    free(kinds);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_lattice_sums),  cmocka_unit_test(test_cg),
        cmocka_unit_test(test_free_flight),   cmocka_unit_test(test_free_fall),
        cmocka_unit_test(test_hydrostatic_threads), cmocka_unit_test(test_bad_params),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
