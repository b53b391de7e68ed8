/* SPDX-License-Identifier: GPL-3.0-or-later
 * test_function1.c -- OpenFOAM v1912's Function1 (src/function1.c):
 * constant, table (linear interpolation, clamp, repeat), sine and square
 * in every form v1912 reads, against closed forms and against the values
 * the installed v1912 icoFoam wrote for the same entries (a lid velocity
 * uniformFixedValue in the cavity, 2026-12-03, writePrecision 6), and the
 * refusals with their messages.
 */
#include "testutil.h"
#include "umppm/function1.h"

/* Parse text as a dictionary file and read its Function1 entry v. */
static ump_status read_text(const char *text, int ncomp, unsigned flags, f1 **out, ump_err *err)
{
    foam_file *f = NULL;
    ump_status rc = foam_file_parse("f1test", text, strlen(text), &f, err);
    if (rc == UMP_OK)
        rc = f1_read(f->dict, "v", ncomp, flags, "patch 'lid': uniformValue", out, err);
    foam_file_free(&f);
    return rc;
}

static f1 *must_read(const char *text, int ncomp)
{
    f1 *fn = NULL;
    ump_err err;
    if (read_text(text, ncomp, F1_PATCH, &fn, &err) != UMP_OK)
        fail_msg("'%s': %s", text, err.msg);
    return fn;
}

static double at(const f1 *fn, double t)
{
    double v[3];
    f1_value(fn, t, v);
    return v[0];
}

static void expect_error(const char *text, int ncomp, const char *msg)
{
    f1 *fn = NULL;
    ump_err err;
    assert_int_not_equal(read_text(text, ncomp, F1_PATCH, &fn, &err), UMP_OK);
    assert_null(fn);
    if (!strstr(err.msg, msg))
        fail_msg("'%s': error '%s' lacks '%s'", text, err.msg, msg);
    if (!strstr(err.msg, "f1test:"))
        fail_msg("'%s': error '%s' does not name the file", text, err.msg);
}

static void test_constant(void **state)
{
    (void)state;
    const char *forms[] = {"v 1.5;", "v constant 1.5;", "v uniform 1.5;"};
    for (size_t i = 0; i < 3; i++) {
        f1 *fn = must_read(forms[i], 1);
        assert_int_equal(fn->kind, F1_CONSTANT);
        assert_true(at(fn, 0) == 1.5 && at(fn, 1e6) == 1.5);
        f1_free(&fn);
        assert_null(fn);
    }
    const char *vforms[] = {"v (1 -2 3);", "v constant (1 -2 3);", "v uniform (1 -2 3);"};
    for (size_t i = 0; i < 3; i++) {
        f1 *fn = must_read(vforms[i], 3);
        double v[3];
        f1_value(fn, 7, v);
        assert_true(v[0] == 1 && v[1] == -2 && v[2] == 3);
        assert_true(fabs(f1_max_abs(fn) - sqrt(14)) < 1e-15);
        f1_free(&fn);
    }
    f1_free(NULL);
}

static void test_table(void **state)
{
    (void)state;
    f1 *fn = must_read("v table ((0 0) (1 10) (3 30));", 1);
    assert_int_equal(fn->kind, F1_TABLE);
    assert_int_equal(fn->n, 3);
    assert_true(at(fn, 0.5) == 5);                 /* linear */
    assert_true(fabs(at(fn, 2.2) - 22) < 1e-14);
    assert_true(at(fn, 1) == 10 && at(fn, 3) == 30); /* rows */
    assert_true(at(fn, -1) == 0 && at(fn, 1e9) == 30); /* clamp, the default */
    assert_true(f1_max_abs(fn) == 30);
    f1 *cp = NULL;
    ump_err err;
    assert_int_equal(f1_copy(fn, &cp, &err), UMP_OK);
    f1_free(&fn);
    assert_true(at(cp, 0.5) == 5); /* the copy owns its rows */
    f1_free(&cp);

    /* as OpenFOAM writes it: N((...)...), vector rows; the v1912 lid run:
     * table ((0 (0 0 0)) (0.15 (1.5 0 0))) gave 1 at t = 0.1, 1.5 at 0.2 */
    fn = must_read("v table 2((0 (0 0 0)) (0.15 (1.5 0 0)));", 3);
    double v[3];
    f1_value(fn, 0.1, v);
    assert_true(fabs(v[0] - 1) < 1e-14 && v[1] == 0 && v[2] == 0);
    f1_value(fn, 0.2, v);
    assert_true(v[0] == 1.5);
    f1_free(&fn);

    /* outOfBounds repeat (in the entry's dictionary or in vCoeffs): v1912
     * gave 1, 0.5, 4.996e-16 at t = 0.1, 0.2, 0.3 for the table above */
    const char *rep[] = {"v table ((0 0) (0.15 1.5)); outOfBounds repeat;",
                         "v table ((0 0) (0.15 1.5)); vCoeffs { outOfBounds repeat; }"};
    for (int i = 0; i < 2; i++) {
        fn = must_read(rep[i], 1);
        assert_true(fabs(at(fn, 0.1) - 1) < 1e-14);
        assert_true(fabs(at(fn, 0.2) - 0.5) < 1e-12);
        assert_true(fabs(at(fn, 0.3)) < 1e-12);
        f1_free(&fn);
    }
    fn = must_read("v table ((0.1 (1 0 0)));", 3); /* one row: constant */
    assert_true(at(fn, 0) == 1 && at(fn, 5) == 1);
    f1_free(&fn);
}

static void test_sine(void **state)
{
    (void)state;
    /* amplitude sin(2 pi frequency (t - t0)) scale + level, closed form */
    f1 *fn = must_read("v sine; vCoeffs { amplitude 2; frequency 1.5; scale 3; level 0.5; t0 0.05; }", 1);
    assert_int_equal(fn->kind, F1_SINE);
    for (double t = 0; t < 2; t += 0.137)
        assert_true(fabs(at(fn, t) - (2 * sin(2 * UMP_PI * 1.5 * (t - 0.05)) * 3 + 0.5)) < 1e-14);
    assert_true(f1_max_abs(fn) == 6.5);
    f1_free(&fn);

    /* the v1912 lid runs (uniformValue sine, scale (1 0 0), written
     * values at t = 0.1 0.2 0.3 in 6 digits) */
    static const struct { const char *text; double v[3]; } runs[] = {
        {"v sine; vCoeffs { amplitude 2; frequency 1; scale (1 0 0); level (0.5 0 0); }",
         {1.67557, 2.40211, 2.40211}},
        {"v sine; vCoeffs { amplitude 2; frequency 1; scale (1 0 0); level (0.5 0 0); t0 0.05; }",
         {1.11803, 2.11803, 2.5}},
        {"v sine; amplitude 2; frequency 1; scale (1 0 0); level (0.5 0 0);", /* inline coefficients */
         {1.67557, 2.40211, 2.40211}},
        {"v sine; vCoeffs { amplitude table ((0 0) (1 10)); frequency table ((0 1) (1 2)); "
         "scale (1 0 0); level (0.5 0 0); }", /* Function1 amplitude and frequency */
         {1.13742, 2.49605, 2.41227}},
        {"v { type sine; amplitude 1; frequency 1; scale (1 0 0); level (0 0 0); }", /* dictionary form */
         {0.587785, 0.951057, 0.951057}},
    };
    for (size_t i = 0; i < sizeof runs / sizeof runs[0]; i++) {
        fn = must_read(runs[i].text, 3);
        for (int k = 0; k < 3; k++) {
            double v[3];
            f1_value(fn, 0.1 * (k + 1), v);
            if (fabs(v[0] - runs[i].v[k]) > 5e-6 || v[1] != 0 || v[2] != 0)
                fail_msg("'%s' at t = %g: %.9g, v1912 wrote %g", runs[i].text, 0.1 * (k + 1), v[0],
                         runs[i].v[k]);
        }
        f1_free(&fn);
    }
}

static void test_square(void **state)
{
    (void)state;
    /* v1912 lid runs, amplitude 1, frequency 2, scale (1 0 0), level 0, at
     * t = 0.1 0.2 0.3: markSpace 3 -> 1 1 1; default (1) -> 1 1 -1;
     * t0 0.35 (negative phase, modf keeps the sign) -> 1 1 1 */
    static const struct { const char *text; double v[3]; } runs[] = {
        {"v square; amplitude 1; frequency 2; scale (1 0 0); level (0 0 0); markSpace 3;", {1, 1, 1}},
        {"v square; amplitude 1; frequency 2; scale (1 0 0); level (0 0 0);", {1, 1, -1}},
        {"v square; amplitude 1; frequency 2; scale (1 0 0); level (0 0 0); t0 0.35;", {1, 1, 1}},
        {"v { type square; amplitude 1; frequency 2; scale (1 0 0); level (0 0 0); }", {1, 1, -1}},
    };
    for (size_t i = 0; i < sizeof runs / sizeof runs[0]; i++) {
        f1 *fn = must_read(runs[i].text, 3);
        assert_int_equal(fn->kind, F1_SQUARE);
        for (int k = 0; k < 3; k++)
            if (at(fn, 0.1 * (k + 1)) != runs[i].v[k])
                fail_msg("'%s' at t = %g: %g, v1912 wrote %g", runs[i].text, 0.1 * (k + 1), at(fn, 0.1 * (k + 1)),
                         runs[i].v[k]);
        f1_free(&fn);
    }
    /* closed form: mark fraction markSpace/(1 + markSpace) of each period */
    f1 *fn = must_read("v square; amplitude 2; frequency 0.5; scale 1; level 3; markSpace 0.25;", 1);
    assert_true(at(fn, 0.1) == 5);  /* phase 0.05 < 0.2 */
    assert_true(at(fn, 0.5) == 1);  /* phase 0.25 >= 0.2 */
    assert_true(at(fn, 2.3) == 5);  /* phase 1.15: fraction 0.15 */
    assert_true(f1_max_abs(fn) == 5);
    f1_free(&fn);
}

static void test_refusals(void **state)
{
    (void)state;
    expect_error("v foo 1;", 1, "f1test:1: patch 'lid': uniformValue: Function1 type 'foo' is not implemented");
    expect_error("v polynomial ((1 0));", 1, "Function1 type 'polynomial' is not implemented");
    expect_error("v { type csvFile; }", 1, "Function1 type 'csvFile' is not implemented");
    expect_error("v nonuniform List<scalar> 2(1 2);", 1, "'nonuniform' (a value per face) is not implemented");
    expect_error("w 1;", 1, "keyword 'v' is undefined");
    expect_error("v sine; vCoeffs { frequency 1; scale 1; level 0; }", 1, "sine needs 'amplitude'");
    expect_error("v sine; vCoeffs { amplitude 1; scale 1; level 0; }", 1, "sine needs 'frequency'");
    expect_error("v square; amplitude 1; frequency 1; level 0;", 1, "square needs 'scale'");
    expect_error("v sine; amplitude 1; frequency 1; scale 1;", 1, "sine needs 'level'");
    expect_error("v sine; amplitude 1; frequency 1; scale 1; level 0; start 0.5;", 1,
                 "key 'start' is the OpenFOAM Foundation's");
    expect_error("v sine; amplitude sine; frequency 1; scale 1; level 0;", 1, "nested more than");
    expect_error("v sine; amplitude foo; frequency 1; scale 1; level 0;", 1,
                 "uniformValue: sine amplitude: Function1 type 'foo'");
    expect_error("v { type table; values ((0 0) (1 1)); }", 1, "reads a table only inline");
    expect_error("v { type constant; value 1; }", 1, "reads a constant only inline");
    expect_error("v table ();", 1, "the table is empty");
    expect_error("v table ((0 0) (0 1));", 1, "table times must increase");
    expect_error("v table 3((0 0) (1 1));", 1, "the table says 3 rows but has 2");
    expect_error("v table ((0 0 1));", 1, "a table row is (t value)");
    expect_error("v table ((0 (1 0)));", 3, "expected a number, found ')'");
    expect_error("v table ((0 0) (1 1)); outOfBounds error;", 1, "outOfBounds 'error' is not implemented");
    expect_error("v table ((0 0) (1 1)); outOfBounds warn;", 1, "outOfBounds 'warn' is not implemented");
    expect_error("v table ((0 0) (1 1)); interpolationScheme step;", 1, "interpolationScheme 'step'");
    expect_error("v (1 2);", 3, "expected a number, found ')'");
    expect_error("v 1 2;", 1, "unexpected");
    expect_error("v constant 1 2;", 1, "unexpected");
    expect_error("v sine 1; amplitude 1; frequency 1; scale 1; level 0;", 1, "unexpected");
    expect_error("v square; amplitude 1; frequency 1; scale 1; level 0; markSpace -1;", 1, "markSpace >= 0");
}

/* Allocation failures anywhere in reading a nested Function1 are errors,
 * never crashes or leaks (the sanitizer build checks the leaks). */
static void test_out_of_memory(void **state)
{
    (void)state;
    const char *text = "v sine; vCoeffs { amplitude table ((0 0) (1 10)); frequency 1; scale (1 0 0); "
                       "level (0 0 0); }";
    foam_file *f = NULL;
    ump_err err;
    assert_int_equal(foam_file_parse("f1test", text, strlen(text), &f, &err), UMP_OK);
    int failed = 0;
    for (long k = 0; k < 40; k++) {
        f1 *fn = NULL, *cp = NULL;
        ump_alloc_fail_after(k);
        ump_status rc = f1_read(f->dict, "v", 3, 0, "v", &fn, &err);
        if (rc == UMP_OK)
            rc = f1_copy(fn, &cp, &err);
        ump_alloc_fail_after(-1);
        if (rc != UMP_OK) {
            assert_int_equal(rc, UMP_ERR_NOMEM);
            failed++;
        }
        f1_free(&fn);
        f1_free(&cp);
    }
    assert_true(failed > 0);
    foam_file_free(&f);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_constant),
        cmocka_unit_test(test_table),
        cmocka_unit_test(test_sine),
        cmocka_unit_test(test_square),
        cmocka_unit_test(test_refusals),
        cmocka_unit_test(test_out_of_memory),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
