/* SPDX-License-Identifier: GPL-3.0-or-later
 * vor.h -- the largest holes of a 2-D point cloud (module prefix vor_), for
 * particle insertion in the meshless solver: new particles go to the
 * largest Voronoi holes (finite particle method).
 *
 * The Voronoi vertices are the circumcentres of the Delaunay triangles, and
 * each triangle's circumcircle is empty of points, so the holes are the
 * triangles' circumcircles sorted by radius. The Delaunay triangulation is
 * qhull's (reentrant libqhull_r, Debian package libqhull-dev), O(n log n);
 * centres and radii are recomputed here from the input coordinates.
 *
 * Notes for callers:
 *   - triangles along the convex hull of the cloud can be slivers whose
 *     circumcircle is huge and centred far outside the cloud; filter the
 *     centres by the domain (or keep the hull points out with mask) before
 *     inserting at them;
 *   - cocircular points (a lattice) give several triangles with one circle
 *     (a lattice square: two triangles of radius h*sqrt(2)/2, same centre):
 *     each is returned, so equal centres can appear twice;
 *   - of exactly coincident points only one becomes a Delaunay vertex
 *     (qhull's choice);
 *   - triangles flatter than VOR_FLAT (twice the area below VOR_FLAT times
 *     the longest edge squared) are skipped: their circumcentre is not
 *     numerically meaningful.
 * Reentrant: no global state (one qhull instance per workspace), so
 * threads may call it concurrently, each with its own workspace. Prints
 * nothing.
 *
 * Memory: vor_work_holes_inside works in a vor_work that only grows, so a
 * caller that keeps one (the meshless solver, at every step) allocates
 * nothing of ours once the sizes have been reached; qhull's own blocks are
 * allocated and freed inside each triangulation (vor.c). vor_holes and
 * vor_holes_inside are the one-shot forms: a workspace of their own, the
 * result copied out.
 */
#ifndef UMPPM_VOR_H
#define UMPPM_VOR_H

#include <stddef.h>

#include "umppm/ump.h"

#define VOR_FLAT 1.0e-10

typedef struct vor_hole {
    double x, y;   /* circumcentre of the Delaunay triangle = a Voronoi vertex */
    double r;      /* circumradius: the empty circle's radius */
    size_t v[3];   /* the triangle's vertices (indices into the input), ascending */
} vor_hole;

/* Delaunay triangulation of the n points (x[i], y[i]) by qhull; every
 * triangle whose circumradius exceeds rmin and whose three vertices all have
 * mask[v] != 0 (mask NULL: every point) is returned in *holes (allocated,
 * caller frees; NULL and *nholes = 0 when none), sorted by decreasing radius,
 * ties broken by the vertex triple, so the result does not depend on qhull's
 * internal order. Fewer than 3 points, or all points collinear/coincident
 * (within VOR_FLAT of the cloud's extent, or flat at qhull's precision):
 * UMP_OK with no holes (not an error). Non-finite coordinates, n too large
 * for qhull (int point ids) and other qhull failures: UMP_ERR_INPUT with
 * qhull's message in err; qhull out of memory: UMP_ERR_NOMEM. */
ump_status vor_holes(const double *x, const double *y, size_t n, const unsigned char *mask, double rmin,
                     vor_hole **holes, size_t *nholes, ump_err *err);

/* The holes of vor_holes worth filling -- circumradius > rmin > 0, all
 * three vertices kept by mask, and the centre inside its triangle
 * (barycentric coordinates >= -inside, inside >= 0, the vertices in
 * ascending index order) -- in the same order, without triangulating the
 * whole cloud. A vertex of an empty circle of radius > rmin has an empty
 * open disk of radius rmin on its boundary; only the points that have one
 * (by the arcs their neighbours within 2 rmin block; a point of a lattice
 * has none) go to qhull, and each circle qhull finds among them is kept if
 * no point of the whole cloud lies inside it. So the result is vor_holes'
 * filtered, up to the split of cocircular points into triangles (the same
 * circles) and points inside a circle by less than 1e-10 r^2. A cloud
 * scattered over more than 4 n + 4096 grid cells of side 2 rmin is
 * triangulated whole. Errors as vor_holes', and a bad rmin or inside. */
ump_status vor_holes_inside(const double *x, const double *y, size_t n, const unsigned char *mask, double rmin,
                            double inside, vor_hole **holes, size_t *nholes, ump_err *err);

/* The search's arrays (qhull's input and its state, the holes, a grid and
 * the candidates), kept between calls. */
typedef struct vor_work vor_work;

/* An empty workspace (its arrays grow at the first calls). UMP_ERR_NOMEM. */
ump_status vor_work_create(vor_work **w, ump_err *err);
/* Frees the workspace and sets *w to NULL; NULL is a no-op. */
void vor_work_free(vor_work **w);

/* vor_holes_inside in the workspace w: *holes points into w, valid until
 * the next call with w or vor_work_free (NULL when *nholes = 0). The same
 * holes, in the same order, as vor_holes_inside; the same errors. */
ump_status vor_work_holes_inside(vor_work *w, const double *x, const double *y, size_t n,
                                 const unsigned char *mask, double rmin, double inside, const vor_hole **holes,
                                 size_t *nholes, ump_err *err);

#endif
