/* SPDX-License-Identifier: GPL-3.0-or-later
 * app.h -- the umppmFoam run (module prefix app_): reads the case, runs the
 * UMPPM time loop with an icoFoam-style log, writes time directories
 * (U, p, the particle cloud, uniform/time). Printing happens here and in
 * main.c only; errors come back as ump_status for main() to report.
 */
#ifndef UMPPM_APP_H
#define UMPPM_APP_H

#include "umppm/case.h"
#include "umppm/mesh2d.h"
#include "umppm/polymesh.h"
#include "umppm/ump.h"

/* Command-line choices of a run. */
typedef struct app_options {
    int reseed;   /* -reseed: a restart seeds new particles from the fields
                     instead of reading (or requiring) the start time's cloud */
    int no_function_objects; /* -noFunctionObjects: controlDict's functions
                                are read and checked but not run */
} app_options;

/* Start-up recovery: the hidden directories killed runs left in case_dir
 * are recovered or removed (fio_recover), one log line each. */
ump_status app_recover(const char *case_dir, ump_err *err);
/* The run; opt may be NULL (defaults). SIGINT/SIGTERM finish the current
 * step, write it and return UMP_OK (stopAt writeNow). */
ump_status app_run(const char *case_dir, const app_options *opt, ump_err *err);

/* The checks of a run before the mesh is read (used by -checkMesh too):
 * endTime not before the start time t0 (directory tname), then every
 * feature umppmFoam does not implement refused by name (feat_check_case). */
ump_status app_check_case(const char *case_dir, const case_control *c, const char *tname, double t0,
                          ump_err *err);
/* The checks of a run after the mesh (pm, m borrowed) and before the
 * fields: transportProperties, fvSolution (PISO/PIMPLE/SIMPLE, UMPPM),
 * constant/g, the function objects and their patches, the ddt scheme,
 * pRefPoint inside the mesh. Used by -checkMesh. */
ump_status app_check_settings(const char *case_dir, pmesh *pm, mesh2d *m, ump_err *err);

#endif
