/* SPDX-License-Identifier: GPL-3.0-or-later
 * ump.c -- status codes, error records and checked allocation.
 *
 * The only file-scope state is the solver's name for messages, the
 * allocation test hook and the running total of bytes requested: none is
 * read by numerics.
 */
#include "umppm/ump.h"

#include <stdarg.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const char *ump_solver = "umppmFoam";

/* atomic: allocations also happen in threads (per-thread work buffers,
 * concurrent readers); relaxed order, as neither value orders anything */
static _Atomic long fail_after = -1;   /* test hook: allocations left before failing */
static _Atomic size_t requested = 0;   /* bytes requested so far */

ump_status ump_fail(ump_err *err, ump_status code, const char *src_file,
                    int src_line, const char *fmt, ...)
{
    if (err) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(err->msg, sizeof err->msg, fmt, ap);
        va_end(ap);
        err->code = code;
        err->src_file = src_file;
        err->src_line = src_line;
    }
    return code;
}

const char *ump_status_name(ump_status s)
{
    switch (s) {
    case UMP_OK: return "ok";
    case UMP_ERR_NOMEM: return "out of memory";
    case UMP_ERR_IO: return "I/O error";
    case UMP_ERR_PARSE: return "parse error";
    case UMP_ERR_INPUT: return "invalid input";
    case UMP_ERR_UNSUPPORTED: return "unsupported input";
    case UMP_ERR_SINGULAR: return "singular system";
    }
    return "unknown error";
}

static int take_allocation(size_t bytes)
{
    long left = atomic_load_explicit(&fail_after, memory_order_relaxed);
    if (left == 0)
        return 0;
    if (left > 0)
        atomic_fetch_sub_explicit(&fail_after, 1, memory_order_relaxed);
    atomic_fetch_add_explicit(&requested, bytes, memory_order_relaxed);
    return 1;
}

void *ump_alloc_array(size_t n, size_t size)
{
    if (size != 0 && n > SIZE_MAX / size)
        return NULL;
    if (!take_allocation(n * size))
        return NULL;
    /* calloc(0, s) may return NULL: always ask for at least one byte */
    return calloc(n ? n : 1, size ? size : 1);
}

void *ump_realloc_array(void *p, size_t n, size_t size)
{
    if (size != 0 && n > SIZE_MAX / size)
        return NULL;
    if (!take_allocation(n * size))
        return NULL;
    size_t bytes = n * size;
    return realloc(p, bytes ? bytes : 1);
}

char *ump_strndup(const char *s, size_t n)
{
    char *d = ump_alloc_array(n + 1, 1);
    if (d) {
        memcpy(d, s, n);
        d[n] = '\0';
    }
    return d;
}

char *ump_strdup(const char *s)
{
    return s ? ump_strndup(s, strlen(s)) : NULL;
}

void ump_alloc_fail_after(long n) { atomic_store_explicit(&fail_after, n, memory_order_relaxed); }

size_t ump_alloc_requested(void) { return atomic_load_explicit(&requested, memory_order_relaxed); }
