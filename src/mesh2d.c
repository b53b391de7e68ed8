/* SPDX-License-Identifier: GPL-3.0-or-later
 * mesh2d.c -- the 2-D UMPPM pressure mesh built from a one-cell-thick
 * OpenFOAM polyMesh (docs/METHOD.md section 3.1; Ng, Sheu & Hwang 2016
 * [NSH16] Section 3.2.2, Figs. 1-5).
 *
 * Everything here depends on the mesh only and is computed once (Step 1 and
 * Step 3 of the paper's algorithm). Geometry is exact for planar polygons:
 * the centroid and area of the back-side polygon equal OpenFOAM's cell centre
 * (projected) and cell volume / thickness to round-off, which the
 * integration tests check against postProcess -func writeCellCentres.
 *
 * The face normal comes from the polyMesh face (right-hand rule, owner ->
 * neighbour); the edge end points come from the face's points on the back
 * side. Every cell is then checked to be closed in 2-D (sum of outward
 * normal * length vanishes) and to have a 2-D area, by the divergence
 * theorem, equal to its polygon area: an inconsistent polyMesh is refused.
 */
#include "umppm/mesh2d.h"

#include <math.h>
#ifdef _OPENMP
#include <omp.h>
#endif
#include <stdlib.h>
#include <string.h>

#define ALLOC(p, n) ((p) = ump_alloc_array((size_t)(n), sizeof *(p)))

static void free_mesh_arrays(mesh2d *m)
{
    void *arr[] = {
        m->vx, m->vy, m->vert_pm, m->vert_id, m->cell_off, m->cell_verts,
        m->cx, m->cy, m->area, m->dx, m->dy, m->dc, m->cell_face_off,
        m->cell_faces, m->owner, m->neigh, m->fv0, m->fv1, m->fx, m->fy,
        m->nx, m->ny, m->len, m->sepx, m->sepy, m->face_pm, m->face_pm2,
        m->pmface_to_face, m->face_patch, m->patch, m->n1_off, m->n1,
        m->n2_off, m->n2, m->n1_sx, m->n1_sy, m->n2_sx, m->n2_sy
    };
    for (size_t i = 0; i < sizeof arr / sizeof arr[0]; i++)
        free(arr[i]);
}

void mesh_free(mesh2d **pm)
{
    if (!pm || !*pm)
        return;
    free_mesh_arrays(*pm);
    free(*pm);
    *pm = NULL;
}

void mesh_to3d(const mesh2d *m, double X, double Y, double out[3])
{
    out[m->normal] = 0.5 * (m->zmin + m->zmax);
    out[m->ax[0]] = X;
    out[m->ax[1]] = Y;
}

double mesh_patch_area(const mesh2d *m, int p, double *nrm)
{
    const pmesh_patch *pp = &m->pm->patch[p];
    double area = 0;
    for (ump_idx i = 0; i < pp->n; i++) {
        ump_idx f = m->pmface_to_face[pp->start + i];
        if (nrm) {
            double *n = nrm + 3 * (size_t)i;
            n[0] = n[1] = n[2] = 0;
            if (f >= m->ninternal) {
                n[m->ax[0]] = m->nx[f];
                n[m->ax[1]] = m->ny[f];
            }
        }
        if (f >= m->ninternal)
            area += m->len[f] * (m->zmax - m->zmin); /* the face's 3-D area */
    }
    return area;
}

/* Newell area vector of polyMesh face f (3-D, |A| = area, right-hand rule). */
static void face_area_vector(const pmesh *pm, ump_idx f, double A[3])
{
    A[0] = A[1] = A[2] = 0.0;
    ump_idx b = pm->face_off[f], e = pm->face_off[f + 1];
    for (ump_idx i = b; i < e; i++) {
        const double *p = pm->points + 3 * (size_t)pm->face_pts[i];
        const double *q = pm->points + 3 * (size_t)pm->face_pts[i + 1 < e ? i + 1 : b];
        A[0] += 0.5 * (p[1] - q[1]) * (p[2] + q[2]);
        A[1] += 0.5 * (p[2] - q[2]) * (p[0] + q[0]);
        A[2] += 0.5 * (p[0] - q[0]) * (p[1] + q[1]);
    }
}

/* Union-find over vertices (cyclic identification). */
static ump_idx uf_find(ump_idx *par, ump_idx a)
{
    while (par[a] != a) {
        par[a] = par[par[a]];
        a = par[a];
    }
    return a;
}

static void uf_union(ump_idx *par, ump_idx a, ump_idx b)
{
    a = uf_find(par, a);
    b = uf_find(par, b);
    if (a < b)
        par[b] = a;
    else if (b < a)
        par[a] = b;
}

static int cmp_idx(const void *a, const void *b)
{
    ump_idx x = *(const ump_idx *)a, y = *(const ump_idx *)b;
    return (x > y) - (x < y);
}

/* Step 1: normal axis and extent from the empty faces. */
static ump_status find_plane(const pmesh *pm, mesh2d *m, const char *dir, ump_err *err)
{
    int any = 0;
    double nsum[3] = {0, 0, 0};
    for (int p = 0; p < pm->npatches; p++) {
        const pmesh_patch *pp = &pm->patch[p];
        if (pp->kind == PMESH_WEDGE)
            return UMP_FAIL(err, UMP_ERR_UNSUPPORTED,
                            "%s/boundary: patch '%s' is of type wedge: axisymmetric cases are not supported "
                            "(%s needs a planar 2-D mesh with empty front and back patches)",
                            dir, pp->name, ump_solver);
        if (pp->kind != PMESH_EMPTY)
            continue;
        for (ump_idx f = pp->start; f < pp->start + pp->n; f++) {
            double A[3];
            face_area_vector(pm, f, A);
            for (int k = 0; k < 3; k++)
                nsum[k] += fabs(A[k]);
            any = 1;
        }
    }
    if (!any)
        return UMP_FAIL(err, UMP_ERR_UNSUPPORTED,
                        "%s/boundary: no face is on an 'empty' patch: this is a 3-D mesh; %s "
                        "solves 2-D cases (one cell thick, front and back patches of type empty)", dir, ump_solver);
    int k = 0;
    for (int i = 1; i < 3; i++)
        if (nsum[i] > nsum[k])
            k = i;
    m->normal = k;
    m->ax[0] = (k + 1) % 3;
    m->ax[1] = (k + 2) % 3;

    /* every empty face must be a plane normal to axis k */
    double zmin = INFINITY, zmax = -INFINITY;
    for (ump_idx i = 0; i < pm->npoints; i++) {
        double z = pm->points[3 * (size_t)i + k];
        zmin = fmin(zmin, z);
        zmax = fmax(zmax, z);
    }
    double thick = zmax - zmin;
    if (!(thick > 0))
        return UMP_FAIL(err, UMP_ERR_INPUT, "%s/points: mesh has zero thickness along %c",
                        dir, "xyz"[k]);
    m->zmin = zmin;
    m->zmax = zmax;
    double tol = 1e-8 * thick;
    for (int p = 0; p < pm->npatches; p++) {
        const pmesh_patch *pp = &pm->patch[p];
        if (pp->kind != PMESH_EMPTY)
            continue;
        for (ump_idx f = pp->start; f < pp->start + pp->n; f++) {
            double A[3];
            face_area_vector(pm, f, A);
            double a = sqrt(A[0] * A[0] + A[1] * A[1] + A[2] * A[2]), per = 0;
            for (ump_idx i = pm->face_off[f]; i < pm->face_off[f + 1]; i++) {
                ump_idx j = i + 1 < pm->face_off[f + 1] ? i + 1 : pm->face_off[f];
                const double *p0 = pm->points + 3 * (size_t)pm->face_pts[i];
                const double *p1 = pm->points + 3 * (size_t)pm->face_pts[j];
                per += sqrt((p1[0] - p0[0]) * (p1[0] - p0[0]) + (p1[1] - p0[1]) * (p1[1] - p0[1]) +
                            (p1[2] - p0[2]) * (p1[2] - p0[2]));
            }
            if (!(a > 1e-12 * per * per))
                return UMP_FAIL(err, UMP_ERR_INPUT,
                                "%s/points: cell %ld has zero area: its face %ld on empty patch '%s' has "
                                "area %g (collapsed or collinear points; checkMesh: Zero or negative cell "
                                "volume)", dir, (long)pm->owner[f], (long)f, pp->name, a);
            if (!(fabs(A[k]) > (1 - 1e-6) * a))
                return UMP_FAIL(err, UMP_ERR_UNSUPPORTED,
                                "%s/faces: face %ld of empty patch '%s' is not normal to %c: %s "
                                "needs the empty sides to be planes normal to x, y or z",
                                dir, (long)f, pp->name, "xyz"[k], ump_solver);
            for (ump_idx i = pm->face_off[f]; i < pm->face_off[f + 1]; i++) {
                double z = pm->points[3 * (size_t)pm->face_pts[i] + k];
                if (fabs(z - zmin) > tol && fabs(z - zmax) > tol)
                    return UMP_FAIL(err, UMP_ERR_UNSUPPORTED,
                                    "%s/points: point %ld of empty patch '%s' lies at %c = %g, between the "
                                    "front (%g) and back (%g) planes: not a one-cell-thick 2-D mesh",
                                    dir, (long)pm->face_pts[i], pp->name, "xyz"[k], z, zmax, zmin);
            }
        }
    }
    return UMP_OK;
}

static int on_back(const pmesh *pm, const mesh2d *m, ump_idx pt)
{
    double z = pm->points[3 * (size_t)pt + m->normal];
    return fabs(z - m->zmin) <= 1e-8 * (m->zmax - m->zmin);
}

/* Step 2: the back face of every cell gives its polygon. */
static ump_status build_cells(const pmesh *pm, mesh2d *m, const char *dir,
                              ump_idx *pm2vert, ump_err *err)
{
    ump_idx nc = pm->ncells;
    ump_idx *backface = NULL, *nempty = NULL;
    ump_status rc = UMP_OK;
    ALLOC(backface, nc);
    ALLOC(nempty, nc);
    ALLOC(m->cell_off, nc + 1);
    if (!backface || !nempty || !m->cell_off) {
        rc = UMP_FAIL(err, UMP_ERR_NOMEM, "%s: out of memory building the 2-D mesh", dir);
        goto done;
    }
    for (ump_idx c = 0; c < nc; c++)
        backface[c] = -1;
    for (int p = 0; p < pm->npatches; p++) {
        const pmesh_patch *pp = &pm->patch[p];
        if (pp->kind != PMESH_EMPTY)
            continue;
        for (ump_idx f = pp->start; f < pp->start + pp->n; f++) {
            ump_idx c = pm->owner[f];
            nempty[c]++;
            if (on_back(pm, m, pm->face_pts[pm->face_off[f]])) {
                if (backface[c] >= 0) {
                    rc = UMP_FAIL(err, UMP_ERR_INPUT,
                                  "%s/owner: cell %ld has two faces on the back empty plane: not a "
                                  "one-cell-thick 2-D mesh", dir, (long)c);
                    goto done;
                }
                backface[c] = f;
            }
        }
    }
    size_t nv = 0;
    for (ump_idx c = 0; c < nc; c++) {
        if (nempty[c] != 2 || backface[c] < 0) {
            rc = UMP_FAIL(err, UMP_ERR_INPUT,
                          "%s/owner: cell %ld has %ld faces on empty patches (%s back face); a 2-D "
                          "mesh needs exactly one front and one back face per cell",
                          dir, (long)c, (long)nempty[c], backface[c] < 0 ? "no" : "a");
            goto done;
        }
        ump_idx f = backface[c];
        ump_idx n = pm->face_off[f + 1] - pm->face_off[f];
        if (n < 3) {
            rc = UMP_FAIL(err, UMP_ERR_INPUT, "%s/faces: face %ld has %ld points", dir, (long)f, (long)n);
            goto done;
        }
        m->cell_off[c + 1] = m->cell_off[c] + n;
        nv += (size_t)n;
    }
    ALLOC(m->cell_verts, nv);
    ALLOC(m->cx, nc);
    ALLOC(m->cy, nc);
    ALLOC(m->area, nc);
    ALLOC(m->dx, nc);
    ALLOC(m->dy, nc);
    ALLOC(m->dc, nc);
    if (!m->cell_verts || !m->cx || !m->cy || !m->area || !m->dx || !m->dy || !m->dc) {
        rc = UMP_FAIL(err, UMP_ERR_NOMEM, "%s: out of memory building the 2-D mesh", dir);
        goto done;
    }
    /* number the back-side points used by cells as 2-D vertices */
    ump_idx nvert = 0;
    for (ump_idx c = 0; c < nc; c++) {
        ump_idx f = backface[c];
        for (ump_idx i = pm->face_off[f]; i < pm->face_off[f + 1]; i++) {
            ump_idx pt = pm->face_pts[i];
            if (pm2vert[pt] < 0)
                pm2vert[pt] = nvert++;
        }
    }
    m->nverts = nvert;
    ALLOC(m->vx, nvert);
    ALLOC(m->vy, nvert);
    ALLOC(m->vert_pm, nvert);
    ALLOC(m->vert_id, nvert);
    if (!m->vx || !m->vy || !m->vert_pm || !m->vert_id) {
        rc = UMP_FAIL(err, UMP_ERR_NOMEM, "%s: out of memory building the 2-D mesh", dir);
        goto done;
    }
    for (ump_idx pt = 0; pt < pm->npoints; pt++) {
        ump_idx v = pm2vert[pt];
        if (v < 0)
            continue;
        m->vx[v] = pm->points[3 * (size_t)pt + m->ax[0]];
        m->vy[v] = pm->points[3 * (size_t)pt + m->ax[1]];
        m->vert_pm[v] = pt;
        m->vert_id[v] = v;
    }
    for (ump_idx c = 0; c < nc; c++) {
        ump_idx f = backface[c], b = pm->face_off[f], n = pm->face_off[f + 1] - b;
        ump_idx *cv = m->cell_verts + m->cell_off[c];
        for (ump_idx i = 0; i < n; i++)
            cv[i] = pm2vert[pm->face_pts[b + i]];
        /* polygon area and centroid relative to the first vertex (round-off) */
        double x0 = m->vx[cv[0]], y0 = m->vy[cv[0]];
        double a2 = 0, sx = 0, sy = 0;
        double xmin = x0, xmax = x0, ymin = y0, ymax = y0;
        for (ump_idx i = 0; i < n; i++) {
            double xi = m->vx[cv[i]] - x0, yi = m->vy[cv[i]] - y0;
            double xj = m->vx[cv[(i + 1) % n]] - x0, yj = m->vy[cv[(i + 1) % n]] - y0;
            double cr = xi * yj - xj * yi;
            a2 += cr;
            sx += (xi + xj) * cr;
            sy += (yi + yj) * cr;
            xmin = fmin(xmin, m->vx[cv[i]]);
            xmax = fmax(xmax, m->vx[cv[i]]);
            ymin = fmin(ymin, m->vy[cv[i]]);
            ymax = fmax(ymax, m->vy[cv[i]]);
        }
        if (!(fabs(a2) > 0) || !isfinite(a2)) {
            rc = UMP_FAIL(err, UMP_ERR_INPUT, "%s/faces: cell %ld has zero or undefined area",
                          dir, (long)c);
            goto done;
        }
        if (a2 < 0) { /* make the polygon counter-clockwise */
            for (ump_idx i = 0, j = n - 1; i < j; i++, j--) {
                ump_idx t = cv[i];
                cv[i] = cv[j];
                cv[j] = t;
            }
        }
        m->area[c] = 0.5 * fabs(a2);
        m->cx[c] = x0 + sx / (3.0 * a2);
        m->cy[c] = y0 + sy / (3.0 * a2);
        m->dx[c] = xmax - xmin;
        m->dy[c] = ymax - ymin;
        m->dc[c] = sqrt(m->dx[c] * m->dx[c] + m->dy[c] * m->dy[c]);
    }
done:
    free(backface);
    free(nempty);
    return rc;
}

/* Edge of polyMesh face f: its two back-side vertices, ordered so that the
 * in-plane normal (dy, -dx)/len agrees with the face's area vector. */
static ump_status face_edge(const pmesh *pm, const mesh2d *m, const ump_idx *pm2vert,
                            ump_idx f, const char *dir, ump_idx *v0, ump_idx *v1,
                            double n[2], double *len, ump_err *err)
{
    ump_idx a = -1, b = -1;
    for (ump_idx i = pm->face_off[f]; i < pm->face_off[f + 1]; i++) {
        ump_idx pt = pm->face_pts[i];
        if (!on_back(pm, m, pt))
            continue;
        ump_idx v = pm2vert[pt];
        if (v < 0)
            return UMP_FAIL(err, UMP_ERR_INPUT,
                            "%s/faces: face %ld uses back-plane point %ld that belongs to no cell's back face",
                            dir, (long)f, (long)pt);
        if (a < 0 || a == v)
            a = v;
        else if (b < 0 || b == v)
            b = v;
        else
            return UMP_FAIL(err, UMP_ERR_INPUT,
                            "%s/faces: face %ld has more than two points on the back plane: not a 2-D mesh face",
                            dir, (long)f);
    }
    if (a < 0 || b < 0)
        return UMP_FAIL(err, UMP_ERR_INPUT,
                        "%s/faces: face %ld does not span the mesh thickness (needs two back-plane points)",
                        dir, (long)f);
    double A[3];
    face_area_vector(pm, f, A);
    double ex = m->vx[b] - m->vx[a], ey = m->vy[b] - m->vy[a];
    double l = sqrt(ex * ex + ey * ey);
    if (!(l > 0))
        return UMP_FAIL(err, UMP_ERR_INPUT, "%s/faces: face %ld has zero length", dir, (long)f);
    double nxx = ey / l, nyy = -ex / l;
    if (nxx * A[m->ax[0]] + nyy * A[m->ax[1]] < 0) {
        ump_idx t = a;
        a = b;
        b = t;
        nxx = -nxx;
        nyy = -nyy;
    }
    *v0 = a;
    *v1 = b;
    n[0] = nxx;
    n[1] = nyy;
    *len = l;
    return UMP_OK;
}

static void set_face(mesh2d *m, ump_idx i, ump_idx v0, ump_idx v1, const double n[2], double len)
{
    m->fv0[i] = v0;
    m->fv1[i] = v1;
    m->fx[i] = 0.5 * (m->vx[v0] + m->vx[v1]);
    m->fy[i] = 0.5 * (m->vy[v0] + m->vy[v1]);
    m->nx[i] = n[0];
    m->ny[i] = n[1];
    m->len[i] = len;
}

/* Step 3: 2-D faces (internal, cyclic pairs, boundary by patch). */
static ump_status build_faces(const pmesh *pm, mesh2d *m, const char *dir,
                              const ump_idx *pm2vert, ump_err *err)
{
    ump_idx ncyc = 0, nbnd = 0;
    for (int p = 0; p < pm->npatches; p++) {
        const pmesh_patch *pp = &pm->patch[p];
        if (pp->kind == PMESH_CYCLIC) {
            if (pp->nbr < 0)
                return UMP_FAIL(err, UMP_ERR_INPUT,
                                "%s/boundary: cyclic patch '%s' has no valid neighbourPatch", dir, pp->name);
            const pmesh_patch *q = &pm->patch[pp->nbr];
            if (q->kind != PMESH_CYCLIC || q->nbr != p || q->n != pp->n)
                return UMP_FAIL(err, UMP_ERR_INPUT,
                                "%s/boundary: cyclic patches '%s' and '%s' do not pair up (neighbourPatch or "
                                "nFaces disagree)", dir, pp->name, q->name);
            if (pp->transform && strcmp(pp->transform, "rotational") == 0)
                return UMP_FAIL(err, UMP_ERR_UNSUPPORTED,
                                "%s/boundary: cyclic patch '%s' has a rotational transform; only "
                                "translational cyclics are supported", dir, pp->name);
            if (p < pp->nbr)
                ncyc += pp->n;
        } else if (pp->kind != PMESH_EMPTY) {
            nbnd += pp->n;
        }
    }
    m->has_cyclic = ncyc > 0;
    m->ninternal = pm->ninternal + ncyc;
    m->nfaces = m->ninternal + nbnd;
    ump_idx nf = m->nfaces, ni = m->ninternal;
    ALLOC(m->owner, nf);
    ALLOC(m->neigh, ni);
    ALLOC(m->fv0, nf);
    ALLOC(m->fv1, nf);
    ALLOC(m->fx, nf);
    ALLOC(m->fy, nf);
    ALLOC(m->nx, nf);
    ALLOC(m->ny, nf);
    ALLOC(m->len, nf);
    ALLOC(m->face_pm, nf);
    ALLOC(m->face_pm2, ni);
    ALLOC(m->face_patch, nf);
    ALLOC(m->pmface_to_face, pm->nfaces);
    ALLOC(m->patch, pm->npatches);
    if (!m->owner || !m->neigh || !m->fv0 || !m->fv1 || !m->fx || !m->fy || !m->nx ||
        !m->ny || !m->len || !m->face_pm || !m->face_pm2 || !m->face_patch ||
        !m->pmface_to_face || !m->patch)
        return UMP_FAIL(err, UMP_ERR_NOMEM, "%s: out of memory building the 2-D mesh", dir);
    if (m->has_cyclic) {
        ALLOC(m->sepx, ni);
        ALLOC(m->sepy, ni);
        if (!m->sepx || !m->sepy)
            return UMP_FAIL(err, UMP_ERR_NOMEM, "%s: out of memory building the 2-D mesh", dir);
    }
    m->npatches = pm->npatches;
    for (ump_idx f = 0; f < pm->nfaces; f++)
        m->pmface_to_face[f] = -1;

    ump_idx i = 0;
    double n[2], len;
    ump_idx v0, v1;
    for (ump_idx f = 0; f < pm->ninternal; f++, i++) {
        UMP_CALL(face_edge(pm, m, pm2vert, f, dir, &v0, &v1, n, &len, err));
        set_face(m, i, v0, v1, n, len);
        m->owner[i] = pm->owner[f];
        m->neigh[i] = pm->neighbour[f];
        m->face_pm[i] = f;
        m->face_pm2[i] = -1;
        m->face_patch[i] = -1;
        m->pmface_to_face[f] = i;
    }
    /* cyclic pairs: face k of patch A pairs with face k of its neighbour B */
    for (int p = 0; p < pm->npatches; p++) {
        const pmesh_patch *pa = &pm->patch[p];
        m->patch[p].pm_patch = p;
        if (pa->kind != PMESH_CYCLIC || p > pa->nbr)
            continue;
        const pmesh_patch *pb = &pm->patch[pa->nbr];
        double sep[2] = {0, 0};
        int given = pa->has_separation;
        if (given) {
            sep[0] = pa->separation[m->ax[0]];
            sep[1] = pa->separation[m->ax[1]];
        }
        m->patch[p].start = i;
        m->patch[p].n = 0;
        for (ump_idx k = 0; k < pa->n; k++, i++) {
            ump_idx fa = pa->start + k, fb = pb->start + k;
            double nb[2], lb;
            ump_idx w0, w1;
            UMP_CALL(face_edge(pm, m, pm2vert, fa, dir, &v0, &v1, n, &len, err));
            UMP_CALL(face_edge(pm, m, pm2vert, fb, dir, &w0, &w1, nb, &lb, err));
            double cax = 0.5 * (m->vx[v0] + m->vx[v1]), cay = 0.5 * (m->vy[v0] + m->vy[v1]);
            double cbx = 0.5 * (m->vx[w0] + m->vx[w1]), cby = 0.5 * (m->vy[w0] + m->vy[w1]);
            if (!given && k == 0) {
                sep[0] = cbx - cax;
                sep[1] = cby - cay;
            }
            /* the pair must match: same length, opposite normals, translated by sep */
            double mis = hypot(cbx - cax - sep[0], cby - cay - sep[1]);
            if (mis > 1e-4 * len || fabs(lb - len) > 1e-4 * len || n[0] * nb[0] + n[1] * nb[1] > -0.9999)
                return UMP_FAIL(err, UMP_ERR_INPUT,
                                "%s/boundary: face %ld of cyclic patch '%s' does not match face %ld of '%s' "
                                "under the translation (%g %g) (mismatch %g m)",
                                dir, (long)k, pa->name, (long)k, pb->name, sep[0], sep[1], mis);
            if (pm->owner[fa] == pm->owner[fb])
                return UMP_FAIL(err, UMP_ERR_INPUT,
                                "%s/boundary: cell %ld owns face %ld of cyclic patch '%s' and its partner "
                                "face %ld of '%s': the mesh is one cell wide between the pair, so the cell "
                                "is its own periodic neighbour and its stencil (least-squares gradient, "
                                "Eq. 26) is degenerate; %s needs at least 2 cells between cyclic "
                                "patches (3 or more for a centred stencil)",
                                dir, (long)pm->owner[fa], (long)fa, pa->name, (long)fb, pb->name, ump_solver);
            set_face(m, i, v0, v1, n, len);
            m->owner[i] = pm->owner[fa];
            m->neigh[i] = pm->owner[fb];
            m->sepx[i] = sep[0];
            m->sepy[i] = sep[1];
            m->face_pm[i] = fa;
            m->face_pm2[i] = fb;
            m->face_patch[i] = -1;
            m->pmface_to_face[fa] = i;
            m->pmface_to_face[fb] = i;
            /* identify the vertices across the pair: w0 pairs with v1 */
            ump_idx ma = v0, mb = (hypot(m->vx[w0] - m->vx[v0] - sep[0], m->vy[w0] - m->vy[v0] - sep[1]) <
                                   hypot(m->vx[w1] - m->vx[v0] - sep[0], m->vy[w1] - m->vy[v0] - sep[1]))
                                      ? w0 : w1;
            uf_union(m->vert_id, ma, mb);
            uf_union(m->vert_id, v1, mb == w0 ? w1 : w0);
        }
    }
    for (int p = 0; p < pm->npatches; p++) {
        const pmesh_patch *pp = &pm->patch[p];
        m->patch[p].pm_patch = p;
        if (pp->kind == PMESH_CYCLIC) {
            /* both sides of a pair point at the pair's internal-face range */
            if (p > pp->nbr)
                m->patch[p].start = m->patch[pp->nbr].start;
            m->patch[p].n = 0;
            continue;
        }
        m->patch[p].start = i;
        m->patch[p].n = 0;
        if (pp->kind == PMESH_EMPTY)
            continue;
        m->patch[p].n = pp->n;
        for (ump_idx f = pp->start; f < pp->start + pp->n; f++, i++) {
            UMP_CALL(face_edge(pm, m, pm2vert, f, dir, &v0, &v1, n, &len, err));
            set_face(m, i, v0, v1, n, len);
            m->owner[i] = pm->owner[f];
            m->face_pm[i] = f;
            m->face_patch[i] = p;
            m->pmface_to_face[f] = i;
        }
    }
    for (ump_idx v = 0; v < m->nverts; v++)
        m->vert_id[v] = uf_find(m->vert_id, v);
    return UMP_OK;
}

/* Faces of each cell (CSR) and the closedness check. */
static ump_status build_cell_faces(mesh2d *m, const char *dir, ump_err *err)
{
    ump_idx nc = m->ncells;
    ALLOC(m->cell_face_off, nc + 1);
    ALLOC(m->cell_faces, (size_t)m->ninternal * 2 + (size_t)(m->nfaces - m->ninternal));
    double *sx = NULL, *sy = NULL, *dv = NULL, *per = NULL;
    ALLOC(sx, nc);
    ALLOC(sy, nc);
    ALLOC(dv, nc);
    ALLOC(per, nc);
    ump_status rc = UMP_OK;
    if (!m->cell_face_off || !m->cell_faces || !sx || !sy || !dv || !per) {
        rc = UMP_FAIL(err, UMP_ERR_NOMEM, "%s: out of memory building the 2-D mesh", dir);
        goto done;
    }
    for (ump_idx f = 0; f < m->nfaces; f++) {
        m->cell_face_off[m->owner[f] + 1]++;
        if (f < m->ninternal)
            m->cell_face_off[m->neigh[f] + 1]++;
    }
    for (ump_idx c = 0; c < nc; c++)
        m->cell_face_off[c + 1] += m->cell_face_off[c];
    ump_idx *fill = NULL;
    ALLOC(fill, nc);
    if (!fill) {
        rc = UMP_FAIL(err, UMP_ERR_NOMEM, "%s: out of memory building the 2-D mesh", dir);
        goto done;
    }
    for (ump_idx f = 0; f < m->nfaces; f++) {
        /* divergence theorem per cell: sum n len = 0, sum (x_f - x_c).n len = 2 A */
        ump_idx o = m->owner[f];
        m->cell_faces[m->cell_face_off[o] + fill[o]++] = f;
        double w = m->len[f];
        sx[o] += m->nx[f] * w;
        sy[o] += m->ny[f] * w;
        dv[o] += ((m->fx[f] - m->cx[o]) * m->nx[f] + (m->fy[f] - m->cy[o]) * m->ny[f]) * w;
        per[o] += w;
        if (f < m->ninternal) {
            ump_idx nb = m->neigh[f];
            double fxn = m->fx[f], fyn = m->fy[f];
            if (m->sepx) {
                fxn += m->sepx[f];
                fyn += m->sepy[f];
            }
            m->cell_faces[m->cell_face_off[nb] + fill[nb]++] = f;
            sx[nb] -= m->nx[f] * w;
            sy[nb] -= m->ny[f] * w;
            dv[nb] -= ((fxn - m->cx[nb]) * m->nx[f] + (fyn - m->cy[nb]) * m->ny[f]) * w;
            per[nb] += w;
        }
    }
    free(fill);
    for (ump_idx c = 0; c < nc; c++) {
        double open = hypot(sx[c], sy[c]);
        if (open > 1e-8 * per[c] || fabs(0.5 * dv[c] - m->area[c]) > 1e-8 * m->area[c]) {
            rc = UMP_FAIL(err, UMP_ERR_INPUT,
                          "%s/faces: cell %ld is not closed in 2-D (open by %g m, face-based area %g vs "
                          "polygon area %g): inconsistent faces/owner/neighbour",
                          dir, (long)c, open, 0.5 * dv[c], m->area[c]);
            goto done;
        }
    }
done:
    free(sx);
    free(sy);
    free(dv);
    free(per);
    return rc;
}

/* Lattice of periodic translations (one vector per cyclic pair), with its
 * shifts s = sum_i k_i v_i, k_i in {-1, 0, 1}, tabulated by lattice_shifts. */
typedef struct lattice {
    int n;
    double v[3][2];
    int ns;            /* 3^n shifts; shift 0 is k = (-1, -1, ...) */
    double s[27][2];
    double rmin2;      /* (half the shortest non-zero shift)^2 */
} lattice;

static void lattice_shifts(lattice *L)
{
    L->ns = 1;
    for (int i = 0; i < L->n; i++)
        L->ns *= 3;
    double smin2 = INFINITY;
    for (int c = 0; c < L->ns; c++) {
        double tx = 0, ty = 0;
        for (int i = 0, r = c; i < L->n; i++, r /= 3) {
            int k = r % 3 - 1;
            tx += k * L->v[i][0];
            ty += k * L->v[i][1];
        }
        L->s[c][0] = tx;
        L->s[c][1] = ty;
        double s2 = tx * tx + ty * ty;
        if (s2 > 0 && s2 < smin2)
            smin2 = s2;
    }
    L->rmin2 = 0.25 * smin2 * (1 - 1e-9);
}

static void closest_image(const lattice *L, double dx, double dy, double *sx, double *sy)
{
    /* shift s minimising |d + s|; with |d| below half the shortest shift
     * s != 0, |d + s| >= |s| - |d| > |d|: no shift (most pairs) */
    double best = dx * dx + dy * dy;
    *sx = *sy = 0;
    if (best < L->rmin2)
        return;
    /* c = 0 is k = (-1, -1, ...), not the zero shift (which cannot pass the
     * strict test below): start there */
    for (int c = 0; c < L->ns; c++) {
        double tx = L->s[c][0], ty = L->s[c][1];
        double d2 = (dx + tx) * (dx + tx) + (dy + ty) * (dy + ty);
        if (d2 < best - 1e-12 * best) {
            best = d2;
            *sx = tx;
            *sy = ty;
        }
    }
}

/* Step 4: vertex-neighbour stencils N1, N2 (Figs. 1, 4, 5). */
/* Sorted CSR stencils by union: list(c) = (outer(c) if with_outer) united
 * with inner(o) for o in outer(c), without c itself; outer(c) =
 * oidx[ooff[c] .. ooff[c+1]-1], mapped through omap when given; inner(o) =
 * iidx[ioff[o] .. ioff[o+1]-1]. Two passes (count, then fill) with a stamp
 * per cell in mark [nc] (any contents on entry). off [nc+1] is filled, *out
 * allocated. */
/* Ascending sort of a stencil: insertion sort up to 32 entries (a cell's
 * N1/N2 has ~9-60; qsort's comparator calls were a third of the mesh
 * set-up), qsort beyond, so a vertex shared by many cells stays
 * O(k log k). */
static void sort_idx(ump_idx *a, ump_idx k)
{
    if (k > 32) {
        qsort(a, (size_t)k, sizeof *a, cmp_idx);
        return;
    }
    for (ump_idx i = 1; i < k; i++) {
        ump_idx v = a[i], j = i;
        for (; j > 0 && a[j - 1] > v; j--)
            a[j] = a[j - 1];
        a[j] = v;
    }
}

/* The union stencil of every cell: for each "outer" entry o of c (a vertex,
 * through omap, or a cell of N1(c)), the inner list of o; with_outer adds
 * o itself. Two passes (count, then fill and sort), each over the cells in
 * parallel with a private mark array per thread: mark[q] == c means q is in
 * c's list already, so no clearing between cells. The lists do not depend
 * on the thread count. */
static ump_status stencil_union(ump_idx nc, const ump_idx *ooff, const ump_idx *oidx, const ump_idx *omap,
                                const ump_idx *ioff, const ump_idx *iidx, int with_outer, ump_idx *mark,
                                ump_idx *off, ump_idx **out)
{
    ump_idx *list = NULL;
    off[0] = 0;
    for (int pass = 0; pass < 2; pass++) {
        int nomem = 0;
#pragma omp parallel
        {
            ump_idx *mk = mark;
#ifdef _OPENMP
            if (omp_get_thread_num() > 0)
                mk = ump_alloc_array((size_t)nc, sizeof *mk);
#endif
            if (!mk) {
#pragma omp atomic write
                nomem = 1;
            } else {
                for (ump_idx c = 0; c < nc; c++)
                    mk[c] = -1;
            }
#pragma omp for schedule(static)
            for (ump_idx c = 0; c < nc; c++) {
                if (!mk)
                    continue;
                ump_idx cnt = 0, base = pass ? off[c] : 0;
                mk[c] = c;
                for (ump_idx a = ooff[c]; a < ooff[c + 1]; a++) {
                    ump_idx o = omap ? omap[oidx[a]] : oidx[a];
                    if (with_outer && mk[o] != c) {
                        mk[o] = c;
                        if (pass)
                            list[base + cnt] = o;
                        cnt++;
                    }
                    for (ump_idx b = ioff[o]; b < ioff[o + 1]; b++) {
                        ump_idx q = iidx[b];
                        if (mk[q] == c)
                            continue;
                        mk[q] = c;
                        if (pass)
                            list[base + cnt] = q;
                        cnt++;
                    }
                }
                if (!pass)
                    off[c + 1] = cnt; /* counts; prefix sum below */
                else
                    sort_idx(list + base, cnt);
            }
            if (mk != mark)
                free(mk);
        }
        if (nomem) {
            free(list);
            return UMP_ERR_NOMEM;
        }
        if (!pass) {
            int64_t sum = 0;
            for (ump_idx c = 0; c < nc; c++) {
                sum += off[c + 1];
                if (sum > UMP_IDX_MAX)
                    return UMP_ERR_INPUT;
                off[c + 1] = (ump_idx)sum;
            }
            if (!(list = ump_alloc_array((size_t)off[nc], sizeof *list)))
                return UMP_ERR_NOMEM;
        }
    }
    *out = list;
    return UMP_OK;
}

static ump_status build_stencils(mesh2d *m, const char *dir, ump_err *err)
{
    ump_idx nc = m->ncells, nv = m->nverts;
    ump_idx *voff = NULL, *vcell = NULL, *mark = NULL, *fill = NULL;
    ump_status rc = UMP_OK;
    size_t nbuf = 0;
    ALLOC(voff, nv + 1);
    ALLOC(vcell, m->cell_off[nc]);
    ALLOC(mark, nc);
    ALLOC(fill, nv);
    ALLOC(m->n1_off, nc + 1);
    ALLOC(m->n2_off, nc + 1);
    if (!voff || !vcell || !mark || !fill || !m->n1_off || !m->n2_off)
        goto nomem;
    /* vertex -> cells, through the cyclic representative */
    for (ump_idx k = 0; k < m->cell_off[nc]; k++)
        voff[m->vert_id[m->cell_verts[k]] + 1]++;
    for (ump_idx v = 0; v < nv; v++)
        voff[v + 1] += voff[v];
    for (ump_idx c = 0; c < nc; c++)
        for (ump_idx k = m->cell_off[c]; k < m->cell_off[c + 1]; k++) {
            ump_idx v = m->vert_id[m->cell_verts[k]];
            vcell[voff[v] + fill[v]++] = c;
        }
    /* N1(c): the cells of c's vertices; N2(c): N1(c) and the N1 of each */
    ump_status su = stencil_union(nc, m->cell_off, m->cell_verts, m->vert_id, voff, vcell, 0, mark,
                                  m->n1_off, &m->n1);
    if (su == UMP_OK)
        su = stencil_union(nc, m->n1_off, m->n1, NULL, m->n1_off, m->n1, 1, mark, m->n2_off, &m->n2);
    if (su == UMP_ERR_INPUT) {
        rc = UMP_FAIL(err, UMP_ERR_INPUT, "%s: the vertex-neighbour stencils hold more than %d entries "
                      "(points shared by very many cells?)", dir, UMP_IDX_MAX);
        goto done;
    }
    if (su != UMP_OK)
        goto nomem;
    nbuf = (size_t)m->n2_off[nc];
    if (m->has_cyclic) {
        lattice L = {.n = 0};
        for (ump_idx f = m->ninternal - 1; f >= 0 && m->face_pm2[f] >= 0; f--) {
            int dup = 0;
            for (int i = 0; i < L.n; i++)
                if (hypot(L.v[i][0] - m->sepx[f], L.v[i][1] - m->sepy[f]) <
                    1e-6 * hypot(m->sepx[f], m->sepy[f]))
                    dup = 1;
            if (!dup && L.n < 3) {
                L.v[L.n][0] = m->sepx[f];
                L.v[L.n][1] = m->sepy[f];
                L.n++;
            }
        }
        lattice_shifts(&L);
        ALLOC(m->n1_sx, m->n1_off[nc]);
        ALLOC(m->n1_sy, m->n1_off[nc]);
        ALLOC(m->n2_sx, nbuf);
        ALLOC(m->n2_sy, nbuf);
        if (!m->n1_sx || !m->n1_sy || !m->n2_sx || !m->n2_sy)
            goto nomem;
        for (ump_idx c = 0; c < nc; c++) {
            for (ump_idx a = m->n1_off[c]; a < m->n1_off[c + 1]; a++)
                closest_image(&L, m->cx[m->n1[a]] - m->cx[c], m->cy[m->n1[a]] - m->cy[c],
                              &m->n1_sx[a], &m->n1_sy[a]);
            for (ump_idx a = m->n2_off[c]; a < m->n2_off[c + 1]; a++)
                closest_image(&L, m->cx[m->n2[a]] - m->cx[c], m->cy[m->n2[a]] - m->cy[c],
                              &m->n2_sx[a], &m->n2_sy[a]);
        }
    }
    goto done;
nomem:
    rc = UMP_FAIL(err, UMP_ERR_NOMEM, "%s: out of memory building the stencils", dir);
done:
    free(voff);
    free(vcell);
    free(mark);
    free(fill);
    return rc;
}

ump_status mesh_build(const pmesh *pm, mesh2d **out, ump_err *err)
{
    const char *dir = pm->dir ? pm->dir : "constant/polyMesh";
    *out = NULL;
    mesh2d *m = ump_alloc_array(1, sizeof *m);
    ump_idx *pm2vert = ump_alloc_array((size_t)pm->npoints, sizeof *pm2vert);
    ump_status rc;
    if (!m || !pm2vert) {
        rc = UMP_FAIL(err, UMP_ERR_NOMEM, "%s: out of memory building the 2-D mesh", dir);
        goto fail;
    }
    for (ump_idx i = 0; i < pm->npoints; i++)
        pm2vert[i] = -1;
    m->pm = pm;
    m->ncells = pm->ncells;
    if ((rc = find_plane(pm, m, dir, err)) != UMP_OK ||
        (rc = build_cells(pm, m, dir, pm2vert, err)) != UMP_OK ||
        (rc = build_faces(pm, m, dir, pm2vert, err)) != UMP_OK ||
        (rc = build_cell_faces(m, dir, err)) != UMP_OK ||
        (rc = build_stencils(m, dir, err)) != UMP_OK)
        goto fail;
    free(pm2vert);
    *out = m;
    return UMP_OK;
fail:
    free(pm2vert);
    mesh_free(&m);
    return rc;
}

/* OpenFOAM-style face skewness (primitiveMeshTools::faceSkewness) in 2-D. */
static double face_skewness(const mesh2d *m, ump_idx f)
{
    ump_idx o = m->owner[f];
    double cpfx = m->fx[f] - m->cx[o], cpfy = m->fy[f] - m->cy[o];
    double dx, dy;
    if (f < m->ninternal) {
        ump_idx nb = m->neigh[f];
        dx = m->cx[nb] - (m->sepx ? m->sepx[f] : 0) - m->cx[o];
        dy = m->cy[nb] - (m->sepy ? m->sepy[f] : 0) - m->cy[o];
    } else {
        double dn = cpfx * m->nx[f] + cpfy * m->ny[f];
        dx = m->nx[f] * dn;
        dy = m->ny[f] * dn;
    }
    double sd = m->nx[f] * dx + m->ny[f] * dy;
    double t = (m->nx[f] * cpfx + m->ny[f] * cpfy) / (sd + 1e-150);
    double svx = cpfx - t * dx, svy = cpfy - t * dy;
    double sv = hypot(svx, svy);
    double hx = svx / (sv + 1e-150), hy = svy / (sv + 1e-150);
    /* faceSkewness: 0.2 |d|; boundaryFaceSkewness: 0.4 |d|, d reaching the
     * face only */
    double fd = (f < m->ninternal ? 0.2 : 0.4) * hypot(dx, dy) + 1e-150;
    ump_idx vv[2] = {m->fv0[f], m->fv1[f]};
    for (int k = 0; k < 2; k++)
        fd = fmax(fd, fabs(hx * (m->vx[vv[k]] - m->fx[f]) + hy * (m->vy[vv[k]] - m->fy[f])));
    return sv / fd;
}

void mesh_compute_stats(const mesh2d *m, mesh_stats *s)
{
    memset(s, 0, sizeof *s);
    s->area_min = INFINITY;
    s->area_max = 0;
    s->len_min = INFINITY;
    s->n1_min = s->n2_min = UMP_IDX_MAX;
    for (ump_idx c = 0; c < m->ncells; c++) {
        ump_idx n = m->cell_off[c + 1] - m->cell_off[c];
        if (n == 3)
            s->ntri++;
        else if (n == 4)
            s->nquad++;
        else
            s->npoly++;
        s->nsides_max = UMP_MAX(s->nsides_max, n);
        s->area_min = fmin(s->area_min, m->area[c]);
        s->area_max = fmax(s->area_max, m->area[c]);
        s->area_total += m->area[c];
        ump_idx k1 = m->n1_off[c + 1] - m->n1_off[c], k2 = m->n2_off[c + 1] - m->n2_off[c];
        s->n1_min = UMP_MIN(s->n1_min, k1);
        s->n1_max = UMP_MAX(s->n1_max, k1);
        s->n2_min = UMP_MIN(s->n2_min, k2);
        s->n2_max = UMP_MAX(s->n2_max, k2);
        s->n1_mean += k1;
        s->n2_mean += k2;
    }
    if (m->ncells > 0) {
        s->area_mean = s->area_total / m->ncells;
        s->n1_mean /= m->ncells;
        s->n2_mean /= m->ncells;
    }
    double sum = 0;
    for (ump_idx f = 0; f < m->nfaces; f++) {
        s->len_min = fmin(s->len_min, m->len[f]);
        s->len_max = fmax(s->len_max, m->len[f]);
        s->skew_max = fmax(s->skew_max, face_skewness(m, f));
        if (f >= m->ninternal)
            continue;
        ump_idx o = m->owner[f], nb = m->neigh[f];
        double dx = m->cx[nb] - (m->sepx ? m->sepx[f] : 0) - m->cx[o];
        double dy = m->cy[nb] - (m->sepy ? m->sepy[f] : 0) - m->cy[o];
        double c = (dx * m->nx[f] + dy * m->ny[f]) / (hypot(dx, dy) + 1e-300);
        double ang = acos(fmax(-1.0, fmin(1.0, c))) * 180.0 / UMP_PI;
        s->nonorth_max = fmax(s->nonorth_max, ang);
        sum += c;
    }
    /* checkMesh's "average" (primitiveMeshCheck.C): the angle of the mean
     * cosine, not the mean angle */
    if (m->ninternal > 0)
        s->nonorth_mean = acos(fmax(-1.0, fmin(1.0, sum / m->ninternal))) * 180.0 / UMP_PI;
}
