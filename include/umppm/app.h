/* SPDX-License-Identifier: GPL-3.0-or-later
 * app.h -- the umppmFoam run (module prefix app_): reads the case, runs the
 * UMPPM time loop with an icoFoam-style log, writes time directories
 * (U, p, the particle cloud, uniform/time). Printing happens here and in
 * main.c only; errors come back as ump_status for main() to report.
 */
#ifndef UMPPM_APP_H
#define UMPPM_APP_H

#include "umppm/case.h"
#include "umppm/field.h"
#include "umppm/mesh2d.h"
#include "umppm/polymesh.h"
#include "umppm/runtime.h"
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
/* runTimeModifiable, the steps both solvers share. app_control_modified:
 * 1 when controlDict (path; shown in the log) is another version than
 * *stamp, which then takes the new one and the log says it is re-read; 0
 * otherwise (a file that cannot be stat'ed is a warning, once: *missing).
 * app_control_apply: a re-read controlDict c that passed the start-up
 * checks goes to t and *ctl, with the log's lines; returns c's
 * runTimeModifiable (0: stop watching). */
int app_control_modified(const char *path, const char *shown, case_stamp *stamp, int *missing);
int app_control_apply(rt_time *t, case_control *ctl, const case_control *c);
/* Both solvers' restart rule: is start time tname a restart from the cloud
 * `cloud` (*restart = 1), or are the particles seeded (a first start, or
 * -reseed: reseed)? A time some solver wrote (uniform/time) or one with the
 * cloud's directory but without its positions is an error naming the path
 * and -reseed (seed_from: what seeds, for the message); a cloud in v1912's
 * barycentric format (coordinates only) too. */
ump_status app_restart_policy(const char *case_dir, const char *tname, const char *cloud, int reseed,
                              const char *seed_from, int *restart, ump_err *err);
/* The fields' digest beside a cloud, both solvers: app_write_digest writes
 * uniform/<ump_solver> into time directory dir (location tname): cloudName,
 * the write format and precision (binary, precision), the cells, and for
 * each of the nfields fields the sums over the cells of its components and
 * of their squares. app_check_digest, at a restart from the cloud: fields
 * read from dir that differ from those sums beyond the round-off of the
 * writes (another solver, mapFields or setFields changed them after the
 * cloud was written), or another cloudName, are an error naming the field
 * and -reseed. A time without the file passes (written before it existed);
 * fields after the first that the file does not record are not checked. */
ump_status app_write_digest(const char *dir, const char *tname, const char *cloud, int binary, int precision,
                            const fld_field *const *fields, int nfields, ump_err *err);
ump_status app_check_digest(const char *dir, const char *tname, const char *cloud, int binary, int precision,
                            const fld_field *const *fields, int nfields, ump_err *err);
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
