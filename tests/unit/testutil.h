/* SPDX-License-Identifier: GPL-3.0-or-later
 * testutil.h -- helpers shared by the cmocka unit tests.
 * Tests run from the repository root; scratch files go under a fresh
 * directory made by tu_tmpdir() (removed by tu_rmtree()).
 */
#ifndef UMPPM_TESTUTIL_H
#define UMPPM_TESTUTIL_H

#include <stdarg.h>
#include <stddef.h>
#include <setjmp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>
#include <cmocka.h>

/* Fresh directory /tmp/umppm-test-XXXXXX; path written into buf. */
static inline const char *tu_tmpdir(char *buf, size_t len)
{
    snprintf(buf, len, "/tmp/umppm-test-XXXXXX");
    if (!mkdtemp(buf))
        fail_msg("mkdtemp failed");
    return buf;
}

/* Write text to dir/name (creating nothing else). */
static inline void tu_write(const char *dir, const char *name, const char *text)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *fp = fopen(path, "wb");
    if (!fp)
        fail_msg("cannot write %s", path);
    fputs(text, fp);
    fclose(fp);
}

/* Write len raw bytes to dir/name. */
static inline void tu_write_bytes(const char *dir, const char *name, const void *p, size_t len)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *fp = fopen(path, "wb");
    if (!fp)
        fail_msg("cannot write %s", path);
    fwrite(p, 1, len, fp);
    fclose(fp);
}

static inline void tu_rmtree(const char *dir)
{
    char cmd[4200];
    if (strncmp(dir, "/tmp/umppm-test-", 16) != 0)
        return;
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    if (system(cmd) != 0)
        fprintf(stderr, "warning: could not remove %s\n", dir);
}

/* |a-b| <= tol*max(1,|a|,|b|) */
#define TU_CLOSE(a, b, tol) do { \
    double tu_a_ = (a), tu_b_ = (b); \
    double tu_s_ = fabs(tu_a_) > fabs(tu_b_) ? fabs(tu_a_) : fabs(tu_b_); \
    if (tu_s_ < 1) tu_s_ = 1; \
    if (!(fabs(tu_a_ - tu_b_) <= (tol) * tu_s_)) \
        fail_msg("%s = %.17g, %s = %.17g, tol %g", #a, tu_a_, #b, tu_b_, (double)(tol)); \
} while (0)

#endif
