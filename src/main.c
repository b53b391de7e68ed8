/* SPDX-License-Identifier: GPL-3.0-or-later
 * main.c -- the umppmFoam application: OpenFOAM-style command line, banner
 * and log; the only place that prints errors and exits.
 *
 *   umppmFoam [-case DIR] [-reseed] [-noFunctionObjects] [-checkMesh [-writeFields]] [-help] [-version]
 *
 * Both the run and -checkMesh first recover or remove what killed runs left
 * in the case (app_recover). The exit status is non-zero when the log could
 * not be written to standard output (e.g. umppmFoam > /dev/full).
 *
 * -help also lists the keys of the UMPPM dictionary of system/fvSolution
 * (case_umppm_help: key, default, allowed values, help; the reader's table).
 *
 * -checkMesh reads the case (controlDict, polyMesh), applies every check of
 * a run before its fields (app_check_case: unsupported features refused by
 * name; app_check_settings: transportProperties, fvSolution, function
 * objects, pRefPoint), builds the 2-D UMPPM pressure mesh and prints its
 * statistics. With -writeFields it also reads
 * the start-time fields U and p and writes them back into the start time
 * directory in the case's writeFormat/writePrecision/writeCompression (as
 * foamFormatConvert does), together with C and V (cell centres and volumes,
 * as postProcess -func writeCellCentres / writeCellVolumes), each file
 * written under a temporary name and renamed into place.
 */
#include "umppm/app.h"
#include "umppm/case.h"
#include "umppm/field.h"
#include "umppm/fieldio.h"
#include "umppm/lsq.h"
#include "umppm/mesh2d.h"
#include "umppm/polymesh.h"

#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#define UMPPM_VERSION "0.1"

typedef struct app_opts {
    const char *case_dir;
    int check_mesh;
    int write_fields;
    int reseed;
    int no_fo;
} app_opts;

static void usage(FILE *fp)
{
    fprintf(fp,
            "\nUsage: umppmFoam [OPTIONS]\n"
            "options:\n"
            "  -case <dir>       Specify case directory to use (instead of the cwd)\n"
            "  -reseed           Seed new particles from the fields on a restart: needed\n"
            "                    when the start time has no cloud (lagrangian/<cloudName>),\n"
            "                    which is otherwise an error; an existing cloud is not read\n"
            "  -noFunctionObjects  Do not execute function objects (they are still read\n"
            "                    and checked)\n"
            "  -checkMesh        Read the case, build the 2-D UMPPM pressure mesh and print\n"
            "                    its statistics (cells by polygon type, faces, patches, areas,\n"
            "                    non-orthogonality, skewness, stencil sizes), then exit\n"
            "  -writeFields      With -checkMesh: rewrite the start-time U and p in the\n"
            "                    controlDict write format and write C and V (cell centres and\n"
            "                    volumes) into the start time directory\n"
            "  -version          Print the version and exit\n"
            "  -help             Print this usage and the UMPPM options, then exit\n"
            "\nUnstructured Moving Particle Pressure Mesh (UMPPM) solver for 2-D\n"
            "incompressible flow (Ng, Sheu & Hwang 2016), for OpenFOAM case directories.\n\n");
}

/* -help: the usage, then the UMPPM dictionary's options from case.c's table. */
static void help(FILE *fp)
{
    usage(fp);
    size_t n = case_umppm_help(NULL, 0);
    char *text = malloc(n + 1);
    if (text) {
        case_umppm_help(text, n + 1);
        fputs(text, fp);
        fputs("\n", fp);
    }
    free(text);
}

static void banner(int argc, char **argv, const char *case_dir)
{
    char host[256] = "unknown", cwd[PATH_MAX], when[64], clock[64];
    gethostname(host, sizeof host);
    time_t now = time(NULL);
    struct tm tmv;
    localtime_r(&now, &tmv);
    strftime(when, sizeof when, "%b %d %Y", &tmv);
    strftime(clock, sizeof clock, "%H:%M:%S", &tmv);
    const char *abs = realpath(case_dir, cwd) ? cwd : case_dir;
    printf("/*---------------------------------------------------------------------------*\\\n"
           "| umppmFoam: Unstructured Moving Particle Pressure Mesh solver                |\n"
           "| Version:   %-65s|\n"
           "| Reads and writes OpenFOAM (v1912) case directories                          |\n"
           "\\*---------------------------------------------------------------------------*/\n",
           UMPPM_VERSION);
    printf("Build  : umppmFoam-%s (C11, SuiteSparse)\n", UMPPM_VERSION);
    printf("Arch   : \"LSB;label=32;scalar=64\"\n");
    printf("Exec   :");
    for (int i = 0; i < argc; i++)
        printf(" %s", argv[i]);
    printf("\nDate   : %s\nTime   : %s\nHost   : %s\nPID    : %ld\nCase   : %s\nnProcs : 1\n",
           when, clock, host, (long)getpid(), abs);
    printf("\n// * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * * //\n");
}

static int fatal(const ump_err *err)
{
    fflush(stdout);
    fprintf(stderr, "--> umppmFoam FATAL ERROR: %s\n", err->msg);
    return 1;
}

static void print_mesh(const pmesh *pm, const mesh2d *m)
{
    mesh_stats s;
    mesh_compute_stats(m, &s);
    double thick = m->zmax - m->zmin;
    printf("Mesh stats (polyMesh)\n");
    printf("    points:           %ld\n    faces:            %ld\n    internal faces:   %ld\n"
           "    cells:            %ld\n    boundary patches: %d\n\n",
           (long)pm->npoints, (long)pm->nfaces, (long)pm->ninternal, (long)pm->ncells, pm->npatches);
    printf("UMPPM pressure mesh (2-D, normal %c, plane (%c %c), thickness %g)\n",
           "xyz"[m->normal], "xyz"[m->ax[0]], "xyz"[m->ax[1]], thick);
    printf("    vertices:         %ld\n    cells:            %ld\n"
           "        triangles:    %ld\n        quadrilaterals: %ld\n        polygons:     %ld"
           " (max %ld sides)\n",
           (long)m->nverts, (long)m->ncells, (long)s.ntri, (long)s.nquad, (long)s.npoly,
           (long)s.nsides_max);
    printf("    faces:            %ld (internal %ld, of which cyclic %ld; boundary %ld)\n\n",
           (long)m->nfaces, (long)m->ninternal, (long)(m->ninternal - pm->ninternal),
           (long)(m->nfaces - m->ninternal));
    printf("Patches\n    %-20s %-14s %8s  %s\n", "patch", "type", "faces", "groups");
    for (int p = 0; p < pm->npatches; p++) {
        const pmesh_patch *pp = &pm->patch[p];
        char groups[256] = "";
        for (int g = 0; g < pp->ngroups; g++) {
            strncat(groups, g ? " " : "", sizeof groups - strlen(groups) - 1);
            strncat(groups, pp->groups[g], sizeof groups - strlen(groups) - 1);
        }
        printf("    %-20s %-14s %8ld  %s", pp->name, pp->type, (long)pp->n, groups);
        if (pp->kind == PMESH_CYCLIC)
            printf("  (neighbourPatch %s)", pp->neighbour_patch);
        printf("\n");
    }
    printf("\nGeometry\n");
    printf("    cell area:        min %.6g  max %.6g  mean %.6g  total %.6g\n",
           s.area_min, s.area_max, s.area_mean, s.area_total);
    printf("    face length:      min %.6g  max %.6g\n", s.len_min, s.len_max);
    printf("    non-orthogonality: max %.6g  average %.6g (degrees)\n", s.nonorth_max, s.nonorth_mean);
    printf("    max skewness:     %.6g\n", s.skew_max);
    printf("\nStencils (cells sharing a vertex; docs/METHOD.md section 3.1)\n");
    printf("    first neighbours N1:          min %ld  max %ld  mean %.3g\n",
           (long)s.n1_min, (long)s.n1_max, s.n1_mean);
    printf("    first+second neighbours N2:   min %ld  max %ld  mean %.3g\n\n",
           (long)s.n2_min, (long)s.n2_max, s.n2_mean);
    if (s.nonorth_max > 70)
        printf("  ***High non-orthogonality: max %.6g degrees\n", s.nonorth_max);
    if (s.skew_max > 4)
        printf("  ***High skewness: max %.6g\n", s.skew_max);
    printf("Mesh OK.\n\n");
}

/* C and V fields as postProcess writes them (boundary values = face centres / 0). */
static ump_status make_geometry_fields(const pmesh *pm, const mesh2d *m, fld_field **C, fld_field **V,
                                       ump_err *err)
{
    ump_idx *sizes = ump_alloc_array((size_t)pm->npatches, sizeof *sizes);
    if (!sizes)
        return UMP_FAIL(err, UMP_ERR_NOMEM, "out of memory");
    for (int p = 0; p < pm->npatches; p++)
        sizes[p] = pm->patch[p].n;
    ump_status rc = fld_create("C", 3, m->ncells, pm->npatches, sizes, C, err);
    if (rc == UMP_OK)
        rc = fld_create("V", 1, m->ncells, pm->npatches, sizes, V, err);
    free(sizes);
    if (rc != UMP_OK)
        return rc;
    (*C)->dims[1] = 1;
    (*V)->dims[1] = 3;
    double thick = m->zmax - m->zmin;
    for (ump_idx c = 0; c < m->ncells; c++) {
        mesh_to3d(m, m->cx[c], m->cy[c], (*C)->internal + 3 * (size_t)c);
        (*V)->internal[c] = m->area[c] * thick;
    }
    for (int p = 0; p < pm->npatches; p++) {
        const pmesh_patch *pp = &pm->patch[p];
        fld_bc_type t = pp->kind == PMESH_EMPTY ? FLD_BC_EMPTY
                        : pp->kind == PMESH_CYCLIC ? FLD_BC_CYCLIC
                        : pp->kind == PMESH_SYMMETRYPLANE ? FLD_BC_SYMMETRYPLANE
                        : pp->kind == PMESH_SYMMETRY ? FLD_BC_SYMMETRY : FLD_BC_CALCULATED;
        (*C)->patch[p].type = (*V)->patch[p].type = t;
        for (ump_idx i = 0; i < pp->n && t != FLD_BC_EMPTY; i++) {
            ump_idx f = m->pmface_to_face[pp->start + i];
            double *cv = (*C)->patch[p].value + 3 * (size_t)i;
            if (t == FLD_BC_CYCLIC) {
                /* as OpenFOAM: the face centre of this side */
                double sx = m->face_pm[f] == pp->start + i ? 0 : m->sepx[f];
                double sy = m->face_pm[f] == pp->start + i ? 0 : m->sepy[f];
                mesh_to3d(m, m->fx[f] + sx, m->fy[f] + sy, cv);
            } else {
                mesh_to3d(m, m->fx[f], m->fy[f], cv);
            }
            (*V)->patch[p].value[i] = 0;
        }
    }
    return UMP_OK;
}

/* Boundary conditions that are functions of time and were read without a
 * `value` (uniformFixedValue, flowRateInletVelocity): their value at the
 * start time t0, as OpenFOAM evaluates them when it reads them. */
static ump_status start_values(fld_field *f, const pmesh *pm, const mesh2d *m, double t0, ump_err *err)
{
    for (int p = 0; p < pm->npatches; p++) {
        fld_patch *fp = &f->patch[p];
        const pmesh_patch *pp = &pm->patch[p];
        if (!fp->fn || fp->value_given)
            continue;
        double *nrm = ump_alloc_array(3 * (size_t)pp->n + 3, sizeof *nrm);
        if (!nrm)
            return UMP_FAIL(err, UMP_ERR_NOMEM, "out of memory");
        double area = mesh_patch_area(m, p, nrm);
        fld_bc_eval(fp, f->ncomp, t0, nrm, area, fp->value);
        free(nrm);
    }
    return UMP_OK;
}

static int write_fields(const char *case_dir, const char *tname, double t0, const pmesh *pm, const mesh2d *m,
                        const case_control *ctl)
{
    ump_err err;
    fio_format fmt = {ctl->write_binary, ctl->write_precision, ctl->write_compression};
    const char *names[2] = {"U", "p"};
    int ncomp[2] = {3, 1};
    char dir[4096], path[4200];
    snprintf(dir, sizeof dir, "%s/%s", case_dir, tname);
    fld_field *f[4] = {NULL, NULL, NULL, NULL};
    int rc = 0;
    for (int i = 0; i < 2; i++) {
        snprintf(path, sizeof path, "%s/%s", dir, names[i]);
        printf("Reading field %s\n\n", names[i]);
        if (fio_read_field(path, pm, ncomp[i], &f[i], &err) != UMP_OK ||
            start_values(f[i], pm, m, t0, &err) != UMP_OK) {
            rc = fatal(&err);
            goto done;
        }
    }
    if (make_geometry_fields(pm, m, &f[2], &f[3], &err) != UMP_OK) {
        rc = fatal(&err);
        goto done;
    }
    /* write into a scratch time directory, then move each file into place */
    fio_timedir td;
    if (fio_timedir_begin(case_dir, tname, &td, &err) != UMP_OK) {
        rc = fatal(&err);
        goto done;
    }
    for (int i = 0; i < 4; i++) {
        printf("Writing %s/%s\n", tname, f[i]->name);
        if (fio_write_field(td.tmp_dir, tname, pm, f[i], &fmt, &err) != UMP_OK) {
            fio_timedir_abort(&td);
            rc = fatal(&err);
            goto done;
        }
    }
    for (int i = 0; i < 4; i++) {
        const char *ext[2] = {"", ".gz"};
        for (int k = 0; k < 2; k++) {
            char from[4200], to[4200], other[4200];
            snprintf(from, sizeof from, "%s/%s%s", td.tmp_dir, f[i]->name, ext[k]);
            snprintf(to, sizeof to, "%s/%s%s", dir, f[i]->name, ext[k]);
            snprintf(other, sizeof other, "%s/%s%s", dir, f[i]->name, ext[1 - k]);
            if (access(from, F_OK) != 0)
                continue;
            if (rename(from, to) != 0) {
                ump_fail(&err, UMP_ERR_IO, __FILE__, __LINE__, "%s: cannot move the new file into place", to);
                fio_timedir_abort(&td);
                rc = fatal(&err);
                goto done;
            }
            remove(other); /* a stale U.gz must not shadow the new U (or vice versa) */
        }
    }
    fio_timedir_abort(&td);
    printf("\n");
done:
    for (int i = 0; i < 4; i++)
        fld_free(&f[i]);
    return rc;
}

static int run(int argc, char **argv)
{
    app_opts o = {".", 0, 0, 0, 0};
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (a[0] == '-' && a[1] == '-')
            a++; /* accept --help etc. */
        if (strcmp(a, "-case") == 0) {
            if (i + 1 >= argc) {
                fprintf(stderr, "--> umppmFoam FATAL ERROR: option -case needs a directory\n");
                usage(stderr);
                return 1;
            }
            o.case_dir = argv[++i];
            if (o.case_dir[0] == '\0') {
                fprintf(stderr, "--> umppmFoam FATAL ERROR: option -case: the directory name is empty\n");
                return 1;
            }
        } else if (strcmp(a, "-reseed") == 0) {
            o.reseed = 1;
        } else if (strcmp(a, "-noFunctionObjects") == 0) {
            o.no_fo = 1;
        } else if (strcmp(a, "-checkMesh") == 0) {
            o.check_mesh = 1;
        } else if (strcmp(a, "-writeFields") == 0) {
            o.write_fields = 1;
        } else if (strcmp(a, "-help") == 0 || strcmp(a, "-h") == 0) {
            help(stdout);
            return 0;
        } else if (strcmp(a, "-version") == 0) {
            printf("umppmFoam %s (reads OpenFOAM v1912 cases)\n", UMPPM_VERSION);
            return 0;
        } else if (strcmp(a, "-parallel") == 0) {
            fprintf(stderr, "--> umppmFoam FATAL ERROR: option -parallel is not implemented: umppmFoam runs "
                    "one process on the undecomposed case, with threads (set OMP_NUM_THREADS)\n");
            return 1;
        } else {
            fprintf(stderr, "--> umppmFoam FATAL ERROR: unknown option '%s'\n", argv[i]);
            usage(stderr);
            return 1;
        }
    }
    if (o.write_fields && !o.check_mesh) {
        fprintf(stderr, "--> umppmFoam FATAL ERROR: -writeFields goes with -checkMesh\n");
        return 1;
    }
    banner(argc, argv, o.case_dir);

    ump_err err;
    if (!o.check_mesh) {
        app_options ao = {o.reseed, o.no_fo};
        if (app_run(o.case_dir, &ao, &err) != UMP_OK)
            return fatal(&err);
        printf("End\n\n");
        return 0;
    }
    if (o.reseed) {
        fprintf(stderr, "--> umppmFoam FATAL ERROR: -reseed goes with a run, not with -checkMesh\n");
        return 1;
    }
    case_control ctl;
    printf("Create time\n\n");
    if (app_recover(o.case_dir, &err) != UMP_OK || case_read_control(o.case_dir, &ctl, &err) != UMP_OK)
        return fatal(&err);
    char tname[256];
    double t0;
    if (case_start_dir(o.case_dir, &ctl, tname, sizeof tname, &t0, &err) != UMP_OK ||
        app_check_case(o.case_dir, &ctl, tname, t0, &err) != UMP_OK)
        return fatal(&err);

    char pmdir[4096];
    snprintf(pmdir, sizeof pmdir, "%s/constant/polyMesh", o.case_dir);
    printf("Create mesh for time = %s\n\n", tname);
    pmesh *pm = NULL;
    mesh2d *m = NULL;
    if (pmesh_read(pmdir, &pm, &err) != UMP_OK)
        return fatal(&err);
    /* every mesh check of a run: the least-squares gradient's stencils too */
    lsq_grad *g = NULL;
    if (mesh_build(pm, &m, &err) != UMP_OK || lsq_build(m, &g, &err) != UMP_OK) {
        mesh_free(&m);
        pmesh_free(&pm);
        return fatal(&err);
    }
    lsq_free(&g);
    int rc = 0;
    if (app_check_settings(o.case_dir, pm, m, &err) != UMP_OK) {
        mesh_free(&m);
        pmesh_free(&pm);
        return fatal(&err);
    }
    print_mesh(pm, m);
    if (o.write_fields)
        rc = write_fields(o.case_dir, tname, t0, pm, m, &ctl);
    mesh_free(&m);
    pmesh_free(&pm);
    if (rc == 0)
        printf("End\n\n");
    return rc;
}

int main(int argc, char **argv)
{
    int rc = run(argc, argv);
    /* the log is the run's record: losing it is a failure */
    errno = 0;
    if ((fflush(stdout) != 0 || ferror(stdout)) && rc == 0) {
        /* (a failed run has said why already) */
        fprintf(stderr, "--> umppmFoam FATAL ERROR: standard output: cannot write the log (%s)\n",
                errno ? strerror(errno) : "write error");
        rc = 1;
    }
    return rc;
}
