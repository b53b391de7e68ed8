/* SPDX-License-Identifier: GPL-3.0-or-later
 * write_cavity_fields.c -- writes known U and p fields for the blockMesh
 * icoFoam cavity (20x20x1 cells; patches movingWall 20, fixedWalls 60,
 * frontAndBack 800 faces) into time directories 0.1 (ascii), 0.2 (binary)
 * and 0.3 (ascii + gzip) through the fieldio/runtime API, so that
 * test_writer_foamToVTK.sh can check OpenFOAM reads them back.
 *
 * Values: cell c has U = (c, 2c, 0) and p = c + 0.25; movingWall face i
 * has U = (1 + i, 0, 0) (a nonuniform patch list), fixedWalls noSlip,
 * p zeroGradient, frontAndBack empty.
 *
 * Usage: write_cavity_fields <case-dir>   (exit status 0 on success)
 */
#include <stdio.h>
#include <string.h>

#include "umppm/field.h"
#include "umppm/fieldio.h"
#include "umppm/runtime.h"

enum { NCELLS = 400, NPATCH = 3 };

static int fail(const ump_err *err)
{
    fprintf(stderr, "write_cavity_fields: %s\n", err->msg);
    return 1;
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: %s <case-dir>\n", argv[0]);
        return 2;
    }
    const char *case_dir = argv[1];
    static char *names[NPATCH] = {"movingWall", "fixedWalls", "frontAndBack"};
    const ump_idx sizes[NPATCH] = {20, 60, 800};
    pmesh_patch patches[NPATCH];
    memset(patches, 0, sizeof patches);
    pmesh pm;
    memset(&pm, 0, sizeof pm);
    pm.ncells = NCELLS;
    pm.npatches = NPATCH;
    pm.patch = patches;
    for (int i = 0; i < NPATCH; i++) {
        patches[i].name = names[i];
        patches[i].n = sizes[i];
    }

    ump_err err;
    fld_field *U = NULL, *p = NULL;
    if (fld_create("U", 3, NCELLS, NPATCH, sizes, &U, &err) != UMP_OK
        || fld_create("p", 1, NCELLS, NPATCH, sizes, &p, &err) != UMP_OK)
        return fail(&err);
    U->dims[1] = 1;
    U->dims[2] = -1;
    p->dims[1] = 2;
    p->dims[2] = -2;
    for (int c = 0; c < NCELLS; c++) {
        U->internal[3 * c] = c;
        U->internal[3 * c + 1] = 2.0 * c;
        U->internal[3 * c + 2] = 0;
        p->internal[c] = c + 0.25;
    }
    U->patch[0].type = FLD_BC_FIXEDVALUE;
    for (int i = 0; i < sizes[0]; i++)
        U->patch[0].value[3 * i] = 1 + i;
    U->patch[1].type = FLD_BC_NOSLIP;
    U->patch[2].type = FLD_BC_EMPTY;
    p->patch[0].type = FLD_BC_ZEROGRADIENT;
    p->patch[1].type = FLD_BC_ZEROGRADIENT;
    p->patch[2].type = FLD_BC_EMPTY;

    /* the cavity's controlDict: deltaT 0.005, writeInterval 20 steps */
    case_control ctl;
    memset(&ctl, 0, sizeof ctl);
    ctl.delta_t = 0.005;
    ctl.end_time = 0.3;
    ctl.write_control = CASE_WRITE_TIMESTEP;
    ctl.write_interval = 20;
    ctl.write_precision = 6;
    ctl.time_precision = 6;
    rt_time t;
    rt_init(&t, &ctl, 0, "0");

    const fio_format formats[3] = {{0, 6, 0}, {1, 6, 0}, {0, 6, 1}};
    int nwritten = 0;
    while (rt_running(&t)) {
        rt_advance(&t);
        if (!t.write_time)
            continue;
        const fio_format *fmt = &formats[nwritten % 3];
        fio_timedir td;
        if (fio_timedir_begin(case_dir, t.name, &td, &err) != UMP_OK)
            return fail(&err);
        if (fio_write_field(td.tmp_dir, t.name, &pm, U, fmt, &err) != UMP_OK
            || fio_write_field(td.tmp_dir, t.name, &pm, p, fmt, &err) != UMP_OK
            || fio_write_uniform_time(td.tmp_dir, t.name, t.value, t.name, t.index, t.delta_t,
                                      t.delta_t0, ctl.write_precision,
                                      ctl.time_format_fixed, &err) != UMP_OK
            || fio_timedir_commit(&td, &err) != UMP_OK) {
            fio_timedir_abort(&td);
            return fail(&err);
        }
        printf("%s %s\n", t.name,
               fmt->binary ? "binary" : fmt->compress ? "ascii+gzip" : "ascii");
        nwritten++;
    }
    fld_free(&U);
    fld_free(&p);
    return nwritten == 3 ? 0 : 1;
}
