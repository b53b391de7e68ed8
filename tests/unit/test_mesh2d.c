/* SPDX-License-Identifier: GPL-3.0-or-later
 * test_mesh2d.c -- geometry and stencils of the 2-D pressure mesh on
 * hand-checkable meshes (built in memory with pmesh_extrude).
 */
#include "testmesh.h"
#include "testutil.h"
#include "umppm/mesh2d.h"
#include "umppm/polymesh.h"

/* patches of the unit square: 0 bottom, 1 right, 2 top, 3 left */
static int square_patch(double x, double y, void *ctx)
{
    (void)ctx;
    if (y < 1e-12) return 0;
    if (x > 1 - 1e-12) return 1;
    if (y > 1 - 1e-12) return 2;
    return 3;
}
static const char *const SQ_NAMES[] = {"bottom", "right", "top", "left"};
static const char *const SQ_TYPES[] = {"wall", "patch", "wall", "patch"};

/* n x n quads on the unit square */
static pmesh *quad_square(int n)
{
    int nv = (n + 1) * (n + 1);
    double *xy = malloc(2 * sizeof(double) * (size_t)nv);
    ump_idx *off = malloc(sizeof(ump_idx) * (size_t)(n * n + 1));
    ump_idx *pv = malloc(sizeof(ump_idx) * 4 * (size_t)(n * n));
    for (int j = 0; j <= n; j++)
        for (int i = 0; i <= n; i++) {
            xy[2 * (j * (n + 1) + i)] = (double)i / n;
            xy[2 * (j * (n + 1) + i) + 1] = (double)j / n;
        }
    off[0] = 0;
    for (int j = 0, c = 0; j < n; j++)
        for (int i = 0; i < n; i++, c++) {
            ump_idx a = j * (n + 1) + i;
            pv[4 * c] = a;
            pv[4 * c + 1] = a + 1;
            pv[4 * c + 2] = a + n + 2;
            pv[4 * c + 3] = a + n + 1;
            off[c + 1] = 4 * (c + 1);
        }
    pmesh *pm = NULL;
    ump_err err;
    ump_status rc = pmesh_extrude(xy, nv, off, pv, n * n, 0.1, square_patch, NULL, SQ_NAMES,
                                  SQ_TYPES, 4, &pm, &err);
    if (rc != UMP_OK)
        fail_msg("%s", err.msg);
    free(xy);
    free(off);
    free(pv);
    return pm;
}

static void test_quads(void **state)
{
    (void)state;
    pmesh *pm = quad_square(2);
    mesh2d *m = NULL;
    ump_err err;
    assert_int_equal(mesh_build(pm, &m, &err), UMP_OK);
    assert_int_equal(m->normal, 2);
    assert_int_equal(m->ax[0], 0);
    assert_int_equal(m->ax[1], 1);
    assert_int_equal(m->ncells, 4);
    assert_int_equal(m->nverts, 9);
    assert_int_equal(m->ninternal, 4);
    assert_int_equal(m->nfaces, 12);
    double cx[] = {0.25, 0.75, 0.25, 0.75}, cy[] = {0.25, 0.25, 0.75, 0.75};
    for (int c = 0; c < 4; c++) {
        TU_CLOSE(m->cx[c], cx[c], 1e-15);
        TU_CLOSE(m->cy[c], cy[c], 1e-15);
        TU_CLOSE(m->area[c], 0.25, 1e-15);
        TU_CLOSE(m->dx[c], 0.5, 1e-15);
        TU_CLOSE(m->dc[c], sqrt(0.5), 1e-15);
        /* every cell sees the 3 others as first neighbours */
        assert_int_equal(m->n1_off[c + 1] - m->n1_off[c], 3);
        assert_int_equal(m->n2_off[c + 1] - m->n2_off[c], 3);
    }
    for (ump_idx f = 0; f < m->nfaces; f++) {
        TU_CLOSE(m->len[f], 0.5, 1e-15);
        /* normal points from owner towards neighbour / outwards */
        double d = (m->fx[f] - m->cx[m->owner[f]]) * m->nx[f] + (m->fy[f] - m->cy[m->owner[f]]) * m->ny[f];
        assert_true(d > 0);
    }
    /* patches: bottom faces sorted by x, each with outward normal (0,-1) */
    const mesh_patch *b = &m->patch[0];
    assert_int_equal(b->n, 2);
    for (ump_idx f = b->start; f < b->start + b->n; f++) {
        TU_CLOSE(m->ny[f], -1, 1e-15);
        TU_CLOSE(m->fy[f], 0, 1e-15);
    }
    assert_int_equal(m->patch[4].n, 0); /* empty */
    mesh_stats s;
    mesh_compute_stats(m, &s);
    assert_int_equal(s.nquad, 4);
    TU_CLOSE(s.area_total, 1.0, 1e-14);
    TU_CLOSE(s.nonorth_max, 0.0, 1e-12);
    TU_CLOSE(s.skew_max, 0.0, 1e-12);
    mesh_free(&m);
    assert_null(m);
    pmesh_free(&pm);
}

static void test_stencil_sizes(void **state)
{
    (void)state;
    pmesh *pm = quad_square(6);
    mesh2d *m = NULL;
    ump_err err;
    assert_int_equal(mesh_build(pm, &m, &err), UMP_OK);
    /* interior cell of a structured quad mesh: 8 first, 24 first+second neighbours */
    ump_idx c = 2 * 6 + 2;
    assert_int_equal(m->n1_off[c + 1] - m->n1_off[c], 8);
    assert_int_equal(m->n2_off[c + 1] - m->n2_off[c], 24);
    /* corner cell: 3 and 8 */
    assert_int_equal(m->n1_off[1] - m->n1_off[0], 3);
    assert_int_equal(m->n2_off[1] - m->n2_off[0], 8);
    /* entries sorted, without the cell itself */
    for (ump_idx k = m->n2_off[c]; k + 1 < m->n2_off[c + 1]; k++)
        assert_true(m->n2[k] < m->n2[k + 1] && m->n2[k] != c);
    mesh_free(&m);
    pmesh_free(&pm);
}

/* a hybrid mesh: one quad, two triangles, one pentagon (given clockwise) */
static void test_hybrid(void **state)
{
    (void)state;
    /*  3---4---5
     *  | q | t/|
     *  0---1/ t|        pentagon under: 0 1 2 7 6 (y<0)
     *  6---7---2 */
    double xy[] = {0, 0.5, 0.5, 0.5, 1, 0, 0, 1, 0.5, 1, 1, 1, 0, 0, 0.5, -0.2};
    /* quad 0 1 4 3 ; tri 1 2 5? keep edges consistent: tri (1,5,4) and (1,2,5) */
    ump_idx off[] = {0, 4, 7, 10, 15};
    ump_idx pv[] = {0, 1, 4, 3, 1, 5, 4, 1, 2, 5, 0, 6, 7, 2, 1};
    /* pentagon listed 0 6 7 2 1 is counter-clockwise? make it clockwise: */
    ump_idx pv_cw[15];
    memcpy(pv_cw, pv, sizeof pv);
    for (int i = 0; i < 5; i++)
        pv_cw[10 + i] = pv[14 - i];
    pmesh *pm = NULL;
    ump_err err;
    assert_int_equal(pmesh_extrude(xy, 8, off, pv_cw, 4, 0.01, square_patch, NULL, SQ_NAMES, SQ_TYPES,
                                   4, &pm, &err), UMP_OK);
    mesh2d *m = NULL;
    if (mesh_build(pm, &m, &err) != UMP_OK)
        fail_msg("%s", err.msg);
    TU_CLOSE(m->area[0], 0.25, 1e-15);
    TU_CLOSE(m->area[1], 0.125, 1e-15);
    TU_CLOSE(m->area[2], 0.25, 1e-15);
    /* triangle centroid = vertex mean */
    TU_CLOSE(m->cx[1], (0.5 + 1 + 0.5) / 3, 1e-15);
    TU_CLOSE(m->cy[1], (0.5 + 1 + 1) / 3, 1e-15);
    /* pentagon (0,0.5) (0,0) (0.5,-0.2) (1,0) (0.5,0.5): shoelace by hand */
    double px[] = {0, 0, 0.5, 1, 0.5}, py[] = {0.5, 0, -0.2, 0, 0.5};
    double a2 = 0, sx = 0, sy = 0;
    for (int i = 0; i < 5; i++) {
        int j = (i + 1) % 5;
        double cr = px[i] * py[j] - px[j] * py[i];
        a2 += cr;
        sx += (px[i] + px[j]) * cr;
        sy += (py[i] + py[j]) * cr;
    }
    TU_CLOSE(m->area[3], 0.5 * a2, 1e-14);
    TU_CLOSE(m->cx[3], sx / (3 * a2), 1e-14);
    TU_CLOSE(m->cy[3], sy / (3 * a2), 1e-14);
    TU_CLOSE(m->dx[3], 1.0, 1e-15);
    TU_CLOSE(m->dy[3], 0.7, 1e-15);
    mesh_stats s;
    mesh_compute_stats(m, &s);
    assert_int_equal(s.ntri, 2);
    assert_int_equal(s.nquad, 1);
    assert_int_equal(s.npoly, 1);
    assert_int_equal(s.nsides_max, 5);
    assert_true(s.nonorth_max > 0);
    /* all 4 cells share vertex 1: everyone is everyone's first neighbour */
    for (int c = 0; c < 4; c++)
        assert_int_equal(m->n1_off[c + 1] - m->n1_off[c], 3);
    mesh_free(&m);
    pmesh_free(&pm);
}

/* the same mesh rotated so the empty sides are normal to x or y */
static void test_orientation(void **state)
{
    (void)state;
    for (int axis = 0; axis < 2; axis++) {
        pmesh *pm = quad_square(3);
        /* permute coordinates: (x,y,z) -> place z on 'axis' keeping right-handedness */
        for (ump_idx i = 0; i < pm->npoints; i++) {
            double *p = pm->points + 3 * (size_t)i, x = p[0], y = p[1], z = p[2];
            if (axis == 0) { p[0] = z; p[1] = x; p[2] = y; }  /* (X,Y) = (y,z) */
            else { p[1] = z; p[2] = x; p[0] = y; }            /* (X,Y) = (z,x) */
        }
        mesh2d *m = NULL;
        ump_err err;
        if (mesh_build(pm, &m, &err) != UMP_OK)
            fail_msg("%s", err.msg);
        assert_int_equal(m->normal, axis);
        TU_CLOSE(m->cx[0], 1.0 / 6, 1e-15);
        TU_CLOSE(m->cy[0], 1.0 / 6, 1e-15);
        TU_CLOSE(m->area[4], 1.0 / 9, 1e-14);
        double p3[3];
        mesh_to3d(m, m->cx[0], m->cy[0], p3);
        TU_CLOSE(p3[axis], 0.05, 1e-15);
        mesh_free(&m);
        pmesh_free(&pm);
    }
}

/* left/right and bottom/top turned into cyclic pairs */
static void test_cyclic(void **state)
{
    (void)state;
    pmesh *pm = quad_square(4);
    const char *nb[] = {"top", "left", "bottom", "right"};
    for (int p = 0; p < 4; p++) {
        pmesh_patch *pp = &pm->patch[p];
        free(pp->type);
        pp->type = ump_strdup("cyclic");
        pp->kind = PMESH_CYCLIC;
        pp->neighbour_patch = ump_strdup(nb[p]);
        pp->nbr = pmesh_patch_index(pm, nb[p]);
    }
    mesh2d *m = NULL;
    ump_err err;
    if (mesh_build(pm, &m, &err) != UMP_OK)
        fail_msg("%s", err.msg);
    assert_true(m->has_cyclic);
    assert_int_equal(m->ninternal, 24 + 8);
    assert_int_equal(m->nfaces, 32);
    /* every cell is now an interior cell: 8 first, 15 = all others in N2 */
    for (ump_idx c = 0; c < 16; c++) {
        assert_int_equal(m->n1_off[c + 1] - m->n1_off[c], 8);
        assert_int_equal(m->n2_off[c + 1] - m->n2_off[c], 15);
    }
    /* bottom/top pair: separation (0,1); neighbour image across the face is adjacent */
    for (ump_idx f = 24; f < 32; f++) {
        double ddx = m->cx[m->neigh[f]] - m->sepx[f] - m->cx[m->owner[f]];
        double ddy = m->cy[m->neigh[f]] - m->sepy[f] - m->cy[m->owner[f]];
        TU_CLOSE(hypot(ddx, ddy), 0.25, 1e-14);
        TU_CLOSE(ddx * m->nx[f] + ddy * m->ny[f], 0.25, 1e-14);
    }
    /* the shift of cell 3 (bottom-right) seen from cell 0 (bottom-left) is -1 in x */
    for (ump_idx k = m->n1_off[0]; k < m->n1_off[1]; k++)
        if (m->n1[k] == 3) {
            TU_CLOSE(m->n1_sx[k], -1, 1e-15);
            TU_CLOSE(m->n1_sy[k], 0, 1e-15);
        }
    mesh_stats s;
    mesh_compute_stats(m, &s);
    TU_CLOSE(s.nonorth_max, 0.0, 1e-10);
    mesh_free(&m);
    pmesh_free(&pm);
}

static void test_refusals(void **state)
{
    (void)state;
    ump_err err;
    mesh2d *m = NULL;
    /* 3-D: no empty patch */
    pmesh *pm = quad_square(2);
    pm->patch[4].kind = PMESH_PATCH;
    assert_int_equal(mesh_build(pm, &m, &err), UMP_ERR_UNSUPPORTED);
    assert_non_null(strstr(err.msg, "3-D"));
    assert_null(m);
    /* wedge */
    pm->patch[4].kind = PMESH_WEDGE;
    assert_int_equal(mesh_build(pm, &m, &err), UMP_ERR_UNSUPPORTED);
    assert_non_null(strstr(err.msg, "wedge"));
    pm->patch[4].kind = PMESH_EMPTY;
    /* a point of the front plane moved half way: not one cell thick */
    ump_idx last = pm->npoints - 1;
    pm->points[3 * (size_t)last + 2] = 0.05;
    assert_int_equal(mesh_build(pm, &m, &err), UMP_ERR_UNSUPPORTED);
    assert_non_null(strstr(err.msg, "empty patch 'frontAndBack'"));
    pm->points[3 * (size_t)last + 2] = 0.1;
    /* a flipped internal face: cells no longer close */
    ump_idx *fp = pm->face_pts + pm->face_off[0];
    ump_idx t = fp[1];
    fp[1] = fp[3];
    fp[3] = t;
    assert_int_equal(mesh_build(pm, &m, &err), UMP_ERR_INPUT);
    assert_non_null(strstr(err.msg, "not closed"));
    pmesh_free(&pm);
}

/* pmesh_check's topology checks (issue 15), on a 2x2 square */
static void test_topology(void **state)
{
    (void)state;
    ump_err err;
    pmesh *pm = quad_square(2);
    assert_int_equal(pmesh_check(pm, &err), UMP_OK);
    ump_idx *fp = pm->face_pts + pm->face_off[0], save[4];
    memcpy(save, fp, sizeof save);
    /* a flipped face: every edge still used twice, the area vectors do not cancel */
    ump_idx t = fp[1];
    fp[1] = fp[3];
    fp[3] = t;
    assert_int_equal(pmesh_check(pm, &err), UMP_ERR_INPUT);
    assert_non_null(strstr(err.msg, "is open: the sum of its outward face area vectors"));
    memcpy(fp, save, sizeof save);
    /* a point used twice by a face */
    fp[2] = fp[1];
    assert_int_equal(pmesh_check(pm, &err), UMP_ERR_INPUT);
    assert_non_null(strstr(err.msg, "twice"));
    memcpy(fp, save, sizeof save);
    /* face 1 a copy of face 0 */
    ump_idx *f1 = pm->face_pts + pm->face_off[1], save1[4];
    assert_int_equal(pm->face_off[2] - pm->face_off[1], 4);
    memcpy(save1, f1, sizeof save1);
    memcpy(f1, save, sizeof save);
    assert_int_equal(pmesh_check(pm, &err), UMP_ERR_INPUT);
    assert_non_null(strstr(err.msg, "faces 0 and 1 have the same 4 points"));
    memcpy(f1, save1, sizeof save1);
    /* a boundary face given to another cell: edges used once */
    ump_idx bf = pm->patch[0].start, o = pm->owner[bf];
    pm->owner[bf] = (o + 1) % pm->ncells;
    assert_int_equal(pmesh_check(pm, &err), UMP_ERR_INPUT);
    assert_non_null(strstr(err.msg, "is open: its edge"));
    pm->owner[bf] = o;
    /* nFaces near the label limit: no overflow, a clear refusal */
    ump_idx n0 = pm->patch[0].n;
    pm->patch[0].n = UMP_IDX_MAX;
    assert_int_equal(pmesh_check(pm, &err), UMP_ERR_INPUT);
    assert_non_null(strstr(err.msg, "beyond the"));
    pm->patch[0].n = n0;
    assert_int_equal(pmesh_check(pm, &err), UMP_OK);
    pmesh_free(&pm);
    /* one cell between a cyclic pair: the cell is its own periodic neighbour */
    mesh2d *m = NULL;
    pm = tm_pmesh(TM_QUAD, 1, 0.0, 1);
    assert_int_equal(pmesh_check(pm, &err), UMP_OK);
    assert_int_equal(mesh_build(pm, &m, &err), UMP_ERR_INPUT);
    assert_non_null(strstr(err.msg, "one cell wide between the pair"));
    assert_null(m);
    pmesh_free(&pm);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_quads),
        cmocka_unit_test(test_stencil_sizes),
        cmocka_unit_test(test_hybrid),
        cmocka_unit_test(test_orientation),
        cmocka_unit_test(test_cyclic),
        cmocka_unit_test(test_refusals),
        cmocka_unit_test(test_topology),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
