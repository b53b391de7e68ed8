/* SPDX-License-Identifier: GPL-3.0-or-later
 * test_case.c -- controlDict / transportProperties / fvSolution reading,
 * time directory discovery, field reading with OpenFOAM's boundary
 * matching rules (name, then group, then regex), and the UMPPM dictionary
 * of fvSolution: its options table, defaults, errors, -help text and the
 * README's Settings table.
 */
#include "testutil.h"
#include "umppm/case.h"
#include "umppm/features.h"
#include "umppm/fieldio.h"
#include "umppm/laplacian.h"
#include "umppm/lsolve.h"
#include "umppm/polymesh.h"
#include "umppm/solver.h"

#include <sys/stat.h>
#include <unistd.h>

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

/* stopAt other than endTime: endTime is not read (Time::readDict), so it
 * may be absent or not a number; the file stamp tells versions apart. */
static void test_control_stop_at_and_stamp(void **state)
{
    (void)state;
    char d[64], path[128];
    tu_tmpdir(d, sizeof d);
    mk(d, "system");
    snprintf(path, sizeof path, "%s/system/controlDict", d);
    case_control c;
    ump_err err;
    write2(d, "system/controlDict", HDR, "startTime 0; stopAt writeNow; deltaT 0.1; writeInterval 1;\n");
    assert_int_equal(case_read_control(d, &c, &err), UMP_OK);
    assert_int_equal(c.stop_at, CASE_STOP_WRITENOW);
    write2(d, "system/controlDict", HDR, "startTime 0; stopAt nextWrite; endTime nan; deltaT 0.1; writeInterval 1;\n");
    assert_int_equal(case_read_control(d, &c, &err), UMP_OK);
    assert_int_equal(case_check_start(d, &c, "2", 2.0, &err), UMP_OK); /* endTime unused */
    write2(d, "system/controlDict", HDR, "startTime 0; stopAt endTime; deltaT 0.1; writeInterval 1;\n");
    assert_int_not_equal(case_read_control(d, &c, &err), UMP_OK);
    assert_non_null(strstr(err.msg, "endTime"));
    write2(d, "system/controlDict", HDR, "startTime 0; endTime 1; stopAt foo; deltaT 0.1; writeInterval 1;\n");
    assert_int_equal(case_read_control(d, &c, &err), UMP_ERR_INPUT);
    assert_non_null(strstr(err.msg, "stopAt 'foo' is not one of: endTime writeNow noWriteNow nextWrite"));

    case_stamp a, b, e;
    assert_int_equal(case_file_stamp(path, &a), 0);
    assert_int_equal(case_file_stamp(path, &b), 0);
    assert_true(case_stamp_equal(&a, &b));
    /* a new file renamed over it (what editors and sed -i do), even of the
     * same size and within the same clock tick, is another version */
    char other[160];
    snprintf(other, sizeof other, "%s/system/controlDict.new", d);
    FILE *fp = fopen(path, "rb");
    assert_non_null(fp);
    char text[1024];
    size_t n = fread(text, 1, sizeof text, fp);
    fclose(fp);
    fp = fopen(other, "wb");
    assert_non_null(fp);
    fwrite(text, 1, n, fp);
    fclose(fp);
    assert_int_equal(rename(other, path), 0);
    assert_int_equal(case_file_stamp(path, &b), 0);
    assert_false(case_stamp_equal(&a, &b));
    assert_int_equal(a.size, b.size);
    /* so is an append */
    fp = fopen(path, "ab");
    assert_non_null(fp);
    fputs("// edited\n", fp);
    fclose(fp);
    assert_int_equal(case_file_stamp(path, &e), 0);
    assert_false(case_stamp_equal(&b, &e));
    assert_int_equal(unlink(path), 0);
    assert_int_equal(case_file_stamp(path, &e), -1);
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

/* Issue 15: non-finite or inconsistent times, a missing PISO, unsafe
 * names, and the features refused by name. */
static void test_refusals(void **state)
{
    (void)state;
    char d[64];
    tu_tmpdir(d, sizeof d);
    mk(d, "constant");
    mk(d, "system");
    mk(d, "0");
    case_control c;
    ump_err err;
    const char *bad[][2] = {{"startTime 0; endTime nan; deltaT 0.1; writeInterval 1;\n", "endTime must be a finite"},
                            {"startTime 0; endTime 1; deltaT inf; writeInterval 1;\n", "deltaT must be a finite"},
                            {"startTime 0; endTime 1; deltaT 0.1; writeInterval 0;\n", "writeInterval must be positive"},
                            {"startTime 2; endTime 1; deltaT 0.1; writeInterval 1;\n", "before startTime"}};
    for (int i = 0; i < 4; i++) {
        write2(d, "system/controlDict", HDR, bad[i][0]);
        assert_int_equal(case_read_control(d, &c, &err), UMP_ERR_INPUT);
        if (!strstr(err.msg, bad[i][1]))
            fail_msg("case %d: %s", i, err.msg);
    }
    write2(d, "system/controlDict", HDR, "startFrom latestTime; endTime 1; deltaT 0.1; writeInterval 1;\n");
    assert_int_equal(case_read_control(d, &c, &err), UMP_OK);
    assert_int_equal(case_check_start(d, &c, "2", 2.0, &err), UMP_ERR_INPUT);
    assert_int_equal(case_check_start(d, &c, "1", 1.0, &err), UMP_OK);

    case_solution so;
    write2(d, "system/fvSolution", HDR, "solvers { }\n");
    assert_int_equal(case_read_solution(d, &so, &err), UMP_ERR_INPUT);
    assert_non_null(strstr(err.msg, "keyword PISO is undefined"));
    case_umppm u;
    write2(d, "system/fvSolution", HDR, "PISO { }\nUMPPM { cloudName \"a/../b\"; }\n");
    assert_int_equal(case_read_umppm(d, &u, &err), UMP_ERR_INPUT);
    assert_non_null(strstr(err.msg, "not a plain name"));
    assert_true(case_name_is_safe("umppmCloud"));
    assert_false(case_name_is_safe(""));
    assert_false(case_name_is_safe(".."));
    assert_false(case_name_is_safe("a/b"));

    /* features: accepted, then refused by name */
    write2(d, "constant/transportProperties", HDR, "transportModel Newtonian; nu 0.01;\n");
    write2(d, "constant/fvOptions", HDR, "");
    write2(d, "constant/MRFProperties", HDR, "zone { active false; }\n");
    write2(d, "system/fvSchemes", HDR, "ddtSchemes { default none; ddt(U) backward; }\n");
    assert_int_equal(feat_check_case(d, "0", &err), UMP_OK);
    char ddt[64];
    assert_int_equal(feat_ddt_scheme(d, ddt, sizeof ddt, &err), UMP_OK);
    assert_string_equal(ddt, "backward");
    /* file, bad content, expected text, accepted content (restored) */
    const char *feat[][4] = {
        {"constant/fvOptions", "src { type meanVelocityForce; }\n", "entry 'src', type meanVelocityForce", ""},
        {"constant/MRFProperties", "zone { active yes; }\n", "MRF (rotating frame)", ""},
        {"system/fvSchemes", "ddtSchemes { default CrankNicolson 0.9; }\n", "ddtSchemes default CrankNicolson",
         "ddtSchemes { default Euler; }\n"},
        {"constant/transportProperties", "transportModel powerLaw;\n", "transportModel powerLaw: non-Newtonian",
         "nu 0.01;\n"},
        {"constant/dynamicMeshDict", "dynamicFvMesh dynamicInkJetFvMesh;\n", "moving or topology-changing",
         "dynamicFvMesh staticFvMesh;\n"}};
    for (int i = 0; i < 5; i++) {
        write2(d, feat[i][0], HDR, feat[i][1]);
        assert_int_equal(feat_check_case(d, "0", &err), UMP_ERR_UNSUPPORTED);
        if (!strstr(err.msg, feat[i][2]))
            fail_msg("feature %d: %s", i, err.msg);
        write2(d, feat[i][0], HDR, feat[i][3]);
        assert_int_equal(feat_check_case(d, "0", &err), UMP_OK);
    }
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

/* The boundary conditions of issue 15 item 4 read, copied, written and
 * read back: types, Function1s, second value lists (outletValue, p0,
 * tangentialVelocity), v1912's start values without `value`, the keys kept
 * verbatim (a sub-dictionary too), fld_bc_eval. */
static void test_field_new_bcs(void **state)
{
    (void)state;
    char d[64], path[256], out[128];
    tu_tmpdir(d, sizeof d);
    snprintf(path, sizeof path, "%s/U", d);
    snprintf(out, sizeof out, "%s/w", d);
    if (mkdir(out, 0755) != 0)
        fail_msg("mkdir %s", out);
    pmesh *pm = strip();
    fld_field *f = NULL, *g = NULL, *c = NULL;
    ump_err err;
    write2(d, "U", VHDR,
           "internalField uniform (1 0 0);\n"
           "boundaryField {\n"
           "  inlet { type flowRateInletVelocity; volumetricFlowRate table ((0 0) (1 0.2)); outOfBounds repeat;\n"
           "          extrapolateProfile false; }\n"
           "  outlet { type outletInlet; outletValue uniform (0.5 0 0); phi phi; }\n"
           "  sides { type slip; }\n"
           "  frontAndBack { type empty; }\n"
           "}\n");
    if (fio_read_field(path, pm, 3, &f, &err) != UMP_OK)
        fail_msg("%s", err.msg);
    assert_int_equal(f->patch[0].type, FLD_BC_FLOWRATEINLETVELOCITY);
    assert_non_null(f->patch[0].fn);
    assert_int_equal(f->patch[0].fn->kind, F1_TABLE);
    assert_int_equal(f->patch[0].fn->bounds, F1_REPEAT);
    assert_int_equal(f->patch[0].value_given, 0);
    assert_int_equal(f->patch[1].type, FLD_BC_OUTLETINLET);
    TU_CLOSE(f->patch[1].aux[0], 0.5, 0);
    TU_CLOSE(f->patch[1].value[0], 0.5, 0); /* v1912: no value -> outletValue */
    assert_int_equal(f->patch[2].type, FLD_BC_SLIP);
    /* flowRateInletVelocity: -Q(t)/A n; Q(1.5) = 0.1 (repeat), A = 0.1, n = (-1 0 0) */
    double n3[3] = {-1, 0, 0}, v[3];
    assert_int_equal(fld_bc_eval(&f->patch[0], 3, 1.5, n3, 0.1, v), 1);
    TU_CLOSE(v[0], 1, 1e-14);
    TU_CLOSE(v[1], 0, 0);
    assert_int_equal(fld_bc_eval(&f->patch[1], 3, 1.5, n3, 0.1, v), 0);
    /* deep copy, write, read back */
    assert_int_equal(fld_copy(f, &c, &err), UMP_OK);
    fld_free(&f);
    assert_int_equal(fio_write_field(out, "0", pm, c, NULL, &err), UMP_OK);
    snprintf(path, sizeof path, "%s/U", out);
    if (fio_read_field(path, pm, 3, &g, &err) != UMP_OK)
        fail_msg("written U does not read back: %s", err.msg);
    assert_int_equal(g->patch[0].type, FLD_BC_FLOWRATEINLETVELOCITY);
    assert_int_equal(g->patch[0].value_given, 1);
    double a[1], b[1];
    for (double t = -0.3; t < 3; t += 0.35) {
        f1_value(c->patch[0].fn, t, a);
        f1_value(g->patch[0].fn, t, b);
        TU_CLOSE(a[0], b[0], 0);
    }
    TU_CLOSE(g->patch[1].aux[0], 0.5, 0);
    assert_int_equal(g->patch[2].type, FLD_BC_SLIP);
    fld_free(&c);
    fld_free(&g);

    /* pressure: totalPressure with the defaults v1912 writes, uniformFixedValue
     * sine with a Coeffs sub-dictionary kept verbatim */
    static const char *PHDR = "FoamFile { version 2.0; format ascii; class volScalarField; object p; }\n"
                              "dimensions [0 2 -2 0 0 0 0];\n";
    write2(d, "p", PHDR,
           "internalField uniform 0;\n"
           "boundaryField {\n"
           "  inlet { type totalPressure; rho rho; psi none; gamma 1; p0 uniform 2; }\n"
           "  outlet { type uniformFixedValue; uniformValue sine;\n"
           "           uniformValueCoeffs { amplitude 1; frequency 0.25; scale 3; level 1; } }\n"
           "  sides { type slip; }\n"
           "  frontAndBack { type empty; }\n"
           "}\n");
    snprintf(path, sizeof path, "%s/p", d);
    if (fio_read_field(path, pm, 1, &f, &err) != UMP_OK)
        fail_msg("%s", err.msg);
    assert_int_equal(f->patch[0].type, FLD_BC_TOTALPRESSURE);
    TU_CLOSE(f->patch[0].aux[0], 2, 0);
    TU_CLOSE(f->patch[0].value[0], 2, 0); /* v1912: no value -> p0 */
    assert_int_equal(f->patch[0].nextra, 3);
    assert_int_equal(f->patch[1].type, FLD_BC_UNIFORMFIXEDVALUE);
    assert_int_equal(fld_bc_eval(&f->patch[1], 1, 1, NULL, 0, v), 1);
    TU_CLOSE(v[0], 4, 1e-14); /* sin(pi/2) 3 + 1 */
    assert_int_equal(f->patch[1].nextra, 2);
    assert_string_equal(f->patch[1].extra[1].key, "uniformValueCoeffs");
    assert_string_equal(f->patch[1].extra[1].text, "{ amplitude 1; frequency 0.25; scale 3; level 1; }");
    assert_int_equal(fio_write_field(out, "0", pm, f, NULL, &err), UMP_OK);
    snprintf(path, sizeof path, "%s/p", out);
    if (fio_read_field(path, pm, 1, &g, &err) != UMP_OK)
        fail_msg("written p does not read back: %s", err.msg);
    assert_int_equal(fld_bc_eval(&g->patch[1], 1, 1, NULL, 0, v), 1);
    TU_CLOSE(v[0], 4, 1e-14);
    assert_int_equal(g->patch[0].type, FLD_BC_TOTALPRESSURE);
    fld_free(&f);
    fld_free(&g);

    /* pressureInletOutletVelocity: tangentialVelocity optional (aux NULL) */
    write2(d, "U", VHDR,
           "internalField uniform (1 0 0);\n"
           "boundaryField {\n"
           "  inlet { type pressureInletOutletVelocity; tangentialVelocity uniform (0 0.1 0); value uniform (0 0 0); }\n"
           "  outlet { type pressureInletOutletVelocity; value uniform (0 0 0); }\n"
           "  sides { type noSlip; }\n"
           "  frontAndBack { type empty; }\n"
           "}\n");
    snprintf(path, sizeof path, "%s/U", d);
    if (fio_read_field(path, pm, 3, &f, &err) != UMP_OK)
        fail_msg("%s", err.msg);
    assert_non_null(f->patch[0].aux);
    TU_CLOSE(f->patch[0].aux[1], 0.1, 0);
    assert_null(f->patch[1].aux);
    assert_int_equal(fio_write_field(out, "0", pm, f, NULL, &err), UMP_OK);
    fld_free(&f);
    snprintf(path, sizeof path, "%s/U", out);
    if (fio_read_field(path, pm, 3, &f, &err) != UMP_OK)
        fail_msg("written U does not read back: %s", err.msg);
    assert_non_null(f->patch[0].aux);
    assert_null(f->patch[1].aux);
    fld_free(&f);
    pmesh_free(&pm);
    tu_rmtree(d);
}

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
    /* an empty patch left out, or reached only by a regex, is empty (as
     * OpenFOAM's GeometricBoundaryField: empty before the regexes) */
    write2(d, "U", VHDR, "internalField uniform (1 0 0);\nboundaryField { \".*\" { type zeroGradient; } }\n");
    if (fio_read_field(path, pm, 3, &f, &err) != UMP_OK)
        fail_msg("%s", err.msg);
    assert_int_equal(f->patch[0].type, FLD_BC_ZEROGRADIENT);
    assert_int_equal(f->patch[3].type, FLD_BC_EMPTY);
    fld_free(&f);

    struct { const char *body; const char *needle; } bad[] = {
        {"internalField uniform (1 0 0);\nboundaryField { inlet { type fancy; } outlet { type zeroGradient; }"
         " sides { type noSlip; } frontAndBack { type empty; } }\n", "'fancy' is not supported"},
        {"internalField uniform (1 0 0);\nboundaryField { inlet { type zeroGradient; }"
         " sides { type noSlip; } frontAndBack { type empty; } }\n", "no entry for patch 'outlet'"},
        {"internalField uniform (1 0 0);\nboundaryField { \".*\" { type zeroGradient; } frontAndBack "
         "{ type zeroGradient; } }\n", "mesh type 'empty'"},
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

/* ---- UMPPM { } of system/fvSolution ------------------------------------------ */

static const case_option *opt(const char *key)
{
    size_t n;
    const case_option *t = case_umppm_options(&n);
    for (size_t i = 0; i < n; i++)
        if (strcmp(t[i].key, key) == 0)
            return &t[i];
    fail_msg("no option %s", key);
    return NULL;
}

/* system/fvSolution with HDR on line 1 and "UMPPM {" on lines 2-3, then
 * body (so that its first line is line 4). */
static void write_umppm(const char *d, const char *body)
{
    char text[8192];
    snprintf(text, sizeof text, "%sUMPPM\n{\n%s}\n", HDR, body);
    tu_write(d, "system/fvSolution", text);
}

/* One option set to value; returns the line of the entry. */
static int write_one(const char *d, const char *key, const char *value)
{
    char body[1024];
    const char *dot = strchr(key, '.');
    if (dot) {
        snprintf(body, sizeof body, "    %.*s\n    {\n        %s %s;\n    }\n", (int)(dot - key), key, dot + 1,
                 value);
        write_umppm(d, body);
        return 6;
    }
    snprintf(body, sizeof body, "    %s %s;\n", key, value);
    write_umppm(d, body);
    return 4;
}

static void assert_umppm_equal(const case_umppm *a, const case_umppm *b)
{
    assert_int_equal(a->variant_star, b->variant_star);
    TU_CLOSE(a->alpha, b->alpha, 0);
    assert_string_equal(a->laplacian, b->laplacian);
    TU_CLOSE(a->re_factor, b->re_factor, 0);
    assert_int_equal(a->write_quality, b->write_quality);
    assert_string_equal(a->ppe_solver, b->ppe_solver);
    assert_string_equal(a->pred_pc, b->pred_pc);
    TU_CLOSE(a->pred_tol, b->pred_tol, 0);
    assert_int_equal(a->pred_maxit, b->pred_maxit);
    assert_string_equal(a->cloud_name, b->cloud_name);
    assert_int_equal(a->sort_interval, b->sort_interval);
    TU_CLOSE(a->max_velocity, b->max_velocity, 0);
    assert_int_equal(a->positive_rows, b->positive_rows);
    assert_int_equal(a->bounded_fits, b->bounded_fits);
    assert_int_equal(a->refill_increment, b->refill_increment);
    assert_int_equal(a->q_transpose, b->q_transpose);
    TU_CLOSE(a->face_support, b->face_support, 0);
}

/* The table itself: keys unique, field sizes match the types, defaults are
 * valid values whose text and number agree. */
static void test_umppm_table(void **state)
{
    (void)state;
    size_t n;
    const case_option *t = case_umppm_options(&n);
    assert_int_equal(n, 23);
    for (size_t i = 0; i < n; i++) {
        const case_option *o = &t[i];
        assert_non_null(o->key);
        assert_non_null(o->help);
        assert_true(o->help[0] && !strchr(o->help, '\n'));
        for (size_t j = 0; j < i; j++)
            assert_string_not_equal(t[j].key, o->key);
        assert_true(o->offset + o->size <= sizeof(case_umppm));
        char *end;
        switch (o->type) {
        case CASE_OPT_CHOICE: {
            assert_non_null(o->choices);
            int k = -1;
            for (int c = 0; o->choices[c]; c++) {
                if (strcmp(o->choices[c], o->default_text) == 0)
                    k = c;
                if (!o->choice_values)
                    assert_true(strlen(o->choices[c]) < o->size);
            }
            if (k < 0)
                fail_msg("%s: default %s is not a choice", o->key, o->default_text);
            if (o->choice_values) {
                assert_int_equal(o->size, sizeof(int));
                TU_CLOSE(o->default_value, o->choice_values[k], 0);
            }
            break;
        }
        case CASE_OPT_SCALAR:
            assert_int_equal(o->size, sizeof(double));
            if (o->range.or_auto && strcmp(o->default_text, "auto") == 0) { /* auto is stored as -1 */
                TU_CLOSE(o->default_value, -1, 0);
                break;
            }
            TU_CLOSE(strtod(o->default_text, &end), o->default_value, 0);
            assert_true(*end == '\0');
            break;
        case CASE_OPT_LABEL:
            assert_int_equal(o->size, sizeof(long));
            TU_CLOSE((double)strtol(o->default_text, &end, 10), o->default_value, 0);
            assert_true(*end == '\0');
            break;
        case CASE_OPT_BOOL:
            assert_int_equal(o->size, sizeof(int));
            assert_true(strcmp(o->default_text, o->default_value ? "yes" : "no") == 0);
            break;
        case CASE_OPT_WORD:
            assert_null(o->choices);
            assert_true(strlen(o->default_text) < o->size);
            break;
        }
    }
    /* what the brief of each entry says */
    char b[256];
    assert_string_equal(case_option_allowed(opt("variant"), b, sizeof b), "auto UMPPM UMPPMstar UMPPM*");
    assert_string_equal(case_option_allowed(opt("alpha"), b, sizeof b), "(0, 1)");
    assert_string_equal(case_option_allowed(opt("reFactor"), b, sizeof b), "0 or [1, 4]");
    assert_string_equal(case_option_allowed(opt("predictorSolver.tolerance"), b, sizeof b), "> 0");
    assert_string_equal(case_option_allowed(opt("predictorSolver.maxIter"), b, sizeof b), ">= 1");
    assert_string_equal(case_option_allowed(opt("sortInterval"), b, sizeof b), ">= 0");
    assert_string_equal(case_option_allowed(opt("writeQuality"), b, sizeof b), "yes/no");
    assert_int_equal(opt("sortInterval")->type, CASE_OPT_LABEL);
    assert_string_equal(opt("sortInterval")->default_text, "1");
}

static void test_umppm_defaults(void **state)
{
    (void)state;
    char d[64];
    tu_tmpdir(d, sizeof d);
    mk(d, "system");
    case_umppm def, u;
    ump_err err;
    case_umppm_defaults(&def);
    /* the defaults as they always were */
    assert_int_equal(def.variant_star, -1); /* auto: by the mesh and the flow (app.c) */
    TU_CLOSE(def.alpha, 0.09, 0);
    assert_string_equal(def.laplacian, "auto"); /* CPM4 without walls, else CPM (app.c) */
    TU_CLOSE(def.p_theta, -1, 0);               /* auto: 0.5 without walls, else 0 */
    TU_CLOSE(def.face_support, -1, 0);          /* auto: 3 beside triangles if closed (app.c) */
    TU_CLOSE(def.re_factor, 0, 0);
    assert_int_equal(def.write_quality, 0);
    assert_string_equal(def.ppe_solver, "auto");
    assert_string_equal(def.pred_pc, "Jacobi");
    TU_CLOSE(def.pred_tol, 1e-12, 0);
    assert_int_equal(def.pred_maxit, 500);
    assert_string_equal(def.cloud_name, "umppmCloud");
    assert_int_equal(def.sort_interval, 1);
    assert_int_equal(def.positive_rows, 1);
    assert_int_equal(def.bounded_fits, 1);
    assert_int_equal(def.refill_increment, 1);

    /* no UMPPM, an empty one, and every default written out from the table */
    write2(d, "system/fvSolution", HDR, "PISO { nCorrectors 2; }\n");
    assert_int_equal(case_read_umppm(d, &u, &err), UMP_OK);
    assert_umppm_equal(&u, &def);
    assert_memory_equal(&u, &def, sizeof u);
    write_umppm(d, "");
    assert_int_equal(case_read_umppm(d, &u, &err), UMP_OK);
    assert_umppm_equal(&u, &def);
    char body[4096] = "", sub[1024] = "";
    size_t n;
    const case_option *t = case_umppm_options(&n);
    for (size_t i = 0; i < n; i++) {
        const char *dot = strchr(t[i].key, '.');
        char *dst = dot ? sub : body;
        size_t cap = dot ? sizeof sub : sizeof body;
        snprintf(dst + strlen(dst), cap - strlen(dst), "    %s %s;\n", dot ? dot + 1 : t[i].key,
                 t[i].default_text);
    }
    snprintf(body + strlen(body), sizeof body - strlen(body), "    predictorSolver\n    {\n%s    }\n", sub);
    write_umppm(d, body);
    if (case_read_umppm(d, &u, &err) != UMP_OK)
        fail_msg("%s\n%s", err.msg, body);
    assert_umppm_equal(&u, &def);

    /* the solver's own defaults agree with the table */
    sol_settings s;
    sol_default_settings(&s);
    /* variant auto is decided by the mesh and the flow in app.c; the
     * solver's own default is UMPPM*, auto's choice but on closed flows
     * over non-square quadrilaterals */
    assert_int_equal(def.variant_star, -1);
    assert_int_equal(s.variant, PART_UMPPM_STAR);
    TU_CLOSE(s.alpha, def.alpha, 0);
    /* laplacian auto and pressureTheta auto are decided by the mesh in
     * app.c; the solver's own defaults are their choice for a mesh with
     * walls, the paper's */
    assert_int_equal((int)s.lap.model, LAP_CPM);
    TU_CLOSE(s.p_theta, 0, 0);
    TU_CLOSE(s.lap.re_factor, def.re_factor, 0);
    assert_int_equal(s.ppe_solver, LSOLVE_AUTO);
    assert_string_equal(def.ppe_solver, "auto");
    assert_int_equal(s.pred_pc, LSOLVE_PC_JACOBI);
    assert_string_equal(def.pred_pc, "Jacobi");
    assert_int_equal(s.sort_interval, (int)def.sort_interval);
    assert_int_equal(s.refill_increment, def.refill_increment);
    TU_CLOSE(s.pred_tol, def.pred_tol, 0);
    assert_int_equal(s.pred_maxit, def.pred_maxit);
    tu_rmtree(d);
}

static void test_umppm_values(void **state)
{
    (void)state;
    char d[64];
    tu_tmpdir(d, sizeof d);
    mk(d, "system");
    case_umppm u;
    ump_err err;
    write_umppm(d, "    variant UMPPM; alpha 0.05; laplacian IPS; reFactor 2.5; writeQuality yes;\n"
                   "    ppeSolver KLU; predictorSolver { preconditioner ILU0; tolerance 1e-8; maxIter 50; }\n"
                   "    cloudName myCloud; sortInterval 0; positiveRows no;\n"
                   "    boundedFits off; refillWeights distance;\n");
    if (case_read_umppm(d, &u, &err) != UMP_OK)
        fail_msg("%s", err.msg);
    assert_int_equal(u.variant_star, 0);
    TU_CLOSE(u.alpha, 0.05, 0);
    assert_string_equal(u.laplacian, "IPS");
    TU_CLOSE(u.re_factor, 2.5, 0);
    assert_int_equal(u.write_quality, 1);
    assert_string_equal(u.ppe_solver, "KLU");
    assert_string_equal(u.pred_pc, "ILU0");
    TU_CLOSE(u.pred_tol, 1e-8, 0);
    assert_int_equal(u.pred_maxit, 50);
    assert_string_equal(u.cloud_name, "myCloud");
    assert_int_equal(u.sort_interval, 0);
    assert_int_equal(u.positive_rows, 0);
    assert_int_equal(u.bounded_fits, 0);
    assert_int_equal(u.refill_increment, 0);
    write_one(d, "refillWeights", "increment");
    if (case_read_umppm(d, &u, &err) != UMP_OK)
        fail_msg("refillWeights increment: %s", err.msg);
    assert_int_equal(u.refill_increment, 1);
    /* boundary and special values that are allowed */
    struct { const char *key, *value; } ok[] = {
        {"variant", "\"UMPPM*\""}, {"variant", "UMPPM*"}, {"variant", "UMPPMstar"}, {"variant", "auto"}, {"reFactor", "0"}, {"reFactor", "1"},
        {"reFactor", "4"}, {"predictorSolver.maxIter", "1"}, {"sortInterval", "100"},
        {"writeQuality", "on"}, {"writeQuality", "1"}, {"alpha", "1e-6"}, {"cloudName", "\"my cloud\""},
    };
    for (size_t i = 0; i < sizeof ok / sizeof ok[0]; i++) {
        write_one(d, ok[i].key, ok[i].value);
        if (case_read_umppm(d, &u, &err) != UMP_OK)
            fail_msg("%s %s: %s", ok[i].key, ok[i].value, err.msg);
    }
    assert_string_equal(u.cloud_name, "my cloud");
    /* pressureTheta: auto (stored as -1) or a number in [0, 0.5] */
    struct { const char *w; double v; } th[] = {{"auto", -1}, {"0", 0}, {"0.25", 0.25}, {"0.5", 0.5}};
    for (size_t i = 0; i < sizeof th / sizeof th[0]; i++) {
        write_one(d, "pressureTheta", th[i].w);
        if (case_read_umppm(d, &u, &err) != UMP_OK)
            fail_msg("pressureTheta %s: %s", th[i].w, err.msg);
        TU_CLOSE(u.p_theta, th[i].v, 0);
    }
    /* faceSupport: auto (stored as -1), 0 or a number in [1, 4] */
    struct { const char *w; double v; } fs[] = {{"auto", -1}, {"0", 0}, {"1", 1}, {"3", 3}, {"4", 4}};
    for (size_t i = 0; i < sizeof fs / sizeof fs[0]; i++) {
        write_one(d, "faceSupport", fs[i].w);
        if (case_read_umppm(d, &u, &err) != UMP_OK)
            fail_msg("faceSupport %s: %s", fs[i].w, err.msg);
        TU_CLOSE(u.face_support, fs[i].v, 0);
    }
    /* anisotropicCells: auto or any OpenFOAM Switch word */
    struct { const char *w; int v; } an[] = {{"auto", -1}, {"yes", 1}, {"off", 0}, {"y", 1}, {"n", 0},
                                             {"t", 1}, {"f", 0}, {"none", 0}, {"true", 1}};
    for (size_t i = 0; i < sizeof an / sizeof an[0]; i++) {
        write_one(d, "anisotropicCells", an[i].w);
        if (case_read_umppm(d, &u, &err) != UMP_OK)
            fail_msg("anisotropicCells %s: %s", an[i].w, err.msg);
        assert_int_equal(u.anisotropic, an[i].v);
    }
    /* interpolationError: auto (-1), transpose (1) or gradient (0) */
    struct { const char *w; int v; } qe[] = {{"auto", -1}, {"transpose", 1}, {"gradient", 0}};
    for (size_t i = 0; i < sizeof qe / sizeof qe[0]; i++) {
        write_one(d, "interpolationError", qe[i].w);
        if (case_read_umppm(d, &u, &err) != UMP_OK)
            fail_msg("interpolationError %s: %s", qe[i].w, err.msg);
        assert_int_equal(u.q_transpose, qe[i].v);
    }
    /* a pattern key reads as OpenFOAM's (and is not an unknown key) */
    write_umppm(d, "    \"alph.*\" 0.2;\n");
    assert_int_equal(case_read_umppm(d, &u, &err), UMP_OK);
    TU_CLOSE(u.alpha, 0.2, 0);
    /* $macros and #include'd entries are entries like the others */
    write2(d, "system/fvSolution", HDR, "a 0.3;\nUMPPM { alpha $a; }\n");
    assert_int_equal(case_read_umppm(d, &u, &err), UMP_OK);
    TU_CLOSE(u.alpha, 0.3, 0);
    tu_rmtree(d);
}

/* Refused values: the one-line message names file:line, the key, the value
 * and what is allowed. */
static void test_umppm_bad_values(void **state)
{
    (void)state;
    char d[64];
    tu_tmpdir(d, sizeof d);
    mk(d, "system");
    case_umppm u;
    ump_err err;
    struct { const char *key, *value, *msg; } bad[] = {
        {"variant", "foo", "system/fvSolution:4: UMPPM variant 'foo' is not one of: auto UMPPM UMPPMstar UMPPM*"},
        {"variant", "UMPPM star", "system/fvSolution:4: UMPPM variant: expected one word, found word 'UMPPM' ...; "
                                  "allowed auto UMPPM UMPPMstar UMPPM*"},
        {"laplacian", "SPH", "system/fvSolution:4: UMPPM laplacian 'SPH' is not one of: auto CPM MPS IPS PS CPM4"},
        {"pressureTheta", "0.6", "system/fvSolution:4: UMPPM pressureTheta 0.6 is out of range: allowed auto or [0, 0.5]"},
        {"pressureTheta", "half", "system/fvSolution:4: UMPPM pressureTheta: expected a number, found word 'half'; "
                                  "allowed auto or [0, 0.5]"},
        {"faceSupport", "0.5", "system/fvSolution:4: UMPPM faceSupport 0.5 is out of range: allowed auto or 0 or [1, 4]"},
        {"faceSupport", "5", "system/fvSolution:4: UMPPM faceSupport 5 is out of range: allowed auto or 0 or [1, 4]"},
        {"ppeSolver", "MUMPS", "system/fvSolution:4: UMPPM ppeSolver 'MUMPS' is not one of: auto UMFPACK KLU CHOLMOD"},
        {"predictorSolver.preconditioner", "ILU1",
         "system/fvSolution:6: UMPPM predictorSolver.preconditioner 'ILU1' is not one of: ILU0 Jacobi none"},
        {"alpha", "0", "system/fvSolution:4: UMPPM alpha 0 is out of range: allowed (0, 1)"},
        {"alpha", "1", "system/fvSolution:4: UMPPM alpha 1 is out of range: allowed (0, 1)"},
        {"alpha", "1.5", "system/fvSolution:4: UMPPM alpha 1.5 is out of range: allowed (0, 1)"},
        {"alpha", "-0.1", "system/fvSolution:4: UMPPM alpha -0.1 is out of range: allowed (0, 1)"},
        {"alpha", "nan", "system/fvSolution:4: UMPPM alpha nan is out of range: allowed (0, 1)"},
        {"alpha", "big", "system/fvSolution:4: UMPPM alpha: expected a number, found word 'big'; allowed (0, 1)"},
        {"alpha", "{ x 1; }", "system/fvSolution:4: UMPPM alpha: expected a number, found a dictionary; allowed (0, 1)"},
        {"reFactor", "7", "system/fvSolution:4: UMPPM reFactor 7 is out of range: allowed 0 or [1, 4]"},
        {"reFactor", "0.5", "system/fvSolution:4: UMPPM reFactor 0.5 is out of range: allowed 0 or [1, 4]"},
        {"reFactor", "-1", "system/fvSolution:4: UMPPM reFactor -1 is out of range: allowed 0 or [1, 4]"},
        {"writeQuality", "maybe", "system/fvSolution:4: UMPPM writeQuality: expected a switch (yes/no, on/off, "
                                  "true/false, 1/0), found word 'maybe'"},
        {"predictorSolver.tolerance", "0",
         "system/fvSolution:6: UMPPM predictorSolver.tolerance 0 is out of range: allowed > 0"},
        {"predictorSolver.tolerance", "-1e-3",
         "system/fvSolution:6: UMPPM predictorSolver.tolerance -0.001 is out of range: allowed > 0"},
        {"predictorSolver.maxIter", "0",
         "system/fvSolution:6: UMPPM predictorSolver.maxIter 0 is out of range: allowed >= 1"},
        {"predictorSolver.maxIter", "1.5",
         "system/fvSolution:6: UMPPM predictorSolver.maxIter: expected an integer, found scalar 1.5; allowed >= 1"},
        {"sortInterval", "-1", "system/fvSolution:4: UMPPM sortInterval -1 is out of range: allowed >= 0"},
        {"sortInterval", "2.5", "system/fvSolution:4: UMPPM sortInterval: expected an integer, found scalar 2.5; allowed >= 0"},
        {"cloudName", "(a b)", "system/fvSolution:4: UMPPM cloudName: expected one word, found '(' ..."},
        {"cloudName", "a0123456789012345678901234567890123456789012345678901234567890123",
         "system/fvSolution:4: UMPPM cloudName 'a012345678901234567890123456789012345678...' is too long: "
         "at most 63 characters"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        write_one(d, bad[i].key, bad[i].value);
        ump_status rc = case_read_umppm(d, &u, &err);
        if (rc == UMP_OK)
            fail_msg("%s %s accepted", bad[i].key, bad[i].value);
        assert_true(rc == UMP_ERR_INPUT || rc == UMP_ERR_PARSE);
        if (!strstr(err.msg, bad[i].msg) || !strstr(err.msg, d))
            fail_msg("%s %s:\n  got  '%s'\n  want '%s'", bad[i].key, bad[i].value, err.msg, bad[i].msg);
        assert_null(strchr(err.msg, '\n'));
    }
    /* every option of the table: values just outside what it allows */
    size_t n;
    const case_option *t = case_umppm_options(&n);
    for (size_t i = 0; i < n; i++) {
        const case_option *o = &t[i];
        const case_opt_range *r = &o->range;
        char vals[6][64];
        int nv = 0;
        if (o->type == CASE_OPT_CHOICE)
            snprintf(vals[nv++], 64, "bogus");
        if (o->type == CASE_OPT_BOOL)
            snprintf(vals[nv++], 64, "2");
        if (o->type == CASE_OPT_SCALAR || o->type == CASE_OPT_LABEL) {
            double step = o->type == CASE_OPT_LABEL ? 1 : 0.5 * (fabs(r->lo) + fabs(r->hi)) + 0.25;
            if (r->has_lo)
                snprintf(vals[nv++], 64, "%.17g", r->lo - step);
            if (r->has_lo && r->lo_open && !(r->or_zero && r->lo == 0))
                snprintf(vals[nv++], 64, "%.17g", r->lo);
            if (r->has_hi)
                snprintf(vals[nv++], 64, "%.17g", r->hi + step);
            if (r->has_hi && r->hi_open)
                snprintf(vals[nv++], 64, "%.17g", r->hi);
            snprintf(vals[nv++], 64, "word");
        }
        if (o->type == CASE_OPT_WORD)
            snprintf(vals[nv++], 64, "1");
        assert_true(nv > 0);
        char allowed[256], want[512];
        case_option_allowed(o, allowed, sizeof allowed);
        for (int k = 0; k < nv; k++) {
            int line = write_one(d, o->key, vals[k]);
            if (case_read_umppm(d, &u, &err) == UMP_OK)
                fail_msg("%s %s accepted", o->key, vals[k]);
            snprintf(want, sizeof want, "system/fvSolution:%d: UMPPM %s", line, o->key);
            if (!strstr(err.msg, want) || (o->type != CASE_OPT_BOOL && o->type != CASE_OPT_WORD &&
                                           !strstr(err.msg, allowed)))
                fail_msg("%s %s: '%s' lacks '%s' or '%s'", o->key, vals[k], err.msg, want, allowed);
        }
    }
    tu_rmtree(d);
}

static void test_umppm_unknown_keys(void **state)
{
    (void)state;
    char d[64];
    tu_tmpdir(d, sizeof d);
    mk(d, "system");
    case_umppm u;
    ump_err err;
    struct { const char *body, *msg; } bad[] = {
        {"    variant UMPPM;\n    alpah 0.1;\n",
         "system/fvSolution:5: UMPPM: unknown key 'alpah'; known keys: variant alpha laplacian reFactor "
         "writeQuality ppeSolver predictorSolver cloudName sortInterval"},
        {"    predictorSolver\n    {\n        tol 1e-6;\n    }\n",
         "system/fvSolution:6: UMPPM predictorSolver: unknown key 'tol'; known keys: preconditioner tolerance "
         "maxIter"},
        {"    \"zz.*\" 1;\n", "system/fvSolution:4: UMPPM: unknown key 'zz.*'; known keys: variant"},
        {"    predictorSolver 3;\n",
         "system/fvSolution:4: UMPPM predictorSolver must be a dictionary { ... }, found label 3"},
        {"    tolerance 1e-6;\n", "system/fvSolution:4: UMPPM: unknown key 'tolerance'"},
        {"    sub { alpha 0.1; }\n", "system/fvSolution:4: UMPPM: unknown key 'sub'"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        write_umppm(d, bad[i].body);
        assert_int_equal(case_read_umppm(d, &u, &err), UMP_ERR_INPUT);
        if (!strstr(err.msg, bad[i].msg))
            fail_msg("case %zu:\n  got  '%s'\n  want '%s'", i, err.msg, bad[i].msg);
    }
    /* UMPPM that is not a dictionary */
    write2(d, "system/fvSolution", HDR, "PISO { }\nUMPPM 3;\n");
    assert_int_equal(case_read_umppm(d, &u, &err), UMP_ERR_INPUT);
    if (!strstr(err.msg, "system/fvSolution:3: UMPPM must be a dictionary { ... }, found label 3"))
        fail_msg("%s", err.msg);
    write2(d, "system/fvSolution", HDR, "UMPPM UMPPMstar;\n");
    assert_int_equal(case_read_umppm(d, &u, &err), UMP_ERR_INPUT);
    assert_non_null(strstr(err.msg, "UMPPM must be a dictionary { ... }, found word 'UMPPMstar'"));
    /* a missing fvSolution stays an I/O error */
    char path[128];
    snprintf(path, sizeof path, "%s/system/fvSolution", d);
    remove(path);
    assert_int_equal(case_read_umppm(d, &u, &err), UMP_ERR_IO);
    tu_rmtree(d);
}

/* umppmFoam -help: heading, then every key with its default, allowed values
 * and help line. */
static void test_umppm_help(void **state)
{
    (void)state;
    size_t len = case_umppm_help(NULL, 0);
    assert_true(len > 100);
    char *text = malloc(len + 1);
    assert_int_equal(case_umppm_help(text, len + 1), len);
    assert_int_equal(strlen(text), len);
    assert_non_null(strstr(text, "UMPPM dictionary (system/fvSolution)"));
    assert_non_null(strstr(text, "unknown keys are refused"));
    size_t n;
    const case_option *t = case_umppm_options(&n);
    for (size_t i = 0; i < n; i++) {
        char allowed[256], row[512];
        case_option_allowed(&t[i], allowed, sizeof allowed);
        snprintf(row, sizeof row, "\n  %s ", t[i].key);
        const char *p = strstr(text, row);
        if (!p)
            fail_msg("-help lacks %s", t[i].key);
        p++;
        /* key, default and allowed on one line, the help on the next */
        const char *eol = strchr(p, '\n');
        snprintf(row, sizeof row, "%.*s", (int)(eol - p), p);
        if (!strstr(row, t[i].default_text) || !strstr(row, allowed))
            fail_msg("-help row '%s' lacks '%s' or '%s'", row, t[i].default_text, allowed);
        snprintf(row, sizeof row, "\n      %s\n", t[i].help);
        if (!strstr(eol, row))
            fail_msg("-help lacks the help of %s", t[i].key);
    }
    /* lines fit a terminal */
    for (const char *p = text; *p;) {
        const char *e = strchr(p, '\n');
        size_t l = e ? (size_t)(e - p) : strlen(p);
        if (l > 79)
            fail_msg("-help line longer than 79: '%.*s'", (int)l, p);
        p += l + (e != NULL);
    }
    /* truncated output is NUL-terminated and reports the full length */
    char small[16];
    assert_int_equal(case_umppm_help(small, sizeof small), len);
    assert_int_equal(strlen(small), sizeof small - 1);
    free(text);
}

/* README.md's Settings table has one row per option: key, default, allowed. */
static void test_umppm_readme(void **state)
{
    (void)state;
    FILE *fp = fopen("README.md", "rb");
    if (!fp)
        skip();
    static char text[1 << 20];
    size_t len = fread(text, 1, sizeof text - 1, fp);
    fclose(fp);
    text[len] = '\0';
    const char *table = strstr(text, "| key | default | allowed | meaning |");
    assert_non_null(table);
    const char *end = strstr(table, "\n\n");
    assert_non_null(end);
    size_t n, rows = 0;
    const case_option *t = case_umppm_options(&n);
    for (size_t i = 0; i < n; i++) {
        char allowed[256], row[512];
        case_option_allowed(&t[i], allowed, sizeof allowed);
        snprintf(row, sizeof row, "\n| `%s` | `%s` | `%s` | ", t[i].key, t[i].default_text, allowed);
        const char *p = strstr(table, row);
        if (!p || p > end)
            fail_msg("README.md Settings table lacks the row '%s'", row + 1);
    }
    for (const char *p = table; p && p < end; p = strchr(p + 1, '\n'))
        rows += p[1] == '|' && p[2] == ' ' && p[3] == '`';
    assert_int_equal(rows, n);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_control_defaults),
        cmocka_unit_test(test_control_stop_at_and_stamp),
        cmocka_unit_test(test_transport_and_solution),
        cmocka_unit_test(test_times),
        cmocka_unit_test(test_refusals),
        cmocka_unit_test(test_field_matching),
        cmocka_unit_test(test_field_new_bcs),
        cmocka_unit_test(test_umppm_table),
        cmocka_unit_test(test_umppm_defaults),
        cmocka_unit_test(test_umppm_values),
        cmocka_unit_test(test_umppm_bad_values),
        cmocka_unit_test(test_umppm_unknown_keys),
        cmocka_unit_test(test_umppm_help),
        cmocka_unit_test(test_umppm_readme),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
