/* SPDX-License-Identifier: GPL-3.0-or-later
 * runtime.c -- OpenFOAM v1912's Time logic without I/O: time names,
 * advancing, write decisions, stopAt, and deltaT adjustment for maxCo and
 * adjustableRunTime.
 *
 * Behaviour was checked against icoFoam and pimpleFoam runs (logs printed
 * with writePrecision 17), not only against the source; in particular the
 * adjustableRunTime step count is max(nSteps, 1) rounded to nearest, which
 * is what pimpleFoam v1912 does (label(nSteps) + 1 does not reproduce its
 * deltaT sequences).
 */
#include "umppm/runtime.h"

#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* OpenFOAM's SMALL for double. */
#define RT_SMALL 1e-15
/* Time::maxPrecision_ = 3 + digits10 of double. */
#define RT_MAX_PRECISION 18

void rt_name(double value, int precision, int format, char *buf, size_t len)
{
    if (!buf || len == 0)
        return;
    if (precision < 0)
        precision = 6;
    if (format == 1)
        snprintf(buf, len, "%.*f", precision, value);
    else if (format == 2)
        snprintf(buf, len, "%.*e", precision, value);
    else
        snprintf(buf, len, "%.*g", precision, value);
}

static void set_name(rt_time *t)
{
    rt_name(t->value, t->precision, t->ctl.time_format_fixed, t->name, sizeof t->name);
}

void rt_init(rt_time *t, const case_control *c, double t0, const char *tname)
{
    if (!t)
        return;
    memset(t, 0, sizeof *t);
    if (!c)
        return;
    t->ctl = *c;
    /* Time's startTime_ is the value actually started from (also with
     * startFrom latestTime/firstTime); runTime writes count from it */
    t->ctl.start_time = t0;
    /* Time::readDict reads endTime only for stopAt endTime; otherwise
     * endTime is GREAT and the run ends through stopAt (checked: icoFoam
     * with endTime = startTime and stopAt nextWrite runs to the next write) */
    if (c->stop_at != CASE_STOP_ENDTIME)
        t->ctl.end_time = 1e15;
    t->value = t0;
    t->delta_t = t->delta_t0 = t->delta_t_save = c->delta_t;
    t->precision = c->time_precision > 0 ? c->time_precision : 6;
    t->cpu_start = (double)clock() / CLOCKS_PER_SEC;
    t->wall_start = (double)time(NULL);
    set_name(t);
    if (tname && strcmp(tname, t->name) != 0) {
        /* the start directory was written with more digits than
         * timePrecision: use the smallest precision that reproduces it */
        char buf[64];
        for (int p = t->precision + 1; p <= RT_MAX_PRECISION; p++) {
            rt_name(t0, p, c->time_format_fixed, buf, sizeof buf);
            if (strcmp(buf, tname) == 0) {
                t->precision = p;
                break;
            }
        }
        snprintf(t->name, sizeof t->name, "%s", tname);
    }
}

int rt_running(const rt_time *t)
{
    return t->value < t->ctl.end_time - 0.5 * t->delta_t;
}

/* label(q) of OpenFOAM without undefined behaviour for huge q. */
static long to_label(double q)
{
    if (!(q < (double)LONG_MAX))
        return q > 0 ? LONG_MAX : 0;
    if (q < (double)LONG_MIN)
        return LONG_MIN;
    return (long)q;
}

/* Write decision of Time::operator++ for the interval-based controls. */
static void decide_write(rt_time *t)
{
    const case_control *c = &t->ctl;
    double wi = c->write_interval;
    long idx;
    switch (c->write_control) {
    case CASE_WRITE_TIMESTEP: {
        long every = to_label(wi);
        if (every < 1)
            every = 1; /* OpenFOAM refuses writeInterval < 1 here */
        t->write_time = (t->index % every) == 0;
        return;
    }
    case CASE_WRITE_RUNTIME:
    case CASE_WRITE_ADJUSTABLERUNTIME:
        if (!(wi > 0))
            return;
        idx = to_label(((t->value - c->start_time) + 0.5 * t->delta_t) / wi);
        break;
    case CASE_WRITE_CPUTIME:
        if (!(wi > 0))
            return;
        idx = to_label(((double)clock() / CLOCKS_PER_SEC - t->cpu_start) / wi);
        break;
    case CASE_WRITE_CLOCKTIME:
        if (!(wi > 0))
            return;
        /* elapsedClockTime() is whole seconds */
        idx = to_label((double)to_label((double)time(NULL) - t->wall_start) / wi);
        break;
    default:
        return;
    }
    if (idx > t->write_index) {
        t->write_time = 1;
        t->write_index = idx;
    }
}

void rt_advance(rt_time *t)
{
    t->delta_t0 = t->delta_t_save;
    t->delta_t_save = t->delta_t;
    const double old_value = t->value;

    t->value += t->delta_t;
    t->index++;
    t->precision_raised = 0;
    t->write_time = 0;
    /* round-off next to zero (e.g. starting at a negative time) gives 0 */
    if (fabs(t->value) < 10 * RT_SMALL * t->delta_t)
        t->value = 0.0;
    set_name(t);

    decide_write(t);

    /* stopAt moves endTime to stop at the next rt_running, unless the time
     * is already past it (Time::end()) */
    if (!(t->value > t->ctl.end_time + 0.5 * t->delta_t)) {
        switch (t->ctl.stop_at) {
        case CASE_STOP_NOWRITENOW:
            t->ctl.end_time = t->value;
            break;
        case CASE_STOP_WRITENOW:
            t->ctl.end_time = t->value;
            t->write_time = 1;
            break;
        case CASE_STOP_NEXTWRITE:
            if (t->write_time)
                t->ctl.end_time = t->value;
            break;
        default:
            break;
        }
    }

    /* A time directory name must tell this time from the previous one: when
     * the name read back is off by more than the tolerance, add digits (and
     * keep them). Only done at write times, as v1912. */
    if (t->write_time) {
        const int old_precision = t->precision;
        const double tol =
            fmax(fmin(pow(10.0, -t->precision), 0.1 * t->delta_t), RT_SMALL);
        for (;;) {
            char *end;
            double named = strtod(t->name, &end);
            if (end == t->name || *end != '\0')
                break; /* not a number: OpenFOAM's readScalar fails too */
            if (!(fabs(named - old_value - t->delta_t) > tol)
                || t->precision >= RT_MAX_PRECISION)
                break;
            t->precision++;
            set_name(t);
        }
        t->precision_raised = t->precision != old_precision;
    }
}

/* Time::adjustDeltaT: shorten (or lengthen, within x2 / x0.2) delta_t so an
 * integer number of steps reaches the next adjustableRunTime write time. */
static void adjust_to_write(rt_time *t)
{
    const case_control *c = &t->ctl;
    if (c->write_control != CASE_WRITE_ADJUSTABLERUNTIME || !(c->write_interval > 0))
        return;
    double to_next = fmax(0.0, (double)(t->write_index + 1) * c->write_interval
                                   - (t->value - c->start_time));
    double nsteps = to_next / t->delta_t;
    if (!(nsteps < (double)INT32_MAX)) /* label overflow guard, as OpenFOAM */
        return;
    long n = (long)(fmax(nsteps, 1.0) + 0.5);
    double dt = to_next / (double)n;
    if (dt >= t->delta_t)
        t->delta_t = fmin(dt, 2.0 * t->delta_t);
    else
        t->delta_t = fmax(dt, 0.2 * t->delta_t);
}

static double max_delta_t(const case_control *c)
{
    /* 0 or less means "not given" (OpenFOAM's default is GREAT) */
    return c->max_delta_t > 0 ? c->max_delta_t : HUGE_VAL;
}

void rt_adjust_delta_t(rt_time *t, double courant_max)
{
    if (!t->ctl.adjust_time_step)
        return;
    double max_fact = t->ctl.max_co / (courant_max + RT_SMALL);
    double fact = fmin(fmin(max_fact, 1.0 + 0.1 * max_fact), 1.2);
    t->delta_t = fmin(fact * t->delta_t, max_delta_t(&t->ctl));
    t->delta_t_changed = 1; /* runTime.setDeltaT */
    adjust_to_write(t);
}

void rt_restore_delta_t(rt_time *t, double delta_t)
{
    if (!t->ctl.adjust_time_step || !(delta_t > 0) || !isfinite(delta_t))
        return;
    t->delta_t = t->delta_t0 = t->delta_t_save = delta_t;
    t->delta_t_changed = 1;
    t->restored = 1;
}

void rt_set_initial_delta_t(rt_time *t, double courant_max)
{
    if (!t->ctl.adjust_time_step || t->index != 0 || t->restored || !(courant_max > RT_SMALL))
        return;
    t->delta_t = fmin(t->ctl.max_co * t->delta_t / courant_max,
                      fmin(t->delta_t, max_delta_t(&t->ctl)));
    t->delta_t_changed = 1; /* runTime.setDeltaT */
    adjust_to_write(t);
}

void rt_reread(rt_time *t, const case_control *c)
{
    case_control *o = &t->ctl;
    const case_start_from from = o->start_from;
    const double start = o->start_time, old_wi = o->write_interval;
    const int old_tprec = o->time_precision;
    *o = *c;
    o->start_from = from;
    o->start_time = start; /* startTime_: the value the run started from */
    if (!t->delta_t_changed)
        t->delta_t = c->delta_t;
    /* Time::readDict: the writes so far counted in the new interval */
    if (c->write_interval != old_wi &&
        (c->write_control == CASE_WRITE_RUNTIME || c->write_control == CASE_WRITE_ADJUSTABLERUNTIME))
        t->write_index = to_label((double)t->write_index * old_wi / c->write_interval);
    if (c->stop_at != CASE_STOP_ENDTIME)
        o->end_time = 1e15;
    if (c->time_precision != old_tprec)
        t->precision = c->time_precision > 0 ? c->time_precision : 6;
}
