/* SPDX-License-Identifier: GPL-3.0-or-later
 * test_funcobj.c -- controlDict function objects: reading, the
 * surfaceFieldValue operations, the written file, errors naming the line.
 */
#include "testutil.h"
#include "umppm/funcobj.h"

#include <sys/stat.h>

#define HEADER "FoamFile { version 2.0; format ascii; class dictionary; object controlDict; }\n"

static void write_control(const char *dir, const char *functions)
{
    char sys[256], text[4096];
    snprintf(sys, sizeof sys, "%s/system", dir);
    if (mkdir(sys, 0755) != 0)
        fail_msg("mkdir %s", sys);
    snprintf(text, sizeof text, HEADER "application umppmFoam;\nfunctions\n{\n%s}\n", functions);
    tu_write(sys, "controlDict", text);
}

static void test_read_surface_field_value(void **state)
{
    (void)state;
    char dir[64];
    tu_tmpdir(dir, sizeof dir);
    write_control(dir, "pIn { type surfaceFieldValue; libs (\"libfieldFunctionObjects.so\");\n"
                       " regionType patch; name inlet; operation areaAverage; fields (p U);\n"
                       " writeFields false; writeControl timeStep; writeInterval 5; }\n"
                       "probes1 { type probes; }\n");
    fob_list L;
    ump_err err;
    assert_int_equal(fob_read(dir, &L, &err), UMP_OK);
    assert_int_equal(L.nsf, 1);
    assert_int_equal(L.n, 0);
    assert_string_equal(L.sf[0].c.name, "pIn");
    assert_string_equal(L.sf[0].c.patch, "inlet");
    assert_int_equal(L.sf[0].op, FOB_AREA_AVERAGE);
    assert_int_equal(L.sf[0].nfields, 2);
    assert_int_equal(L.sf[0].field[1], FOB_FIELD_U);
    assert_int_equal(L.sf[0].c.interval, 5);
    assert_non_null(strstr(L.ignored, "probes1 (probes)"));
    assert_true(fob_due(&L.sf[0].c, 10, 0));
    assert_false(fob_due(&L.sf[0].c, 11, 0));
    fob_free(&L);
    tu_rmtree(dir);
}

static void expect_error(const char *functions, const char *msg)
{
    char dir[64];
    tu_tmpdir(dir, sizeof dir);
    write_control(dir, functions);
    fob_list L;
    ump_err err;
    assert_int_not_equal(fob_read(dir, &L, &err), UMP_OK);
    if (!strstr(err.msg, msg))
        fail_msg("error '%s' lacks '%s'", err.msg, msg);
    assert_non_null(strstr(err.msg, "controlDict:"));
    tu_rmtree(dir);
}

static void test_bad_entries(void **state)
{
    (void)state;
    expect_error("a { type surfaceFieldValue; regionType faceZone; name z; operation sum; fields (p); }\n",
                 "regionType 'faceZone' is not supported");
    expect_error("a { type surfaceFieldValue; regionType patch; name in;\n operation mean; fields (p); }\n",
                 ":6: function object 'a': operation 'mean' is not one of");
    expect_error("a { type surfaceFieldValue; regionType patch; name in; operation sum; fields p; }\n",
                 "expected 'fields (f1 f2 ...);'");
    expect_error("a { type surfaceFieldValue; regionType patch; name in; operation sum; fields (); }\n",
                 "expected 'fields (f1 f2 ...);'");
    expect_error("a { type surfaceFieldValue; regionType patch; name in; operation sum; fields (p k); }\n",
                 "field 'k' is not one of: U p T p_rgh");
    expect_error("a { type surfaceFieldValue; regionType patch; name in; operation sum; fields (p);\n"
                 " writeFields true; }\n",
                 "writeFields true is not supported");
}

/* Three faces of areas 1, 2, 3 with p = 3, 6, 9: sum 18, average 6,
 * areaAverage (3 + 12 + 27) / 6 = 7, areaIntegrate 42, min 3, max 9. */
static void test_operations(void **state)
{
    (void)state;
    const double area[] = {1, 2, 3}, p[] = {3, 6, 9};
    const double U[] = {1, 0, 0, 2, -1, 0, 4, 1, 0};
    fob_patch_field d = {3, 1, area, p}, dU = {3, 3, area, U};
    fob_sfv f;
    memset(&f, 0, sizeof f);
    const struct { fob_op op; double p, Ux, Uy; } want[] = {
        {FOB_SUM, 18, 7, 0},          {FOB_AVERAGE, 6, 7.0 / 3, 0},    {FOB_AREA_AVERAGE, 7, 17.0 / 6, 1.0 / 6},
        {FOB_AREA_INTEGRATE, 42, 17, 1}, {FOB_MIN, 3, 1, -1}, {FOB_MAX, 9, 4, 1},
    };
    for (size_t i = 0; i < sizeof want / sizeof *want; i++) {
        double out[3];
        f.op = want[i].op;
        fob_sfv_eval(&f, &d, out);
        TU_CLOSE(out[0], want[i].p, 1e-14);
        fob_sfv_eval(&f, &dU, out);
        TU_CLOSE(out[0], want[i].Ux, 1e-14);
        TU_CLOSE(out[1], want[i].Uy, 1e-14);
    }
}

/* The time series file: OpenFOAM's header, one row per call, and a second
 * run from the same start time keeps the first file. */
static void test_append(void **state)
{
    (void)state;
    char dir[64], path[4200], line[512];
    tu_tmpdir(dir, sizeof dir);
    fob_sfv f;
    memset(&f, 0, sizeof f);
    snprintf(f.c.name, sizeof f.c.name, "dp");
    snprintf(f.c.patch, sizeof f.c.patch, "outlet");
    f.op = FOB_AREA_AVERAGE;
    f.nfields = 2;
    f.field[0] = FOB_FIELD_P;
    f.field[1] = FOB_FIELD_U;
    const double area[] = {0.5, 0.5}, p[] = {1, 3}, U[] = {1, 0, 0, 1, 0, 0};
    fob_patch_field vals[2] = {{2, 1, area, p}, {2, 3, area, U}};
    ump_err err;
    assert_int_equal(fob_sfv_append(&f, dir, "0", 0.5, vals, 6, &err), UMP_OK);
    assert_int_equal(fob_sfv_append(&f, dir, "0", 1.0, vals, 6, &err), UMP_OK);
    fclose(f.c.fp);
    snprintf(path, sizeof path, "%s/postProcessing/dp/0/surfaceFieldValue.dat", dir);
    FILE *fp = fopen(path, "r");
    assert_non_null(fp);
    int rows = 0, header = 0;
    while (fgets(line, sizeof line, fp)) {
        if (line[0] == '#') {
            header++;
            if (strstr(line, "Time"))
                assert_non_null(strstr(line, "areaAverage(p)\tareaAverage(U)"));
            continue;
        }
        double t, pv, ux;
        assert_int_equal(sscanf(line, "%lf %lf (%lf", &t, &pv, &ux), 3);
        TU_CLOSE(pv, 2, 1e-14);
        TU_CLOSE(ux, 1, 1e-14);
        rows++;
    }
    fclose(fp);
    assert_int_equal(rows, 2);
    assert_int_equal(header, 5);
    memset(&f.c.fp, 0, sizeof f.c.fp);
    assert_int_equal(fob_sfv_append(&f, dir, "0", 1.5, vals, 6, &err), UMP_OK);
    fclose(f.c.fp);
    assert_non_null(strstr(f.c.path, "surfaceFieldValue_0.dat"));
    tu_rmtree(dir);
}

/* runTimeModifiable: after a re-read, an unchanged function object
 * continues its series in the same file; a changed or new one starts its
 * own, suffixed with the time of the re-read when the name is taken. */
static void test_take_over(void **state)
{
    (void)state;
    char dir[64], path[1024];
    tu_tmpdir(dir, sizeof dir);
    write_control(dir, "a { type surfaceFieldValue; regionType patch; name inlet; operation sum; fields (p); }\n"
                       "b { type surfaceFieldValue; regionType patch; name inlet; operation sum; fields (p); }\n");
    fob_list old, nw;
    ump_err err;
    assert_int_equal(fob_read(dir, &old, &err), UMP_OK);
    const double area[] = {1}, p[] = {2};
    fob_patch_field v[1] = {{1, 1, area, p}};
    for (int i = 0; i < 2; i++)
        assert_int_equal(fob_sfv_append(&old.sf[i], dir, "0", 0.1, v, 6, &err), UMP_OK);
    FILE *fa = old.sf[0].c.fp;
    /* a unchanged, b with another operation, c new */
    snprintf(path, sizeof path, "%s/system", dir);
    tu_write(path, "controlDict", HEADER "functions\n{\n"
             "a { type surfaceFieldValue; regionType patch; name inlet; operation sum; fields (p); }\n"
             "b { type surfaceFieldValue; regionType patch; name inlet; operation max; fields (p); }\n"
             "c { type surfaceFieldValue; regionType patch; name inlet; operation sum; fields (p); }\n}\n");
    assert_int_equal(fob_read(dir, &nw, &err), UMP_OK);
    fob_take_over(&nw, &old, "0.3");
    assert_true(nw.sf[0].c.continued && nw.sf[0].c.fp == fa && old.sf[0].c.fp == NULL);
    assert_false(nw.sf[1].c.continued);
    assert_null(nw.sf[1].c.fp);
    assert_false(nw.sf[2].c.continued);
    fob_free(&old); /* closes b's old series, not a's */
    for (int i = 0; i < 3; i++)
        assert_int_equal(fob_sfv_append(&nw.sf[i], dir, "0", 0.35, v, 6, &err), UMP_OK);
    assert_non_null(strstr(nw.sf[0].c.path, "/a/0/surfaceFieldValue.dat"));
    assert_non_null(strstr(nw.sf[1].c.path, "/b/0/surfaceFieldValue_0.3.dat"));
    assert_non_null(strstr(nw.sf[2].c.path, "/c/0/surfaceFieldValue.dat"));
    fob_free(&nw);
    /* a's file: one header, both rows */
    snprintf(path, sizeof path, "%s/postProcessing/a/0/surfaceFieldValue.dat", dir);
    FILE *fp = fopen(path, "r");
    assert_non_null(fp);
    char line[512];
    int rows = 0, times = 0;
    while (fgets(line, sizeof line, fp)) {
        rows += line[0] != '#';
        times += strstr(line, "# Time") != NULL;
    }
    fclose(fp);
    assert_int_equal(rows, 2);
    assert_int_equal(times, 1);
    tu_rmtree(dir);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_read_surface_field_value),
        cmocka_unit_test(test_bad_entries),
        cmocka_unit_test(test_operations),
        cmocka_unit_test(test_append),
        cmocka_unit_test(test_take_over),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
