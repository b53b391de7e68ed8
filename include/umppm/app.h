/* SPDX-License-Identifier: GPL-3.0-or-later
 * app.h -- the umppmFoam run (module prefix app_): reads the case, runs the
 * UMPPM time loop with an icoFoam-style log, writes time directories
 * (U, p, the particle cloud, uniform/time). Printing happens here and in
 * main.c only; errors come back as ump_status for main() to report.
 */
#ifndef UMPPM_APP_H
#define UMPPM_APP_H

#include "umppm/ump.h"

ump_status app_run(const char *case_dir, ump_err *err);

#endif
