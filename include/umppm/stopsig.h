/* SPDX-License-Identifier: GPL-3.0-or-later
 * stopsig.h -- SIGINT and SIGTERM as OpenFOAM's stopAtWriteNowSignal
 * (module prefix stopsig_): the signal only raises a flag; the time loop
 * finishes the current step, writes that time and ends as stopAt writeNow
 * does ("End", exit 0). The handler is installed with SA_RESETHAND, so a
 * second signal kills the process at once (as OpenFOAM's resetHandler).
 */
#ifndef UMPPM_STOPSIG_H
#define UMPPM_STOPSIG_H

/* Install the handler for SIGINT and SIGTERM; 0 on success. */
int stopsig_install(void);
/* The signal number received since stopsig_install (0: none). */
int stopsig_pending(void);
/* "SIGINT", "SIGTERM" or "signal N" for a signal number. */
const char *stopsig_name(int sig);

#endif
