/* SPDX-License-Identifier: GPL-3.0-or-later
 * test_vor.c -- the largest holes of a point cloud (vor_holes): a lattice
 * with one point removed (exact hole of radius 1, then the lattice squares'
 * sqrt(2)/2), the mask removing that hole, random clouds checked against a
 * brute-force emptiness test and the triangle count of a triangulation,
 * independence of the input order, degenerate input (n < 3, collinear,
 * coincident, non-finite), concurrent calls, and silence of qhull;
 * vor_holes_inside (the candidates only) against vor_holes filtered by the
 * same centre-inside test on lattices, random and jittered clouds, masks
 * and a scattered cloud; vor_work_holes_inside's workspace over clouds of
 * every kind: the same holes, and no allocation of ours once grown.
 */
#include "testutil.h"
#include "umppm/ump.h"
#include "umppm/vor.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

/* ---- helpers ---------------------------------------------------------- */

static vor_hole *holes_ok(const double *x, const double *y, size_t n, const unsigned char *mask, double rmin,
                          size_t *nh)
{
    vor_hole *h = NULL;
    ump_err err;
    if (vor_holes(x, y, n, mask, rmin, &h, nh, &err) != UMP_OK)
        fail_msg("%s", err.msg);
    if (*nh == 0)
        assert_null(h);
    else
        assert_non_null(h);
    return h;
}

/* NX-by-NY lattice of spacing 1 without the point (HX, HY); *idx gets the
 * input index of lattice point (i, j), or -1 for the hole. */
#define NX 30
#define NY 30
#define HX 12
#define HY 17
static size_t lattice(double *x, double *y, long idx[NX][NY])
{
    size_t n = 0;
    for (int j = 0; j < NY; j++)
        for (int i = 0; i < NX; i++) {
            if (i == HX && j == HY) {
                idx[i][j] = -1;
                continue;
            }
            idx[i][j] = (long)n;
            x[n] = i;
            y[n] = j;
            n++;
        }
    return n;
}

static int cmp_triple(const void *pa, const void *pb)
{
    const size_t *a = pa, *b = pb;
    for (int k = 0; k < 3; k++)
        if (a[k] != b[k])
            return a[k] < b[k] ? -1 : 1;
    return 0;
}

/* Sorted by radius, equal radii by ascending triple, v[] ascending, each
 * circle through its vertices. */
static void check_shape(const double *x, const double *y, const vor_hole *h, size_t nh)
{
    for (size_t k = 0; k < nh; k++) {
        assert_true(h[k].v[0] < h[k].v[1] && h[k].v[1] < h[k].v[2]);
        if (k > 0)
            assert_true(h[k - 1].r > h[k].r || (h[k - 1].r == h[k].r && cmp_triple(h[k - 1].v, h[k].v) < 0));
        for (int q = 0; q < 3; q++) {
            size_t v = h[k].v[q];
            TU_CLOSE(hypot(x[v] - h[k].x, y[v] - h[k].y), h[k].r, 1e-9);
        }
    }
}

/* Hull vertex count by Andrew's monotone chain (strict turns only). */
static int cmp_xy(const void *pa, const void *pb)
{
    const double *a = pa, *b = pb;
    if (a[0] != b[0])
        return a[0] < b[0] ? -1 : 1;
    return (a[1] > b[1]) - (a[1] < b[1]);
}
static size_t hull_count(const double *x, const double *y, size_t n)
{
    double *p = malloc(sizeof(double) * 2 * n), *hull = malloc(sizeof(double) * 2 * (2 * n + 1));
    for (size_t i = 0; i < n; i++) {
        p[2 * i] = x[i];
        p[2 * i + 1] = y[i];
    }
    qsort(p, n, 2 * sizeof(double), cmp_xy);
    size_t k = 0;
    for (int pass = 0; pass < 2; pass++) {
        size_t lo = k;
        for (size_t s = 0; s < n; s++) {
            const double *c = p + 2 * (pass ? n - 1 - s : s);
            while (k >= lo + 2) {
                const double *a = hull + 2 * (k - 2), *b = hull + 2 * (k - 1);
                if ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]) > 0)
                    break;
                k--;
            }
            hull[2 * k] = c[0];
            hull[2 * k + 1] = c[1];
            k++;
        }
        k--; /* the last point starts the other chain */
    }
    free(p);
    free(hull);
    return k;
}

static void random_cloud(double *x, double *y, size_t n, uint64_t seed)
{
    tu_rng_seed(seed);
    for (size_t i = 0; i < n; i++) {
        x[i] = tu_rnd();
        y[i] = tu_rnd();
    }
}

static int cmp_hole_triple(const void *pa, const void *pb)
{
    return cmp_triple(((const vor_hole *)pa)->v, ((const vor_hole *)pb)->v);
}

/* Triples (mapped through perm when given, then sorted) of the holes, in
 * ascending triple order, with their circles alongside. */
static vor_hole *canonical(const vor_hole *h, size_t nh, const size_t *perm)
{
    vor_hole *c = malloc(sizeof *c * (nh ? nh : 1));
    for (size_t k = 0; k < nh; k++) {
        c[k] = h[k];
        size_t t[3];
        for (int q = 0; q < 3; q++)
            t[q] = perm ? perm[h[k].v[q]] : h[k].v[q];
        for (int a = 0; a < 3; a++)
            for (int b = a + 1; b < 3; b++)
                if (t[b] < t[a]) {
                    size_t s = t[a];
                    t[a] = t[b];
                    t[b] = s;
                }
        memcpy(c[k].v, t, sizeof t);
    }
    qsort(c, nh, sizeof *c, cmp_hole_triple);
    return c;
}

/* ---- tests ------------------------------------------------------------ */

static void test_lattice_hole(void **state)
{
    (void)state;
    static double x[NX * NY], y[NX * NY];
    long idx[NX][NY];
    size_t n = lattice(x, y, idx), nh;
    vor_hole *h = holes_ok(x, y, n, NULL, 0.0, &nh);
    check_shape(x, y, h, nh);
    /* 29 x 29 squares of 2 triangles; the 4 squares round the hole become
     * its diamond (2 triangles) and 4 right triangles. */
    assert_int_equal(nh, 2 * (NX - 1) * (NY - 1) - 8 + 6);
    for (size_t k = 0; k < 2; k++) {
        TU_CLOSE(h[k].r, 1.0, 1e-12);
        TU_CLOSE(h[k].x, HX, 1e-12);
        TU_CLOSE(h[k].y, HY, 1e-12);
        for (int q = 0; q < 3; q++) { /* vertices: the 4 neighbours of the hole */
            size_t v = h[k].v[q];
            assert_true(fabs(x[v] - HX) + fabs(y[v] - HY) == 1.0);
        }
    }
    for (size_t k = 2; k < nh; k++)
        TU_CLOSE(h[k].r, sqrt(2.0) / 2, 1e-12);
    /* The hole's two triangles tile its diamond: 4 distinct vertices. */
    size_t u[6];
    memcpy(u, h[0].v, sizeof h[0].v);
    memcpy(u + 3, h[1].v, sizeof h[1].v);
    int distinct = 0;
    for (int a = 0; a < 6; a++) {
        int seen = 0;
        for (int b = 0; b < a; b++)
            seen |= u[a] == u[b];
        distinct += !seen;
    }
    assert_int_equal(distinct, 4);
    free(h);

    /* rmin keeps only the hole. */
    h = holes_ok(x, y, n, NULL, 0.8, &nh);
    assert_int_equal(nh, 2);
    TU_CLOSE(h[0].r, 1.0, 1e-12);
    free(h);
    h = holes_ok(x, y, n, NULL, 1.5, &nh);
    assert_int_equal(nh, 0);
}

static void test_lattice_mask(void **state)
{
    (void)state;
    static double x[NX * NY], y[NX * NY];
    static unsigned char mask[NX * NY];
    long idx[NX][NY];
    size_t n = lattice(x, y, idx), nh;
    memset(mask, 1, n);
    int nb[4][2] = {{HX - 1, HY}, {HX + 1, HY}, {HX, HY - 1}, {HX, HY + 1}};
    for (int k = 0; k < 4; k++)
        mask[idx[nb[k][0]][nb[k][1]]] = 0;
    vor_hole *h = holes_ok(x, y, n, mask, 0.0, &nh);
    check_shape(x, y, h, nh);
    assert_true(nh > 0);
    TU_CLOSE(h[0].r, sqrt(2.0) / 2, 1e-12); /* the hole is gone */
    /* Exactly the unmasked result without the triangles touching a masked
     * point (the same input gives the same triangulation), in order. */
    size_t nf, m = 0;
    vor_hole *f = holes_ok(x, y, n, NULL, 0.0, &nf);
    for (size_t k = 0; k < nf; k++)
        if (mask[f[k].v[0]] && mask[f[k].v[1]] && mask[f[k].v[2]])
            f[m++] = f[k];
    /* at least the diamond, its 4 right triangles, 1 per outer square */
    assert_true(m <= nf - 6 - 8);
    assert_int_equal(nh, m);
    assert_memory_equal(h, f, m * sizeof *h);
    free(f);
    free(h);

    memset(mask, 0, n); /* nothing kept: no holes */
    h = holes_ok(x, y, n, mask, 0.0, &nh);
    assert_int_equal(nh, 0);
}

static void test_random_empty(void **state)
{
    (void)state;
    enum { N = 400 };
    static double x[N], y[N];
    random_cloud(x, y, N, 12345);
    size_t nh;
    vor_hole *h = holes_ok(x, y, N, NULL, 0.0, &nh);
    check_shape(x, y, h, nh);
    /* A triangulation of N points with H on the hull has 2N - 2 - H
     * triangles; with every circle empty, it is the Delaunay one. */
    assert_int_equal(nh, 2 * N - 2 - hull_count(x, y, N));
    for (size_t k = 0; k < nh; k++)
        for (size_t i = 0; i < N; i++) {
            if (i == h[k].v[0] || i == h[k].v[1] || i == h[k].v[2])
                continue;
            double d = hypot(x[i] - h[k].x, y[i] - h[k].y);
            if (!(d >= h[k].r * (1 - 1e-9)))
                fail_msg("circle %zu (r %g) contains point %zu at distance %g", k, h[k].r, i, d);
        }
    /* rmin: exactly the circles above it, in the same order. */
    double rmin = h[nh / 3].r;
    size_t nh2;
    vor_hole *h2 = holes_ok(x, y, N, NULL, rmin, &nh2);
    size_t above = 0;
    while (above < nh && h[above].r > rmin)
        above++;
    assert_int_equal(nh2, above);
    assert_memory_equal(h2, h, nh2 * sizeof *h);
    free(h2);
    free(h);
}

/* Permuting the input gives the same triangles (mapped back) with
 * bit-identical circles; so does the Fisher-Yates permutation of a second
 * cloud far from the origin. */
static void test_permutation(void **state)
{
    (void)state;
    enum { N = 300 };
    static double x[N], y[N], px[N], py[N];
    static size_t perm[N];
    double offs[2] = {0.0, 1e4};
    for (int o = 0; o < 2; o++) {
        random_cloud(x, y, N, 777 + (uint64_t)o);
        for (size_t i = 0; i < N; i++) {
            x[i] += offs[o];
            y[i] -= 2 * offs[o];
        }
        for (size_t i = 0; i < N; i++)
            perm[i] = i;
        tu_rng_seed(99);
        for (size_t i = N - 1; i > 0; i--) {
            size_t j = (size_t)(tu_rnd() * (double)(i + 1)), s = perm[i];
            perm[i] = perm[j];
            perm[j] = s;
        }
        for (size_t i = 0; i < N; i++) { /* new point i is old point perm[i] */
            px[i] = x[perm[i]];
            py[i] = y[perm[i]];
        }
        size_t na, nb;
        vor_hole *a = holes_ok(x, y, N, NULL, 0.0, &na);
        vor_hole *b = holes_ok(px, py, N, NULL, 0.0, &nb);
        check_shape(px, py, b, nb);
        assert_int_equal(na, nb);
        vor_hole *ca = canonical(a, na, NULL), *cb = canonical(b, nb, perm);
        for (size_t k = 0; k < na; k++) {
            assert_memory_equal(ca[k].v, cb[k].v, sizeof ca[k].v);
            assert_true(ca[k].r == cb[k].r && ca[k].x == cb[k].x && ca[k].y == cb[k].y);
        }
        free(a);
        free(b);
        free(ca);
        free(cb);
    }
}

static void test_degenerate(void **state)
{
    (void)state;
    double x[12], y[12];
    size_t nh = 99;
    static vor_hole dummy;
    vor_hole *h = &dummy; /* must be reset to NULL */
    ump_err err;
    assert_int_equal(vor_holes(NULL, NULL, 0, NULL, 0.0, &h, &nh, &err), UMP_OK);
    assert_null(h);
    assert_int_equal(nh, 0);
    x[0] = 0.5; y[0] = 0.25;
    x[1] = 1.5; y[1] = -3.0;
    for (size_t n = 1; n <= 2; n++) {
        h = holes_ok(x, y, n, NULL, 0.0, &nh);
        assert_int_equal(nh, 0);
    }
    /* Collinear, unevenly spaced, and far from the origin. */
    for (int i = 0; i < 12; i++) {
        x[i] = 1e3 + 0.5 * i * i;
        y[i] = -7 + 1.5 * i * i;
    }
    h = holes_ok(x, y, 12, NULL, 0.0, &nh);
    assert_int_equal(nh, 0);
    for (int i = 0; i < 12; i++) { /* on a vertical line */
        x[i] = 2.0;
        y[i] = i;
    }
    h = holes_ok(x, y, 12, NULL, 0.0, &nh);
    assert_int_equal(nh, 0);
    for (int i = 0; i < 12; i++) { /* coincident */
        x[i] = 3.25;
        y[i] = -1.0;
    }
    h = holes_ok(x, y, 12, NULL, 0.0, &nh);
    assert_int_equal(nh, 0);

    /* Three points: one circle. */
    double tx[3] = {0, 4, 0}, ty[3] = {0, 0, 3};
    h = holes_ok(tx, ty, 3, NULL, 0.0, &nh);
    assert_int_equal(nh, 1);
    TU_CLOSE(h[0].x, 2.0, 1e-14);
    TU_CLOSE(h[0].y, 1.5, 1e-14);
    TU_CLOSE(h[0].r, 2.5, 1e-14);
    free(h);

    /* Four cocircular points (all of the input on one circle: needs Qz),
     * plus a duplicate of one of them. */
    double sx[5] = {1, 0, -1, 0, 1}, sy[5] = {0, 1, 0, -1, 0};
    h = holes_ok(sx, sy, 5, NULL, 0.0, &nh);
    assert_int_equal(nh, 2);
    for (size_t k = 0; k < 2; k++) {
        TU_CLOSE(h[k].r, 1.0, 1e-14);
        TU_CLOSE(h[k].x, 0.0, 1e-14);
        TU_CLOSE(h[k].y, 0.0, 1e-14);
    }
    free(h);

    /* Non-finite input is refused. */
    x[0] = 0; y[0] = 0;
    x[1] = 1; y[1] = 0;
    x[2] = 0; y[2] = NAN;
    h = NULL;
    assert_int_equal(vor_holes(x, y, 3, NULL, 0.0, &h, &nh, &err), UMP_ERR_INPUT);
    assert_null(h);
    assert_int_equal(nh, 0);
    assert_non_null(strstr(err.msg, "point 2"));
}

/* Concurrent calls (one qhull instance each) agree with a serial one. */
static void test_threads(void **state)
{
    (void)state;
    enum { N = 2000, T = 4 };
    static double x[N], y[N];
    random_cloud(x, y, N, 4242);
    size_t nref;
    vor_hole *ref = holes_ok(x, y, N, NULL, 0.0, &nref);
    int bad = 0;
#pragma omp parallel for num_threads(T) reduction(+ : bad)
    for (int t = 0; t < 2 * T; t++) {
        vor_hole *h = NULL;
        size_t nh = 0;
        ump_err err;
        if (vor_holes(x, y, N, NULL, 0.0, &h, &nh, &err) != UMP_OK || nh != nref ||
            memcmp(h, ref, nh * sizeof *h) != 0)
            bad++;
        free(h);
    }
    assert_int_equal(bad, 0);
    free(ref);
}

/* Nothing on stdout/stderr: cocircular lattice input with a duplicate
 * point, and a nearly collinear cloud. (qhull's error path, which writes
 * to a memory stream, cannot be reached with valid options from here.) */
static void test_silent(void **state)
{
    (void)state;
    static double x[NX * NY + 1], y[NX * NY + 1];
    long idx[NX][NY];
    size_t n = lattice(x, y, idx), nh;
    x[n] = x[0]; /* a duplicate point */
    y[n] = y[0];
    char dir[64], path[128];
    tu_tmpdir(dir, sizeof dir);
    snprintf(path, sizeof path, "%s/out", dir);
    fflush(stdout);
    fflush(stderr);
    int fd = open(path, O_WRONLY | O_CREAT | O_TRUNC, 0600);
    assert_true(fd >= 0);
    int o1 = dup(1), o2 = dup(2);
    dup2(fd, 1);
    dup2(fd, 2);
    vor_hole *h = NULL;
    ump_err err;
    ump_status s1 = vor_holes(x, y, n + 1, NULL, 0.0, &h, &nh, &err);
    free(h);
    double lx[4] = {0, 1, 2, 3}, ly[4] = {0, 1e-13, -1e-13, 0};
    ump_status s2 = vor_holes(lx, ly, 4, NULL, 0.0, &h, &nh, &err);
    free(h);
    fflush(stdout);
    fflush(stderr);
    dup2(o1, 1);
    dup2(o2, 2);
    close(o1);
    close(o2);
    close(fd);
    struct stat st;
    assert_int_equal(stat(path, &st), 0);
    tu_rmtree(dir);
    assert_int_equal(s1, UMP_OK);
    assert_int_equal(s2, UMP_OK);
    assert_int_equal(st.st_size, 0);
}


/* ---- vor_holes_inside against vor_holes ------------------------------- */

/* The centre inside the triangle, as vor_holes_inside's filter is stated. */
static int inside_tri(const double *x, const double *y, const vor_hole *o, double tol)
{
    double ax = x[o->v[0]], ay = y[o->v[0]], bx = x[o->v[1]], by = y[o->v[1]], cx = x[o->v[2]], cy = y[o->v[2]];
    double det = (bx - ax) * (cy - ay) - (cx - ax) * (by - ay);
    if (det == 0)
        return 0;
    double l1 = ((bx - o->x) * (cy - o->y) - (cx - o->x) * (by - o->y)) / det;
    double l2 = ((cx - o->x) * (ay - o->y) - (ax - o->x) * (cy - o->y)) / det;
    return l1 >= -tol && l2 >= -tol && 1 - l1 - l2 >= -tol;
}

static int cmp_circle(const void *pa, const void *pb)
{
    const vor_hole *a = pa, *b = pb;
    if (a->r != b->r)
        return a->r < b->r ? -1 : 1;
    if (a->x != b->x)
        return a->x < b->x ? -1 : 1;
    return (a->y > b->y) - (a->y < b->y);
}

/* vor_holes_inside gives vor_holes' holes with the centre inside: the same
 * list (triples too, unless cocircular), *nfull the count. */
static size_t same_as_full(const double *x, const double *y, size_t n, const unsigned char *mask, double rmin,
                           int cocircular)
{
    size_t nf, nh;
    vor_hole *f = holes_ok(x, y, n, mask, rmin, &nf), *h = NULL;
    size_t k = 0;
    for (size_t q = 0; q < nf; q++)
        if (inside_tri(x, y, &f[q], 0.05))
            f[k++] = f[q];
    ump_err err;
    if (vor_holes_inside(x, y, n, mask, rmin, 0.05, &h, &nh, &err) != UMP_OK)
        fail_msg("%s", err.msg);
    assert_int_equal(nh, k);
    check_shape(x, y, h, nh);
    if (cocircular) {
        qsort(f, k, sizeof *f, cmp_circle);
        qsort(h, nh, sizeof *h, cmp_circle);
    }
    for (size_t q = 0; q < k; q++) {
        assert_true(h[q].x == f[q].x && h[q].y == f[q].y && h[q].r == f[q].r);
        if (!cocircular)
            assert_memory_equal(h[q].v, f[q].v, sizeof f[q].v);
    }
    free(f);
    free(h);
    return k;
}

static void test_inside_matches(void **state)
{
    (void)state;
    enum { M = 40, N = 2000 }; /* the random clouds' size; lattices of M x M */
    static double x[N], y[N];
    static unsigned char mask[N];
    static long idx[NX][NY];
    /* a lattice without one point: the hole of radius 1 (4 cocircular points) */
    size_t n = lattice(x, y, idx);
    assert_int_equal(same_as_full(x, y, n, NULL, 0.9, 1), 2);
    /* random clouds: the largest empty circles */
    for (uint64_t seed = 1; seed <= 4; seed++) {
        random_cloud(x, y, 2000, seed);
        size_t k = same_as_full(x, y, 2000, NULL, 1.0 / sqrt(2000.0), 0);
        assert_true(k > 20);
    }
    /* jittered lattices with points taken out, with and without a mask */
    for (uint64_t seed = 1; seed <= 4; seed++) {
        tu_rng_seed(seed + 100);
        n = 0;
        for (int j = 0; j < M; j++)
            for (int i = 0; i < M; i++) {
                if (tu_rnd() < 0.03)
                    continue;
                x[n] = i + 0.6 * (tu_rnd() - 0.5);
                y[n] = j + 0.6 * (tu_rnd() - 0.5);
                mask[n] = tu_rnd() < 0.8;
                n++;
            }
        size_t k0 = same_as_full(x, y, n, NULL, 0.9, 0), k1 = same_as_full(x, y, n, mask, 0.9, 0);
        assert_true(k0 > 10 && k1 < k0);
    }
    /* two clusters far apart: the grid would be too large, the whole cloud */
    random_cloud(x, y, 400, 7);
    for (size_t i = 200; i < 400; i++)
        x[i] += 1e4;
    assert_true(same_as_full(x, y, 400, NULL, 0.05, 0) > 0);
    /* bad arguments */
    vor_hole *h = NULL;
    size_t nh = 7;
    ump_err err;
    assert_int_equal(vor_holes_inside(x, y, 400, NULL, 0.0, 0.05, &h, &nh, &err), UMP_ERR_INPUT);
    assert_int_equal(vor_holes_inside(x, y, 400, NULL, 0.1, -1.0, &h, &nh, &err), UMP_ERR_INPUT);
    assert_int_equal(vor_holes_inside(x, y, 2, NULL, 0.1, 0.05, &h, &nh, &err), UMP_OK);
    assert_int_equal(nh, 0);
}

/* One workspace over clouds of different sizes and kinds (random, a
 * lattice, a masked jittered lattice, a scattered cloud, a refused input,
 * a cloud too small): the same holes, bit for bit, as the one-shot
 * vor_holes_inside; and once the workspace has seen the largest of them,
 * none of our allocations (ump_alloc_fail_after(0) makes one fail). */
static void test_workspace(void **state)
{
    (void)state;
    enum { C = 6, N = 2000 };
    static double x[C][N], y[C][N];
    static unsigned char mask[N];
    static long idx[NX][NY];
    size_t n[C];
    double rmin[C];
    const unsigned char *mk[C] = {0};
    random_cloud(x[0], y[0], N, 11), n[0] = N, rmin[0] = 1.0 / sqrt((double)N);
    n[1] = lattice(x[1], y[1], idx), rmin[1] = 0.9;
    tu_rng_seed(77);
    n[2] = 0;
    for (int j = 0; j < 40; j++)
        for (int i = 0; i < 40; i++) {
            if (tu_rnd() < 0.03)
                continue;
            x[2][n[2]] = i + 0.6 * (tu_rnd() - 0.5);
            y[2][n[2]] = j + 0.6 * (tu_rnd() - 0.5);
            mask[n[2]] = tu_rnd() < 0.8;
            n[2]++;
        }
    mk[2] = mask, rmin[2] = 0.9;
    random_cloud(x[3], y[3], 400, 7), n[3] = 400, rmin[3] = 0.05; /* scattered: the whole cloud */
    for (size_t i = 200; i < 400; i++)
        x[3][i] += 1e4;
    random_cloud(x[4], y[4], 300, 5), n[4] = 300, rmin[4] = 0.05;
    y[4][17] = NAN; /* refused */
    random_cloud(x[5], y[5], 2, 3), n[5] = 2, rmin[5] = 0.05; /* too few: no holes */

    vor_hole *ref[C];
    size_t nref[C];
    ump_status sref[C];
    ump_err err;
    for (int c = 0; c < C; c++) {
        ref[c] = NULL;
        sref[c] = vor_holes_inside(x[c], y[c], n[c], mk[c], rmin[c], 0.05, &ref[c], &nref[c], &err);
    }
    assert_true(sref[0] == UMP_OK && nref[0] > 20 && sref[1] == UMP_OK && nref[1] == 2 && sref[2] == UMP_OK &&
                nref[2] > 0 && sref[3] == UMP_OK && nref[3] > 0 && sref[4] == UMP_ERR_INPUT && sref[5] == UMP_OK &&
                nref[5] == 0);
    vor_work *w = NULL;
    assert_int_equal(vor_work_create(&w, &err), UMP_OK);
    for (int pass = 0; pass < 2; pass++) {
        if (pass == 1)
            ump_alloc_fail_after(0);
        for (int c = 0; c < C; c++) {
            const vor_hole *h = NULL;
            size_t nh = 99;
            ump_status st = vor_work_holes_inside(w, x[c], y[c], n[c], mk[c], rmin[c], 0.05, &h, &nh, &err);
            if (st != sref[c])
                fail_msg("cloud %d, pass %d: status %d (%s), expected %d", c, pass, (int)st, err.msg, (int)sref[c]);
            assert_int_equal(nh, st == UMP_OK ? nref[c] : 0);
            if (nh == 0)
                assert_null(h);
            else
                assert_memory_equal(h, ref[c], nh * sizeof *h);
        }
        ump_alloc_fail_after(-1);
    }
    vor_work_free(&w);
    assert_null(w);
    vor_work_free(&w); /* NULL: a no-op */
    for (int c = 0; c < C; c++)
        free(ref[c]);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_lattice_hole),
        cmocka_unit_test(test_lattice_mask),
        cmocka_unit_test(test_random_empty),
        cmocka_unit_test(test_permutation),
        cmocka_unit_test(test_degenerate),
        cmocka_unit_test(test_threads),
        cmocka_unit_test(test_silent),
        cmocka_unit_test(test_inside_matches),
        cmocka_unit_test(test_workspace),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
