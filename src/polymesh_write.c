/* SPDX-License-Identifier: GPL-3.0-or-later
 * polymesh_write.c -- an ascii OpenFOAM polyMesh, as blockMesh writes it,
 * for meshes made by umppmFoam's tools (e.g. the crossed-triangle periodic
 * meshes of the Taylor-Green case; OpenFOAM's checkMesh reads them).
 */
#include "umppm/fieldio.h"
#include "umppm/polymesh.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>

static ump_status finish(FILE *fp, const char *tmp, const char *path, ump_err *err)
{
    fio_write_footer(fp);
    int bad = ferror(fp);
    if (fclose(fp) != 0 || bad) {
        remove(tmp);
        return UMP_FAIL(err, UMP_ERR_IO, "%s: write failed", path);
    }
    if (rename(tmp, path) != 0) {
        remove(tmp);
        return UMP_FAIL(err, UMP_ERR_IO, "%s: cannot move into place (%s)", path, strerror(errno));
    }
    return UMP_OK;
}

static FILE *start_at(const char *dir, const char *name, const char *cls, const char *location, char *tmp,
                      char *path, size_t len, ump_err *err, ump_status *rc)
{
    snprintf(path, len, "%s/%s", dir, name);
    snprintf(tmp, len, "%s/.%s.tmp", dir, name);
    FILE *fp = fopen(tmp, "w");
    if (!fp) {
        *rc = UMP_FAIL(err, UMP_ERR_IO, "%s: cannot write (%s)", path, strerror(errno));
        return NULL;
    }
    fio_write_header(fp, cls, location, name, 0);
    return fp;
}

static FILE *start(const char *dir, const char *name, const char *cls, char *tmp, char *path, size_t len,
                   ump_err *err, ump_status *rc)
{
    return start_at(dir, name, cls, "constant/polyMesh", tmp, path, len, err, rc);
}

ump_status pmesh_write_points(const double *points, ump_idx npoints, const char *dir, const char *location,
                              int precision, ump_err *err)
{
    char tmp[4200], path[4200];
    ump_status rc = UMP_OK;
    UMP_CALL(fio_mkdir_p(dir, err));
    FILE *fp = start_at(dir, "points", "vectorField", location, tmp, path, sizeof path, err, &rc);
    if (!fp)
        return rc;
    fprintf(fp, "\n%ld\n(\n", (long)npoints);
    for (ump_idx i = 0; i < npoints; i++) {
        const double *p = points + 3 * (size_t)i;
        fprintf(fp, "(%.*g %.*g %.*g)\n", precision, p[0], precision, p[1], precision, p[2]);
    }
    fprintf(fp, ")\n");
    return finish(fp, tmp, path, err);
}

ump_status pmesh_write(const pmesh *m, const char *dir, int precision, ump_err *err)
{
    char tmp[4200], path[4200];
    ump_status rc = UMP_OK;
    UMP_CALL(fio_mkdir_p(dir, err));
    FILE *fp = start(dir, "points", "vectorField", tmp, path, sizeof path, err, &rc);
    if (!fp)
        return rc;
    fprintf(fp, "\n%ld\n(\n", (long)m->npoints);
    for (ump_idx i = 0; i < m->npoints; i++) {
        const double *p = m->points + 3 * (size_t)i;
        fprintf(fp, "(%.*g %.*g %.*g)\n", precision, p[0], precision, p[1], precision, p[2]);
    }
    fprintf(fp, ")\n");
    UMP_CALL(finish(fp, tmp, path, err));

    if (!(fp = start(dir, "faces", "faceList", tmp, path, sizeof path, err, &rc)))
        return rc;
    fprintf(fp, "\n%ld\n(\n", (long)m->nfaces);
    for (ump_idx f = 0; f < m->nfaces; f++) {
        fprintf(fp, "%ld(", (long)(m->face_off[f + 1] - m->face_off[f]));
        for (ump_idx k = m->face_off[f]; k < m->face_off[f + 1]; k++)
            fprintf(fp, k > m->face_off[f] ? " %ld" : "%ld", (long)m->face_pts[k]);
        fprintf(fp, ")\n");
    }
    fprintf(fp, ")\n");
    UMP_CALL(finish(fp, tmp, path, err));

    snprintf(path, sizeof path, "%s/owner", dir);
    if (!(fp = start(dir, "owner", "labelList", tmp, path, sizeof path, err, &rc)))
        return rc;
    /* sizes as a comment (OpenFOAM puts them in a header note) */
    fprintf(fp, "// nPoints:%ld  nCells:%ld  nFaces:%ld  nInternalFaces:%ld\n", (long)m->npoints,
            (long)m->ncells, (long)m->nfaces, (long)m->ninternal);
    fprintf(fp, "\n%ld\n(\n", (long)m->nfaces);
    for (ump_idx f = 0; f < m->nfaces; f++)
        fprintf(fp, "%ld\n", (long)m->owner[f]);
    fprintf(fp, ")\n");
    UMP_CALL(finish(fp, tmp, path, err));

    if (!(fp = start(dir, "neighbour", "labelList", tmp, path, sizeof path, err, &rc)))
        return rc;
    fprintf(fp, "\n%ld\n(\n", (long)m->ninternal);
    for (ump_idx f = 0; f < m->ninternal; f++)
        fprintf(fp, "%ld\n", (long)m->neighbour[f]);
    fprintf(fp, ")\n");
    UMP_CALL(finish(fp, tmp, path, err));

    if (!(fp = start(dir, "boundary", "polyBoundaryMesh", tmp, path, sizeof path, err, &rc)))
        return rc;
    fprintf(fp, "\n%d\n(\n", m->npatches);
    for (int i = 0; i < m->npatches; i++) {
        const pmesh_patch *p = &m->patch[i];
        fprintf(fp, "    %s\n    {\n        type            %s;\n", p->name, p->type);
        if (p->ngroups > 0) {
            fprintf(fp, "        inGroups        %d(", p->ngroups);
            for (int g = 0; g < p->ngroups; g++)
                fprintf(fp, g ? " %s" : "%s", p->groups[g]);
            fprintf(fp, ");\n");
        } else if (p->kind != PMESH_PATCH) {
            fprintf(fp, "        inGroups        1(%s);\n", p->type);
        }
        fprintf(fp, "        nFaces          %ld;\n        startFace       %ld;\n", (long)p->n,
                (long)p->start);
        if (p->kind == PMESH_CYCLIC) {
            fprintf(fp, "        matchTolerance  0.0001;\n");
            if (p->has_separation)
                fprintf(fp, "        transform       translational;\n        separationVector (%.*g %.*g %.*g);\n",
                        precision, p->separation[0], precision, p->separation[1], precision, p->separation[2]);
            else
                fprintf(fp, "        transform       %s;\n", p->transform ? p->transform : "unknown");
            fprintf(fp, "        neighbourPatch  %s;\n", p->neighbour_patch);
        }
        fprintf(fp, "    }\n");
    }
    fprintf(fp, ")\n");
    return finish(fp, tmp, path, err);
}
