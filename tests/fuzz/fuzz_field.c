/* SPDX-License-Identifier: GPL-3.0-or-later
 * fuzz_field.c -- libFuzzer harness for the field reader: the input is
 * written to a private temporary file and read by fio_read_field as a
 * volScalarField and as a volVectorField on a fixed mesh, the 3x3 unit
 * cavity built in memory (patches movingWall, fixedWalls, frontAndBack, as
 * the seeds' blockMesh cavity), then freed.
 *   make fuzz
 *   build/release/fuzz_field -max_len=16384 tests/fuzz/corpus_field
 * Seeds: 0/U and 0/p of the cavity, cell centres C/Cx written by
 * postProcess (nonuniform, ascii and binary).
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "umppm/field.h"
#include "umppm/fieldio.h"
#include "umppm/polymesh.h"

static char path[512];
static pmesh *pm;

static void cleanup(void)
{
    unlink(path);
    pmesh_free(&pm);
}

static int patch_of(double x, double y, void *ctx)
{
    (void)ctx;
    (void)x;
    return y > 1 - 1e-9 ? 0 : 1;
}

static int setup(void)
{
    if (pm)
        return 1;
    const char *t = access("/dev/shm", W_OK) == 0 ? "/dev/shm" : getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp";
    snprintf(path, sizeof path, "%s/fuzz_field.XXXXXX", t);
    int fd = mkstemp(path);
    if (fd < 0)
        return 0;
    close(fd);
    enum { N = 3 };
    double xy[2 * (N + 1) * (N + 1)];
    ump_idx off[N * N + 1], pv[4 * N * N];
    for (int j = 0; j <= N; j++)
        for (int i = 0; i <= N; i++) {
            xy[2 * (j * (N + 1) + i)] = (double)i / N;
            xy[2 * (j * (N + 1) + i) + 1] = (double)j / N;
        }
    off[0] = 0;
    for (int j = 0, c = 0; j < N; j++)
        for (int i = 0; i < N; i++, c++) {
            ump_idx a = j * (N + 1) + i;
            pv[4 * c] = a;
            pv[4 * c + 1] = a + 1;
            pv[4 * c + 2] = a + N + 2;
            pv[4 * c + 3] = a + N + 1;
            off[c + 1] = 4 * (c + 1);
        }
    static const char *const names[] = {"movingWall", "fixedWalls"};
    static const char *const types[] = {"wall", "wall"};
    ump_err err;
    if (pmesh_extrude(xy, (N + 1) * (N + 1), off, pv, N * N, 0.1, patch_of, NULL, names, types, 2, &pm,
                      &err) != UMP_OK) {
        fprintf(stderr, "fuzz_field: %s\n", err.msg);
        abort();
    }
    atexit(cleanup);
    return 1;
}

/* "N{" with N > 2^16 (see fuzz_polymesh.c): skipped. */
static int huge_uniform(const uint8_t *d, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        if (d[i] < '0' || d[i] > '9')
            continue;
        uint64_t v = 0;
        size_t j = i;
        while (j < n && d[j] >= '0' && d[j] <= '9') {
            if (v < (1u << 20))
                v = v * 10 + (uint64_t)(d[j] - '0');
            j++;
        }
        while (j < n && (d[j] == ' ' || d[j] == '\n' || d[j] == '\t' || d[j] == '\r'))
            j++;
        if (j < n && d[j] == '{' && v > (1u << 16))
            return 1;
        i = j;
    }
    return 0;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (!setup() || huge_uniform(data, size))
        return 0;
    FILE *f = fopen(path, "wb");
    if (!f)
        return 0;
    if (size)
        fwrite(data, 1, size, f);
    fclose(f);
    ump_err err;
    for (int nc = 1; nc <= 3; nc += 2) {
        fld_field *fld = NULL;
        if (fio_read_field(path, pm, nc, &fld, &err) == UMP_OK)
            fld_free(&fld);
    }
    return 0;
}
