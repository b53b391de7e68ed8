/* SPDX-License-Identifier: GPL-3.0-or-later
 * vor.c -- the largest holes of a 2-D point cloud: circumcircles of the
 * Delaunay triangles (= Voronoi vertices), by the reentrant qhull library.
 *
 * qhull computes the Delaunay triangulation as the lower convex hull of the
 * points lifted to the paraboloid z = x^2 + y^2. Options (VOR_QHULL_OPTS):
 *   d    Delaunay triangulation (lift, keep the lower hull);
 *   Qbb  scale the lifted coordinate to the x-y range: z is a sum of
 *        squares and otherwise dwarfs x, y (qhull's own advice for 'd');
 *   Qt   triangulated output: cocircular points (every square of a particle
 *        lattice) make qhull merge triangles into polygons; we need
 *        triangles, each with its own vertex triple;
 *   Qz   a point at infinity above the paraboloid: allows and conditions
 *        cocircular input (a lattice, or every point on one circle, which
 *        without it is a flat hull and an error); its facets are upper
 *        Delaunay and skipped;
 *   Q12  nearly coincident particles can create a "wide dupridge" in the
 *        3-D hull, which qhull otherwise reports as an error: a hole list
 *        that is imprecise next to such a pair is better for insertion than
 *        none at all.
 * Not used: Qc (keeps coplanar points with their facets; we read vertices
 * only, so it would be wasted work), QJ (joggle instead of Qt: triangulates
 * randomly perturbed points, so the circles are only nearly empty and the
 * split of a cocircular polygon changes with the perturbation).
 *
 * The points are shifted to their centroid and scaled by a power of two to
 * [-1, 1] before qhull sees them, so the lifted coordinate does not lose the
 * cloud's detail to a large offset (nor overflow). The circumcentres are
 * recomputed here from the original coordinates, relative to one vertex
 * (differences first, so a lattice's holes are exact) and with the vertices
 * in a canonical order of their coordinates, so a circle's bits depend only
 * on its three points, not on their input numbering or qhull's facet order.
 *
 * qhull reports errors on its errfile: that is an fmemopen stream on a
 * fixed buffer of the workspace (nothing reaches stdout/stderr) whose first
 * error line goes into err.
 *
 * Memory: every array of a search (qhull's input, the holes, the grid and
 * the candidates) lives in a vor_work and only grows, so a caller that
 * keeps one workspace allocates nothing of ours once the sizes have been
 * reached. qhull's own memory (its facets, vertices and sets, in blocks of
 * qh_MEMbufsize) is allocated and freed inside each triangulation: the
 * library's qh_new_qhull re-initialises its memory manager on every call,
 * so there is no supported way to keep it.
 */
#include "umppm/vor.h"

#include <libqhull_r/libqhull_r.h>

#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* "qhull " prefix required by qh_new_qhull; see the comment above. */
#define VOR_QHULL_OPTS "qhull d Qbb Qt Qz Q12"
/* Longest qhull message copied into err (err->msg is 1024 bytes). */
#define VOR_MSG_MAX 800
/* qhull's error stream: its first lines, the ones that name the error */
#define VOR_EBUF 16384

struct vor_work {
    qhT *qh;                 /* ~ 9 kB: not on a thread's stack */
    FILE *ferr;              /* fmemopen on ebuf */
    char ebuf[VOR_EBUF];
    coordT *pts;             /* [2 ptcap] qhull's input */
    size_t ptcap;
    vor_hole *h;             /* [hcap] the holes */
    size_t hcap;
    size_t *sub;             /* [scap] the candidates (vor_work_holes_inside) */
    size_t scap;
    double *sxy;             /* [xycap] their coordinates: x[n], then y[n] */
    size_t xycap;
    size_t *gstart, *gidx;   /* [gcap + 1], [icap] the grid */
    size_t gcap, icap;
};

/* p (capacity *cap elements of size sz) grown to at least n elements,
 * doubling: the new block, *cap updated; NULL when out of memory, p then
 * still valid and *cap unchanged. */
static void *grow(void *p, size_t *cap, size_t n, size_t sz)
{
    if (p && n <= *cap)
        return p;
    size_t nc = *cap * 2 > n ? *cap * 2 : n ? n : 1;
    void *q = ump_realloc_array(p, nc, sz);
    if (q)
        *cap = nc;
    return q;
}

ump_status vor_work_create(vor_work **out, ump_err *err)
{
    *out = NULL;
    vor_work *w = ump_alloc_array(1, sizeof *w);
    UMP_CHECK(w, err, UMP_ERR_NOMEM, "vor: out of memory for a workspace");
    memset(w, 0, sizeof *w);
    w->qh = ump_alloc_array(1, sizeof *w->qh);
    w->ferr = w->qh ? fmemopen(w->ebuf, sizeof w->ebuf, "w") : NULL;
    if (!w->ferr) {
        vor_work_free(&w);
        return UMP_FAIL(err, UMP_ERR_NOMEM, "vor: out of memory for a workspace");
    }
    *out = w;
    return UMP_OK;
}

void vor_work_free(vor_work **pw)
{
    vor_work *w = *pw;
    if (!w)
        return;
    if (w->ferr)
        fclose(w->ferr);
    free(w->qh);
    free(w->pts);
    free(w->h);
    free(w->sub);
    free(w->sxy);
    free(w->gstart);
    free(w->gidx);
    free(w);
    *pw = NULL;
}

/* The input, its centroid and its scale: s = 2^-e with the cloud's
 * half-extent in [2^(e-1), 2^e). Multiplying by a power of two is exact, so
 * the scaled arithmetic gives the unscaled results bit for bit, without
 * overflow of squares (|x| ~ 1e200) or underflow (|x| ~ 1e-300). */
typedef struct vor_cloud {
    const double *x, *y;
    size_t n;
    const unsigned char *mask;
    double cx, cy, s;
    int e;
} vor_cloud;

/* Lexicographic (x, y, index) order: canonical order of a triangle's
 * vertices, independent of their numbering up to exactly equal points. */
static int pt_before(const vor_cloud *c, size_t a, size_t b)
{
    if (c->x[a] != c->x[b])
        return c->x[a] < c->x[b];
    if (c->y[a] != c->y[b])
        return c->y[a] < c->y[b];
    return a < b;
}

/* Circumcircle of triangle t into h (v[] ascending). Returns 0 for a
 * triangle flatter than VOR_FLAT. */
static int circumcircle(const vor_cloud *cl, const size_t t[3], vor_hole *h)
{
    const double *x = cl->x, *y = cl->y, s = cl->s;
    size_t p[3] = {t[0], t[1], t[2]}, w;
    /* Three-element sort into canonical order. */
    if (pt_before(cl, p[1], p[0])) { w = p[0]; p[0] = p[1]; p[1] = w; }
    if (pt_before(cl, p[2], p[1])) { w = p[1]; p[1] = p[2]; p[2] = w; }
    if (pt_before(cl, p[1], p[0])) { w = p[0]; p[0] = p[1]; p[1] = w; }
    double l[3];
    for (int k = 0; k < 3; k++) { /* l[k]: squared edge opposite p[k] */
        size_t i = p[(k + 1) % 3], j = p[(k + 2) % 3];
        double dx = (x[j] - x[i]) * s, dy = (y[j] - y[i]) * s;
        l[k] = dx * dx + dy * dy;
    }
    /* Origin at the vertex opposite the longest edge: its two edges are the
     * shortest, so their cross product (2*area) has the least relative
     * rounding error for the given area. */
    int k = 0;
    if (l[1] > l[k])
        k = 1;
    if (l[2] > l[k])
        k = 2;
    size_t a = p[k], b = p[(k + 1) % 3], c = p[(k + 2) % 3];
    double bx = (x[b] - x[a]) * s, by = (y[b] - y[a]) * s;
    double cx = (x[c] - x[a]) * s, cy = (y[c] - y[a]) * s;
    double d = bx * cy - by * cx; /* twice the signed area */
    if (!(fabs(d) > VOR_FLAT * l[k]))
        return 0;
    double b2 = bx * bx + by * by, c2 = cx * cx + cy * cy;
    double ux = (cy * b2 - by * c2) / (2 * d), uy = (bx * c2 - cx * b2) / (2 * d);
    h->x = x[a] + ldexp(ux, cl->e);
    h->y = y[a] + ldexp(uy, cl->e);
    h->r = ldexp(hypot(ux, uy), cl->e);
    h->v[0] = UMP_MIN(t[0], UMP_MIN(t[1], t[2]));
    h->v[2] = UMP_MAX(t[0], UMP_MAX(t[1], t[2]));
    h->v[1] = t[0] + t[1] + t[2] - h->v[0] - h->v[2];
    return 1;
}

/* Decreasing radius, then ascending vertex triple: a total order. */
static int hole_cmp(const void *pa, const void *pb)
{
    const vor_hole *a = pa, *b = pb;
    if (a->r != b->r)
        return a->r > b->r ? -1 : 1;
    for (int k = 0; k < 3; k++)
        if (a->v[k] != b->v[k])
            return a->v[k] < b->v[k] ? -1 : 1;
    return 0;
}

/* The vertex triple of a lower-Delaunay facet whose vertices are all input
 * points (not qhull's point at infinity) kept by mask; 0 otherwise. */
static int facet_triple(qhT *qh, facetT *facet, const vor_cloud *cl, size_t t[3])
{
    vertexT *vertex, **vertexp;
    int nv = 0;
    if (facet->upperdelaunay)
        return 0;
    /* A loop rather than qh_setsize: nothing here may reach qh_errexit,
     * which after qh_new_qhull has returned would call exit(). */
    FOREACHvertex_(facet->vertices) {
        int id = qh_pointid(qh, vertex->point);
        if (nv == 3 || id < 0 || (size_t)id >= cl->n || (cl->mask && !cl->mask[id]))
            return 0;
        t[nv++] = (size_t)id;
    }
    return nv == 3; /* Qt: every facet is a triangle */
}

/* Collect the qualifying circles of the finished triangulation, unsorted,
 * into w->h. */
static ump_status collect(qhT *qh, vor_work *w, const vor_cloud *cl, double rmin, size_t *nholes, ump_err *err)
{
    facetT *facet;
    size_t t[3], cap = 0, m = 0;
    FORALLfacets { /* an upper bound; one pass over the vertices below */
        cap++;
    }
    vor_hole *h = grow(w->h, &w->hcap, cap, sizeof *h);
    UMP_CHECK(h, err, UMP_ERR_NOMEM, "vor: out of memory for %zu Delaunay triangles", cap);
    w->h = h;
    FORALLfacets {
        if (facet_triple(qh, facet, cl, t) && circumcircle(cl, t, &w->h[m]) && w->h[m].r > rmin)
            m++;
    }
    *nholes = m;
    return UMP_OK;
}

/* Sort the list (hole_cmp). */
static void sort_holes(vor_hole *holes, size_t m)
{
    if (m > 1)
        qsort(holes, m, sizeof *holes, hole_cmp);
}

/* qhull's first error line ("QH6xxx ..."), else its first line, from the
 * NUL-terminated buf. */
static void qhull_message(const char *buf, const char **msg, int *len)
{
    const char *s = NULL;
    if (buf) {
        for (const char *q = buf; q && *q; q = strchr(q, '\n'), q = q ? q + 1 : NULL)
            if (strncmp(q, "QH6", 3) == 0) {
                s = q;
                break;
            }
        if (!s)
            for (s = buf; *s == '\n' || *s == ' '; s++)
                ;
    }
    if (!s || !*s) {
        *msg = "(no message)";
        *len = (int)strlen(*msg);
        return;
    }
    size_t l = strcspn(s, "\n");
    *msg = s;
    *len = (int)UMP_MIN(l, (size_t)VOR_MSG_MAX);
}

/* Centroid and scale of the cloud, and whether it is flat: every point
 * within VOR_FLAT * R of the line from the centroid to the farthest point
 * (R its distance), or all points coincident. Fails on non-finite input. */
static ump_status cloud_shape(vor_cloud *c, int *flat, ump_err *err)
{
    const double *x = c->x, *y = c->y;
    size_t n = c->n;
    double sx = 0, sy = 0;
    for (size_t i = 0; i < n; i++) {
        UMP_CHECK(isfinite(x[i]) && isfinite(y[i]), err, UMP_ERR_INPUT,
                  "vor: point %zu (%g, %g) is not finite", i, x[i], y[i]);
        sx += x[i];
        sy += y[i];
    }
    c->cx = sx / (double)n;
    c->cy = sy / (double)n;
    double ext = 0;
    for (size_t i = 0; i < n; i++)
        ext = fmax(ext, fmax(fabs(x[i] - c->cx), fabs(y[i] - c->cy)));
    UMP_CHECK(isfinite(ext), err, UMP_ERR_INPUT, "vor: the cloud's extent overflows (coordinates near %g)",
              fabs(c->cx) > fabs(c->cy) ? c->cx : c->cy);
    *flat = 1;
    if (ext == 0) /* all coincident */
        return UMP_OK;
    frexp(ext, &c->e);
    c->e = c->e < -1000 ? -1000 : c->e; /* keep s finite for subnormal extents */
    c->s = ldexp(1.0, -c->e);
    double r2 = 0, fx = 0, fy = 0;
    for (size_t i = 0; i < n; i++) {
        double dx = (x[i] - c->cx) * c->s, dy = (y[i] - c->cy) * c->s, d2 = dx * dx + dy * dy;
        if (d2 > r2) {
            r2 = d2;
            fx = dx;
            fy = dy;
        }
    }
    double cmax = 0; /* max |cross| = distance to the line times R */
    for (size_t i = 0; i < n; i++)
        cmax = fmax(cmax, fabs((x[i] - c->cx) * c->s * fy - (y[i] - c->cy) * c->s * fx));
    *flat = !(cmax > VOR_FLAT * r2);
    return UMP_OK;
}

/* The qualifying circles of the whole cloud, unsorted, into w->h. */
static ump_status all_holes(vor_work *w, const double *x, const double *y, size_t n, const unsigned char *mask,
                            double rmin, size_t *nholes, ump_err *err)
{
    *nholes = 0;
    if (n < 3)
        return UMP_OK;
    /* qhull numbers points with int, and Qz adds one. */
    UMP_CHECK(n < (size_t)INT_MAX, err, UMP_ERR_INPUT, "vor: %zu points are too many for qhull", n);
    vor_cloud cl = {.x = x, .y = y, .n = n, .mask = mask, .s = 1.0};
    int flat = 1;
    UMP_CALL(cloud_shape(&cl, &flat, err));
    if (flat)
        return UMP_OK;

    coordT *pts = grow(w->pts, &w->ptcap, 2 * n, sizeof *pts);
    UMP_CHECK(pts, err, UMP_ERR_NOMEM, "vor: out of memory for %zu points", n);
    w->pts = pts;
    for (size_t i = 0; i < n; i++) { /* centred and scaled to [-1, 1]: conditioning */
        pts[2 * i] = (x[i] - cl.cx) * cl.s;
        pts[2 * i + 1] = (y[i] - cl.cy) * cl.s;
    }
    char opts[] = VOR_QHULL_OPTS; /* qh_new_qhull takes a non-const string */
    qhT *qh = w->qh;
    rewind(w->ferr); /* and clears its error flag: a full buffer of a last failure */
    qh_zero(qh, w->ferr);
    int code = qh_new_qhull(qh, 2, (int)n, pts, False, opts, NULL, w->ferr);
    ump_status st = UMP_OK;
    if (code == qh_ERRnone)
        st = collect(qh, w, &cl, rmin, nholes, err);
    int curlong, totlong;
    qh_freeqhull(qh, !qh_ALL);
    qh_memfreeshort(qh, &curlong, &totlong);

    if (code == qh_ERRsingular) {
        /* Flat at qhull's precision (nearly collinear): no triangles. */
        *nholes = 0;
        st = UMP_OK;
    } else if (code != qh_ERRnone) {
        /* the text written: at most the buffer less its terminating NUL */
        fflush(w->ferr);
        long end = ftell(w->ferr);
        size_t len0 = end < 0 ? 0 : UMP_MIN((size_t)end, sizeof w->ebuf - 1);
        w->ebuf[len0] = '\0';
        const char *msg;
        int len;
        qhull_message(w->ebuf, &msg, &len);
        st = UMP_FAIL(err, code == qh_ERRmem ? UMP_ERR_NOMEM : UMP_ERR_INPUT,
                      "vor: qhull failed (exit code %d) on %zu points: %.*s", code, n, len, msg);
    }
    return st;
}

/* A copy of the workspace's first m holes for the allocating interfaces. */
static ump_status copy_out(const vor_work *w, size_t m, vor_hole **holes, size_t *nholes, ump_err *err)
{
    *holes = NULL;
    *nholes = 0;
    if (m == 0)
        return UMP_OK;
    vor_hole *h = ump_alloc_array(m, sizeof *h);
    UMP_CHECK(h, err, UMP_ERR_NOMEM, "vor: out of memory for %zu holes", m);
    memcpy(h, w->h, m * sizeof *h);
    *holes = h;
    *nholes = m;
    return UMP_OK;
}

/* The one-shot forms: a workspace of their own, the result copied out.
 * whole: vor_holes (every hole, the whole cloud triangulated), else
 * vor_holes_inside with the margin inside. */
static ump_status one_shot(int whole, const double *x, const double *y, size_t n, const unsigned char *mask,
                           double rmin, double inside, vor_hole **holes, size_t *nholes, ump_err *err)
{
    *holes = NULL;
    *nholes = 0;
    vor_work *w;
    UMP_CALL(vor_work_create(&w, err));
    size_t m = 0;
    ump_status st;
    if (whole) {
        st = all_holes(w, x, y, n, mask, rmin, &m, err);
        if (st == UMP_OK)
            sort_holes(w->h, m);
    } else {
        const vor_hole *h;
        st = vor_work_holes_inside(w, x, y, n, mask, rmin, inside, &h, &m, err);
    }
    if (st == UMP_OK)
        st = copy_out(w, m, holes, nholes, err);
    vor_work_free(&w);
    return st;
}

ump_status vor_holes(const double *x, const double *y, size_t n, const unsigned char *mask, double rmin,
                     vor_hole **holes, size_t *nholes, ump_err *err)
{
    return one_shot(1, x, y, n, mask, rmin, 0.0, holes, nholes, err);
}

/* ---- vor_holes_inside: the Delaunay triangulation of the candidates only ---- */

/* Points binned on a grid of square cells of side g (counting sort); the
 * arrays are the workspace's. */
typedef struct vor_grid {
    double x0, y0, g;
    long nx, ny;
    const size_t *start; /* [nx ny + 1] */
    const size_t *idx;   /* [n] point numbers, by cell */
} vor_grid;

/* *ok 0: too many cells for the points (a scattered cloud), G unset. */
static ump_status grid_build(vor_work *w, vor_grid *G, const double *x, const double *y, size_t n, double g,
                             int *ok, ump_err *err)
{
    *ok = 0;
    double x0 = HUGE_VAL, y0 = HUGE_VAL, x1 = -HUGE_VAL, y1 = -HUGE_VAL;
    for (size_t i = 0; i < n; i++) {
        x0 = fmin(x0, x[i]), x1 = fmax(x1, x[i]);
        y0 = fmin(y0, y[i]), y1 = fmax(y1, y[i]);
    }
    double cx = floor((x1 - x0) / g) + 1, cy = floor((y1 - y0) / g) + 1;
    if (!(cx * cy <= 4.0 * (double)n + 4096))
        return UMP_OK;
    G->x0 = x0, G->y0 = y0, G->g = g, G->nx = (long)cx, G->ny = (long)cy;
    size_t nc = (size_t)G->nx * (size_t)G->ny;
    size_t *start = grow(w->gstart, &w->gcap, nc + 1, sizeof *start);
    if (start)
        w->gstart = start;
    size_t *idx = start ? grow(w->gidx, &w->icap, n, sizeof *idx) : NULL;
    UMP_CHECK(idx, err, UMP_ERR_NOMEM, "vor: out of memory for a grid of %zu cells", nc);
    w->gidx = idx;
    memset(start, 0, sizeof *start * (nc + 1));
    for (size_t i = 0; i < n; i++) {
        long bx = (long)((x[i] - x0) / g), by = (long)((y[i] - y0) / g);
        start[(size_t)(by * G->nx + bx) + 1]++;
    }
    for (size_t c = 0; c < nc; c++)
        start[c + 1] += start[c];
    for (size_t i = 0; i < n; i++) { /* in increasing i within a cell */
        long bx = (long)((x[i] - x0) / g), by = (long)((y[i] - y0) / g);
        size_t c = (size_t)(by * G->nx + bx);
        idx[start[c]++] = i;
    }
    for (size_t c = nc; c > 0; c--)
        start[c] = start[c - 1];
    start[0] = 0;
    G->start = start;
    G->idx = idx;
    *ok = 1;
    return UMP_OK;
}

/* The cell range [lo, hi] covering [a - r, a + r] along one axis. */
static void grid_span(double a, double r, double a0, double g, long ncell, long *lo, long *hi)
{
    double l = floor((a - r - a0) / g), h = floor((a + r - a0) / g);
    *lo = l < 0 ? 0 : l >= (double)ncell ? ncell : (long)l;
    *hi = h < 0 ? -1 : h >= (double)ncell ? ncell - 1 : (long)h;
}

/* Whether point i can be a vertex of an empty circle of radius > rmin:
 * some open disk of radius rmin with i on its boundary (centre i + rmin e)
 * holds no other point. A point j at distance d < 2 rmin from i lies in
 * that disk for the directions e within acos(d / 2 rmin) of its own
 * direction, an open arc; i qualifies when the arcs of its neighbours do
 * not cover the whole circle, i.e. when the end of some arc lies in no
 * arc (or there is no arc). The arcs are narrowed by a relative 1e-9, so a
 * rounding error can only make a point qualify. */
static int can_be_vertex(const vor_grid *G, const double *x, const double *y, size_t i, double rmin)
{
    enum { MAXARC = 256 };
    double th[MAXARC], al[MAXARC];
    int k = 0;
    long cx0, cx1, cy0, cy1;
    grid_span(x[i], 2 * rmin, G->x0, G->g, G->nx, &cx0, &cx1);
    grid_span(y[i], 2 * rmin, G->y0, G->g, G->ny, &cy0, &cy1);
    for (long by = cy0; by <= cy1; by++)
        for (long bx = cx0; bx <= cx1; bx++) {
            size_t c = (size_t)(by * G->nx + bx);
            for (size_t q = G->start[c]; q < G->start[c + 1]; q++) {
                size_t j = G->idx[q];
                double dx = x[j] - x[i], dy = y[j] - y[i], d = hypot(dx, dy);
                if (j == i || d == 0 || !(d < 2 * rmin))
                    continue;
                if (k == MAXARC)
                    return 1; /* a crowd: let qhull decide */
                th[k] = atan2(dy, dx);
                al[k] = acos(d / (2 * rmin)) * (1 - 1e-9);
                k++;
            }
        }
    const double pi = 3.14159265358979323846;
    for (int a = 0; a < k; a++) {
        double e = th[a] + al[a]; /* the end of arc a */
        int in = 0;
        for (int b = 0; b < k && !in; b++) { /* not its own: e is its edge, up to rounding */
            double dth = remainder(e - th[b], 2 * pi);
            in = b != a && fabs(dth) < al[b];
        }
        if (!in)
            return 1;
    }
    return k == 0;
}

/* Whether the open disk (h->x, h->y, h->r) holds a point other than its
 * triangle's three (to a relative 1e-10 of r^2: cocircular points, a
 * lattice's, are on the circle, not in it). The centre's cell first: a
 * circle spanning the liquid between far-apart candidates fails there. */
static int disk_holds_point(const vor_grid *G, const double *x, const double *y, const vor_hole *h)
{
    double r2 = h->r * h->r * (1 - 1e-10);
    long cx0, cx1, cy0, cy1;
    grid_span(h->x, 0, G->x0, G->g, G->nx, &cx0, &cx1);
    grid_span(h->y, 0, G->y0, G->g, G->ny, &cy0, &cy1);
    for (int pass = 0; pass < 2; pass++) {
        if (pass == 1) {
            grid_span(h->x, h->r, G->x0, G->g, G->nx, &cx0, &cx1);
            grid_span(h->y, h->r, G->y0, G->g, G->ny, &cy0, &cy1);
        }
        for (long by = cy0; by <= cy1; by++)
            for (long bx = cx0; bx <= cx1; bx++) {
                size_t c = (size_t)(by * G->nx + bx);
                for (size_t q = G->start[c]; q < G->start[c + 1]; q++) {
                    size_t j = G->idx[q];
                    if (j == h->v[0] || j == h->v[1] || j == h->v[2])
                        continue;
                    double dx = x[j] - h->x, dy = y[j] - h->y;
                    if (dx * dx + dy * dy < r2)
                        return 1;
                }
            }
    }
    return 0;
}

/* The circle's centre inside its triangle: barycentric coordinates >=
 * -inside, the vertices in ascending index order. */
static int centre_inside(const double *x, const double *y, const vor_hole *o, double inside)
{
    double ax = x[o->v[0]], ay = y[o->v[0]], bx = x[o->v[1]], by = y[o->v[1]], cx = x[o->v[2]], cy = y[o->v[2]];
    double det = (bx - ax) * (cy - ay) - (cx - ax) * (by - ay);
    if (det == 0)
        return 0;
    double l1 = ((bx - o->x) * (cy - o->y) - (cx - o->x) * (by - o->y)) / det;
    double l2 = ((cx - o->x) * (ay - o->y) - (ax - o->x) * (cy - o->y)) / det;
    double l3 = 1 - l1 - l2;
    return l1 >= -inside && l2 >= -inside && l3 >= -inside;
}

ump_status vor_work_holes_inside(vor_work *w, const double *x, const double *y, size_t n,
                                 const unsigned char *mask, double rmin, double inside, const vor_hole **holes,
                                 size_t *nholes, ump_err *err)
{
    *holes = NULL;
    *nholes = 0;
    if (n < 3)
        return UMP_OK;
    UMP_CHECK(rmin > 0 && isfinite(rmin) && inside >= 0, err, UMP_ERR_INPUT,
              "vor: hole radius %g, inside %g", rmin, inside);
    for (size_t i = 0; i < n; i++)
        UMP_CHECK(isfinite(x[i]) && isfinite(y[i]), err, UMP_ERR_INPUT, "vor: point %zu (%g, %g) is not finite", i,
                  x[i], y[i]);
    vor_grid G = {0};
    int ok;
    UMP_CALL(grid_build(w, &G, x, y, n, 2 * rmin, &ok, err));
    size_t m = 0, k = 0;
    if (!ok) {
        /* scattered: the whole cloud, then the same filter */
        UMP_CALL(all_holes(w, x, y, n, mask, rmin, &m, err));
        for (size_t q = 0; q < m; q++)
            if (centre_inside(x, y, &w->h[q], inside))
                w->h[k++] = w->h[q];
    } else {
        /* the candidates, kept by mask */
        size_t *sub = grow(w->sub, &w->scap, n, sizeof *sub);
        if (sub)
            w->sub = sub;
        double *sx = sub ? grow(w->sxy, &w->xycap, 2 * n, sizeof *sx) : NULL;
        UMP_CHECK(sx, err, UMP_ERR_NOMEM, "vor: out of memory for %zu points", n);
        w->sxy = sx;
        double *sy = sx + n;
        size_t ns = 0;
        for (size_t i = 0; i < n; i++)
            if ((!mask || mask[i]) && can_be_vertex(&G, x, y, i, rmin)) {
                sub[ns] = i;
                sx[ns] = x[i];
                sy[ns] = y[i];
                ns++;
            }
        UMP_CALL(all_holes(w, sx, sy, ns, NULL, rmin, &m, err));
        for (size_t q = 0; q < m; q++) {
            vor_hole o = w->h[q];
            for (int t = 0; t < 3; t++)
                o.v[t] = sub[o.v[t]]; /* ascending still: sub is increasing */
            if (centre_inside(x, y, &o, inside) && !disk_holds_point(&G, x, y, &o))
                w->h[k++] = o;
        }
    }
    sort_holes(w->h, k);
    *holes = k ? w->h : NULL;
    *nholes = k;
    return UMP_OK;
}

ump_status vor_holes_inside(const double *x, const double *y, size_t n, const unsigned char *mask, double rmin,
                            double inside, vor_hole **holes, size_t *nholes, ump_err *err)
{
    return one_shot(0, x, y, n, mask, rmin, inside, holes, nholes, err);
}
