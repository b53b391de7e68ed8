/* SPDX-License-Identifier: GPL-3.0-or-later
 * fieldio.h -- reading and writing OpenFOAM field files and time
 * directories (module prefix fio_).
 *
 * Reading: <file> (or <file>.gz), ascii or binary, class volScalarField or
 * volVectorField; internalField uniform or nonuniform; boundaryField entries
 * matched to each mesh patch by exact patch name, then by patch group
 * (inGroups, and the patch type for constraint types), then by regex key
 * (latest first), as OpenFOAM's GeometricBoundaryField does. A patch with no
 * entry, an unsupported type, a value of the wrong size, or a constraint
 * patch (empty, cyclic, symmetryPlane) given an incompatible type is an
 * error naming the file and line.
 *
 * Writing: exactly OpenFOAM's layout (banner, FoamFile header with
 * location, dimensions, internalField, boundaryField), ascii or binary
 * (arch "LSB;label=32;scalar=64"), writePrecision significant digits,
 * optional gzip (ascii only, as v1912: binary + compression writes plain).
 * Files are written inside a time directory opened with fio_timedir_begin():
 * everything goes to a hidden temporary directory that fio_timedir_commit()
 * renames into place, so a failed run never leaves a partial time directory
 * and never destroys the previous one.
 */
#ifndef UMPPM_FIELDIO_H
#define UMPPM_FIELDIO_H

#include <stdint.h>
#include <stdio.h>
#include "umppm/ump.h"
#include "umppm/polymesh.h"
#include "umppm/field.h"

typedef struct fio_format {
    int binary;       /* writeFormat binary */
    int precision;    /* writePrecision (significant digits), default 6 */
    int compress;     /* writeCompression on (ignored for binary, as v1912) */
} fio_format;

/* Read a field file. ncomp: 1 or 3 (checked against the class). The name of
 * the field is the header object. */
ump_status fio_read_field(const char *path, const pmesh *pm, int ncomp,
                          fld_field **out, ump_err *err);

/* Write field f as <dir>/<f->name> (.gz when compressing; the other
 * variant, if present, is removed as OpenFOAM does). location is the
 * header's location entry (the time name, e.g. "0.1"), NULL for none. pm
 * gives the patch names (f->patch[i] is pm->patch[i]; counts and sizes must
 * match). fmt NULL means ascii, precision 6, plain. */
ump_status fio_write_field(const char *dir, const char *location, const pmesh *pm,
                           const fld_field *f, const fio_format *fmt, ump_err *err);

/* <dir>/phi, the face fluxes as OpenFOAM's surfaceScalarField (dimensions
 * [0 3 -1 0 0 0 0], "oriented oriented;"): phi [pm->nfaces] in m^3/s over
 * each polyMesh face, oriented by its normal (owner to neighbour, outwards on
 * patches); internalField the internal faces, each patch its faces (empty
 * patches: "value nonuniform 0();", cyclic, symmetryPlane and symmetry
 * patches their own type, the others calculated; uniform when all values are equal, as Field::writeEntry). fmt
 * as fio_write_field. */
ump_status fio_write_phi(const char *dir, const char *location, const pmesh *pm, const double *phi,
                         const fio_format *fmt, ump_err *err);

/* <dir>/uniform/time, always ascii and plain, as OpenFOAM writes it:
 * value with 18 digits in the timeFormat (time_format as
 * case_control.time_format_fixed: 0 general %.18g, 1 fixed %.18f,
 * 2 scientific %.18e), name quoted, index, and deltaT/deltaT0 with
 * write_precision significant digits (writePrecision, <= 0 means 6).
 * location is the time name; the header says "<location>/uniform". */
/* dir/name with the len bytes of text, as they are (a file the solver
 * carries unchanged from the start time: meshlessFoam's pointDisplacement). */
ump_status fio_write_text(const char *dir, const char *name, const char *text, size_t len, ump_err *err);
/* <dir>/uniform/<object>: a dictionary with the FoamFile header and body
 * (entries "key value;" as given). */
ump_status fio_write_uniform_dict(const char *dir, const char *location, const char *object, const char *body,
                                  ump_err *err);

ump_status fio_write_uniform_time(const char *dir, const char *location,
                                  double value, const char *name, long index,
                                  double deltaT, double deltaT0,
                                  int write_precision, int time_format,
                                  ump_err *err);

/* A time directory being written. */
typedef struct fio_timedir {
    char final_dir[4096];  /* <case>/<name> */
    char tmp_dir[4096];    /* <case>/.<name>.tmp.<pid>: write files here */
    char name[64];
    int open;
} fio_timedir;

/* Hidden names next to a time directory <name> while it is written
 * (".<name>.tmp.<pid>"), while an overwrite moves the previous version
 * aside where the filesystem has no RENAME_EXCHANGE (".<name>.old.<pid>"),
 * and while purgeWrite deletes it (".<name>.del.<pid>"). fio_recover()
 * knows them. */
#define FIO_HIDDEN_FMT ".%s.%s.%ld"
#define FIO_HIDDEN_TMP "tmp"
#define FIO_HIDDEN_OLD "old"
#define FIO_HIDDEN_DEL "del"

/* UMP_ERR_IO when <case_dir>/<name> exists and is not a directory (a file
 * in the way of a time directory to be written; it is never deleted). */
ump_status fio_timedir_check(const char *case_dir, const char *name, ump_err *err);
/* Create the temporary directory for time name in case_dir (refused, with
 * nothing written, when a non-directory sits at <case_dir>/<name>). */
ump_status fio_timedir_begin(const char *case_dir, const char *name,
                             fio_timedir *td, ump_err *err);
/* Move it into place. An existing <case>/<name> is replaced only after the
 * new one is complete, by renameat2(RENAME_EXCHANGE) and the removal of the
 * old version (killed at any instant: <name> is complete, old or new); where
 * the filesystem refuses the exchange (EINVAL/ENOSYS), by two renames
 * through .<name>.old.<pid>, which fio_recover() puts back after a kill
 * between them. A non-directory at <name> is an error (never deleted). */
ump_status fio_timedir_commit(fio_timedir *td, ump_err *err);
/* Remove the temporary directory (after a failure). Safe to call twice. */
void fio_timedir_abort(fio_timedir *td);

/* Remove a directory tree. */
ump_status fio_remove_dir(const char *path, ump_err *err);
/* Remove time directory <case_dir>/<name> (purgeWrite): renamed to the
 * hidden .<name>.del.<pid> first, so a kill never leaves a partial <name>. */
ump_status fio_remove_timedir(const char *case_dir, const char *name, ump_err *err);

/* ---- start-up recovery (src/fieldio_recover.c) --------------------------- */
/* What fio_recover() did with one hidden directory. */
typedef enum fio_recovery {
    FIO_RECOVERED,     /* .<t>.old.<pid> renamed back to <t> (none was there) */
    FIO_REMOVED_TMP,   /* .<t>.tmp.<pid>: an unfinished write, removed */
    FIO_REMOVED_OLD,   /* .<t>.old.<pid> while <t> is in place: removed */
    FIO_REMOVED_DEL,   /* .<t>.del.<pid>: an unfinished purgeWrite, removed */
    FIO_LEFT_RUNNING,  /* its process <pid> is still running: left alone */
    FIO_LEFT_BLOCKED   /* .<t>.old.<pid> while a non-directory is at <t>: kept */
} fio_recovery;
typedef void (*fio_recover_report)(void *ctx, fio_recovery what, const char *hidden,
                                   const char *time_name, long pid);
/* Recover or remove the hidden directories (FIO_HIDDEN_*) that killed runs
 * left in case_dir; report (may be NULL) is called once per directory. The
 * .old ones are handled before the .tmp ones. */
ump_status fio_recover(const char *case_dir, fio_recover_report report, void *ctx, ump_err *err);

/* Create directories along path (mkdir -p). */
ump_status fio_mkdir_p(const char *path, ump_err *err);

/* Standard OpenFOAM-style file banner + FoamFile header, the divider and
 * the blank line after it; writes to fp. location may be NULL. binary
 * selects "format binary" and the arch entry. */
void fio_write_header(FILE *fp, const char *cls, const char *location,
                      const char *object, int binary);
/* Two newlines and the trailing divider line, as OpenFOAM ends a file
 * (the caller's last line ends with its own newline). */
void fio_write_footer(FILE *fp);

/* ---- lagrangian clouds (the layout foamToVTK reads; src/fieldio_cloud.c) -- */
/* Write the particle cloud under <dir>/lagrangian/<cloud>/ (positions with
 * the cell of each particle, U, origId, origProcId) and
 * <dir>/uniform/lagrangian/<cloud>/cloudProperties with "geometry positions;",
 * the recipe foamToVTK and paraFoam read in v1912. Always ascii (a file's
 * format is per file in OpenFOAM), writePrecision digits.
 *   pos, vel [3*n] (3-D), cell [n] (polyMesh cell), id [n]. */
ump_status fio_write_cloud(const char *dir, const char *location, const char *cloud, size_t n,
                           const double *pos, const double *vel, const ump_idx *cell,
                           const int64_t *id, int precision, ump_err *err);
/* One more particle field of a cloud (same dir/location/cloud as
 * fio_write_cloud): ncomp 1, 3 or 6 values per particle written as a
 * scalarField, vectorField or symmTensorField (xx xy xz yy yz zz). */
ump_status fio_write_cloud_field(const char *dir, const char *location, const char *cloud,
                                 const char *name, int ncomp, size_t n, const double *v,
                                 int precision, ump_err *err);
/* Read a cloud written by fio_write_cloud (or by OpenFOAM as ascii or
 * binary positions + U): *n particles, *pos, *vel [3*n], *id [n] (origId,
 * or -1 when absent), *cell [n] (celli of positions, a hint: -1 allowed),
 * all caller-freed. */
ump_status fio_read_cloud(const char *dir, const char *cloud, size_t *n, double **pos, double **vel,
                          int64_t **id, ump_idx **cell, ump_err *err);
/* One particle field <dir>/lagrangian/<cloud>/<name> of ncomp values per
 * particle, which must hold n of them: *v [n*ncomp], caller-freed. */
ump_status fio_read_cloud_field(const char *dir, const char *cloud, const char *name, int ncomp, size_t n,
                                double **v, ump_err *err);

#endif
