/* SPDX-License-Identifier: GPL-3.0-or-later
 * killshim.c -- LD_PRELOAD shim for test_nothing_lost.sh: counts the
 * write-related calls of a process and SIGKILLs it at the k-th one, before
 * the call takes effect.
 *
 * Counted: mkdir, rmdir, unlink, remove, rename, renameat2, open/open64
 * with O_WRONLY/O_RDWR/O_CREAT (zlib's gzopen), fopen/fopen64 for writing,
 * and fclose of a FILE opened for writing (so a kill can fall between the
 * last byte written and the close, or between two files).
 *
 * Environment:
 *   UMPPM_KILL_AT=k          SIGKILL at the k-th counted call (unset/0: never)
 *   UMPPM_KILL_COUNT=FILE    at a normal exit, write the number of counted
 *                            calls to FILE
 *   UMPPM_KILL_NOEXCHANGE=1  renameat2(..., RENAME_EXCHANGE) fails with
 *                            EINVAL, as on a filesystem without it (the
 *                            writer's two-rename fallback)
 */
#define _GNU_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <unistd.h>

#include "shim.h"

#ifndef RENAME_EXCHANGE
#define RENAME_EXCHANGE (1 << 1)
#endif

static long count, kill_at; /* under shim_lock, with the FILE table */
static int no_exchange;
static FILE *writing[256]; /* FILEs opened for writing (fclose is counted) */

__attribute__((constructor)) static void shim_init(void)
{
    const char *k = getenv("UMPPM_KILL_AT"), *x = getenv("UMPPM_KILL_NOEXCHANGE");
    kill_at = k ? atol(k) : 0;
    no_exchange = x && *x == '1';
}

typedef int (*open_fn)(const char *, int, ...);
typedef int (*path_fn)(const char *);
typedef int (*mkdir_fn)(const char *, mode_t);
typedef int (*rename_fn)(const char *, const char *);
typedef int (*renameat2_fn)(int, const char *, int, const char *, unsigned int);
typedef FILE *(*fopen_fn)(const char *, const char *);
typedef int (*fclose_fn)(FILE *);

__attribute__((destructor)) static void shim_fini(void)
{
    const char *f = getenv("UMPPM_KILL_COUNT");
    if (!f || !*f)
        return;
    SHIM_NEXT(open_fn, open);
    char buf[32];
    int n = snprintf(buf, sizeof buf, "%ld\n", count);
    int fd = real_open(f, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) {
        ssize_t w = write(fd, buf, (size_t)n);
        (void)w;
        close(fd);
    }
}

static void tick(void)
{
    pthread_mutex_lock(&shim_lock);
    count++;
    if (kill_at > 0 && count == kill_at)
        kill(getpid(), SIGKILL);
    pthread_mutex_unlock(&shim_lock);
}

static int for_writing(int flags)
{
    return (flags & (O_WRONLY | O_RDWR | O_CREAT)) != 0;
}

static int mode_writes(const char *mode)
{
    return mode && (strchr(mode, 'w') || strchr(mode, 'a') || strchr(mode, '+'));
}

static void remember(FILE *fp)
{
    pthread_mutex_lock(&shim_lock);
    for (size_t i = 0; fp && i < sizeof writing / sizeof writing[0]; i++)
        if (!writing[i]) {
            writing[i] = fp;
            break;
        }
    pthread_mutex_unlock(&shim_lock);
}

static int forget(FILE *fp)
{
    int found = 0;
    pthread_mutex_lock(&shim_lock);
    for (size_t i = 0; fp && i < sizeof writing / sizeof writing[0]; i++)
        if (writing[i] == fp) {
            writing[i] = NULL;
            found = 1;
            break;
        }
    pthread_mutex_unlock(&shim_lock);
    return found;
}

int mkdir(const char *path, mode_t mode)
{
    SHIM_NEXT(mkdir_fn, mkdir);
    tick();
    return real_mkdir(path, mode);
}

int rmdir(const char *path)
{
    SHIM_NEXT(path_fn, rmdir);
    tick();
    return real_rmdir(path);
}

int unlink(const char *path)
{
    SHIM_NEXT(path_fn, unlink);
    tick();
    return real_unlink(path);
}

int remove(const char *path)
{
    SHIM_NEXT(path_fn, remove);
    tick();
    return real_remove(path);
}

int rename(const char *from, const char *to)
{
    SHIM_NEXT(rename_fn, rename);
    tick();
    return real_rename(from, to);
}

int renameat2(int fd1, const char *from, int fd2, const char *to, unsigned int flags)
{
    SHIM_NEXT(renameat2_fn, renameat2);
    tick();
    if (no_exchange && (flags & RENAME_EXCHANGE)) {
        errno = EINVAL;
        return -1;
    }
    return real_renameat2(fd1, from, fd2, to, flags);
}

int open(const char *path, int flags, ...)
{
    SHIM_NEXT(open_fn, open);
    mode_t mode = 0;
    if (flags & O_CREAT) {
        va_list ap;
        va_start(ap, flags);
        mode = (mode_t)va_arg(ap, int);
        va_end(ap);
    }
    if (for_writing(flags))
        tick();
    return real_open(path, flags, mode);
}

int open64(const char *path, int flags, ...)
{
    SHIM_NEXT(open_fn, open64);
    mode_t mode = 0;
    if (flags & O_CREAT) {
        va_list ap;
        va_start(ap, flags);
        mode = (mode_t)va_arg(ap, int);
        va_end(ap);
    }
    if (for_writing(flags))
        tick();
    return real_open64(path, flags, mode);
}

FILE *fopen(const char *path, const char *mode)
{
    SHIM_NEXT(fopen_fn, fopen);
    int w = mode_writes(mode);
    if (w)
        tick();
    FILE *fp = real_fopen(path, mode);
    if (w)
        remember(fp);
    return fp;
}

FILE *fopen64(const char *path, const char *mode)
{
    SHIM_NEXT(fopen_fn, fopen64);
    int w = mode_writes(mode);
    if (w)
        tick();
    FILE *fp = real_fopen64(path, mode);
    if (w)
        remember(fp);
    return fp;
}

int fclose(FILE *fp)
{
    SHIM_NEXT(fclose_fn, fclose);
    if (forget(fp))
        tick();
    return real_fclose(fp);
}
