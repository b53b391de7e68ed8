/* SPDX-License-Identifier: GPL-3.0-or-later
 * fieldio_recover.c -- the start-up half of fieldio.h's time directories:
 * what a killed run left behind is recovered or removed.
 *
 * The writer (fieldio_write.c) only ever leaves these hidden directories:
 *   .<t>.tmp.<pid>  a time directory being written, or, after the
 *                   RENAME_EXCHANGE of an overwrite, the previous version
 *                   being deleted: never the only copy of anything, removed;
 *   .<t>.old.<pid>  the previous version moved aside by the two-rename
 *                   overwrite (filesystems without RENAME_EXCHANGE): renamed
 *                   back to <t> when <t> is missing (killed between the two
 *                   renames), else removed (killed while deleting it);
 *   .<t>.del.<pid>  a time directory purgeWrite was deleting: removed.
 * A directory whose process is still running (kill(pid, 0) succeeds, and
 * it is not this process) is left alone, as is an .old one when a
 * non-directory sits at <t>.
 */
#include "umppm/fieldio.h"

#include <dirent.h>
#include <errno.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <unistd.h>

typedef struct hidden {
    char name[256];  /* the entry, .<t>.<kind>.<pid> */
    char time[256];  /* <t> */
    int kind;        /* 0 old, 1 tmp, 2 del (the order of treatment) */
    long pid;
} hidden;

/* Parse ".<t>.<kind>.<pid>"; 0 when name is not one of the writer's. */
static int parse_hidden(const char *name, hidden *h)
{
    static const char *const kinds[3] = {FIO_HIDDEN_OLD, FIO_HIDDEN_TMP, FIO_HIDDEN_DEL};
    size_t len = strlen(name);
    if (name[0] != '.' || len >= sizeof h->name)
        return 0;
    const char *dot = strrchr(name, '.');
    if (!dot || dot == name || !dot[1])
        return 0;
    char *end;
    errno = 0;
    long pid = strtol(dot + 1, &end, 10);
    if (*end || errno || pid <= 0 || dot[1] < '0' || dot[1] > '9')
        return 0;
    for (int k = 0; k < 3; k++) {
        size_t kl = strlen(kinds[k]);
        /* ".<t>" + "." + kind + "." + pid: <t> is at least one character */
        if ((size_t)(dot - name) < kl + 3)
            continue;
        const char *ks = dot - kl;
        if (ks[-1] != '.' || strncmp(ks, kinds[k], kl) != 0)
            continue;
        size_t tl = (size_t)(ks - 1 - (name + 1));
        memcpy(h->name, name, len + 1);
        memcpy(h->time, name + 1, tl);
        h->time[tl] = '\0';
        h->kind = k;
        h->pid = pid;
        return 1;
    }
    return 0;
}

static int process_running(long pid)
{
    if (pid == (long)getpid())
        return 0;
    return kill((pid_t)pid, 0) == 0 || errno == EPERM;
}

static int cmp_hidden(const void *a, const void *b)
{
    const hidden *x = a, *y = b;
    if (x->kind != y->kind)
        return x->kind - y->kind;
    return strcmp(x->name, y->name);
}

ump_status fio_recover(const char *case_dir, fio_recover_report report, void *ctx, ump_err *err)
{
    UMP_CHECK(case_dir && *case_dir, err, UMP_ERR_INPUT, "fio_recover: empty case path");
    DIR *d = opendir(case_dir);
    if (!d)
        return UMP_FAIL(err, UMP_ERR_IO, "%s: cannot read the case directory: %s", case_dir,
                        strerror(errno));
    hidden *list = NULL;
    size_t n = 0, cap = 0;
    ump_status rc = UMP_OK;
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        hidden h;
        if (!parse_hidden(e->d_name, &h))
            continue;
        if (n == cap) {
            size_t nc = cap ? 2 * cap : 8;
            hidden *l = ump_realloc_array(list, nc, sizeof *l);
            if (!l) {
                rc = UMP_FAIL(err, UMP_ERR_NOMEM, "%s: out of memory", case_dir);
                break;
            }
            list = l;
            cap = nc;
        }
        list[n++] = h;
    }
    closedir(d);
    if (rc == UMP_OK && n > 1)
        qsort(list, n, sizeof *list, cmp_hidden);
    for (size_t i = 0; rc == UMP_OK && i < n; i++) {
        const hidden *h = &list[i];
        char path[4400], target[4400];
        snprintf(path, sizeof path, "%s/%s", case_dir, h->name);
        snprintf(target, sizeof target, "%s/%s", case_dir, h->time);
        struct stat st;
        if (lstat(path, &st) != 0 || !S_ISDIR(st.st_mode))
            continue; /* not the writer's (or gone meanwhile) */
        if (process_running(h->pid)) {
            if (report)
                report(ctx, FIO_LEFT_RUNNING, h->name, h->time, h->pid);
            continue;
        }
        if (h->kind == 0 && lstat(target, &st) == 0 && !S_ISDIR(st.st_mode)) {
            /* the old version is the only directory of that time: kept */
            if (report)
                report(ctx, FIO_LEFT_BLOCKED, h->name, h->time, h->pid);
            continue;
        }
        if (h->kind == 0 && lstat(target, &st) != 0 && errno == ENOENT) {
            if (rename(path, target) != 0)
                rc = UMP_FAIL(err, UMP_ERR_IO, "%s: cannot recover time %s from it: %s", path,
                              h->time, strerror(errno));
            else if (report)
                report(ctx, FIO_RECOVERED, h->name, h->time, h->pid);
            continue;
        }
        if ((rc = fio_remove_dir(path, err)) == UMP_OK && report)
            report(ctx, h->kind == 1 ? FIO_REMOVED_TMP : h->kind == 0 ? FIO_REMOVED_OLD : FIO_REMOVED_DEL,
                   h->name, h->time, h->pid);
    }
    free(list);
    return rc;
}
