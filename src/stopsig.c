/* SPDX-License-Identifier: GPL-3.0-or-later
 * stopsig.c -- SIGINT/SIGTERM raise a flag for the time loop (stopsig.h).
 * The handler does nothing but store the signal number (async-signal-safe);
 * printing happens in the loop.
 */
#include "umppm/stopsig.h"

#include <signal.h>
#include <stdio.h>
#include <string.h>

static volatile sig_atomic_t pending;

static void on_signal(int sig)
{
    pending = sig;
}

int stopsig_install(void)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    /* one graceful stop; the second signal takes the default action */
    sa.sa_flags = SA_RESETHAND | SA_RESTART;
    pending = 0;
    if (sigaction(SIGINT, &sa, NULL) != 0 || sigaction(SIGTERM, &sa, NULL) != 0)
        return -1;
    return 0;
}

int stopsig_pending(void)
{
    return (int)pending;
}

const char *stopsig_name(int sig)
{
    static char buf[32];
    if (sig == SIGINT)
        return "SIGINT";
    if (sig == SIGTERM)
        return "SIGTERM";
    snprintf(buf, sizeof buf, "signal %d", sig);
    return buf;
}
