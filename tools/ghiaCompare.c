/* SPDX-License-Identifier: GPL-3.0-or-later
 * ghiaCompare -- lid-driven cavity velocities against Ghia, Ghia & Shin
 * (1982), Tables I and II: u on the vertical centreline, v on the
 * horizontal centreline.
 *
 *   ghiaCompare [-Re 100] [-ref DIR] [-U 1] [-profiles] [-mean] <case> <time> [<case> <time> ...]
 *
 * The cavity is the bounding box of the mesh's face centres, so any square
 * cavity (OpenFOAM's 0.1 m tutorial, a unit one) is mapped onto Ghia's unit
 * square; velocities are divided by the lid speed -U. <time> may be
 * "latestTime". Each case's cell velocities are sampled at Ghia's points
 * by the linear reconstruction u_P + grad u_P . (x - x_P) in the cell that
 * holds the point, grad u_P the least-squares gradient of Eq. 26 -- the
 * same rule for every case, so an icoFoam run and a umppmFoam run of one
 * mesh are compared alike. Points on the walls (u, v fixed there) are left
 * out. Prints per case the RMS and max error of u and v over the interior
 * points (and with -profiles every sampled value). With -mean a last line
 * "mean" gives the errors of the mean of the sampled profiles over all the
 * given times: the sampling is linear in U, so this is the error of the
 * time-averaged field (for a run that does not settle to Ghia's steady
 * state). Exit 0, 1 on bad input.
 */
#include "umppm/case.h"
#include "umppm/fieldio.h"
#include "umppm/lsq.h"
#include "umppm/mesh2d.h"
#include "umppm/particles.h"
#include "umppm/polymesh.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifndef UMPPM_TOOLS_REF
#define UMPPM_TOOLS_REF "tools/reference"
#endif

enum { MAXPTS = 64 };
static const int ghia_re[] = {100, 400, 1000, 3200, 5000, 7500, 10000};

typedef struct profile {
    int n;
    double s[MAXPTS], val[MAXPTS]; /* coordinate along the line, Ghia's value */
} profile;

/* One table: lines "s v100 v400 ... v10000", '#' comments. */
static int read_table(const char *path, int col, profile *p)
{
    FILE *fp = fopen(path, "r");
    if (!fp) {
        fprintf(stderr, "ghiaCompare: cannot open %s (give the directory with -ref)\n", path);
        return 0;
    }
    char line[512];
    int lineno = 0;
    p->n = 0;
    while (fgets(line, sizeof line, fp)) {
        lineno++;
        if (line[0] == '#' || strspn(line, " \t\r\n") == strlen(line))
            continue;
        double v[8];
        if (sscanf(line, "%lf %lf %lf %lf %lf %lf %lf %lf", &v[0], &v[1], &v[2], &v[3], &v[4], &v[5],
                   &v[6], &v[7]) != 8 || p->n == MAXPTS) {
            fprintf(stderr, "ghiaCompare: %s:%d: expected 8 numbers (coordinate and 7 Reynolds numbers)\n",
                    path, lineno);
            fclose(fp);
            return 0;
        }
        p->s[p->n] = v[0];
        p->val[p->n++] = v[1 + col];
    }
    fclose(fp);
    return 1;
}

typedef struct sampled {
    double rms, max;
    double val[MAXPTS]; /* at the interior points */
} sampled;

/* Point i of a profile is inside the cavity (on the walls u, v are fixed
 * and left out). */
static int interior(const profile *ref, int i) { return ref->s[i] > 1e-9 && ref->s[i] < 1 - 1e-9; }

/* RMS and max error of val against the profile over its interior points. */
static void profile_errors(const profile *ref, const double *val, double *rms, double *max)
{
    double s2 = 0, mx = 0;
    int cnt = 0;
    for (int i = 0; i < ref->n; i++) {
        if (!interior(ref, i))
            continue;
        double e = val[i] - ref->val[i];
        s2 += e * e;
        mx = fmax(mx, fabs(e));
        cnt++;
    }
    *rms = sqrt(s2 / cnt);
    *max = mx;
}

/* Sample component k (0: u, 1: v) along the centreline: line 0 is x = 0.5
 * (s = y), line 1 is y = 0.5 (s = x). */
static int sample(const mesh2d *m, const double *uc, const double *gx, const double *gy, const double bb[4],
                  double Ulid, int line, const profile *ref, sampled *out)
{
    ump_idx start = 0;
    for (int i = 0; i < ref->n; i++) {
        if (!interior(ref, i))
            continue;
        double x = line == 0 ? 0.5 : ref->s[i], y = line == 0 ? ref->s[i] : 0.5;
        x = bb[0] + x * (bb[1] - bb[0]);
        y = bb[2] + y * (bb[3] - bb[2]);
        ump_idx cell, face;
        if (part_locate(m, start, &x, &y, &cell, &face) != PART_INSIDE) {
            fprintf(stderr, "ghiaCompare: point (%g, %g) is not inside the mesh\n", x, y);
            return 0;
        }
        start = cell;
        out->val[i] = (uc[cell] + gx[cell] * (x - m->cx[cell]) + gy[cell] * (y - m->cy[cell])) / Ulid;
    }
    profile_errors(ref, out->val, &out->rms, &out->max);
    return 1;
}

/* One line of the table: the RMS and max errors of u on x = 0.5 and of v
 * on y = 0.5. */
static void print_row(const char *name, const char *when, const sampled smp[2])
{
    printf("%-40s %8s %9.5f %9.5f %9.5f %9.5f\n", name, when, smp[0].rms, smp[0].max, smp[1].rms, smp[1].max);
}

static int run_case(const char *c, const char *tname, const profile ref[2], double Ulid, int profiles,
                    sampled smp[2])
{
    char path[4400];
    ump_err err;
    pmesh *pm = NULL;
    mesh2d *m = NULL;
    lsq_grad *g = NULL;
    fld_field *U = NULL;
    char **names = NULL;
    double *values = NULL;
    int nt = 0, ok = 0;
    double *buf = NULL;
    snprintf(path, sizeof path, "%s/constant/polyMesh", c);
    if (pmesh_read(path, &pm, &err) != UMP_OK || mesh_build(pm, &m, &err) != UMP_OK ||
        lsq_build(m, &g, &err) != UMP_OK)
        goto fail;
    if (!strcmp(tname, "latestTime")) {
        if (case_list_times(c, &names, &values, &nt, &err) != UMP_OK)
            goto fail;
        if (nt == 0) {
            fprintf(stderr, "ghiaCompare: %s: no time directories\n", c);
            goto out;
        }
        tname = names[nt - 1];
    }
    snprintf(path, sizeof path, "%s/%s/U", c, tname);
    if (fio_read_field(path, pm, 3, &U, &err) != UMP_OK)
        goto fail;
    size_t nc = (size_t)m->ncells;
    buf = malloc(9 * nc * sizeof *buf);
    if (!buf) {
        fprintf(stderr, "ghiaCompare: out of memory\n");
        goto out;
    }
    double bb[4] = {INFINITY, -INFINITY, INFINITY, -INFINITY};
    for (ump_idx f = 0; f < m->nfaces; f++) {
        bb[0] = fmin(bb[0], m->fx[f]);
        bb[1] = fmax(bb[1], m->fx[f]);
        bb[2] = fmin(bb[2], m->fy[f]);
        bb[3] = fmax(bb[3], m->fy[f]);
    }
    for (int k = 0; k < 2; k++) {
        double *uc = buf + (size_t)(3 * k) * nc, *gx = uc + nc, *gy = gx + nc;
        for (size_t i = 0; i < nc; i++)
            uc[i] = U->internal[3 * i + (size_t)m->ax[k]];
        lsq_gradient(g, uc, gx, gy);
        if (!sample(m, uc, gx, gy, bb, Ulid, k, &ref[k], &smp[k]))
            goto out;
    }
    print_row(c, tname, smp);
    if (profiles)
        for (int k = 0; k < 2; k++)
            for (int i = 0; i < ref[k].n; i++)
                if (interior(&ref[k], i))
                    printf("#   %c(%s = %.4f)  Ghia %9.5f  case %9.5f\n", "uv"[k], k ? "x" : "y", ref[k].s[i],
                           ref[k].val[i], smp[k].val[i]);
    ok = 1;
    goto out;
fail:
    fprintf(stderr, "ghiaCompare: %s\n", err.msg);
out:
    free(buf);
    fld_free(&U);
    case_free_times(names, values, nt);
    lsq_free(&g);
    mesh_free(&m);
    pmesh_free(&pm);
    return ok;
}

int main(int argc, char **argv)
{
    int re = 100, profiles = 0, mean = 0, i = 1;
    double Ulid = 1;
    const char *refdir = UMPPM_TOOLS_REF;
    for (; i < argc && argv[i][0] == '-'; i++) {
        if (!strcmp(argv[i], "-Re") && i + 1 < argc) re = atoi(argv[++i]);
        else if (!strcmp(argv[i], "-ref") && i + 1 < argc) refdir = argv[++i];
        else if (!strcmp(argv[i], "-U") && i + 1 < argc) Ulid = atof(argv[++i]);
        else if (!strcmp(argv[i], "-profiles")) profiles = 1;
        else if (!strcmp(argv[i], "-mean")) mean = 1;
        else break;
    }
    if (i >= argc || (argc - i) % 2 || !(Ulid > 0)) {
        fprintf(stderr, "usage: ghiaCompare [-Re 100] [-ref DIR] [-U 1] [-profiles] [-mean] <case> <time> "
                        "[<case> <time> ...]\n");
        return 1;
    }
    int col = -1;
    for (int k = 0; k < (int)(sizeof ghia_re / sizeof ghia_re[0]); k++)
        if (ghia_re[k] == re)
            col = k;
    if (col < 0) {
        fprintf(stderr, "ghiaCompare: Ghia et al. tabulate Re = 100 400 1000 3200 5000 7500 10000, not %d\n", re);
        return 1;
    }
    profile ref[2];
    char path[4200];
    snprintf(path, sizeof path, "%s/ghia1982_u_vertical_centreline.dat", refdir);
    if (!read_table(path, col, &ref[0]))
        return 1;
    snprintf(path, sizeof path, "%s/ghia1982_v_horizontal_centreline.dat", refdir);
    if (!read_table(path, col, &ref[1]))
        return 1;
    printf("# Ghia et al. (1982) Re = %d: u on x = 0.5 (%d interior points), v on y = 0.5 (%d)\n", re,
           ref[0].n - 2, ref[1].n - 2);
    printf("%-40s %8s %9s %9s %9s %9s\n", "# case", "time", "u_rms", "u_max", "v_rms", "v_max");
    int rc = 0, n = 0;
    sampled avg[2] = {0};
    for (; i + 1 < argc; i += 2) {
        sampled smp[2];
        if (!run_case(argv[i], argv[i + 1], ref, Ulid, profiles, smp)) {
            rc = 1;
            continue;
        }
        n++;
        for (int k = 0; k < 2; k++)
            for (int j = 0; j < ref[k].n; j++)
                avg[k].val[j] += interior(&ref[k], j) ? smp[k].val[j] : 0.0;
    }
    if (mean && n > 0 && !rc) {
        for (int k = 0; k < 2; k++) {
            for (int j = 0; j < ref[k].n; j++)
                avg[k].val[j] /= n;
            profile_errors(&ref[k], avg[k].val, &avg[k].rms, &avg[k].max);
        }
        char what[32];
        snprintf(what, sizeof what, "%d times", n);
        print_row("mean", what, avg);
    }
    return rc;
}
