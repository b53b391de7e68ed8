/* SPDX-License-Identifier: GPL-3.0-or-later
 * fuzz_polymesh.c -- libFuzzer harness for the polyMesh reader and the 2-D
 * mesh: the input is split at each "@@FILE@@\n" into points, faces, owner,
 * neighbour and boundary (missing parts: the file is absent), written into a
 * private temporary directory, then read by pmesh_read and, when that
 * succeeds, turned into the 2-D mesh (mesh_build, its statistics, the LS
 * gradient) exactly as `umppmFoam -checkMesh` does.
 *   make fuzz
 *   build/release/fuzz_polymesh -max_len=16384 tests/fuzz/corpus_polymesh
 * Seeds: the 3x3 cavity and periodic square as blockMesh writes them (ascii,
 * binary).
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "umppm/lsq.h"
#include "umppm/mesh2d.h"
#include "umppm/polymesh.h"

static const char *const names[5] = {"points", "faces", "owner", "neighbour", "boundary"};
static char dir[512];

static void cleanup(void)
{
    char p[600];
    for (int i = 0; i < 5; i++) {
        snprintf(p, sizeof p, "%s/%s", dir, names[i]);
        unlink(p);
    }
    rmdir(dir);
}

static int make_dir(void)
{
    if (dir[0])
        return 1;
    const char *t = access("/dev/shm", W_OK) == 0 ? "/dev/shm" : getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp";
    snprintf(dir, sizeof dir, "%s/fuzz_polymesh.XXXXXX", t);
    if (!mkdtemp(dir)) {
        dir[0] = '\0';
        return 0;
    }
    atexit(cleanup);
    return 1;
}

/* "N{": a uniform list of N elements is expanded; above 2^16 it would only
 * measure the machine's memory (as fuzz_foam.c skips them). */
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

static const uint8_t *find_sep(const uint8_t *d, size_t n, const char *sep, size_t ls)
{
    for (size_t i = 0; i + ls <= n; i++)
        if (d[i] == (uint8_t)sep[0] && memcmp(d + i, sep, ls) == 0)
            return d + i;
    return NULL;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (!make_dir() || huge_uniform(data, size))
        return 0;
    static const char sep[] = "@@FILE@@\n";
    const size_t ls = sizeof sep - 1;
    const uint8_t *p = data, *end = data + size;
    char path[600];
    for (int i = 0; i < 5; i++) {
        snprintf(path, sizeof path, "%s/%s", dir, names[i]);
        unlink(path);
        if (!p)
            continue;
        const uint8_t *s = find_sep(p, (size_t)(end - p), sep, ls);
        size_t len = s ? (size_t)(s - p) : (size_t)(end - p);
        FILE *f = fopen(path, "wb");
        if (!f)
            return 0;
        if (len)
            fwrite(p, 1, len, f);
        fclose(f);
        p = s ? s + ls : NULL;
    }
    pmesh *pm = NULL;
    mesh2d *m = NULL;
    lsq_grad *g = NULL;
    ump_err err;
    if (pmesh_read(dir, &pm, &err) == UMP_OK && mesh_build(pm, &m, &err) == UMP_OK) {
        mesh_stats st;
        mesh_compute_stats(m, &st);
        if (lsq_build(m, &g, &err) == UMP_OK)
            lsq_free(&g);
    }
    mesh_free(&m);
    pmesh_free(&pm);
    return 0;
}
