/* SPDX-License-Identifier: GPL-3.0-or-later
 * write_cloud.c -- writes a known particle cloud into <case>/<time> with
 * fio_write_cloud, reads it back with fio_read_cloud and checks the round
 * trip; the calling script then has foamToVTK convert it.
 *   write_cloud <case> <time> <n>
 * Particle i sits at the centre of cell (i*7) % ncells of the 20x20 cavity
 * (0.1 m, cells of 0.005 m), velocity (i, -i, 0), id 1000+i.
 */
#include "umppm/fieldio.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

int main(int argc, char **argv)
{
    if (argc != 4) {
        fprintf(stderr, "usage: write_cloud <case> <time> <n>\n");
        return 2;
    }
    size_t n = (size_t)atol(argv[3]);
    double *pos = calloc(3 * n + 1, sizeof *pos), *vel = calloc(3 * n + 1, sizeof *vel);
    ump_idx *cell = calloc(n + 1, sizeof *cell);
    int64_t *id = calloc(n + 1, sizeof *id);
    for (size_t i = 0; i < n; i++) {
        ump_idx c = (ump_idx)((i * 7) % 400);
        cell[i] = c;
        pos[3 * i] = 0.0025 + 0.005 * (c % 20);
        pos[3 * i + 1] = 0.0025 + 0.005 * (c / 20);
        pos[3 * i + 2] = 0.005;
        vel[3 * i] = (double)i;
        vel[3 * i + 1] = -(double)i;
        id[i] = 1000 + (int64_t)i;
    }
    char dir[4096];
    snprintf(dir, sizeof dir, "%s/%s", argv[1], argv[2]);
    ump_err err;
    if (fio_write_cloud(dir, argv[2], "umppmCloud", n, pos, vel, cell, id, 10, &err) != UMP_OK) {
        fprintf(stderr, "write_cloud: %s\n", err.msg);
        return 1;
    }
    size_t m;
    double *p2, *v2;
    int64_t *id2;
    ump_idx *c2;
    if (fio_read_cloud(dir, "umppmCloud", &m, &p2, &v2, &id2, &c2, &err) != UMP_OK) {
        fprintf(stderr, "write_cloud: read back: %s\n", err.msg);
        return 1;
    }
    int bad = m != n;
    for (size_t i = 0; i < n && !bad; i++)
        for (int k = 0; k < 3; k++)
            bad |= fabs(p2[3 * i + (size_t)k] - pos[3 * i + (size_t)k]) > 1e-12 ||
                   fabs(v2[3 * i + (size_t)k] - vel[3 * i + (size_t)k]) > 1e-12 || id2[i] != id[i] ||
                   c2[i] != cell[i];
    if (bad) {
        fprintf(stderr, "write_cloud: read back differs\n");
        return 1;
    }
    free(pos); free(vel); free(cell); free(id); free(p2); free(v2); free(id2); free(c2);
    return 0;
}
