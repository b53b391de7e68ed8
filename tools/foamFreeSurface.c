/* SPDX-License-Identifier: GPL-3.0-or-later
 * foamFreeSurface -- the surge front and the residual column height of a 2-D
 * dam break, from the volume-fraction field written by any solver (interFoam,
 * meshlessFoam), with the same formulas for both.
 *
 *   foamFreeSurface <case> [-field alpha.water] [-threshold 0.5] [-x0 X]
 *                   [-column W] [-time T]...
 *
 * Prints "# time front height", then one line per time directory holding
 * the field (all numeric time directories in time order, or only those given
 * with -time, matched by value), coordinates in the mesh's in-plane axes
 * (X, Y) of mesh2d.h (x, y for a z-normal mesh; gravity along -Y):
 *
 *   front  = max over the cells c with alpha_c >= threshold of
 *            X_c + (alpha_c - 0.5) dX_c
 *            (X_c the centroid, dX_c the cell's X extent): the right edge
 *            of a full cell, its centroid when half full, i.e. the water
 *            taken as filling the cell from its left side. A droplet or a
 *            splash that fills a cell past the threshold counts as water,
 *            so this is the farthest wetted point, not only along the floor.
 *            "nan" when no cell reaches the threshold.
 *   height = the water depth at the back wall X = x0 (default: the mesh's
 *            X min): without -column, the sum of alpha_c A_c / dX_c (the
 *            cell's mean height, dY for a rectangle) over the cells whose
 *            X range [Xmin_c, Xmax_c) contains x0 (1e-9 of the domain size
 *            tolerance: at the mesh's X min, its first column of cells);
 *            with -column W, sum(alpha_c A_c) / W over the cells whose
 *            centroid lies in [x0, x0 + W) (a depth averaged over width W).
 *
 * Exit 0 after printing at least one time, 1 on bad options, read errors,
 * a -time without such a directory or field, or no time with the field.
 */
#include "umppm/case.h"
#include "umppm/fieldio.h"
#include "umppm/mesh2d.h"
#include "umppm/polymesh.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define USAGE                                                                                                \
    "usage: foamFreeSurface <case> [-field alpha.water] [-threshold 0.5] [-x0 X] [-column W] [-time T]..."

typedef struct opts {
    const char *dir, *field;
    double threshold, x0, column;
    int has_x0;
    const char **times; /* -time values as given, ntimes of them */
    int ntimes;
} opts;

/* Print msg; returns 0, the failure value of the functions below. */
static int fail(const char *msg)
{
    fprintf(stderr, "foamFreeSurface: %s\n", msg);
    return 0;
}

static int number(const char *s, double *v)
{
    char *end;
    *v = strtod(s, &end);
    return end != s && *end == '\0' && isfinite(*v);
}

/* Options into o; 0 (message printed) on a bad one. */
static int parse(int argc, char **argv, opts *o)
{
    o->field = "alpha.water";
    o->threshold = 0.5;
    o->times = calloc((size_t)argc, sizeof *o->times);
    if (!o->times)
        return fail("out of memory");
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (a[0] != '-') {
            if (o->dir)
                return fail(USAGE);
            o->dir = a;
            continue;
        }
        const char *v = i + 1 < argc ? argv[++i] : NULL;
        if (!v)
            return fail(USAGE);
        if (!strcmp(a, "-field")) o->field = v;
        else if (!strcmp(a, "-threshold") && number(v, &o->threshold)) ;
        else if (!strcmp(a, "-x0") && number(v, &o->x0)) o->has_x0 = 1;
        else if (!strcmp(a, "-column") && number(v, &o->column) && o->column > 0) ;
        else if (!strcmp(a, "-time")) o->times[o->ntimes++] = v;
        else {
            fprintf(stderr, "foamFreeSurface: bad option or value: %s %s\n%s\n", a, v, USAGE);
            return 0;
        }
    }
    if (!o->dir)
        return fail(USAGE);
    return 1;
}

/* Per-cell X range of the polygon (the mesh keeps only its extent dX). */
static void cell_xrange(const mesh2d *m, double *xlo, double *xhi)
{
    for (ump_idx c = 0; c < m->ncells; c++) {
        xlo[c] = INFINITY;
        xhi[c] = -INFINITY;
        for (ump_idx k = m->cell_off[c]; k < m->cell_off[c + 1]; k++) {
            double x = m->vx[m->cell_verts[k]];
            xlo[c] = fmin(xlo[c], x);
            xhi[c] = fmax(xhi[c], x);
        }
    }
}

static double front_of(const mesh2d *m, const double *alpha, double threshold)
{
    double f = NAN;
    for (ump_idx c = 0; c < m->ncells; c++)
        if (alpha[c] >= threshold) {
            double x = m->cx[c] + (alpha[c] - 0.5) * m->dx[c];
            if (isnan(f) || x > f)
                f = x;
        }
    return f;
}

static double height_of(const mesh2d *m, const double *alpha, const double *xlo, const double *xhi,
                        const opts *o, double x0, double tol)
{
    double s = 0;
    for (ump_idx c = 0; c < m->ncells; c++) {
        if (o->column > 0) {
            if (m->cx[c] >= x0 && m->cx[c] < x0 + o->column)
                s += alpha[c] * m->area[c];
        } else if (xlo[c] <= x0 + tol && xhi[c] > x0 + tol) {
            s += alpha[c] * m->area[c] / m->dx[c];
        }
    }
    return o->column > 0 ? s / o->column : s;
}

/* 1 if <path> or <path>.gz exists (fio_read_field reads either). */
static int field_exists(const char *path)
{
    char gz[4410];
    snprintf(gz, sizeof gz, "%s.gz", path);
    return access(path, R_OK) == 0 || access(gz, R_OK) == 0;
}

/* Index k of the -time value t among the time directories, -1 if none
 * (by value, so "-time 0.10" finds directory 0.1). */
static int find_time(const char *t, const double *values, int nt)
{
    double v;
    if (!number(t, &v))
        return -1;
    for (int k = 0; k < nt; k++)
        if (fabs(values[k] - v) <= 1e-12 * fmax(1, fabs(v)))
            return k;
    return -1;
}

/* Print the line of time directory tname; 0 on a read error. */
static int report(const opts *o, const pmesh *pm, const mesh2d *m, const char *tname, const double *xlo,
                  const double *xhi, double x0, double tol)
{
    char path[4400];
    ump_err err;
    fld_field *a = NULL;
    snprintf(path, sizeof path, "%s/%s/%s", o->dir, tname, o->field);
    if (fio_read_field(path, pm, 1, &a, &err) != UMP_OK)
        return fail(err.msg);
    printf("%s %.8g %.8g\n", tname, front_of(m, a->internal, o->threshold),
           height_of(m, a->internal, xlo, xhi, o, x0, tol));
    fld_free(&a);
    return 1;
}

/* The domain's X min (x0's default) into *xmin and 1e-9 of its size (the
 * tolerance of "touches x0") into *tol. */
static void domain(const mesh2d *m, double *xmin, double *tol)
{
    double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
    for (ump_idx v = 0; v < m->nverts; v++) {
        x0 = fmin(x0, m->vx[v]);
        x1 = fmax(x1, m->vx[v]);
        y0 = fmin(y0, m->vy[v]);
        y1 = fmax(y1, m->vy[v]);
    }
    *xmin = x0;
    *tol = 1e-9 * fmax(x1 - x0, y1 - y0);
}

/* The indices of the time directories to report into pick (*npick of
 * them): the -time ones, all checked here so that an error comes before
 * any output; else every one holding the field. 0 (message printed) on a
 * -time without a directory. */
static int pick_times(const opts *o, char **names, const double *values, int nt, int *pick, int *npick)
{
    *npick = 0;
    for (int i = 0; i < o->ntimes; i++)
        if ((pick[(*npick)++] = find_time(o->times[i], values, nt)) < 0) {
            fprintf(stderr, "foamFreeSurface: %s: no time directory %s\n", o->dir, o->times[i]);
            return 0;
        }
    for (int k = 0; k < nt && o->ntimes == 0; k++) {
        char path[4400];
        snprintf(path, sizeof path, "%s/%s/%s", o->dir, names[k], o->field);
        if (field_exists(path)) /* else e.g. a 0/ without the field */
            pick[(*npick)++] = k;
    }
    if (*npick == 0)
        fprintf(stderr, "foamFreeSurface: %s: no time directory holds %s\n", o->dir, o->field);
    return *npick > 0;
}

int main(int argc, char **argv)
{
    opts o = {0};
    pmesh *pm = NULL;
    mesh2d *m = NULL;
    char **names = NULL;
    double *values = NULL, *xlo = NULL, *xhi = NULL, x0, tol;
    int nt = 0, rc = 1, *pick = NULL, npick = 0, i = 0;
    ump_err err;
    char dir[4096];
    if (!parse(argc, argv, &o))
        goto out;
    snprintf(dir, sizeof dir, "%s/constant/polyMesh", o.dir);
    if (pmesh_read(dir, &pm, &err) != UMP_OK || mesh_build(pm, &m, &err) != UMP_OK ||
        case_list_times(o.dir, &names, &values, &nt, &err) != UMP_OK) {
        fail(err.msg);
        goto out;
    }
    xlo = calloc((size_t)m->ncells + 1, sizeof *xlo);
    xhi = calloc((size_t)m->ncells + 1, sizeof *xhi);
    pick = calloc((size_t)nt + (size_t)o.ntimes + 1, sizeof *pick);
    if (!xlo || !xhi || !pick) {
        fail("out of memory");
        goto out;
    }
    cell_xrange(m, xlo, xhi);
    domain(m, &x0, &tol);
    if (o.has_x0)
        x0 = o.x0;
    if (!pick_times(&o, names, values, nt, pick, &npick))
        goto out;
    printf("# time front height\n");
    while (i < npick && report(&o, pm, m, names[pick[i]], xlo, xhi, x0, tol))
        i++;
    rc = i < npick;
out:
    free(xlo);
    free(xhi);
    free(pick);
    free(o.times);
    case_free_times(names, values, nt);
    mesh_free(&m);
    pmesh_free(&pm);
    return rc;
}
