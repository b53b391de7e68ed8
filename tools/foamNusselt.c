/* SPDX-License-Identifier: GPL-3.0-or-later
 * foamNusselt -- the wall Nusselt number of Eqs. 43-45 of Ng, Sheu & Hwang
 * (2016) from the temperature fields written by any solver (umppmFoam or
 * buoyantBoussinesqPimpleFoam), with the same snGrad formula for both:
 * dT/dn = (T_face - T_cell) / (n . (x_face - x_cell)), Nu = dT/dn S / (T1 - T2),
 * area-weighted over the patch.
 *
 *   foamNusselt [-case DIR] -patch NAME -length S [-T1 v] [-T2 v] [-time NAME]
 *
 * Defaults: T1 the patch mean temperature, T2 TRef of
 * constant/transportProperties; every time directory but 0 unless -time.
 * Prints "time Nu_avg Nu_min Nu_max" per time, then a line
 * "RESULT time=... Nu_avg=..." for the last. Exit 1 on bad input.
 */
#include "umppm/case.h"
#include "umppm/fieldio.h"
#include "umppm/funcobj.h"
#include "umppm/mesh2d.h"
#include "umppm/polymesh.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int die(const char *msg)
{
    fprintf(stderr, "foamNusselt: %s\n", msg);
    return 1;
}

static int number(const char *s, double *v)
{
    char *end;
    *v = strtod(s, &end);
    return end != s && *end == '\0' && isfinite(*v);
}

int main(int argc, char **argv)
{
    const char *c = ".", *time = NULL;
    fob_nusselt f;
    memset(&f, 0, sizeof f);
    f.kappa = 1;
    f.snGrad = 1;
    for (int i = 1; i < argc; i++) {
        const char *o = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (!v)
            return die("usage: foamNusselt [-case DIR] -patch NAME -length S [-T1 v] [-T2 v] [-time NAME]");
        i++;
        if (!strcmp(o, "-case")) c = v;
        else if (!strcmp(o, "-time")) time = v;
        else if (!strcmp(o, "-patch")) snprintf(f.c.patch, sizeof f.c.patch, "%s", v);
        else if (!strcmp(o, "-length") && number(v, &f.length) && f.length > 0) ;
        else if (!strcmp(o, "-T1") && number(v, &f.T1)) f.has_T1 = 1;
        else if (!strcmp(o, "-T2") && number(v, &f.T2)) f.has_T2 = 1;
        else {
            fprintf(stderr, "foamNusselt: bad option or value: %s %s\n", o, v);
            return 1;
        }
    }
    if (!f.c.patch[0] || !(f.length > 0))
        return die("-patch and -length are required");
    ump_err err;
    char dir[4096];
    pmesh *pm = NULL;
    mesh2d *m = NULL;
    case_transport tr;
    snprintf(dir, sizeof dir, "%s/constant/polyMesh", c);
    if (pmesh_read(dir, &pm, &err) != UMP_OK || mesh_build(pm, &m, &err) != UMP_OK)
        return die(err.msg);
    if (!f.has_T2) {
        if (case_read_transport(c, &tr, &err) != UMP_OK)
            return die(err.msg);
        if (!tr.has_TRef)
            return die("no -T2 and no TRef in constant/transportProperties");
    }
    int pi = -1;
    for (int p = 0; p < pm->npatches; p++)
        if (!strcmp(pm->patch[p].name, f.c.patch))
            pi = p;
    if (pi < 0) {
        fprintf(stderr, "foamNusselt: %s: no patch '%s'\n", dir, f.c.patch);
        return 1;
    }
    char **names = NULL;
    double *values = NULL;
    int nt = 0;
    if (case_list_times(c, &names, &values, &nt, &err) != UMP_OK)
        return die(err.msg);
    const pmesh_patch *pp = &pm->patch[pi];
    size_t n = (size_t)pp->n;
    double *x3 = calloc(3 * n + 1, sizeof *x3), *A = calloc(n + 1, sizeof *A), *g = calloc(n + 1, sizeof *g),
           *Tf = calloc(n + 1, sizeof *Tf);
    int done = 0, rc = 0;
    fob_result r = {0};
    const char *last = NULL;
    for (int k = 0; k < nt && !rc; k++) {
        if (time ? strcmp(names[k], time) != 0 : values[k] == 0)
            continue;
        char path[4400];
        snprintf(path, sizeof path, "%s/%s/T", c, names[k]);
        fld_field *T = NULL;
        if (fio_read_field(path, pm, 1, &T, &err) != UMP_OK) {
            rc = die(err.msg);
            break;
        }
        size_t q = 0;
        for (ump_idx i = 0; i < pp->n; i++) {
            ump_idx fc = m->pmface_to_face[pp->start + i];
            if (fc < m->ninternal)
                continue;
            ump_idx o = m->owner[fc];
            double d = (m->fx[fc] - m->cx[o]) * m->nx[fc] + (m->fy[fc] - m->cy[o]) * m->ny[fc];
            mesh_to3d(m, m->fx[fc], m->fy[fc], x3 + 3 * q);
            A[q] = m->len[fc];
            Tf[q] = T->patch[pi].value[i];
            g[q] = (Tf[q] - T->internal[o]) / d;
            q++;
        }
        fld_free(&T);
        if (q == 0) {
            rc = die("the patch has no boundary faces in 2-D");
            break;
        }
        fob_faces fd = {q, x3, A, g, Tf};
        r = fob_nusselt_eval(&f, &fd, f.has_T2 ? f.T2 : tr.TRef);
        printf("%s\t%.8g\t%.8g\t%.8g\n", names[k], r.Nu_avg, r.Nu_min, r.Nu_max);
        last = names[k];
        done++;
    }
    if (!rc && !done)
        rc = die(time ? "no such time directory" : "no time directories besides 0");
    if (!rc)
        printf("RESULT time=%s Nu_avg=%.8g Nu_min=%.8g Nu_max=%.8g T1=%.8g T2=%.8g\n", last, r.Nu_avg,
               r.Nu_min, r.Nu_max, r.T1, r.T2);
    free(x3);
    free(A);
    free(g);
    free(Tf);
    case_free_times(names, values, nt);
    mesh_free(&m);
    pmesh_free(&pm);
    return rc;
}
