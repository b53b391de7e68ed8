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

/* splitmix64 random numbers: deterministic, platform-independent. */
static uint64_t tu_rng_state;
static inline void tu_rng_seed(uint64_t s) { tu_rng_state = s; }
static inline double tu_rnd(void) /* [0, 1) */
{
    uint64_t z = (tu_rng_state += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    z ^= z >> 31;
    return (double)(z >> 11) * (1.0 / 9007199254740992.0);
}
static inline double tu_rnd_in(double a, double b) { return a + (b - a) * tu_rnd(); }

/* Least squares min |A x - b| for a tall A (n rows, m <= 9 columns) given
 * column-wise: column i is Q[i * ld + 0 .. n-1]. Modified Gram-Schmidt QR,
 * twice for re-orthogonalisation, then back substitution -- an oracle
 * computed differently from the normal equations the library uses.
 * Overwrites Q; x gets m values. */
static inline void tu_lsq_qr(int m, int n, int ld, double *Q, const double *b, double *x)
{
    double R[9][9] = {{0}}, z[9];
    for (int c = 0; c < m; c++) {
        double *qc = Q + (size_t)c * ld;
        for (int pass = 0; pass < 2; pass++)
            for (int i = 0; i < c; i++) {
                const double *qi = Q + (size_t)i * ld;
                double r = 0;
                for (int j = 0; j < n; j++)
                    r += qi[j] * qc[j];
                R[i][c] += r;
                for (int j = 0; j < n; j++)
                    qc[j] -= r * qi[j];
            }
        double nr = 0;
        for (int j = 0; j < n; j++)
            nr += qc[j] * qc[j];
        R[c][c] = sqrt(nr);
        for (int j = 0; j < n; j++)
            qc[j] /= R[c][c];
    }
    for (int i = 0; i < m; i++) {
        z[i] = 0;
        for (int j = 0; j < n; j++)
            z[i] += Q[(size_t)i * ld + j] * b[j];
    }
    for (int i = m - 1; i >= 0; i--) {
        double v = z[i];
        for (int c = i + 1; c < m; c++)
            v -= R[i][c] * x[c];
        x[i] = v / R[i][i];
    }
}

#endif
