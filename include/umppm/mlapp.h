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

/* Command-line options. */
typedef struct mlapp_options {
    int reseed;               /* -reseed: a restart time without its cloud seeds from alpha */
    int no_function_objects;  /* -noFunctionObjects (none is run anyway) */
} mlapp_options;

/* The run. SIGINT/SIGTERM finish the current step, write it and return
 * UMP_OK (stopAt writeNow). */
ump_status mlapp_run(const char *case_dir, const mlapp_options *opt, ump_err *err);

#endif
