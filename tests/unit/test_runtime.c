/* SPDX-License-Identifier: GPL-3.0-or-later
 * test_runtime.c -- OpenFOAM Time logic (runtime.c) against sequences seen
 * in icoFoam and pimpleFoam v1912 runs of the cavity case. The pimpleFoam
 * runs printed with writePrecision 17, so every logged deltaT reads back as
 * the exact double OpenFOAM used and is compared exactly.
 */
#include "testutil.h"

#include "umppm/runtime.h"

static case_control ctl_defaults(void)
{
    case_control c;
    memset(&c, 0, sizeof c);
    snprintf(c.application, sizeof c.application, "icoFoam");
    c.start_from = CASE_START_STARTTIME;
    c.stop_at = CASE_STOP_ENDTIME;
    c.write_control = CASE_WRITE_TIMESTEP;
    c.write_precision = 6;
    c.time_precision = 6;
    c.max_co = 1;
    c.max_delta_t = 1e300;
    return c;
}

static void test_names(void **state)
{
    (void)state;
    char b[64];
    rt_name(0.1, 6, 0, b, sizeof b);
    assert_string_equal(b, "0.1");
    rt_name(1e-05, 6, 0, b, sizeof b);
    assert_string_equal(b, "1e-05");
    rt_name(2e-05, 6, 0, b, sizeof b);
    assert_string_equal(b, "2e-05");
    rt_name(0, 6, 0, b, sizeof b);
    assert_string_equal(b, "0");
    rt_name(1000.005, 6, 0, b, sizeof b);
    assert_string_equal(b, "1000");
    rt_name(1000.005, 7, 0, b, sizeof b);
    assert_string_equal(b, "1000.005");
    rt_name(0.00370370367, 6, 1, b, sizeof b);
    assert_string_equal(b, "0.003704");
    rt_name(0.1, 6, 1, b, sizeof b);
    assert_string_equal(b, "0.100000");
    rt_name(0.1, 3, 2, b, sizeof b);
    assert_string_equal(b, "1.000e-01");
    rt_name(123456789.0, 6, 0, b, sizeof b);
    assert_string_equal(b, "1.23457e+08");
}

/* icoFoam cavity: deltaT 0.005, endTime 0.5, writeControl timeStep 20. */
static void test_cavity_timestep(void **state)
{
    (void)state;
    case_control c = ctl_defaults();
    c.end_time = 0.5;
    c.delta_t = 0.005;
    c.write_interval = 20;
    rt_time t;
    rt_init(&t, &c, 0, "0");
    assert_string_equal(t.name, "0");
    assert_int_equal(t.index, 0);
    const char *expect[] = {"0.1", "0.2", "0.3", "0.4", "0.5"};
    int nw = 0, steps = 0;
    while (rt_running(&t)) {
        rt_advance(&t);
        steps++;
        if (t.write_time) {
            assert_true(nw < 5);
            assert_string_equal(t.name, expect[nw]);
            assert_int_equal(t.index, 20 * (nw + 1));
            nw++;
        }
        assert_false(t.precision_raised);
    }
    assert_int_equal(steps, 100);
    assert_int_equal(nw, 5);
    /* uniform/time of 0.1 says 0.100000000000000019: the value is the sum */
    char b[64];
    rt_init(&t, &c, 0, NULL);
    for (int i = 0; i < 20; i++)
        rt_advance(&t);
    snprintf(b, sizeof b, "%.18g", t.value);
    assert_string_equal(b, "0.100000000000000019");
    assert_true(t.delta_t == 0.005 && t.delta_t0 == 0.005);
}

/* deltaT 1e-05, writeInterval 1: directories 1e-05 2e-05 3e-05. */
static void test_small_deltat_names(void **state)
{
    (void)state;
    case_control c = ctl_defaults();
    c.end_time = 3e-05;
    c.delta_t = 1e-05;
    c.write_interval = 1;
    rt_time t;
    rt_init(&t, &c, 0, "0");
    const char *expect[] = {"1e-05", "2e-05", "3e-05"};
    int n = 0;
    while (rt_running(&t)) {
        rt_advance(&t);
        assert_true(n < 3);
        assert_true(t.write_time);
        assert_string_equal(t.name, expect[n]);
        n++;
    }
    assert_int_equal(n, 3);
}

/* icoFoam from 999.98 to 1000.01 by 0.005, writing every step: at 1000.005
 * "Increased the timePrecision from 6 to 7", and 7 is kept. */
static void test_precision_raise(void **state)
{
    (void)state;
    case_control c = ctl_defaults();
    c.start_time = 999.98;
    c.end_time = 1000.01;
    c.delta_t = 0.005;
    c.write_interval = 1;
    rt_time t;
    rt_init(&t, &c, 999.98, "999.98");
    assert_int_equal(t.precision, 6);
    const char *expect[] = {"999.985", "999.99", "999.995", "1000", "1000.005", "1000.01"};
    int n = 0;
    while (rt_running(&t)) {
        rt_advance(&t);
        assert_true(n < 6);
        assert_string_equal(t.name, expect[n]);
        assert_true(t.write_time);
        assert_int_equal(t.precision_raised, n == 4);
        assert_int_equal(t.precision, n >= 4 ? 7 : 6);
        n++;
    }
    assert_int_equal(n, 6);

    /* not raised when the step is not written (writeInterval 100): the log
     * shows "Time = 1000" twice */
    c.write_interval = 100;
    rt_init(&t, &c, 999.98, "999.98");
    const char *expect2[] = {"999.985", "999.99", "999.995", "1000", "1000", "1000.01"};
    n = 0;
    while (rt_running(&t)) {
        rt_advance(&t);
        assert_string_equal(t.name, expect2[n]);
        assert_false(t.write_time);
        assert_false(t.precision_raised);
        n++;
    }
    assert_int_equal(n, 6);
    assert_int_equal(t.precision, 6);
}

/* Starting from a directory named with more digits than timePrecision. */
static void test_init_precision(void **state)
{
    (void)state;
    case_control c = ctl_defaults();
    c.delta_t = 0.005;
    c.end_time = 1001;
    rt_time t;
    rt_init(&t, &c, 1000.005, "1000.005");
    assert_int_equal(t.precision, 7);
    assert_string_equal(t.name, "1000.005");
    /* a name that no precision reproduces is kept, precision unchanged */
    rt_init(&t, &c, 0.5, "0.50");
    assert_int_equal(t.precision, 6);
    assert_string_equal(t.name, "0.50");
    rt_init(&t, &c, 0.5, NULL);
    assert_string_equal(t.name, "0.5");
}

/* runTime: write when int((t - start + deltaT/2)/interval) grows. */
static void test_runtime_writes(void **state)
{
    (void)state;
    case_control c = ctl_defaults();
    c.write_control = CASE_WRITE_RUNTIME;
    c.delta_t = 0.001;
    c.write_interval = 0.0123;
    c.end_time = 0.04;
    rt_time t;
    rt_init(&t, &c, 0, "0");
    long written[8];
    int n = 0;
    while (rt_running(&t)) {
        rt_advance(&t);
        if (t.write_time)
            written[n++] = t.index;
    }
    assert_int_equal(n, 3);
    assert_int_equal(written[0], 12);
    assert_int_equal(written[1], 25);
    assert_int_equal(written[2], 37);
    assert_int_equal(t.write_index, 3);
    assert_int_equal(t.index, 40);

    /* counted from the start time (pimpleFoam from 0.5003 wrote 0.5073...) */
    c.start_time = 0.5003;
    c.end_time = 0.52;
    c.delta_t = 0.0001;
    c.write_interval = 0.007;
    rt_init(&t, &c, 0.5003, "0.5003");
    n = 0;
    char names[4][64];
    while (rt_running(&t)) {
        rt_advance(&t);
        if (t.write_time)
            snprintf(names[n++], 64, "%s", t.name);
    }
    assert_int_equal(n, 2);
    assert_string_equal(names[0], "0.5073");
    assert_string_equal(names[1], "0.5143");
}

/* stopAt: writeNow stops after one step and writes it; noWriteNow stops
 * without writing; nextWrite runs to the next write time. */
static void test_stop_at(void **state)
{
    (void)state;
    case_control c = ctl_defaults();
    /* endTime is ignored unless stopAt endTime (icoFoam with endTime equal
     * to startTime still runs these) */
    c.end_time = 0;
    c.delta_t = 0.01;
    c.write_interval = 5;
    rt_time t;
    c.stop_at = CASE_STOP_WRITENOW;
    rt_init(&t, &c, 0, "0");
    int n = 0;
    while (rt_running(&t)) {
        rt_advance(&t);
        n++;
    }
    assert_int_equal(n, 1);
    assert_true(t.write_time);

    c.stop_at = CASE_STOP_NOWRITENOW;
    rt_init(&t, &c, 0, "0");
    n = 0;
    while (rt_running(&t)) {
        rt_advance(&t);
        n++;
    }
    assert_int_equal(n, 1);
    assert_false(t.write_time);

    c.stop_at = CASE_STOP_NEXTWRITE;
    rt_init(&t, &c, 0, "0");
    n = 0;
    while (rt_running(&t)) {
        rt_advance(&t);
        n++;
    }
    assert_int_equal(n, 5);
    assert_true(t.write_time);
    assert_string_equal(t.name, "0.05");
}

/* Run t to its end; the names and indices of the written times into
 * names (space-separated) and idx. Returns the number written. */
static int run_writes(rt_time *t, char *names, size_t len, long *idx, int max)
{
    int n = 0;
    names[0] = '\0';
    while (rt_running(t)) {
        rt_advance(t);
        if (t->write_time && n < max) {
            idx[n++] = t->index;
            size_t k = strlen(names);
            snprintf(names + k, len - k, "%s%s", k ? " " : "", t->name);
        }
    }
    return n;
}

/* runTimeModifiable: the cavity (deltaT 0.005, endTime 0.1) with
 * controlDict edited after time 0.03, against icoFoam v1912 runs with the
 * same edit (tests/integration/editshim.c): the written times and their
 * uniform/time index. */
static void test_reread_icofoam(void **state)
{
    (void)state;
    char names[512];
    long idx[32];
    rt_time t;
    /* writeControl runTime 0.01, deltaT -> 0.003: icoFoam wrote 0.039 (9)
     * 0.051 (13) 0.06 (16) 0.069 (19) 0.081 (23) 0.09 (26) 0.099 (29) */
    case_control c = ctl_defaults();
    c.end_time = 0.1;
    c.delta_t = 0.005;
    c.write_control = CASE_WRITE_RUNTIME;
    c.write_interval = 0.01;
    rt_init(&t, &c, 0, "0");
    for (int k = 0; k < 6; k++)
        rt_advance(&t);
    assert_string_equal(t.name, "0.03");
    case_control e = c;
    e.delta_t = 0.003;
    rt_reread(&t, &e);
    assert_int_equal(run_writes(&t, names, sizeof names, idx, 32), 7);
    assert_string_equal(names, "0.039 0.051 0.06 0.069 0.081 0.09 0.099");
    const long want_rt[] = {9, 13, 16, 19, 23, 26, 29};
    for (int k = 0; k < 7; k++)
        assert_int_equal(idx[k], want_rt[k]);
    assert_true(t.delta_t == 0.003 && t.delta_t0 == 0.003);

    /* writeInterval 0.01 -> 0.025 (runTime): the 3 writes so far count as
     * label(3 * 0.01 / 0.025) = 1, so icoFoam wrote 0.05 0.075 0.1 */
    rt_init(&t, &c, 0, "0");
    for (int k = 0; k < 6; k++)
        rt_advance(&t);
    assert_int_equal(t.write_index, 3);
    e = c;
    e.write_interval = 0.025;
    rt_reread(&t, &e);
    assert_int_equal(t.write_index, 1);
    assert_int_equal(run_writes(&t, names, sizeof names, idx, 32), 3);
    assert_string_equal(names, "0.05 0.075 0.1");

    /* writeControl timeStep 2, deltaT -> 0.002: the index keeps counting,
     * icoFoam wrote 0.034 (8) ... 0.098 (40) */
    c.write_control = CASE_WRITE_TIMESTEP;
    c.write_interval = 2;
    rt_init(&t, &c, 0, "0");
    for (int k = 0; k < 6; k++)
        rt_advance(&t);
    e = c;
    e.delta_t = 0.002;
    rt_reread(&t, &e);
    assert_int_equal(run_writes(&t, names, sizeof names, idx, 32), 17);
    assert_string_equal(names, "0.034 0.038 0.042 0.046 0.05 0.054 0.058 0.062 0.066 0.07 0.074 0.078 0.082 "
                               "0.086 0.09 0.094 0.098");
    assert_int_equal(idx[0], 8);
    assert_int_equal(idx[16], 40);

    /* stopAt writeNow: the next step is written and is the last (0.035);
     * noWriteNow: one more step, not written; nextWrite: to 0.04 */
    const case_stop_at stops[] = {CASE_STOP_WRITENOW, CASE_STOP_NOWRITENOW, CASE_STOP_NEXTWRITE};
    const char *last[] = {"0.035", "0.035", "0.04"};
    const int nwrite[] = {1, 0, 1};
    for (int s = 0; s < 3; s++) {
        rt_init(&t, &c, 0, "0");
        for (int k = 0; k < 6; k++)
            rt_advance(&t);
        e = c;
        e.stop_at = stops[s];
        e.end_time = 0.02; /* not read for these stopAt */
        rt_reread(&t, &e);
        assert_true(rt_running(&t));
        assert_int_equal(run_writes(&t, names, sizeof names, idx, 32), nwrite[s]);
        assert_string_equal(t.name, last[s]);
    }

    /* endTime before the current time: the run ends at once, as icoFoam */
    rt_init(&t, &c, 0, "0");
    for (int k = 0; k < 6; k++)
        rt_advance(&t);
    e = c;
    e.end_time = 0.01;
    rt_reread(&t, &e);
    assert_false(rt_running(&t));
    /* and back to stopAt endTime with a later endTime */
    e.end_time = 0.05;
    rt_reread(&t, &e);
    assert_int_equal(run_writes(&t, names, sizeof names, idx, 32), 2);
    assert_string_equal(names, "0.04 0.05");
    assert_string_equal(t.name, "0.05");
}

/* A deltaT set by adjustTimeStep is kept by a re-read (Time::deltaTchanged_),
 * and so is a timePrecision raised to tell names apart when timePrecision
 * itself is unchanged; the start time stays the one the run started from. */
static void test_reread_kept(void **state)
{
    (void)state;
    case_control c = ctl_defaults();
    c.end_time = 1;
    c.delta_t = 0.01;
    c.write_control = CASE_WRITE_RUNTIME;
    c.write_interval = 0.1;
    c.adjust_time_step = 1;
    c.max_co = 0.5;
    rt_time t;
    rt_init(&t, &c, 0.2, "0.2");
    rt_adjust_delta_t(&t, 1.0); /* Co 1 -> deltaT halved */
    assert_true(t.delta_t_changed);
    double dt = t.delta_t;
    assert_true(dt < 0.01);
    case_control e = c;
    e.delta_t = 0.05;
    e.start_time = 0;
    e.adjust_time_step = 0;
    rt_reread(&t, &e);
    assert_true(t.delta_t == dt);
    assert_true(t.ctl.start_time == 0.2);
    assert_false(t.ctl.adjust_time_step);

    c = ctl_defaults();
    c.end_time = 1;
    c.delta_t = 0.01;
    rt_init(&t, &c, 0, "0");
    assert_false(t.delta_t_changed);
    e = c;
    e.delta_t = 0.02;
    rt_reread(&t, &e);
    assert_true(t.delta_t == 0.02);

    t.precision = 9; /* as raised by rt_advance */
    rt_reread(&t, &e);
    assert_int_equal(t.precision, 9);
    e.time_precision = 4;
    rt_reread(&t, &e);
    assert_int_equal(t.precision, 4);
}

/* adjustTimeStep without adjustableRunTime: factor 1.2 at most, maxDeltaT. */
static void test_adjust_runtime_limits(void **state)
{
    (void)state;
    case_control c = ctl_defaults();
    c.write_control = CASE_WRITE_RUNTIME;
    c.write_interval = 1;
    c.end_time = 10;
    c.delta_t = 0.01;
    c.adjust_time_step = 1;
    c.max_co = 0.5;
    c.max_delta_t = 0.02;
    rt_time t;
    rt_init(&t, &c, 0, "0");
    rt_adjust_delta_t(&t, 0.0);
    TU_CLOSE(t.delta_t, 0.012, 1e-15);
    rt_adjust_delta_t(&t, 0.0);
    TU_CLOSE(t.delta_t, 0.0144, 1e-15);
    rt_adjust_delta_t(&t, 0.0);
    rt_adjust_delta_t(&t, 0.0);
    TU_CLOSE(t.delta_t, 0.02, 1e-15); /* maxDeltaT */
    /* Co = 1 with maxCo 0.5: factor min(0.5, 1.05, 1.2) */
    rt_adjust_delta_t(&t, 1.0);
    TU_CLOSE(t.delta_t, 0.01, 1e-12);
    /* Co just under maxCo: factor 1 + 0.1*f */
    rt_adjust_delta_t(&t, 0.45);
    TU_CLOSE(t.delta_t, 0.01 * fmin(0.5 / 0.45, 1 + 0.05 / 0.45), 1e-12);
    /* without adjustTimeStep nothing changes */
    c.adjust_time_step = 0;
    rt_init(&t, &c, 0, "0");
    rt_adjust_delta_t(&t, 100.0);
    rt_set_initial_delta_t(&t, 100.0);
    assert_true(t.delta_t == 0.01);
}

/* Replays a pimpleFoam run: before step k the max Courant number co[k] is
 * given, and OpenFOAM then used dt[k] and named the time tm[k]. */
static void replay(rt_time *t, int n, const double *co, const double *dt,
                   const char *const *tm, const char *const *writes, int nwrites)
{
    int w = 0;
    for (int k = 0; k < n; k++) {
        assert_true(rt_running(t));
        rt_adjust_delta_t(t, co[k]);
        if (t->delta_t != dt[k])
            fail_msg("step %d: deltaT %.17g, OpenFOAM %.17g", k + 1, t->delta_t, dt[k]);
        rt_advance(t);
        assert_string_equal(t->name, tm[k]);
        if (t->write_time) {
            assert_true(w < nwrites);
            assert_string_equal(t->name, writes[w]);
            w++;
        }
    }
    assert_int_equal(w, nwrites);
    assert_false(rt_running(t));
}

/* pimpleFoam, adjustableRunTime 0.0123, deltaT 0.001, maxCo 0.5, no
 * maxDeltaT, endTime 0.03 (maxDeltaT 0 = not given = unlimited). */
static void test_adjustable_pimple_1(void **state)
{
    (void)state;
    static const double co[] = {
        0, 0.093164289278196227, 0.15840386679700927, 0.2174900261522569,
        0.29564576943308846, 0.30849608200876821, 0.31644550402247779,
        0.32185075297948412, 0.39794460949450994, 0.4019726393547739, 0.404998062809316,
        0.40733934817694961, 0.409183565690172, 0.51370807463882995};
    static const double dt[] = {
        0.00123, 0.00138375, 0.0016143750000000001, 0.0020179687499999998,
        0.0020179687500000002, 0.0020179687499999998, 0.0020179687499999998,
        0.0024599999999999999, 0.0024599999999999999, 0.0024600000000000004,
        0.0024600000000000004, 0.0024600000000000004, 0.0030750000000000005, 0.003075};
    static const char *const tm[] = {
        "0.00123", "0.00261375", "0.00422813", "0.00624609", "0.00826406", "0.010282",
        "0.0123", "0.01476", "0.01722", "0.01968", "0.02214", "0.0246", "0.027675",
        "0.03075"};
    static const char *const writes[] = {"0.0123", "0.0246"};
    case_control c = ctl_defaults();
    c.write_control = CASE_WRITE_ADJUSTABLERUNTIME;
    c.write_interval = 0.0123;
    c.delta_t = 0.001;
    c.end_time = 0.03;
    c.adjust_time_step = 1;
    c.max_co = 0.5;
    c.max_delta_t = 0;
    rt_time t;
    rt_init(&t, &c, 0, "0");
    rt_set_initial_delta_t(&t, 0.0); /* Co 0: unchanged */
    assert_true(t.delta_t == 0.001);
    replay(&t, 14, co, dt, tm, writes, 2);
    assert_true(t.delta_t0 == dt[12]);
}

/* pimpleFoam, adjustableRunTime 0.007, deltaT 1e-4, maxCo 0.9, maxDeltaT
 * 0.003, endTime 0.03: growth by 1.2 then landing on 0.007, 0.014, ... */
static void test_adjustable_pimple_2(void **state)
{
    (void)state;
    static const double co[] = {
        0, 0.001839666053378953, 0.0044182278865140742, 0.0080492039565137341,
        0.012708658263554825, 0.018728840244436624, 0.026236544631537038,
        0.035006549630806648, 0.047691790935598, 0.061992774380508445,
        0.085157986174920597, 0.10758345624011688, 0.14984704774534582,
        0.15436692068335284, 0.15772401068142264, 0.18002372264823968,
        0.22876675937903657, 0.34912982673894599, 0.35346944483572845,
        0.38073112553757138, 0.38356119883185164, 0.38578298318254817,
        0.3875528328622424, 0.38898727493102153, 0.39015834573346092};
    static const double dt[] = {
        0.00012068965517241379, 0.00014331896551724138, 0.00017271772767462422,
        0.00020510230161361627, 0.00024454505192392711, 0.00029112506181419893,
        0.00034250007272258699, 0.00042153855104318401, 0.00050584626125182075,
        0.0006503737644666266, 0.00078044851735995196, 0.0010405980231466027,
        0.0010405980231466025, 0.001040598023146602, 0.0011666666666666668,
        0.0014583333333333332, 0.0021874999999999993, 0.0021875000000000002,
        0.0023333333333333335, 0.0023333333333333331, 0.0023333333333333331,
        0.0023333333333333331, 0.0023333333333333331, 0.0023333333333333331,
        0.0023333333333333344};
    static const char *const tm[] = {
        "0.00012069", "0.000264009", "0.000436726", "0.000641829", "0.000886374",
        "0.0011775", "0.00152", "0.00194154", "0.00244738", "0.00309776", "0.00387821",
        "0.0049188", "0.0059594", "0.007", "0.00816667", "0.009625", "0.0118125", "0.014",
        "0.0163333", "0.0186667", "0.021", "0.0233333", "0.0256667", "0.028", "0.0303333"};
    static const char *const writes[] = {"0.007", "0.014", "0.021", "0.028"};
    case_control c = ctl_defaults();
    c.write_control = CASE_WRITE_ADJUSTABLERUNTIME;
    c.write_interval = 0.007;
    c.delta_t = 0.0001;
    c.end_time = 0.03;
    c.adjust_time_step = 1;
    c.max_co = 0.9;
    c.max_delta_t = 0.003;
    rt_time t;
    rt_init(&t, &c, 0, "0");
    rt_set_initial_delta_t(&t, 0.0);
    replay(&t, 25, co, dt, tm, writes, 4);
    /* uniform/time of 0.014 said deltaT 0.0021875000000000002, deltaT0
     * 0.0021874999999999993: checked via a shorter replay */
    rt_init(&t, &c, 0, "0");
    for (int k = 0; k < 18; k++) {
        rt_adjust_delta_t(&t, co[k]);
        rt_advance(&t);
    }
    assert_string_equal(t.name, "0.014");
    assert_true(t.delta_t == 0.0021875000000000002);
    assert_true(t.delta_t0 == 0.0021874999999999993);
    assert_int_equal(t.index, 18);
}

/* pimpleFoam restarted from 0.5 with deltaT 0.01 and a developed flow:
 * setInitialDeltaT cuts deltaT to maxCo and lands it on 0.5123. */
static void test_adjustable_pimple_initial(void **state)
{
    (void)state;
    static const double co[] = {
        0.52420004085000038, 0.52253949450043713, 0.5227697738003676, 0.5227801122176029,
        0.52280155373885151, 0.52280154931030787, 0.52280081375302123, 0.5227987735482017,
        0.52279703163696845, 0.52279534350765922};
    static const double dt[] = {
        0.003075, 0.0030749999999999836, 0.0030750000000000057, 0.0030749999999999614,
        0.0030750000000000057, 0.0030749999999999909, 0.003075000000000017,
        0.003074999999999984, 0.0030750000000000118, 0.0030749999999999992};
    static const char *const tm[] = {
        "0.503075", "0.50615", "0.509225", "0.5123", "0.515375", "0.51845", "0.521525",
        "0.5246", "0.527675", "0.53075"};
    static const char *const writes[] = {"0.5123", "0.5246"};
    case_control c = ctl_defaults();
    c.start_time = 0.5;
    c.write_control = CASE_WRITE_ADJUSTABLERUNTIME;
    c.write_interval = 0.0123;
    c.delta_t = 0.01;
    c.end_time = 0.53;
    c.adjust_time_step = 1;
    c.max_co = 0.5;
    c.max_delta_t = 1e300;
    rt_time t;
    rt_init(&t, &c, 0.5, "0.5");
    rt_set_initial_delta_t(&t, 1.7047155800000013);
    assert_true(t.delta_t == 0.003075);
    replay(&t, 10, co, dt, tm, writes, 2);
}

/* The adjustment never asks for fewer than one step and keeps within
 * x2 / x0.2 (pimpleFoam, deltaT 0.01, writeInterval 0.003: 0.003). */
static void test_adjust_one_step(void **state)
{
    (void)state;
    case_control c = ctl_defaults();
    c.write_control = CASE_WRITE_ADJUSTABLERUNTIME;
    c.write_interval = 0.003;
    c.delta_t = 0.01;
    c.end_time = 0.02;
    c.adjust_time_step = 1;
    c.max_co = 100;
    c.max_delta_t = 1;
    rt_time t;
    rt_init(&t, &c, 0, "0");
    rt_adjust_delta_t(&t, 0.0);
    TU_CLOSE(t.delta_t, 0.003, 1e-15);
    rt_advance(&t);
    assert_true(t.write_time);
    assert_string_equal(t.name, "0.003");
    /* x0.2 floor: deltaT 0.1 aiming at 0.003 gets 0.02*1.2 */
    c.delta_t = 0.1;
    rt_init(&t, &c, 0, "0");
    rt_adjust_delta_t(&t, 0.0);
    TU_CLOSE(t.delta_t, 0.2 * 0.12, 1e-15);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_names),
        cmocka_unit_test(test_cavity_timestep),
        cmocka_unit_test(test_small_deltat_names),
        cmocka_unit_test(test_precision_raise),
        cmocka_unit_test(test_init_precision),
        cmocka_unit_test(test_runtime_writes),
        cmocka_unit_test(test_stop_at),
        cmocka_unit_test(test_reread_icofoam),
        cmocka_unit_test(test_reread_kept),
        cmocka_unit_test(test_adjust_runtime_limits),
        cmocka_unit_test(test_adjustable_pimple_1),
        cmocka_unit_test(test_adjustable_pimple_2),
        cmocka_unit_test(test_adjustable_pimple_initial),
        cmocka_unit_test(test_adjust_one_step),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
