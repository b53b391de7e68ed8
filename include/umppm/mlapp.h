/* SPDX-License-Identifier: GPL-3.0-or-later
 * mlapp.h -- the meshlessFoam run (module prefix mlapp_): reads an
 * interFoam (laminar) case as it is, seeds particles from alpha.<liquid>,
 * runs the particle method of the meshless dictionary (MPS) with an
 * interFoam-style log, writes time directories (the particle cloud and the
 * mesh fields alpha.<liquid>, U, p_rgh, p). Printing happens here and in
 * main_meshless.c only.
 */
#ifndef UMPPM_MLAPP_H
#define UMPPM_MLAPP_H

#include "umppm/ump.h"

/* The run. SIGINT/SIGTERM finish the current step, write it and return
 * UMP_OK (stopAt writeNow). */
ump_status mlapp_run(const char *case_dir, ump_err *err);

#endif
