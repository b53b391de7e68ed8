/* SPDX-License-Identifier: GPL-3.0-or-later
 * runtime.h -- OpenFOAM's Time logic without any I/O (module prefix rt_):
 * advancing time, deciding write times (writeControl timeStep, runTime,
 * adjustableRunTime), adjusting deltaT to hit write times and to honour
 * maxCo, and naming time directories (%.*g with timePrecision, raised when
 * a name would not distinguish consecutive times, as Time::operator++).
 */
#ifndef UMPPM_RUNTIME_H
#define UMPPM_RUNTIME_H

#include <stddef.h>
#include "umppm/case.h"

typedef struct rt_time {
    case_control ctl;      /* copy of the settings (ctl.start_time is set to
                              the actual start value, as Time's startTime_;
                              ctl.end_time is 1e15 (GREAT) unless stopAt
                              endTime, and is moved by stopAt) */
    double value;          /* current time */
    double delta_t;        /* deltaT of the current step */
    double delta_t0;       /* deltaT of the previous step (Time::deltaT0_) */
    double delta_t_save;   /* Time::deltaTSave_: delta_t when last advanced */
    long index;            /* time step index (0 at start; set it from
                              uniform/time on a restart if wanted) */
    long write_index;      /* writeTimeIndex_ */
    int precision;         /* current timePrecision (may grow) */
    int write_time;        /* 1 when the current step must be written */
    int precision_raised;  /* set when the last ++ raised precision (for a warning) */
    int delta_t_changed;   /* Time::deltaTchanged_: adjustTimeStep has set
                              delta_t, so a re-read keeps it (rt_reread) */
    int restored;          /* delta_t restored from the start time (rt_restore_delta_t) */
    double cpu_start;      /* clock() at rt_init, seconds (writeControl cpuTime) */
    double wall_start;     /* time() at rt_init (writeControl clockTime) */
    char name[64];         /* time name of value */
} rt_time;

/* Start at value t0 (its directory name tname is kept as the name; NULL:
 * named from t0). As OpenFOAM's Time constructor, timePrecision is raised
 * when needed for tname to be the name of t0 ("Increasing the
 * timePrecision ... to support the formatting of the current time
 * directory"). */
void rt_init(rt_time *t, const case_control *c, double t0, const char *tname);
/* Time name of value at the given precision. format as
 * case_control.time_format_fixed: 0 general %.*g, 1 fixed %.*f,
 * 2 scientific %.*e. */
void rt_name(double value, int precision, int format, char *buf, size_t len);
/* 1 while value < endTime - 0.5*deltaT (OpenFOAM Time::run()). */
int rt_running(const rt_time *t);
/* Advance by delta_t: index++, name (raising precision if needed), write_time. */
void rt_advance(rt_time *t);
/* Before rt_advance: with adjustTimeStep, set delta_t from the max Courant
 * number of the last step as OpenFOAM's setDeltaT.H (factor <= 1.2, at most
 * maxDeltaT; maxDeltaT <= 0 means unlimited), then, for adjustableRunTime,
 * change it (within x2 / x0.2) so that round(max(n, 1)) equal steps reach
 * the next write time, as Time::adjustDeltaT (checked against pimpleFoam). */
void rt_adjust_delta_t(rt_time *t, double courant_max);
/* Once before the time loop, with the Courant number of the initial field
 * at the initial delta_t: OpenFOAM's setInitialDeltaT.H (with adjustTimeStep,
 * at index 0 and Courant > 1e-15: delta_t = min(maxCo*delta_t/Co,
 * delta_t, maxDeltaT)), then the adjustableRunTime adjustment. */
void rt_set_initial_delta_t(rt_time *t, double courant_max);

/* runTimeModifiable: apply a re-read system/controlDict c (already
 * validated by case_read_control) to the running time, as OpenFOAM's
 * Time::readDict does between two steps:
 *   deltaT       taken unless adjustTimeStep has set delta_t
 *                (delta_t_changed; Time::deltaTchanged_);
 *   writeControl, writeInterval: taken; with runTime/adjustableRunTime a
 *                new interval rescales the count of writes so far,
 *                write_index = label(write_index * old / new), as v1912;
 *   stopAt, endTime: endTime for stopAt endTime, else 1e15 (GREAT);
 *   timeFormat, timePrecision: taken when they differ from the previous
 *                read (an unchanged timePrecision keeps a precision raised
 *                to tell time names apart);
 *   the rest (purgeWrite, write format, adjustTimeStep, maxCo,
 *                maxDeltaT, runTimeModifiable): taken.
 * startFrom and startTime are not re-read (Time's startTime_ is fixed).
 * The next rt_running/rt_advance use the new settings. */
void rt_reread(rt_time *t, const case_control *c);
/* A restart with adjustTimeStep: the deltaT saved in the start time's
 * uniform/time (Time::setControls reads it then; setInitialDeltaT.H is then
 * skipped, the time index not being 0). Without adjustTimeStep controlDict's
 * deltaT stays, as OpenFOAM's. */
void rt_restore_delta_t(rt_time *t, double delta_t);

#endif
