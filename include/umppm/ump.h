/* SPDX-License-Identifier: GPL-3.0-or-later
 * ump.h -- shared utilities of umppmFoam: index type, status codes, error
 * records, checked allocation.
 *
 * Contract used by every module:
 *   - a function that can fail returns ump_status and, on failure, fills the
 *     caller's ump_err with ONE line that names the input file (and line for
 *     text input) and says what was expected;
 *   - only main() prints the error and exits;
 *   - allocation goes through ump_alloc_array()/ump_realloc_array(), which
 *     check n*size for overflow.
 */
#ifndef UMPPM_UMP_H
#define UMPPM_UMP_H

#include <stddef.h>
#include <stdint.h>

/* Index type for cells, faces, points and particles: chosen in one place. */
typedef int32_t ump_idx;
#define UMP_IDX_MAX INT32_MAX

typedef enum ump_status {
    UMP_OK = 0,
    UMP_ERR_NOMEM,       /* allocation failed or size overflow */
    UMP_ERR_IO,          /* file missing, unreadable, cut short */
    UMP_ERR_PARSE,       /* text/binary not in OpenFOAM form */
    UMP_ERR_INPUT,       /* well-formed but inconsistent or out of range */
    UMP_ERR_UNSUPPORTED, /* valid OpenFOAM input umppmFoam does not handle */
    UMP_ERR_SINGULAR     /* a linear system could not be factorized/solved */
} ump_status;

/* An error record. msg is one line, "<file>[:<line>]: <what>". */
typedef struct ump_err {
    ump_status code;
    char msg[1024];
    const char *src_file; /* where in umppmFoam it was raised (debugging) */
    int src_line;
} ump_err;

/* Record an error (printf-style message) and return code. */
ump_status ump_fail(ump_err *err, ump_status code, const char *src_file,
                    int src_line, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 5, 6)))
#endif
    ;

/* The running solver's name ("umppmFoam" unless main sets it), for the
 * messages of the modules both solvers share. */
extern const char *ump_solver;

/* Name of a status code ("I/O error", ...). */
const char *ump_status_name(ump_status s);

#define UMP_FAIL(err, code, ...) \
    ump_fail((err), (code), __FILE__, __LINE__, __VA_ARGS__)

/* Stays on in release builds. */
#define UMP_CHECK(cond, err, code, ...) \
    do { if (!(cond)) return UMP_FAIL((err), (code), __VA_ARGS__); } while (0)

/* Propagate a failing status. */
#define UMP_CALL(expr) \
    do { ump_status ump_rc_ = (expr); if (ump_rc_ != UMP_OK) return ump_rc_; } while (0)

/* Zeroed array of n elements of size bytes; NULL on overflow or failure.
 * ump_alloc_array(0, s) returns a valid (freeable) pointer. */
void *ump_alloc_array(size_t n, size_t size);
/* Resize; on failure returns NULL and leaves p untouched. New tail is NOT zeroed. */
void *ump_realloc_array(void *p, size_t n, size_t size);
/* Copy of a NUL-terminated string (NULL on failure). */
char *ump_strdup(const char *s);
/* Copy of the first n bytes of s, NUL-terminated. */
char *ump_strndup(const char *s, size_t n);

/* Test hook: make the n-th following allocation fail (n < 0: never). */
void ump_alloc_fail_after(long n);
/* Peak bytes requested through ump_alloc_array/ump_realloc_array so far
 * (approximate: frees are not tracked; use getrusage for RSS). */
size_t ump_alloc_requested(void);

#define UMP_PI 3.14159265358979323846

#define UMP_MIN(a, b) ((a) < (b) ? (a) : (b))
/* Hot kernels compiled for AVX2 and baseline x86-64, one chosen at load
 * time (gcc's target_clones, an ifunc); elsewhere (other CPUs, clang's
 * sanitizer build) one baseline version. */
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
#define UMP_TARGET_CLONES __attribute__((target_clones("arch=x86-64-v3", "default")))
#else
#define UMP_TARGET_CLONES
#endif

#define UMP_MAX(a, b) ((a) > (b) ? (a) : (b))

#endif
