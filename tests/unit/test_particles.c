/* SPDX-License-Identifier: GPL-3.0-or-later
 * test_particles.c -- the particle module against brute-force oracles:
 * point location vs point-in-polygon over all cells (quad, triangle,
 * hybrid, holed and periodic meshes built in memory), neighbour search vs a
 * scan of all particles, management invariants, and timings on a 100x100
 * quad mesh.
 */
#include "testutil.h"
#include "umppm/mesh2d.h"
#include "umppm/particles.h"
#include "umppm/polymesh.h"
#include "../../src/part_internal.h"

#include <time.h>
#include <omp.h>

/* ---------------------------------------------------------------- helpers */

static uint64_t rng_state = 0x9E3779B97F4A7C15ull;
static void rng_seed(uint64_t s) { rng_state = s * 0x9E3779B97F4A7C15ull + 1; }
static double urand(void) /* [0, 1) */
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 7;
    rng_state ^= rng_state << 17;
    return (double)(rng_state >> 11) * (1.0 / 9007199254740992.0);
}
static long irand(long n) { return (long)(urand() * (double)n); }

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

typedef struct tmesh {
    pmesh *pm;
    mesh2d *m;
    int n;
} tmesh;

enum { K_QUAD, K_TRI2, K_TRI4, K_HOLE };

static int box_patch(double x, double y, void *ctx)
{
    (void)ctx;
    if (y < 1e-9) return 0;
    if (x > 1 - 1e-9) return 1;
    if (y > 1 - 1e-9) return 2;
    if (x < 1e-9) return 3;
    return 4;
}
static const char *const NAMES[] = {"bottom", "right", "top", "left", "hole"};
static const char *const TYPES[] = {"wall", "wall", "wall", "wall", "wall"};

static int kind_quad(int i, int j, int n) { (void)i; (void)j; (void)n; return K_QUAD; }
static int kind_tri4(int i, int j, int n) { (void)i; (void)j; (void)n; return K_TRI4; }
static int kind_tri2(int i, int j, int n) { (void)i; (void)j; (void)n; return K_TRI2; }
static int kind_hybrid(int i, int j, int n) { (void)n; return (i + 2 * j) % 3; }
/* quads with a rectangular hole [n/3, 2n/3) x [n/3, n/2) */
static int kind_hole(int i, int j, int n)
{
    if (i >= n / 3 && i < 2 * n / 3 && j >= n / 3 && j < n / 2)
        return K_HOLE;
    return (i + j) % 4 == 0 ? K_TRI4 : K_QUAD;
}

/* n x n squares on the unit square, interior vertices moved by up to
 * jitter*h; each square a quad, 2 or 4 triangles, or left out (hole). */
static tmesh build_grid(int n, double jitter, int (*kind)(int, int, int), int periodic)
{
    double h = 1.0 / n;
    size_t ng = (size_t)(n + 1) * (size_t)(n + 1);
    double *xy = malloc(sizeof(double) * 2 * (ng + (size_t)n * (size_t)n));
    ump_idx *off = malloc(sizeof(ump_idx) * (4 * (size_t)n * (size_t)n + 1));
    ump_idx *pv = malloc(sizeof(ump_idx) * 12 * (size_t)n * (size_t)n);
    for (int j = 0; j <= n; j++)
        for (int i = 0; i <= n; i++) {
            double x = i * h, y = j * h;
            if (i > 0 && i < n && j > 0 && j < n) {
                x += jitter * h * (2 * urand() - 1);
                y += jitter * h * (2 * urand() - 1);
            }
            xy[2 * (j * (n + 1) + i)] = x;
            xy[2 * (j * (n + 1) + i) + 1] = y;
        }
    ump_idx nv = (ump_idx)ng, np = 0, npv = 0;
    off[0] = 0;
#define POLY3(a, b, c) do { pv[npv++] = a; pv[npv++] = b; pv[npv++] = c; off[++np] = npv; } while (0)
    for (int j = 0; j < n; j++)
        for (int i = 0; i < n; i++) {
            ump_idx a = j * (n + 1) + i, b = a + 1, c = a + n + 2, d = a + n + 1;
            switch (kind(i, j, n)) {
            case K_QUAD:
                pv[npv++] = a; pv[npv++] = b; pv[npv++] = c; pv[npv++] = d;
                off[++np] = npv;
                break;
            case K_TRI2:
                if ((i + j) % 2) { POLY3(a, b, c); POLY3(a, c, d); }
                else { POLY3(a, b, d); POLY3(b, c, d); }
                break;
            case K_TRI4: {
                ump_idx e = nv++;
                xy[2 * e] = 0.25 * (xy[2 * a] + xy[2 * b] + xy[2 * c] + xy[2 * d]);
                xy[2 * e + 1] = 0.25 * (xy[2 * a + 1] + xy[2 * b + 1] + xy[2 * c + 1] + xy[2 * d + 1]);
                POLY3(a, b, e); POLY3(b, c, e); POLY3(c, d, e); POLY3(d, a, e);
                break;
            }
            default:
                break;
            }
        }
#undef POLY3
    /* drop vertices no polygon uses (inside holes) */
    ump_idx *map = malloc(sizeof(ump_idx) * (size_t)nv);
    for (ump_idx v = 0; v < nv; v++) map[v] = -1;
    for (ump_idx k = 0; k < npv; k++) map[pv[k]] = 0;
    ump_idx nu = 0;
    for (ump_idx v = 0; v < nv; v++)
        if (map[v] == 0) {
            xy[2 * nu] = xy[2 * v];
            xy[2 * nu + 1] = xy[2 * v + 1];
            map[v] = nu++;
        }
    for (ump_idx k = 0; k < npv; k++) pv[k] = map[pv[k]];
    tmesh t = {NULL, NULL, n};
    ump_err err;
    if (pmesh_extrude(xy, nu, off, pv, np, 0.1, box_patch, NULL, NAMES, TYPES, 5, &t.pm, &err) != UMP_OK)
        fail_msg("%s", err.msg);
    if (periodic) {
        const char *nb[] = {"top", "left", "bottom", "right"};
        for (int p = 0; p < 4; p++) {
            pmesh_patch *pp = &t.pm->patch[p];
            free(pp->type);
            pp->type = ump_strdup("cyclic");
            pp->kind = PMESH_CYCLIC;
            pp->neighbour_patch = ump_strdup(nb[p]);
            pp->nbr = pmesh_patch_index(t.pm, nb[p]);
        }
    }
    if (mesh_build(t.pm, &t.m, &err) != UMP_OK)
        fail_msg("%s", err.msg);
    free(map);
    free(xy);
    free(off);
    free(pv);
    return t;
}

static void tmesh_free(tmesh *t)
{
    mesh_free(&t->m);
    pmesh_free(&t->pm);
}

/* Brute force, written independently of part_in_cell: winding number. */
static int bf_inside(const mesh2d *m, ump_idx c, double x, double y)
{
    int wn = 0;
    ump_idx b = m->cell_off[c], e = m->cell_off[c + 1];
    for (ump_idx k = b; k < e; k++) {
        ump_idx v0 = m->cell_verts[k], v1 = m->cell_verts[k + 1 < e ? k + 1 : b];
        double x0 = m->vx[v0], y0 = m->vy[v0], x1 = m->vx[v1], y1 = m->vy[v1];
        double cr = (x1 - x0) * (y - y0) - (x - x0) * (y1 - y0);
        if (y0 <= y) {
            if (y1 > y && cr > 0) wn++;
        } else if (y1 <= y && cr < 0) {
            wn--;
        }
    }
    return wn != 0;
}

static ump_idx bf_locate(const mesh2d *m, double x, double y)
{
    for (ump_idx c = 0; c < m->ncells; c++)
        if (bf_inside(m, c, x, y))
            return c;
    return -1;
}

/* distance from (x, y) to the polygon outline of c */
static double bf_edge_dist(const mesh2d *m, ump_idx c, double x, double y)
{
    double best = INFINITY;
    ump_idx b = m->cell_off[c], e = m->cell_off[c + 1];
    for (ump_idx k = b; k < e; k++) {
        ump_idx v0 = m->cell_verts[k], v1 = m->cell_verts[k + 1 < e ? k + 1 : b];
        double ax = m->vx[v0], ay = m->vy[v0], ex = m->vx[v1] - ax, ey = m->vy[v1] - ay;
        double t = ((x - ax) * ex + (y - ay) * ey) / (ex * ex + ey * ey);
        t = t < 0 ? 0 : (t > 1 ? 1 : t);
        double d = hypot(ax + t * ex - x, ay + t * ey - y);
        if (d < best) best = d;
    }
    return best;
}

/* random point inside cell c (rejection in its bounding box around the centroid) */
static void point_in_cell(const mesh2d *m, ump_idx c, double *x, double *y)
{
    for (;;) {
        *x = m->cx[c] + m->dx[c] * (2 * urand() - 1);
        *y = m->cy[c] + m->dy[c] * (2 * urand() - 1);
        if (bf_inside(m, c, *x, *y))
            return;
    }
}

/* locate from `start`, compare with the brute force; returns walk steps */
typedef struct loc_stats {
    long n, walk_fail, ambiguous, steps;
} loc_stats;

static void check_locate(const mesh2d *m, ump_idx start, double x, double y, loc_stats *ls)
{
    ump_idx want = bf_locate(m, x, y);
    double px = x, py = y, wx = x, wy = y;
    ump_idx cell, face, wcell, wface;
    long steps = 0;
    part_where r = part_locate(m, start, &px, &py, &cell, &face);
    part_where rw = part_walk(m, start, &wx, &wy, &wcell, &wface, (long)m->ncells + 16, &steps);
    ls->n++;
    ls->steps += steps;
    if (rw == PART_LOST)
        ls->walk_fail++;
    if (want < 0) {
        /* outside the domain (in a hole): must leave through a wall */
        if (r != PART_LEFT || face < m->ninternal || face >= m->nfaces)
            fail_msg("point (%.17g, %.17g) outside the domain: r=%d face=%ld", x, y, (int)r, (long)face);
        return;
    }
    if (r != PART_INSIDE)
        fail_msg("point (%.17g, %.17g) in cell %ld from start %ld: r=%d", x, y, (long)want, (long)start, (int)r);
    if (px != x || py != y)
        fail_msg("point moved without cyclics");
    if (cell != want) {
        double tol = 1e-9 * m->dc[want];
        if (bf_edge_dist(m, cell, x, y) > tol || bf_edge_dist(m, want, x, y) > tol)
            fail_msg("point (%.17g, %.17g): located in %ld, brute force %ld (start %ld)", x, y, (long)cell,
                     (long)want, (long)start);
        ls->ambiguous++;
    }
}

/* --------------------------------------------------------------- tests */

static void test_set_seed_compact_grow(void **state)
{
    (void)state;
    rng_seed(1);
    tmesh t = build_grid(7, 0.2, kind_hybrid, 0);
    const mesh2d *m = t.m;
    part_set *s = NULL;
    ump_err err;
    assert_int_equal(part_create(0, &s, &err), UMP_OK);
    double *u = malloc(sizeof(double) * (size_t)m->ncells), *v = malloc(sizeof(double) * (size_t)m->ncells);
    for (ump_idx c = 0; c < m->ncells; c++) {
        u[c] = c;
        v[c] = -c;
    }
    assert_int_equal(part_seed_centroids(s, m, u, v, NULL, &err), UMP_OK);
    assert_int_equal(s->n, (size_t)m->ncells);
    for (ump_idx c = 0; c < m->ncells; c++) {
        assert_int_equal(s->cell[c], c);
        assert_true(s->x[c] == m->cx[c] && s->y[c] == m->cy[c]);
        assert_true(s->u[c] == c && s->v[c] == -c && s->T[c] == 0);
        assert_int_equal(s->id[c], c);
        assert_true(part_in_cell(m, c, s->x[c], s->y[c]));
    }
    assert_int_equal(s->next_id, m->ncells);
    /* compaction keeps order and ids */
    size_t n0 = s->n;
    unsigned char *keep = malloc(n0);
    for (size_t i = 0; i < n0; i++) keep[i] = (unsigned char)(urand() < 0.6);
    part_compact(s, keep);
    size_t k = 0;
    for (size_t i = 0; i < n0; i++)
        if (keep[i]) {
            assert_int_equal(s->id[k], (int64_t)i);
            assert_int_equal(s->cell[k], (ump_idx)i);
            assert_true(s->x[k] == m->cx[i] && s->u[k] == (double)i);
            k++;
        }
    assert_int_equal(s->n, k);
    free(keep);
    part_free(&s);
    assert_null(s);
    part_free(&s); /* NULL is fine */

    /* growth: 1e5 particles one by one from capacity 1 */
    assert_int_equal(part_create(1, &s, &err), UMP_OK);
    for (size_t i = 0; i < 100000; i++) {
        size_t idx;
        assert_int_equal(part_add(s, (double)i, 2.0 * (double)i, 1, 2, 3, (ump_idx)(i % 7), &idx, &err), UMP_OK);
        assert_int_equal(idx, i);
    }
    assert_int_equal(s->n, 100000);
    assert_true(s->cap >= 100000 && s->cap < 400000);
    for (size_t i = 0; i < 100000; i += 997)
        assert_true(s->x[i] == (double)i && s->y[i] == 2.0 * (double)i && s->id[i] == (int64_t)i &&
                    s->cell[i] == (ump_idx)(i % 7) && s->T[i] == 3);
    /* out-of-memory on growth leaves the set usable */
    size_t cap = s->cap;
    ump_alloc_fail_after(3);
    assert_int_equal(part_reserve(s, 2 * cap + 1, &err), UMP_ERR_NOMEM);
    ump_alloc_fail_after(-1);
    assert_null(strchr(err.msg, '\n'));
    assert_non_null(strstr(err.msg, "particles"));
    assert_int_equal(s->cap, cap);
    assert_true(s->x[99999] == 99999.0 && s->id[99999] == 99999);
    assert_int_equal(part_reserve(s, 2 * cap + 1, &err), UMP_OK);
    assert_true(s->id[99999] == 99999 && s->cell[99999] == (ump_idx)(99999 % 7));
    part_free(&s);
    ump_alloc_fail_after(0);
    assert_int_equal(part_create(10, &s, &err), UMP_ERR_NOMEM);
    ump_alloc_fail_after(-1);
    assert_null(s);
    free(u);
    free(v);
    tmesh_free(&t);
}

/* strict: the walk alone must succeed for the neighbour and small-move cases
 * (convex cells); otherwise only the result (with fall-backs) is checked */
static void run_locate_suite(tmesh *t, const char *name, int npts, int strict)
{
    const mesh2d *m = t->m;
    loc_stats rnd = {0, 0, 0, 0}, nbr = {0, 0, 0, 0}, small = {0, 0, 0, 0};
    /* random points from random start cells */
    for (int k = 0; k < npts; k++) {
        double x = urand(), y = urand();
        check_locate(m, (ump_idx)irand(m->ncells), x, y, &rnd);
    }
    /* a point of cell c located from a random first neighbour of c */
    for (int k = 0; k < npts; k++) {
        ump_idx c = (ump_idx)irand(m->ncells);
        double x, y;
        point_in_cell(m, c, &x, &y);
        ump_idx q = m->n1[m->n1_off[c] + irand(m->n1_off[c + 1] - m->n1_off[c])];
        check_locate(m, q, x, y, &nbr);
    }
    /* small moves (up to 0.5 h) from a point of the start cell */
    for (int k = 0; k < npts; k++) {
        ump_idx c = (ump_idx)irand(m->ncells);
        double x, y;
        point_in_cell(m, c, &x, &y);
        x += 0.5 / t->n * (2 * urand() - 1);
        y += 0.5 / t->n * (2 * urand() - 1);
        if (x < 0 || x > 1 || y < 0 || y > 1)
            continue;
        check_locate(m, c, x, y, &small);
    }
    print_message("locate %-8s %6ld cells: random start %ld pts (mean %.1f faces crossed, %ld walk "
                  "fall-backs), from N1 %ld (mean %.2f, %ld), small move %ld (mean %.2f, %ld); %ld on edges\n",
                  name, (long)m->ncells, rnd.n, (double)rnd.steps / (double)rnd.n, rnd.walk_fail, nbr.n,
                  (double)nbr.steps / (double)nbr.n, nbr.walk_fail, small.n,
                  (double)small.steps / (double)small.n, small.walk_fail,
                  rnd.ambiguous + nbr.ambiguous + small.ambiguous);
    /* the walk itself must succeed in the typical cases */
    if (strict) {
        assert_int_equal(nbr.walk_fail, 0);
        assert_int_equal(small.walk_fail, 0);
    }
}

static void test_locate_meshes(void **state)
{
    (void)state;
    rng_seed(2);
    struct { int n; double jit; int (*kind)(int, int, int); const char *name; } cases[] = {
        {30, 0.0, kind_quad, "quad"},   {30, 0.2, kind_quad, "quad~"}, {20, 0.0, kind_tri4, "tri4"},
        {25, 0.15, kind_tri2, "tri2~"}, {24, 0.2, kind_hybrid, "hybrid~"}, {24, 0.15, kind_hole, "hole~"},
        /* jitter 0.45: some quads non-convex, a few arrowheads */
        {20, 0.45, kind_quad, "quad!!"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        tmesh t = build_grid(cases[i].n, cases[i].jit, cases[i].kind, 0);
        run_locate_suite(&t, cases[i].name, 3000, cases[i].jit < 0.4);
        tmesh_free(&t);
    }
}

/* every vertex and points on every edge, from random start cells and from
 * each cell touching them */
static void test_locate_edges_vertices(void **state)
{
    (void)state;
    rng_seed(3);
    int (*kinds[])(int, int, int) = {kind_quad, kind_hybrid, kind_hole};
    for (int kk = 0; kk < 3; kk++) {
        tmesh t = build_grid(12, kk ? 0.2 : 0.0, kinds[kk], 0);
        const mesh2d *m = t.m;
        long npts = 0;
        for (ump_idx f = 0; f < m->nfaces; f++) {
            double ax = m->vx[m->fv0[f]], ay = m->vy[m->fv0[f]];
            double bx = m->vx[m->fv1[f]], by = m->vy[m->fv1[f]];
            double ts[] = {0.0, 0.5, urand(), 1.0};
            for (int q = 0; q < 4; q++) {
                double x = ax + ts[q] * (bx - ax), y = ay + ts[q] * (by - ay);
                ump_idx starts[] = {(ump_idx)irand(m->ncells), m->owner[f],
                                    f < m->ninternal ? m->neigh[f] : m->owner[f]};
                for (int s = 0; s < 3; s++) {
                    double px = x, py = y;
                    ump_idx cell, face;
                    part_where r = part_locate(m, starts[s], &px, &py, &cell, &face);
                    if (r != PART_INSIDE || !part_in_cell(m, cell, x, y) ||
                        bf_edge_dist(m, cell, x, y) > 1e-12)
                        fail_msg("edge point (%.17g, %.17g) of face %ld: r=%d cell %ld", x, y, (long)f,
                                 (int)r, (long)cell);
                    /* an edge point found from one of its own cells stays there */
                    if (s > 0)
                        assert_int_equal(cell, starts[s]);
                    npts++;
                }
            }
        }
        print_message("edges/vertices: %ld locates on %ld faces, all inside a touching cell\n", npts,
                      (long)m->nfaces);
        tmesh_free(&t);
    }
}

static void test_locate_walls(void **state)
{
    (void)state;
    rng_seed(4);
    for (int kk = 0; kk < 2; kk++) {
        tmesh t = build_grid(10, 0.15, kk ? kind_hole : kind_hybrid, 0);
        const mesh2d *m = t.m;
        for (ump_idx f = m->ninternal; f < m->nfaces; f++) {
            ump_idx c = m->owner[f];
            double ax = m->vx[m->fv0[f]], ay = m->vy[m->fv0[f]];
            double bx = m->vx[m->fv1[f]], by = m->vy[m->fv1[f]];
            for (int q = 0; q < 5; q++) {
                double tt = 0.2 + 0.6 * urand(), out = (0.01 + 0.1 * urand()) * m->len[f];
                double x = ax + tt * (bx - ax) + out * m->nx[f], y = ay + tt * (by - ay) + out * m->ny[f];
                double px = x, py = y;
                ump_idx cell, face;
                part_where r = part_locate(m, c, &px, &py, &cell, &face);
                if (r != PART_LEFT || face != f || cell != c)
                    fail_msg("crossing face %ld of cell %ld: r=%d face %ld cell %ld", (long)f, (long)c, (int)r,
                             (long)face, (long)cell);
                assert_true(px == x && py == y);
            }
            /* exactly on the wall: inside */
            double px = m->fx[f], py = m->fy[f];
            ump_idx cell, face;
            assert_int_equal(part_locate(m, c, &px, &py, &cell, &face), PART_INSIDE);
            assert_int_equal(cell, c);
        }
        /* non-finite input */
        double px = NAN, py = 0.5;
        ump_idx cell, face;
        assert_int_equal(part_locate(m, 0, &px, &py, &cell, &face), PART_LOST);
        assert_int_equal(cell, -1);
        /* an invalid start cell goes to the global search */
        px = 0.51;
        py = 0.93;
        assert_int_equal(part_locate(m, -1, &px, &py, &cell, &face), PART_INSIDE);
        assert_int_equal(cell, bf_locate(m, 0.51, 0.93));
        tmesh_free(&t);
    }
    /* re-entrant corner of the hole: the point is beyond the hole wall line
     * of the start cell but in the fluid: the walk goes round the corner */
    tmesh t = build_grid(12, 0.0, kind_hole, 0);
    const mesh2d *m = t.m;
    double h = 1.0 / 12;
    /* hole = [4,8) x [4,6) in cells; start below its left end, point left of it */
    double sx = 4.5 * h, sy = 3.5 * h, x = 3.9 * h, y = 4.4 * h;
    ump_idx start = bf_locate(m, sx, sy), want = bf_locate(m, x, y), cell, face;
    assert_true(start >= 0 && want >= 0);
    assert_int_equal(part_locate(m, start, &x, &y, &cell, &face), PART_INSIDE);
    assert_int_equal(cell, want);
    /* into the hole from far away: left through a hole wall */
    x = 6 * h;
    y = 5 * h;
    assert_int_equal(part_locate(m, 0, &x, &y, &cell, &face), PART_LEFT);
    assert_int_equal(m->face_patch[face], 4);
    tmesh_free(&t);
}

/* wrap x into [0, 1) */
static double wrap01(double x) { return x - floor(x); }

static void test_locate_periodic(void **state)
{
    (void)state;
    rng_seed(5);
    int n = 8;
    double h = 1.0 / n;
    tmesh t = build_grid(n, 0.0, kind_quad, 1);
    const mesh2d *m = t.m;
    ump_idx cell, face;
    /* right column, row 3: across the right edge into the left column */
    ump_idx c = 3 * n + (n - 1);
    double x = m->cx[c] + 0.8 * h, y = m->cy[c];
    assert_int_equal(part_locate(m, c, &x, &y, &cell, &face), PART_INSIDE);
    assert_int_equal(cell, 3 * n + 0);
    TU_CLOSE(x, 0.3 * h, 1e-14);
    TU_CLOSE(y, 3.5 * h, 1e-14);
    /* and back across the left edge */
    x -= 0.6 * h;
    assert_int_equal(part_locate(m, cell, &x, &y, &cell, &face), PART_INSIDE);
    assert_int_equal(cell, 3 * n + n - 1);
    TU_CLOSE(x, 1 - 0.3 * h, 1e-14);
    /* top edge -> bottom row, and the corner (both wraps) */
    c = (n - 1) * n + 2;
    x = m->cx[c];
    y = m->cy[c] + 0.7 * h;
    assert_int_equal(part_locate(m, c, &x, &y, &cell, &face), PART_INSIDE);
    assert_int_equal(cell, 2);
    TU_CLOSE(y, 0.2 * h, 1e-14);
    c = n * n - 1;
    x = m->cx[c] + 0.9 * h;
    y = m->cy[c] + 0.6 * h;
    assert_int_equal(part_locate(m, c, &x, &y, &cell, &face), PART_INSIDE);
    assert_int_equal(cell, 0);
    TU_CLOSE(x, 0.4 * h, 1e-14);
    TU_CLOSE(y, 0.1 * h, 1e-14);
    tmesh_free(&t);

    /* one cell across the period (owner == neighbour on both cyclic faces)
     * is refused by mesh_build since issue 15: such a cell's least-squares
     * stencil is degenerate, so no run could use it (tests/unit/test_mesh2d.c,
     * test_badmesh_topology.sh) */

    /* random small moves on periodic triangle and hybrid meshes */
    int (*kinds[])(int, int, int) = {kind_tri4, kind_hybrid};
    for (int kk = 0; kk < 2; kk++) {
        t = build_grid(10, 0.2, kinds[kk], 1);
        m = t.m;
        long nwrap = 0, steps_tot = 0, nfail = 0;
        for (int k = 0; k < 4000; k++) {
            ump_idx c0 = (ump_idx)irand(m->ncells);
            double px, py;
            point_in_cell(m, c0, &px, &py);
            px += 0.6 / 10 * (2 * urand() - 1);
            py += 0.6 / 10 * (2 * urand() - 1);
            double wx = wrap01(px), wy = wrap01(py);
            ump_idx want = bf_locate(m, wx, wy);
            assert_true(want >= 0);
            double x1 = px, y1 = py, x2 = px, y2 = py;
            long steps;
            ump_idx c2, f2;
            if (part_walk(m, c0, &x2, &y2, &c2, &f2, m->ncells + 16, &steps) == PART_LOST)
                nfail++;
            steps_tot += steps;
            assert_int_equal(part_locate(m, c0, &x1, &y1, &cell, &face), PART_INSIDE);
            if (x1 != px || y1 != py)
                nwrap++;
            /* the returned point is the image inside the box, in the returned cell */
            TU_CLOSE(x1, wx, 1e-13);
            TU_CLOSE(y1, wy, 1e-13);
            if (cell != want && (bf_edge_dist(m, cell, x1, y1) > 1e-9 || bf_edge_dist(m, want, wx, wy) > 1e-9))
                fail_msg("periodic: (%g %g) -> cell %ld, brute force %ld", px, py, (long)cell, (long)want);
        }
        print_message("periodic %s: 4000 small moves, %ld wrapped, mean %.2f faces crossed, %ld walk fall-backs\n",
                      kk ? "hybrid~" : "tri4~", nwrap, (double)steps_tot / 4000, nfail);
        assert_true(nwrap > 100);
        assert_int_equal(nfail, 0);
        tmesh_free(&t);
    }
}

/* n particles at random points of random cells */
static part_set *random_particles(const mesh2d *m, size_t n)
{
    part_set *s = NULL;
    ump_err err;
    assert_int_equal(part_create(n, &s, &err), UMP_OK);
    for (size_t i = 0; i < n; i++) {
        ump_idx c = (ump_idx)irand(m->ncells);
        double x, y;
        point_in_cell(m, c, &x, &y);
        assert_int_equal(part_add(s, x, y, urand(), urand(), urand(), c, NULL, &err), UMP_OK);
    }
    return s;
}

static void check_bins(const mesh2d *m, const part_set *s, const part_bins *b)
{
    assert_int_equal(b->ncells, m->ncells);
    assert_int_equal(b->off[0], 0);
    size_t nbinned = 0;
    for (size_t i = 0; i < s->n; i++)
        nbinned += s->cell[i] >= 0;
    assert_int_equal((size_t)b->off[m->ncells], nbinned);
    for (ump_idx c = 0; c < m->ncells; c++) {
        assert_true(b->off[c] <= b->off[c + 1]);
        for (ump_idx k = b->off[c]; k < b->off[c + 1]; k++) {
            assert_int_equal(s->cell[b->idx[k]], c);
            if (k > b->off[c])
                assert_true(b->idx[k - 1] < b->idx[k]);
        }
    }
}

static void test_bins_boundary(void **state)
{
    (void)state;
    rng_seed(6);
    tmesh t = build_grid(9, 0.2, kind_hybrid, 0);
    const mesh2d *m = t.m;
    part_set *s = random_particles(m, 1000);
    part_bins b = {0};
    ump_err err;
    assert_int_equal(part_bins_build(&b, m, s, &err), UMP_OK);
    check_bins(m, s, &b);
    /* re-bin after moves, marking some particles as left, and after growth */
    for (size_t i = 0; i < s->n; i++)
        s->cell[i] = urand() < 0.1 ? -1 : (ump_idx)irand(m->ncells);
    size_t *idx0 = b.idx;
    assert_int_equal(part_bins_build(&b, m, s, &err), UMP_OK);
    assert_ptr_equal(b.idx, idx0); /* storage reused */
    check_bins(m, s, &b);
    for (int i = 0; i < 3000; i++)
        assert_int_equal(part_add(s, 0.5, 0.5, 0, 0, 0, (ump_idx)irand(m->ncells), NULL, &err), UMP_OK);
    assert_int_equal(part_bins_build(&b, m, s, &err), UMP_OK);
    check_bins(m, s, &b);
    /* a cell out of range is refused with one line */
    s->cell[5] = m->ncells;
    assert_int_equal(part_bins_build(&b, m, s, &err), UMP_ERR_INPUT);
    assert_null(strchr(err.msg, '\n'));
    s->cell[5] = 0;
    /* a large set (40 000 particles, 5 % left) */
    while (s->n < 40000)
        assert_int_equal(part_add(s, 0.5, 0.5, 0, 0, 0, urand() < 0.05 ? -1 : (ump_idx)irand(m->ncells), NULL,
                                  &err), UMP_OK);
    assert_int_equal(part_bins_build(&b, m, s, &err), UMP_OK);
    check_bins(m, s, &b);
    /* sorting by cell: particles of a cell consecutive, ids travel along */
    for (size_t i = 0; i < s->n; i++)
        if (s->cell[i] < 0)
            s->cell[i] = 1;
    double *xs = malloc(sizeof(double) * s->n);
    int64_t *ids = malloc(sizeof(int64_t) * s->n);
    for (size_t i = 0; i < s->n; i++) {
        s->x[i] = (double)i;
        ids[i] = s->id[i];
    }
    assert_int_equal(part_sort_by_cell(s, &b, m, &err), UMP_OK);
    for (size_t i = 0; i < s->n; i++) {
        assert_true(i == 0 || s->cell[i] >= s->cell[i - 1]);
        assert_true(i == 0 || s->cell[i] != s->cell[i - 1] || s->x[i] > s->x[i - 1]); /* stable */
        assert_true(s->id[i] == ids[(size_t)s->x[i]]);
        assert_true(b.idx[i] == i);
        xs[i] = s->x[i];
    }
    check_bins(m, s, &b);
    free(xs);
    free(ids);
    part_bins_free(&b);
    part_bins_free(&b);

    part_boundary bp;
    assert_int_equal(part_boundary_create(&bp, m, &err), UMP_OK);
    assert_int_equal(bp.n, m->nfaces - m->ninternal);
    assert_int_equal(bp.off[m->ncells], bp.n);
    unsigned char *seen = calloc((size_t)bp.n, 1);
    for (ump_idx c = 0; c < m->ncells; c++)
        for (ump_idx k = bp.off[c]; k < bp.off[c + 1]; k++) {
            ump_idx j = bp.idx[k];
            assert_false(seen[j]);
            seen[j] = 1;
            assert_int_equal(m->owner[bp.face[j]], c);
            assert_true(bp.x[j] == m->fx[bp.face[j]] && bp.y[j] == m->fy[bp.face[j]]);
            assert_true(bp.face[j] >= m->ninternal);
        }
    free(seen);
    part_boundary_free(&bp);
    part_boundary_free(&bp);
    part_free(&s);
    tmesh_free(&t);
}

static int cmp_nbr(const void *p, const void *q)
{
    const part_nbr *a = p, *b = q;
    if (a->is_boundary != b->is_boundary)
        return a->is_boundary - b->is_boundary;
    return (a->index > b->index) - (a->index < b->index);
}

/* shift of cell q in c's stencil {c} + N2(c); 0 if absent */
static int stencil_shift(const mesh2d *m, ump_idx c, ump_idx q, double *sx, double *sy)
{
    *sx = *sy = 0;
    if (q == c)
        return 1;
    for (ump_idx a = m->n2_off[c]; a < m->n2_off[c + 1]; a++)
        if (m->n2[a] == q) {
            if (m->n2_sx) {
                *sx = m->n2_sx[a];
                *sy = m->n2_sy[a];
            }
            return 1;
        }
    return 0;
}

static void test_neighbours(void **state)
{
    (void)state;
    rng_seed(7);
    for (int kk = 0; kk < 3; kk++) {
        int periodic = kk > 0;
        tmesh t = build_grid(9, 0.2, kk == 2 ? kind_tri4 : kind_hybrid, periodic);
        const mesh2d *m = t.m;
        part_set *s = random_particles(m, 3 * (size_t)m->ncells);
        part_bins b = {0};
        part_boundary bp;
        ump_err err;
        assert_int_equal(part_bins_build(&b, m, s, &err), UMP_OK);
        assert_int_equal(part_boundary_create(&bp, m, &err), UMP_OK);
        if (periodic)
            assert_int_equal(bp.n, 0);
        size_t cap = s->n + (size_t)bp.n;
        part_nbr *got = malloc(sizeof *got * cap), *want = malloc(sizeof *want * cap);
        long nshift = 0, ntot = 0;
        for (int trial = 0; trial < 300; trial++) {
            size_t i = (size_t)irand((long)s->n);
            ump_idx c = s->cell[i];
            double x = s->x[i], y = s->y[i];
            size_t ng = part_neighbours(m, s, &b, &bp, c, x, y, i, got, cap);
            size_t nw = 0;
            double sx, sy;
            for (size_t j = 0; j < s->n; j++)
                if (j != i && stencil_shift(m, c, s->cell[j], &sx, &sy))
                    want[nw++] = (part_nbr){j, 0, s->x[j] + sx - x, s->y[j] + sy - y};
            for (ump_idx j = 0; j < bp.n; j++)
                if (stencil_shift(m, c, m->owner[bp.face[j]], &sx, &sy))
                    want[nw++] = (part_nbr){(size_t)j, 1, bp.x[j] + sx - x, bp.y[j] + sy - y};
            assert_int_equal(ng, nw);
            /* a too-small buffer: same count, only max written */
            assert_int_equal(part_neighbours(m, s, &b, &bp, c, x, y, i, got, 3), nw);
            assert_int_equal(part_neighbours(m, s, &b, &bp, c, x, y, i, got, cap), nw);
            qsort(got, ng, sizeof *got, cmp_nbr);
            qsort(want, nw, sizeof *want, cmp_nbr);
            for (size_t k = 0; k < ng; k++) {
                assert_int_equal(got[k].index, want[k].index);
                assert_int_equal(got[k].is_boundary, want[k].is_boundary);
                TU_CLOSE(got[k].dx, want[k].dx, 1e-13);
                TU_CLOSE(got[k].dy, want[k].dy, 1e-13);
                /* neighbours are near (3 cells of 1/9 at most per axis): the
                 * cyclic shift brought the far images next to the point */
                assert_true(fabs(got[k].dx) < 0.5 && fabs(got[k].dy) < 0.5);
                if (fabs(got[k].dx - (s->x[got[k].index] - x)) > 0.5 && !got[k].is_boundary)
                    nshift++;
            }
            ntot += (long)ng;
        }
        print_message("neighbours (%s): 300 queries match the brute force, mean %.1f neighbours, "
                      "%ld seen across cyclics\n", periodic ? "periodic" : "walls", (double)ntot / 300, nshift);
        if (periodic)
            assert_true(nshift > 0);
        free(got);
        free(want);
        part_boundary_free(&bp);
        part_bins_free(&b);
        part_free(&s);
        tmesh_free(&t);
    }
}

static double d2c(const mesh2d *m, const part_set *s, size_t i)
{
    double dx = s->x[i] - m->cx[s->cell[i]], dy = s->y[i] - m->cy[s->cell[i]];
    return dx * dx + dy * dy;
}

/* every pair of particles in the same or N1 cells is far enough apart */
static void check_spacing(const mesh2d *m, const part_set *s, const part_bins *b, double alpha, int64_t id0,
                          double *dmin_rel, long *nclose_new)
{
    *nclose_new = 0;
    *dmin_rel = INFINITY;
    for (size_t i = 0; i < s->n; i++) {
        ump_idx c = s->cell[i];
        for (ump_idx a = m->n1_off[c] - 1; a < m->n1_off[c + 1]; a++) {
            ump_idx q = a < m->n1_off[c] ? c : m->n1[a];
            double sx = a >= m->n1_off[c] && m->n1_sx ? m->n1_sx[a] : 0;
            double sy = a >= m->n1_off[c] && m->n1_sy ? m->n1_sy[a] : 0;
            for (ump_idx k = b->off[q]; k < b->off[q + 1]; k++) {
                size_t j = b->idx[k];
                if (j == i)
                    continue;
                double d = hypot(s->x[j] + sx - s->x[i], s->y[j] + sy - s->y[i]);
                if (s->id[i] >= id0 || s->id[j] >= id0) {
                    /* refilled centroid particles are exempt (added after the deletion) */
                    *nclose_new += d < sqrt(alpha) * fmin(m->dc[c], m->dc[q]);
                    continue;
                }
                /* d_c of the cell of the member nearer its centroid (ties: lower index) */
                double di = d2c(m, s, i), dj = d2c(m, s, j);
                size_t kept = (di < dj || (di == dj && i < j)) ? i : j;
                double lim = sqrt(alpha) * m->dc[s->cell[kept]];
                if (d < lim * (1 - 1e-12))
                    fail_msg("particles %zu and %zu at %g < sqrt(alpha) d_c = %g", i, j, d, lim);
                double rel = d / (sqrt(alpha) * fmin(m->dc[c], m->dc[q]));
                if (rel < *dmin_rel)
                    *dmin_rel = rel;
            }
        }
    }
}

static void test_manage_umppm(void **state)
{
    (void)state;
    rng_seed(8);
    for (int kk = 0; kk < 2; kk++) {
        tmesh t = build_grid(12, 0.2, kind_hybrid, kk);
        const mesh2d *m = t.m;
        size_t nc = (size_t)m->ncells;
        /* clustered: 6 per cell on average, two cells in three left empty */
        part_set *s = NULL;
        ump_err err;
        assert_int_equal(part_create(0, &s, &err), UMP_OK);
        for (size_t i = 0; i < 6 * nc; i++) {
            ump_idx c = (ump_idx)(3 * irand((long)nc / 3));
            double x, y;
            point_in_cell(m, c, &x, &y);
            assert_int_equal(part_add(s, x, y, 1, 2, 3, c, NULL, &err), UMP_OK);
        }
        /* two exact duplicates and some particles marked as left */
        assert_int_equal(part_add(s, s->x[0], s->y[0], 0, 0, 0, s->cell[0], NULL, &err), UMP_OK);
        for (size_t i = 10; i < 20; i++)
            s->cell[i] = -1;
        double *uc = malloc(sizeof(double) * nc), *vc = malloc(sizeof(double) * nc), *Tc = malloc(sizeof(double) * nc);
        for (size_t c = 0; c < nc; c++) {
            uc[c] = (double)c;
            vc[c] = 2.0 * (double)c;
            Tc[c] = 3.0 * (double)c;
        }
        part_bins b = {0};
        part_manage_stats st;
        size_t n0 = s->n;
        int64_t id0 = s->next_id;
        /* the state before, to check each deletion afterwards */
        double *x0 = malloc(sizeof(double) * n0), *y0 = malloc(sizeof(double) * n0);
        ump_idx *c0 = malloc(sizeof(ump_idx) * n0);
        for (size_t i = 0; i < n0; i++) {
            x0[i] = s->x[i];
            y0[i] = s->y[i];
            c0[i] = s->cell[i];
            assert_int_equal(s->id[i], (int64_t)i);
        }
        double alpha = 0.09;
        assert_int_equal(part_manage(s, &b, m, PART_UMPPM, alpha, uc, vc, Tc, &st, &err), UMP_OK);
        assert_int_equal(st.removed_left, 10);
        assert_int_equal(st.deleted_extra, 0);
        assert_int_equal(s->n, n0 - st.removed_left - st.deleted_close + st.added);
        assert_true(st.deleted_close > 0 && st.added > 0);
        check_bins(m, s, &b);
        /* refill: every cell populated; the new particles sit at centroids with (uc, vc, Tc) */
        for (ump_idx c = 0; c < m->ncells; c++)
            assert_true(b.off[c + 1] > b.off[c]);
        unsigned char *alive = calloc(n0, 1);
        for (size_t i = 0; i < s->n; i++) {
            if (i > 0)
                assert_true(s->id[i] > s->id[i - 1]); /* order kept, new ones appended */
            if (s->id[i] >= id0) {
                ump_idx c = s->cell[i];
                assert_true(s->x[i] == m->cx[c] && s->y[i] == m->cy[c]);
                assert_true(s->u[i] == uc[c] && s->v[i] == vc[c] && s->T[i] == Tc[c]);
            } else {
                alive[s->id[i]] = 1;
                assert_true(s->x[i] == x0[s->id[i]] && s->cell[i] == c0[s->id[i]]);
            }
        }
        /* survivors: no pair closer than sqrt(alpha) d_c (d_c of the member nearer its centroid) */
        double dmin;
        long nclose_new;
        check_spacing(m, s, &b, alpha, id0, &dmin, &nclose_new);
        /* every deleted particle had a kept partner in its cell or N1 cells,
         * nearer its own centroid and closer than sqrt(alpha) d_c of its cell */
        for (size_t j = 0; j < n0; j++) {
            if (alive[j] || c0[j] < 0)
                continue;
            double dj = hypot(x0[j] - m->cx[c0[j]], y0[j] - m->cy[c0[j]]);
            int found = 0;
            ump_idx c = c0[j];
            for (ump_idx a = m->n1_off[c] - 1; a < m->n1_off[c + 1] && !found; a++) {
                ump_idx q = a < m->n1_off[c] ? c : m->n1[a];
                double sx = a >= m->n1_off[c] && m->n1_sx ? m->n1_sx[a] : 0;
                double sy = a >= m->n1_off[c] && m->n1_sy ? m->n1_sy[a] : 0;
                for (ump_idx k = b.off[q]; k < b.off[q + 1] && !found; k++) {
                    size_t i = b.idx[k];
                    if (s->id[i] >= id0)
                        continue;
                    double di = hypot(s->x[i] - m->cx[q], s->y[i] - m->cy[q]);
                    double d = hypot(s->x[i] + sx - x0[j], s->y[i] + sy - y0[j]);
                    found = di <= dj && d < sqrt(alpha) * m->dc[q];
                }
            }
            if (!found)
                fail_msg("particle %zu deleted without a kept close partner", j);
        }
        print_message("UMPPM (%s): %zu particles -> %zu (%zu deleted as close, %zu left, %zu added); "
                      "closest surviving neighbour pair %.3f sqrt(alpha) min d_c; %ld pairs with a refilled "
                      "particle closer\n", kk ? "periodic" : "walls", n0, s->n, st.deleted_close, st.removed_left,
                      st.added, dmin, nclose_new);
        free(alive);
        free(x0);
        free(y0);
        free(c0);
        /* a second pass keeps the refilled particles (at their centroids, so
         * first in line) and leaves every cell populated */
        assert_int_equal(part_manage(s, &b, m, PART_UMPPM, alpha, uc, vc, Tc, &st, &err), UMP_OK);
        assert_int_equal(st.removed_left, 0);
        for (ump_idx c = 0; c < m->ncells; c++)
            assert_true(b.off[c + 1] > b.off[c]);
        check_bins(m, s, &b);
        /* bad input */
        assert_int_equal(part_manage(s, &b, m, PART_UMPPM, 0.0, uc, vc, Tc, &st, &err), UMP_ERR_INPUT);
        assert_null(strchr(err.msg, '\n'));
        assert_int_equal(part_manage(s, &b, m, (part_variant)7, alpha, uc, vc, Tc, &st, &err), UMP_ERR_INPUT);
        free(uc);
        free(vc);
        free(Tc);
        part_bins_free(&b);
        part_free(&s);
        tmesh_free(&t);
    }
}

/* A cloud of about n_per * ncells particles at random points of random
 * cells, leaving out the cells c with c % skip == 0 (they start empty). */
static part_set *random_cloud(const mesh2d *m, size_t n_per, ump_idx skip)
{
    part_set *s = NULL;
    ump_err err;
    assert_int_equal(part_create(0, &s, &err), UMP_OK);
    size_t nc = (size_t)m->ncells;
    for (size_t i = 0; i < n_per * nc; i++) {
        ump_idx c = (ump_idx)irand((long)nc);
        if (c % skip == 0)
            continue;
        double x, y;
        point_in_cell(m, c, &x, &y);
        assert_int_equal(part_add(s, x, y, 0, 0, 0, c, NULL, &err), UMP_OK);
    }
    return s;
}

/* part_manage_refill: the refill function sees every particle in the bins
 * with the survivors flagged, and the values it sets for the cells no
 * survivor occupies are the ones the new particles get, including cells
 * whose only particle UMPPM deleted (a neighbour's kept one too close). */
typedef struct refill_probe {
    const mesh2d *m;
    const part_set *s;
    const part_bins *b;
    double *uc, *vc;
    size_t calls, emptied, occupied_before;
} refill_probe;

static ump_status probe_refill(void *ctx, const unsigned char *alive, ump_err *err)
{
    (void)err;
    refill_probe *p = ctx;
    p->calls++;
    assert_int_equal((size_t)p->b->off[p->m->ncells], p->s->n); /* every particle still binned */
    for (ump_idx c = 0; c < p->m->ncells; c++) {
        int any = 0;
        for (ump_idx k = p->b->off[c]; k < p->b->off[c + 1]; k++)
            any |= alive[p->b->idx[k]] != 0;
        if (!any) {
            p->uc[c] = 1000.0 + c;
            p->vc[c] = -1.0 - c;
            p->emptied++;
            p->occupied_before += p->b->off[c + 1] > p->b->off[c];
        }
    }
    return UMP_OK;
}

static void test_manage_refill_fn(void **state)
{
    (void)state;
    rng_seed(17);
    tmesh t = build_grid(12, 0.2, kind_hybrid, 0);
    const mesh2d *m = t.m;
    size_t nc = (size_t)m->ncells;
    part_set *s = random_cloud(m, 3, 4); /* some cells start empty */
    ump_err err;
    double *uc = calloc(nc, sizeof(double)), *vc = calloc(nc, sizeof(double));
    part_bins b = {0};
    part_manage_stats st;
    refill_probe p = {m, s, &b, uc, vc, 0, 0, 0};
    assert_int_equal(part_manage_refill(s, &b, m, PART_UMPPM, 0.3, probe_refill, &p, uc, vc, NULL, &st, &err),
                     UMP_OK);
    assert_int_equal(p.calls, 1);
    assert_int_equal(p.emptied, st.added);
    assert_true(p.occupied_before > 0); /* UMPPM emptied some occupied cells */
    check_bins(m, s, &b);
    size_t seen = 0;
    for (ump_idx c = 0; c < m->ncells; c++)
        for (ump_idx k = b.off[c]; k < b.off[c + 1]; k++) {
            size_t i = b.idx[k];
            if (s->x[i] == m->cx[c] && s->y[i] == m->cy[c] && s->u[i] >= 1000) {
                assert_true(s->u[i] == 1000.0 + c && s->v[i] == -1.0 - c);
                seen++;
            }
        }
    assert_int_equal(seen, st.added);
    print_message("refill function: %zu cells refilled, %zu of them emptied by the deletion\n", st.added,
                  p.occupied_before);
    free(uc);
    free(vc);
    part_bins_free(&b);
    part_free(&s);
    tmesh_free(&t);
}

static void test_manage_star(void **state)
{
    (void)state;
    rng_seed(9);
    tmesh t = build_grid(12, 0.2, kind_hybrid, 0);
    const mesh2d *m = t.m;
    size_t nc = (size_t)m->ncells;
    part_set *s = random_cloud(m, 4, 5); /* some cells stay empty */
    ump_err err;
    /* a tie: a copy of particle 0 (the lower index must win if 0 is nearest) */
    assert_int_equal(part_add(s, s->x[0], s->y[0], 0, 0, 0, s->cell[0], NULL, &err), UMP_OK);
    /* expected survivor per cell: nearest to the centroid, lower index on ties */
    int64_t *want = malloc(sizeof(int64_t) * nc);
    for (size_t c = 0; c < nc; c++)
        want[c] = -1;
    double *best = malloc(sizeof(double) * nc);
    for (size_t i = 0; i < s->n; i++) {
        ump_idx c = s->cell[i];
        double d = d2c(m, s, i);
        if (want[c] < 0 || d < best[c]) {
            want[c] = s->id[i];
            best[c] = d;
        }
    }
    double *uc = calloc(nc, sizeof(double)), *vc = calloc(nc, sizeof(double));
    part_bins b = {0};
    part_manage_stats st;
    size_t n0 = s->n;
    assert_int_equal(part_manage(s, &b, m, PART_UMPPM_STAR, 0.0, uc, vc, NULL, &st, &err), UMP_OK);
    assert_int_equal(s->n, nc);
    assert_int_equal(st.deleted_close, 0);
    assert_int_equal(n0 - st.deleted_extra + st.added, nc);
    check_bins(m, s, &b);
    size_t nnew = 0;
    for (ump_idx c = 0; c < m->ncells; c++) {
        assert_int_equal(b.off[c + 1] - b.off[c], 1);
        size_t i = b.idx[b.off[c]];
        if (want[c] >= 0) {
            assert_int_equal(s->id[i], want[c]);
        } else {
            assert_true(s->x[i] == m->cx[c] && s->y[i] == m->cy[c] && s->T[i] == 0);
            nnew++;
        }
    }
    assert_int_equal(nnew, st.added);
    assert_true(nnew > 0);
    print_message("UMPPM*: %zu particles -> %zu, one per cell (%zu extra deleted, %zu added)\n", n0, s->n,
                  st.deleted_extra, st.added);
    free(want);
    free(best);
    free(uc);
    free(vc);
    part_bins_free(&b);
    part_free(&s);
    tmesh_free(&t);
}

/* timings on a 100 x 100 quad mesh, one particle per cell */
static void test_timings(void **state)
{
    (void)state;
    rng_seed(10);
    int n = 100;
    double h = 1.0 / n;
    tmesh t = build_grid(n, 0.0, kind_quad, 0);
    const mesh2d *m = t.m;
    part_set *s = NULL;
    ump_err err;
    assert_int_equal(part_create(0, &s, &err), UMP_OK);
    double *zero = calloc((size_t)m->ncells, sizeof(double));
    assert_int_equal(part_seed_centroids(s, m, zero, zero, NULL, &err), UMP_OK);
    size_t np = s->n;
    double *dx = malloc(sizeof(double) * np), *dy = malloc(sizeof(double) * np);
    /* locate after small moves (|step| <= 0.3 h per axis, i.e. CFL ~ 0.3),
     * reflected at the walls so no particle leaves */
    int reps = 20;
    double tloc = 0;
    long nleft = 0;
    for (int r = 0; r < reps; r++) {
        for (size_t i = 0; i < np; i++) {
            dx[i] = 0.3 * h * (2 * urand() - 1);
            dy[i] = 0.3 * h * (2 * urand() - 1);
            double x = s->x[i] + dx[i], y = s->y[i] + dy[i];
            if (x < 0 || x > 1) dx[i] = -dx[i];
            if (y < 0 || y > 1) dy[i] = -dy[i];
        }
        double t0 = now();
        for (size_t i = 0; i < np; i++) {
            s->x[i] += dx[i];
            s->y[i] += dy[i];
            ump_idx face;
            nleft += part_locate(m, s->cell[i], &s->x[i], &s->y[i], &s->cell[i], &face) != PART_INSIDE;
        }
        tloc += now() - t0;
    }
    assert_int_equal(nleft, 0);
    for (size_t i = 0; i < np; i += 97)
        assert_int_equal(s->cell[i], bf_locate(m, s->x[i], s->y[i]));
    part_bins b = {0};
    part_boundary bp;
    assert_int_equal(part_boundary_create(&bp, m, &err), UMP_OK);
    assert_int_equal(part_bins_build(&b, m, s, &err), UMP_OK);
    double t0 = now();
    int breps = 200;
    for (int r = 0; r < breps; r++)
        assert_int_equal(part_bins_build(&b, m, s, &err), UMP_OK);
    double tbin = now() - t0;
    part_nbr buf[256];
    size_t tot = 0;
    int nreps = 20;
    t0 = now();
    for (int r = 0; r < nreps; r++)
        for (size_t i = 0; i < np; i++) {
            size_t k = part_neighbours(m, s, &b, &bp, s->cell[i], s->x[i], s->y[i], i, buf, 256);
            assert_true(k <= 256);
            tot += k;
        }
    double tnbr = now() - t0;
    print_message("timings, 100x100 quads, 1 particle/cell: locate after a small move %.3f us/particle, "
                  "binning %.4f us/particle, part_neighbours %.3f us/particle (mean %.1f neighbours)\n",
                  1e6 * tloc / ((double)reps * (double)np), 1e6 * tbin / ((double)breps * (double)np),
                  1e6 * tnbr / ((double)nreps * (double)np), (double)tot / ((double)nreps * (double)np));
    free(dx);
    free(dy);
    free(zero);
    part_boundary_free(&bp);
    part_bins_free(&b);
    part_free(&s);
    tmesh_free(&t);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_set_seed_compact_grow),
        cmocka_unit_test(test_locate_meshes),
        cmocka_unit_test(test_locate_edges_vertices),
        cmocka_unit_test(test_locate_walls),
        cmocka_unit_test(test_locate_periodic),
        cmocka_unit_test(test_bins_boundary),
        cmocka_unit_test(test_neighbours),
        cmocka_unit_test(test_manage_umppm),
        cmocka_unit_test(test_manage_star),
        cmocka_unit_test(test_manage_refill_fn),
        cmocka_unit_test(test_timings),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
