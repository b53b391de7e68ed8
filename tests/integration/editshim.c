/* SPDX-License-Identifier: GPL-3.0-or-later
 * editshim.c -- LD_PRELOAD shim for test_runtime_modifiable.sh: edits a
 * file (system/controlDict) at a chosen moment of a run, deterministically,
 * as a user would between two time steps.
 *
 * The moment is the creation of a time directory: when the process calls
 * mkdir on a path whose last component is T (OpenFOAM's solvers create
 * <case>/T) or starts with ".T.tmp." (umppmFoam writes into .T.tmp.<pid>
 * and renames it into place), the prepared file is renamed over the target
 * before that mkdir runs. The edit thus happens while time T is written,
 * and the solver sees it at the start of the step after T, both for
 * umppmFoam and for icoFoam: one test can run the same edit on both. Each
 * edit fires once; its source file is gone afterwards (the test checks
 * that).
 *
 * Environment:
 *   UMPPM_EDIT_TARGET=FILE     the file to replace
 *   UMPPM_EDIT_AT="T=SRC ..."  space-separated: at time directory T, rename
 *                              SRC over FILE (at most 16 edits)
 * A rename that fails aborts the process (the test then fails loudly).
 */
#define _GNU_SOURCE
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <unistd.h>

#include "shim.h"

#define MAX_EDITS 16

static struct {
    char time[64];
    char src[4096];
    int done;
} edits[MAX_EDITS];
static int nedits;
static const char *target;

__attribute__((constructor)) static void shim_init(void)
{
    target = getenv("UMPPM_EDIT_TARGET");
    const char *at = getenv("UMPPM_EDIT_AT");
    if (!target || !at)
        return;
    char buf[MAX_EDITS * 4200];
    snprintf(buf, sizeof buf, "%s", at);
    for (char *save = NULL, *tok = strtok_r(buf, " ", &save); tok; tok = strtok_r(NULL, " ", &save)) {
        char *eq = strchr(tok, '=');
        if (!eq || nedits == MAX_EDITS || (size_t)(eq - tok) >= sizeof edits[0].time)
            shim_die("editshim: UMPPM_EDIT_AT must be \"T=SRC ...\" (at most 16)\n");
        memcpy(edits[nedits].time, tok, (size_t)(eq - tok));
        edits[nedits].time[eq - tok] = '\0';
        snprintf(edits[nedits].src, sizeof edits[nedits].src, "%s", eq + 1);
        nedits++;
    }
}

/* 1 if the last component of path is t or starts with ".<t>.tmp." */
static int is_time_dir(const char *path, const char *t)
{
    const char *base = strrchr(path, '/');
    base = base ? base + 1 : path;
    size_t n = strlen(t);
    if (strcmp(base, t) == 0)
        return 1;
    return base[0] == '.' && strncmp(base + 1, t, n) == 0 && strncmp(base + 1 + n, ".tmp.", 5) == 0;
}

typedef int (*mkdir_fn)(const char *, mode_t);

int mkdir(const char *path, mode_t mode)
{
    SHIM_NEXT(mkdir_fn, mkdir);
    pthread_mutex_lock(&shim_lock);
    for (int i = 0; i < nedits; i++)
        if (!edits[i].done && is_time_dir(path, edits[i].time)) {
            edits[i].done = 1;
            if (rename(edits[i].src, target) != 0)
                shim_die("editshim: rename of the prepared file over the target failed\n");
        }
    pthread_mutex_unlock(&shim_lock);
    return real_mkdir(path, mode);
}
