/* SPDX-License-Identifier: GPL-3.0-or-later
 * test_solver.c -- the UMPPM step (src/solver.c) on flows it must reproduce
 * exactly, and its refusal of inconsistent boundary conditions.
 *   - uniform flow on periodic triangle/hybrid meshes: every particle and
 *     cell keeps the velocity, pressure stays level, N_p stays N_m;
 *   - fluid at rest in a closed box stays at rest;
 *   - plane Couette flow u = y between a fixed and a moving wall, periodic
 *     in x: a steady solution that MLS (quadratic basis) and CPM (exact for
 *     quadratics) represent exactly, so it must persist to round-off while
 *     the particles stream across the cyclic pair;
 *   - a patch with both U and p fixed, and an unsupported velocity
 *     condition, are refused with the patch named.
 */
#include "testmesh.h"
#include "umppm/solver.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* U and p fields for mesh pm: patch p gets types tu[p], tp[p] (the 5th,
 * frontAndBack, is empty) and, for fixed U, the value uw[p] (x velocity). */
static void make_fields(const pmesh *pm, const mesh2d *m, const fld_bc_type *tu, const fld_bc_type *tp,
                        const double *uw, fld_field **U, fld_field **p)
{
    ump_idx sizes[8];
    ump_err err;
    for (int k = 0; k < pm->npatches; k++)
        sizes[k] = pm->patch[k].n;
    if (fld_create("U", 3, m->ncells, pm->npatches, sizes, U, &err) != UMP_OK ||
        fld_create("p", 1, m->ncells, pm->npatches, sizes, p, &err) != UMP_OK)
        fail_msg("%s", err.msg);
    for (int k = 0; k < pm->npatches; k++) {
        int empty = pm->patch[k].kind == PMESH_EMPTY;
        (*U)->patch[k].type = empty ? FLD_BC_EMPTY : tu[k];
        (*p)->patch[k].type = empty ? FLD_BC_EMPTY : tp[k];
        if (!empty && tu[k] == FLD_BC_FIXEDVALUE)
            for (ump_idx i = 0; i < pm->patch[k].n; i++)
                (*U)->patch[k].value[3 * (size_t)i] = uw[k];
    }
}

static sol *make_solver(const mesh2d *m, const fld_field *U, const fld_field *p, double nu)
{
    sol_settings s;
    sol_default_settings(&s);
    s.nu = nu;
    sol *S = NULL;
    ump_err err;
    if (sol_create(m, &s, U, p, NULL, &S, &err) != UMP_OK)
        fail_msg("%s", err.msg);
    return S;
}

static void test_uniform_periodic(void **state)
{
    (void)state;
    const tm_kind kinds[] = {TM_TRI, TM_HYBRID};
    for (int q = 0; q < 2; q++) {
        pmesh *pm = NULL;
        mesh2d *m = tm_mesh(kinds[q], 12, q ? 0.04 : 0, 1, &pm);
        fld_bc_type cyc[4] = {FLD_BC_CYCLIC, FLD_BC_CYCLIC, FLD_BC_CYCLIC, FLD_BC_CYCLIC};
        fld_field *U = NULL, *p = NULL;
        make_fields(pm, m, cyc, cyc, NULL, &U, &p);
        for (ump_idx c = 0; c < m->ncells; c++) {
            U->internal[3 * (size_t)c] = 0.3;
            U->internal[3 * (size_t)c + 1] = -0.2;
        }
        sol *S = make_solver(m, U, p, 0.01);
        ump_err err;
        sol_stats st;
        for (int k = 0; k < 40; k++)
            assert_int_equal(sol_step(S, 0.02, &st, &err), UMP_OK);
        const part_set *P = sol_particles(S);
        assert_int_equal(P->n, (size_t)m->ncells);
        double e = 0;
        for (size_t i = 0; i < P->n; i++)
            e = fmax(e, fmax(fabs(P->u[i] - 0.3), fabs(P->v[i] + 0.2)));
        const double *uc = sol_cell_u(S), *vc = sol_cell_v(S), *pc = sol_cell_p(S);
        for (ump_idx c = 0; c < m->ncells; c++) {
            e = fmax(e, fmax(fabs(uc[c] - 0.3), fabs(vc[c] + 0.2)));
            e = fmax(e, fabs(pc[c] - pc[0]));
        }
        if (e > 1e-11)
            fail_msg("%s: uniform flow drifted by %g", tm_name(kinds[q], q ? 0.04 : 0), e);
        sol_free(&S);
        fld_free(&U);
        fld_free(&p);
        mesh_free(&m);
        pmesh_free(&pm);
    }
}

static void test_rest(void **state)
{
    (void)state;
    pmesh *pm = NULL;
    mesh2d *m = tm_mesh(TM_HYBRID, 10, 0.04, 0, &pm);
    fld_bc_type tu[4] = {FLD_BC_NOSLIP, FLD_BC_NOSLIP, FLD_BC_NOSLIP, FLD_BC_NOSLIP};
    fld_bc_type tp[4] = {FLD_BC_ZEROGRADIENT, FLD_BC_ZEROGRADIENT, FLD_BC_ZEROGRADIENT, FLD_BC_ZEROGRADIENT};
    fld_field *U = NULL, *p = NULL;
    make_fields(pm, m, tu, tp, NULL, &U, &p);
    sol *S = make_solver(m, U, p, 0.1);
    ump_err err;
    sol_stats st;
    for (int k = 0; k < 10; k++)
        assert_int_equal(sol_step(S, 0.01, &st, &err), UMP_OK);
    const part_set *P = sol_particles(S);
    double e = 0;
    for (size_t i = 0; i < P->n; i++)
        e = fmax(e, hypot(P->u[i], P->v[i]));
    for (ump_idx c = 0; c < m->ncells; c++)
        e = fmax(e, fabs(sol_cell_p(S)[c]) + hypot(sol_cell_u(S)[c], sol_cell_v(S)[c]));
    assert_true(e < 1e-14);
    assert_int_equal(P->n, (size_t)m->ncells);
    sol_free(&S);
    fld_free(&U);
    fld_free(&p);
    mesh_free(&m);
    pmesh_free(&pm);
}

/* periodic in x only: left/right become a cyclic pair, bottom/top stay walls */
static pmesh *couette_pmesh(tm_kind kind, int n)
{
    pmesh *pm = tm_pmesh(kind, n, 0, 0);
    tm_make_cyclic(pm, 1, 3);
    return pm;
}

static void test_couette(void **state)
{
    (void)state;
    const tm_kind kinds[] = {TM_QUAD, TM_TRI, TM_HYBRID};
    for (int q = 0; q < 3; q++) {
        pmesh *pm = couette_pmesh(kinds[q], 10);
        mesh2d *m = NULL;
        ump_err err;
        if (mesh_build(pm, &m, &err) != UMP_OK)
            fail_msg("%s", err.msg);
        fld_bc_type tu[4] = {FLD_BC_NOSLIP, FLD_BC_CYCLIC, FLD_BC_FIXEDVALUE, FLD_BC_CYCLIC};
        fld_bc_type tp[4] = {FLD_BC_ZEROGRADIENT, FLD_BC_CYCLIC, FLD_BC_ZEROGRADIENT, FLD_BC_CYCLIC};
        double uw[4] = {0, 0, 1, 0};
        fld_field *U = NULL, *p = NULL;
        make_fields(pm, m, tu, tp, uw, &U, &p);
        for (ump_idx c = 0; c < m->ncells; c++)
            U->internal[3 * (size_t)c] = m->cy[c];
        sol *S = make_solver(m, U, p, 0.05);
        sol_stats st;
        /* 30 steps of 0.02: the top row travels 0.57, across the cyclic pair */
        for (int k = 0; k < 30; k++)
            assert_int_equal(sol_step(S, 0.02, &st, &err), UMP_OK);
        const part_set *P = sol_particles(S);
        double e = 0;
        for (size_t i = 0; i < P->n; i++)
            e = fmax(e, fmax(fabs(P->u[i] - P->y[i]), fabs(P->v[i])));
        for (ump_idx c = 0; c < m->ncells; c++)
            e = fmax(e, fmax(fabs(sol_cell_u(S)[c] - m->cy[c]), fabs(sol_cell_v(S)[c])));
        if (e > 1e-9)
            fail_msg("%s: Couette flow off by %g", tm_name(kinds[q], 0), e);
        sol_free(&S);
        fld_free(&U);
        fld_free(&p);
        mesh_free(&m);
        pmesh_free(&pm);
    }
}

static void test_refused(void **state)
{
    (void)state;
    pmesh *pm = NULL;
    mesh2d *m = tm_mesh(TM_QUAD, 4, 0, 0, &pm);
    sol_settings s;
    sol_default_settings(&s);
    s.nu = 0.1;
    ump_err err;
    sol *S = NULL;
    /* both U and p fixed on "right" */
    fld_bc_type tu[4] = {FLD_BC_NOSLIP, FLD_BC_FIXEDVALUE, FLD_BC_NOSLIP, FLD_BC_NOSLIP};
    fld_bc_type tp[4] = {FLD_BC_ZEROGRADIENT, FLD_BC_FIXEDVALUE, FLD_BC_ZEROGRADIENT, FLD_BC_ZEROGRADIENT};
    fld_field *U = NULL, *p = NULL;
    make_fields(pm, m, tu, tp, (double[4]){0, 1, 0, 0}, &U, &p);
    assert_int_equal(sol_create(m, &s, U, p, NULL, &S, &err), UMP_ERR_INPUT);
    assert_non_null(strstr(err.msg, "'right'"));
    assert_null(S);
    fld_free(&U);
    fld_free(&p);
    /* fixedFluxPressure is a pressure condition, not a velocity one */
    tu[1] = FLD_BC_FIXEDFLUXPRESSURE;
    tp[1] = FLD_BC_ZEROGRADIENT;
    make_fields(pm, m, tu, tp, NULL, &U, &p);
    assert_int_equal(sol_create(m, &s, U, p, NULL, &S, &err), UMP_ERR_UNSUPPORTED);
    assert_non_null(strstr(err.msg, "fixedFluxPressure"));
    assert_non_null(strstr(err.msg, "'right'"));
    fld_free(&U);
    fld_free(&p);
    mesh_free(&m);
    pmesh_free(&pm);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_uniform_periodic),
        cmocka_unit_test(test_rest),
        cmocka_unit_test(test_couette),
        cmocka_unit_test(test_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
