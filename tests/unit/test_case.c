/* SPDX-License-Identifier: GPL-3.0-or-later
 * test_case.c -- controlDict / transportProperties / fvSolution reading,
 * time directory discovery, and field reading with OpenFOAM's boundary
 * matching rules (name, then group, then regex).
 */
#include "testutil.h"
#include "umppm/case.h"
#include "umppm/fieldio.h"
#include "umppm/polymesh.h"

#include <sys/stat.h>

static const char *HDR = "FoamFile { version 2.0; format ascii; class dictionary; object x; }\n";

static void mk(const char *dir, const char *sub)
{
    char p[4096];
    snprintf(p, sizeof p, "%s/%s", dir, sub);
    mkdir(p, 0755);
}

static void write2(const char *dir, const char *name, const char *a, const char *b)
{
    char *s = malloc(strlen(a) + strlen(b) + 1);
    strcpy(s, a);
    strcat(s, b);
    tu_write(dir, name, s);
    free(s);
}

static void test_control_defaults(void **state)
{
    (void)state;
    char d[64];
    tu_tmpdir(d, sizeof d);
    mk(d, "system");
    write2(d, "system/controlDict", HDR,
           "startTime 0; endTime 0.5; deltaT 0.005; writeInterval 20;\n");
    case_control c;
    ump_err err;
    assert_int_equal(case_read_control(d, &c, &err), UMP_OK);
    assert_int_equal(c.start_from, CASE_START_STARTTIME);
    assert_int_equal(c.write_control, CASE_WRITE_TIMESTEP);
    assert_int_equal(c.write_precision, 6);
    assert_int_equal(c.time_precision, 6);
    assert_int_equal(c.write_binary, 0);
    assert_int_equal(c.adjust_time_step, 0);
    TU_CLOSE(c.max_co, 1.0, 0);
    TU_CLOSE(c.delta_t, 0.005, 0);
    TU_CLOSE(c.end_time, 0.5, 0);

    write2(d, "system/controlDict", HDR,
           "startFrom latestTime; endTime 10; deltaT 1e-3; writeControl adjustableRunTime;\n"
           "writeInterval 0.1; writeFormat binary; writePrecision 12; writeCompression on;\n"
           "adjustTimeStep yes; maxCo 0.25; timeFormat general; timePrecision 8; purgeWrite 2;\n");
    assert_int_equal(case_read_control(d, &c, &err), UMP_OK);
    assert_int_equal(c.start_from, CASE_START_LATESTTIME);
    assert_int_equal(c.write_control, CASE_WRITE_ADJUSTABLERUNTIME);
    assert_int_equal(c.write_binary, 1);
    assert_int_equal(c.write_compression, 1);
    assert_int_equal(c.write_precision, 12);
    assert_int_equal(c.purge_write, 2);
    assert_int_equal(c.adjust_time_step, 1);
    TU_CLOSE(c.max_co, 0.25, 0);

    /* errors name the file and line */
    write2(d, "system/controlDict", HDR, "startTime 0;\nendTime 1;\ndeltaT 0.1;\nwriteInterval 1;\n"
                                         "writeControl everyNow;\n");
    assert_int_equal(case_read_control(d, &c, &err), UMP_ERR_INPUT);
    assert_non_null(strstr(err.msg, "controlDict:6"));
    assert_non_null(strstr(err.msg, "adjustableRunTime"));
    write2(d, "system/controlDict", HDR, "startTime 0; endTime 1; writeInterval 1;\n");
    assert_int_not_equal(case_read_control(d, &c, &err), UMP_OK);
    assert_non_null(strstr(err.msg, "deltaT"));
    write2(d, "system/controlDict", HDR, "startTime 0; endTime 1; deltaT -1; writeInterval 1;\n");
    assert_int_equal(case_read_control(d, &c, &err), UMP_ERR_INPUT);
    assert_non_null(strstr(err.msg, "positive"));
    tu_rmtree(d);
}

static void test_transport_and_solution(void **state)
{
    (void)state;
    char d[64];
    tu_tmpdir(d, sizeof d);
    mk(d, "constant");
    mk(d, "system");
    case_transport t;
    ump_err err;
    const char *forms[] = {"nu 0.01;\n", "nu [0 2 -1 0 0 0 0] 0.01;\n", "nu nu [0 2 -1 0 0 0 0] 0.01;\n",
                           "transportModel Newtonian;\nnu 1e-2;\n"};
    for (int i = 0; i < 4; i++) {
        write2(d, "constant/transportProperties", HDR, forms[i]);
        if (case_read_transport(d, &t, &err) != UMP_OK)
            fail_msg("form %d: %s", i, err.msg);
        TU_CLOSE(t.nu, 0.01, 1e-15);
    }
    write2(d, "constant/transportProperties", HDR, "nu [0 1 -1 0 0 0 0] 0.01;\n");
    assert_int_equal(case_read_transport(d, &t, &err), UMP_ERR_INPUT);
    write2(d, "constant/transportProperties", HDR, "mu 0.01;\n");
    assert_int_not_equal(case_read_transport(d, &t, &err), UMP_OK);
    assert_non_null(strstr(err.msg, "transportProperties"));

    case_solution s;
    write2(d, "system/fvSolution", HDR, "solvers { p { solver PCG; } pFinal { $p; relTol 0; } }\n"
                                        "PISO { nCorrectors 2; pRefCell 3; pRefValue 1.5; }\n");
    assert_int_equal(case_read_solution(d, &s, &err), UMP_OK);
    assert_int_equal(s.p_ref_cell, 3);
    TU_CLOSE(s.p_ref_value, 1.5, 0);
    write2(d, "system/fvSolution", HDR, "PIMPLE { pRefPoint (0.1 0.2 0); pRefValue 0; }\n");
    assert_int_equal(case_read_solution(d, &s, &err), UMP_OK);
    assert_true(s.has_p_ref_point);
    TU_CLOSE(s.p_ref_point[1], 0.2, 0);
    tu_rmtree(d);
}

static void test_times(void **state)
{
    (void)state;
    char d[64];
    tu_tmpdir(d, sizeof d);
    const char *dirs[] = {"0", "0.5", "1e-05", "10", "2", "constant", "system", "0.orig", "1000.005"};
    for (size_t i = 0; i < sizeof dirs / sizeof dirs[0]; i++)
        mk(d, dirs[i]);
    tu_write(d, "3", "not a directory");
    char **names;
    double *vals;
    int n;
    ump_err err;
    assert_int_equal(case_list_times(d, &names, &vals, &n, &err), UMP_OK);
    assert_int_equal(n, 6);
    const char *want[] = {"0", "1e-05", "0.5", "2", "10", "1000.005"};
    for (int i = 0; i < n; i++)
        assert_string_equal(names[i], want[i]);
    case_free_times(names, vals, n);
    case_control c;
    memset(&c, 0, sizeof c);
    c.start_from = CASE_START_LATESTTIME;
    char name[64];
    double v;
    assert_int_equal(case_start_dir(d, &c, name, sizeof name, &v, &err), UMP_OK);
    assert_string_equal(name, "1000.005");
    c.start_from = CASE_START_STARTTIME;
    c.start_time = 0.5;
    assert_int_equal(case_start_dir(d, &c, name, sizeof name, &v, &err), UMP_OK);
    assert_string_equal(name, "0.5");
    c.start_time = 0.7;
    assert_int_equal(case_start_dir(d, &c, name, sizeof name, &v, &err), UMP_ERR_IO);
    tu_rmtree(d);
}

/* 2x1 quads on [0,2]x[0,1]: patches left, right, walls (group wall), frontAndBack */
static int strip_patch(double x, double y, void *ctx)
{
    (void)ctx;
    (void)y;
    if (x < 1e-12) return 0;
    if (x > 2 - 1e-12) return 1;
    return 2;
}

static pmesh *strip(void)
{
    double xy[] = {0, 0, 1, 0, 2, 0, 0, 1, 1, 1, 2, 1};
    ump_idx off[] = {0, 4, 8}, pv[] = {0, 1, 4, 3, 1, 2, 5, 4};
    const char *names[] = {"inlet", "outlet", "sides"}, *types[] = {"patch", "patch", "wall"};
    pmesh *pm = NULL;
    ump_err err;
    if (pmesh_extrude(xy, 6, off, pv, 2, 0.1, strip_patch, NULL, names, types, 3, &pm, &err) != UMP_OK)
        fail_msg("%s", err.msg);
    return pm;
}

static const char *VHDR = "FoamFile { version 2.0; format ascii; class volVectorField; object U; }\n"
                          "dimensions [0 1 -1 0 0 0 0];\n";

static void test_field_matching(void **state)
{
    (void)state;
    char d[64];
    tu_tmpdir(d, sizeof d);
    pmesh *pm = strip();
    fld_field *f = NULL;
    ump_err err;
    char path[128];
    snprintf(path, sizeof path, "%s/U", d);
    /* name beats group beats regex; regex keys latest first */
    write2(d, "U", VHDR,
           "internalField nonuniform List<vector> 2((1 2 0) (3 4 0));\n"
           "boundaryField {\n"
           "  \".*\" { type fixedValue; value uniform (9 9 9); }\n"
           "  \"in.*\" { type fixedValue; value uniform (5 0 0); }\n"
           "  wall { type noSlip; }\n"
           "  outlet { type zeroGradient; }\n"
           "  sides { type fixedValue; value uniform (0 0 7); }\n"
           "  frontAndBack { type empty; }\n"
           "}\n");
    if (fio_read_field(path, pm, 3, &f, &err) != UMP_OK)
        fail_msg("%s", err.msg);
    assert_string_equal(f->name, "U");
    TU_CLOSE(f->internal[3], 3, 0);
    assert_int_equal(f->patch[0].type, FLD_BC_FIXEDVALUE); /* inlet: "in.*" (latest regex) */
    TU_CLOSE(f->patch[0].value[0], 5, 0);
    assert_int_equal(f->patch[1].type, FLD_BC_ZEROGRADIENT);
    TU_CLOSE(f->patch[1].value[0], 3, 0);                  /* zeroGradient: cell value */
    assert_int_equal(f->patch[2].type, FLD_BC_FIXEDVALUE);  /* name beats group 'wall' */
    TU_CLOSE(f->patch[2].value[2], 7, 0);
    assert_int_equal(f->patch[3].type, FLD_BC_EMPTY);
    fld_free(&f);

    /* group match, inletOutlet with its inletValue, extra keys kept */
    write2(d, "U", VHDR,
           "internalField uniform (1 0 0);\n"
           "boundaryField {\n"
           "  inlet { type fixedValue; value nonuniform List<vector> 1((2 0 0)); }\n"
           "  outlet { type inletOutlet; inletValue uniform (0 0 0); phi phi; }\n"
           "  wall { type noSlip; }\n"
           "  #includeEtc \"caseDicts/setConstraintTypes\"\n"
           "}\n");
    if (fio_read_field(path, pm, 3, &f, &err) != UMP_OK)
        fail_msg("%s", err.msg);
    assert_int_equal(f->patch[2].type, FLD_BC_NOSLIP);
    TU_CLOSE(f->patch[2].value[0], 0, 0);
    assert_int_equal(f->patch[1].type, FLD_BC_INLETOUTLET);
    assert_int_equal(f->patch[1].nextra, 1);
    assert_string_equal(f->patch[1].extra[0].key, "phi");
    assert_string_equal(f->patch[1].extra[0].text, "phi");
    assert_int_equal(f->patch[3].type, FLD_BC_EMPTY); /* from setConstraintTypes' empty group */
    fld_free(&f);

    struct { const char *body; const char *needle; } bad[] = {
        {"internalField uniform (1 0 0);\nboundaryField { inlet { type fancy; } outlet { type zeroGradient; }"
         " sides { type noSlip; } frontAndBack { type empty; } }\n", "'fancy' is not supported"},
        {"internalField uniform (1 0 0);\nboundaryField { inlet { type zeroGradient; }"
         " sides { type noSlip; } frontAndBack { type empty; } }\n", "no entry for patch 'outlet'"},
        {"internalField uniform (1 0 0);\nboundaryField { \".*\" { type zeroGradient; } }\n",
         "mesh type 'empty'"},
        {"internalField nonuniform List<vector> 3((1 0 0) (1 0 0) (1 0 0));\nboundaryField { }\n",
         "3 values for 2 cells"},
        {"internalField uniform (1 0 0);\nboundaryField { inlet { type fixedValue; } \".*\" { type empty; } }\n",
         "needs a 'value'"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        write2(d, "U", VHDR, bad[i].body);
        assert_int_not_equal(fio_read_field(path, pm, 3, &f, &err), UMP_OK);
        assert_null(f);
        if (!strstr(err.msg, bad[i].needle) || !strstr(err.msg, "/U"))
            fail_msg("case %zu: message '%s' lacks '%s'", i, err.msg, bad[i].needle);
    }
    /* wrong class */
    write2(d, "U", "FoamFile { version 2.0; format ascii; class volScalarField; object U; }\n",
           "dimensions [0 1 -1 0 0 0 0];\ninternalField uniform 0;\nboundaryField { }\n");
    assert_int_equal(fio_read_field(path, pm, 3, &f, &err), UMP_ERR_INPUT);
    assert_non_null(strstr(err.msg, "volVectorField"));
    pmesh_free(&pm);
    tu_rmtree(d);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_control_defaults),
        cmocka_unit_test(test_transport_and_solution),
        cmocka_unit_test(test_times),
        cmocka_unit_test(test_field_matching),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
