/* SPDX-License-Identifier: GPL-3.0-or-later
 * fieldio_cloud.c -- the particle cloud as an OpenFOAM v1912 lagrangian
 * cloud that foamToVTK and paraFoam show (tests/integration/test_cloud_foamToVTK.sh):
 *   <time>/lagrangian/<cloud>/positions   Cloud<passiveParticle>, "(x y z) celli"
 *   <time>/lagrangian/<cloud>/U           vectorField
 *   <time>/lagrangian/<cloud>/origId      labelField (persistent particle id)
 *   <time>/lagrangian/<cloud>/origProcId  labelField (0)
 *   <time>/lagrangian/<cloud>/<name>      any further scalar, vector or
 *                                         symmTensor particle field
 *   <time>/uniform/lagrangian/<cloud>/cloudProperties  geometry positions;
 * Reading accepts these files ascii or binary (positions records are
 * "(" 3 doubles + 1 label ")" in binary, 28 bytes for label=32).
 */
#include "umppm/fieldio.h"
#include "umppm/foam.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>

static FILE *open_out(const char *dir, const char *name, char *path, size_t len, ump_err *err,
                      ump_status *rc)
{
    snprintf(path, len, "%s/%s", dir, name);
    FILE *fp = fopen(path, "w");
    if (!fp)
        *rc = UMP_FAIL(err, UMP_ERR_IO, "%s: cannot write (%s)", path, strerror(errno));
    return fp;
}

static ump_status close_out(FILE *fp, const char *path, ump_err *err)
{
    fio_write_footer(fp);
    int bad = ferror(fp);
    if (fclose(fp) != 0 || bad)
        return UMP_FAIL(err, UMP_ERR_IO, "%s: write failed", path);
    return UMP_OK;
}

ump_status fio_write_cloud_field(const char *dir, const char *location, const char *cloud,
                                 const char *name, int ncomp, size_t n, const double *v,
                                 int precision, ump_err *err)
{
    const char *cls = ncomp == 1 ? "scalarField" : ncomp == 3 ? "vectorField"
                      : ncomp == 6 ? "symmTensorField" : NULL;
    UMP_CHECK(cls, err, UMP_ERR_INPUT, "cloud field %s: %d components, expected 1, 3 or 6", name, ncomp);
    char cdir[4096], path[4400], loc[4200];
    snprintf(cdir, sizeof cdir, "%s/lagrangian/%s", dir, cloud);
    snprintf(loc, sizeof loc, "%s/lagrangian/%s", location, cloud);
    UMP_CALL(fio_mkdir_p(cdir, err));
    ump_status rc = UMP_OK;
    FILE *fp = open_out(cdir, name, path, sizeof path, err, &rc);
    if (!fp)
        return rc;
    fio_write_header(fp, cls, loc, name, 0);
    fprintf(fp, "%zu\n(\n", n);
    for (size_t i = 0; i < n; i++) {
        const double *x = v + (size_t)ncomp * i;
        if (ncomp == 1) {
            fprintf(fp, "%.*g\n", precision, x[0]);
            continue;
        }
        fputc('(', fp);
        for (int c = 0; c < ncomp; c++)
            fprintf(fp, c ? " %.*g" : "%.*g", precision, x[c]);
        fputs(")\n", fp);
    }
    fprintf(fp, ")\n");
    return close_out(fp, path, err);
}

ump_status fio_write_cloud(const char *dir, const char *location, const char *cloud, size_t n,
                           const double *pos, const double *vel, const ump_idx *cell,
                           const int64_t *id, int precision, ump_err *err)
{
    char cdir[4096], udir[4096], path[4400], loc[4200];
    snprintf(cdir, sizeof cdir, "%s/lagrangian/%s", dir, cloud);
    snprintf(udir, sizeof udir, "%s/uniform/lagrangian/%s", dir, cloud);
    UMP_CALL(fio_mkdir_p(cdir, err));
    UMP_CALL(fio_mkdir_p(udir, err));
    snprintf(loc, sizeof loc, "%s/lagrangian/%s", location, cloud);
    ump_status rc = UMP_OK;
    int pr = precision;

    FILE *fp = open_out(cdir, "positions", path, sizeof path, err, &rc);
    if (!fp)
        return rc;
    fio_write_header(fp, "Cloud<passiveParticle>", loc, "positions", 0);
    fprintf(fp, "%zu\n(\n", n);
    for (size_t i = 0; i < n; i++)
        fprintf(fp, "(%.*g %.*g %.*g) %ld\n", pr, pos[3 * i], pr, pos[3 * i + 1], pr, pos[3 * i + 2],
                (long)cell[i]);
    fprintf(fp, ")\n");
    UMP_CALL(close_out(fp, path, err));

    UMP_CALL(fio_write_cloud_field(dir, location, cloud, "U", 3, n, vel, precision, err));

    if (!(fp = open_out(cdir, "origId", path, sizeof path, err, &rc)))
        return rc;
    fio_write_header(fp, "labelField", loc, "origId", 0);
    fprintf(fp, "%zu\n(\n", n);
    for (size_t i = 0; i < n; i++)
        fprintf(fp, "%lld\n", (long long)id[i]);
    fprintf(fp, ")\n");
    UMP_CALL(close_out(fp, path, err));

    if (!(fp = open_out(cdir, "origProcId", path, sizeof path, err, &rc)))
        return rc;
    fio_write_header(fp, "labelField", loc, "origProcId", 0);
    if (n > 0)
        fprintf(fp, "%zu{0}\n", n);
    else
        fprintf(fp, "0()\n");
    UMP_CALL(close_out(fp, path, err));

    snprintf(loc, sizeof loc, "%s/uniform/lagrangian/%s", location, cloud);
    if (!(fp = open_out(udir, "cloudProperties", path, sizeof path, err, &rc)))
        return rc;
    fio_write_header(fp, "dictionary", loc, "cloudProperties", 0);
    fprintf(fp, "geometry        positions;\n\nprocessor0\n{\n    particleCount   %zu;\n}\n", n);
    return close_out(fp, path, err);
}

static int is_punct(const foam_token *t, char c)
{
    return t->type == FOAM_TOK_PUNCT && t->v.punct == c;
}

/* ascii "N ( (x y z) celli ... )"; binary positions are refused here with a
 * clear message (umppmFoam writes ascii clouds). */
static ump_status parse_positions(const foam_file *f, size_t *n, double **pos, ump_idx **cell,
                                  ump_err *err)
{
    const foam_token *t = f->body;
    size_t nt = f->nbody, i = 0;
    char w[512];
    if (f->binary)
        return UMP_FAIL(err, UMP_ERR_UNSUPPORTED,
                        "%s: binary lagrangian positions are not read by %s (convert the cloud "
                        "with foamFormatConvert and writeFormat ascii)", f->path, ump_solver);
    if (nt < 2 || t[0].type != FOAM_TOK_LABEL || t[0].v.label < 0 || !is_punct(&t[1], '('))
        return UMP_FAIL(err, UMP_ERR_PARSE, "%s: expected 'N (' starting the positions list", f->path);
    size_t cnt = (size_t)t[0].v.label;
    if (cnt > nt)
        return UMP_FAIL(err, UMP_ERR_PARSE, "%s: positions list declares %zu particles, file too short",
                        f->path, cnt);
    double *p = ump_alloc_array(3 * cnt, sizeof *p);
    ump_idx *cl = ump_alloc_array(cnt, sizeof *cl);
    if (!p || !cl) {
        free(p);
        free(cl);
        return UMP_FAIL(err, UMP_ERR_NOMEM, "%s: out of memory", f->path);
    }
    i = 2;
    for (size_t k = 0; k < cnt; k++) {
        if (i + 6 > nt || !is_punct(&t[i], '(') || !is_punct(&t[i + 4], ')') ||
            t[i + 5].type != FOAM_TOK_LABEL) {
            free(p);
            free(cl);
            return UMP_FAIL(err, UMP_ERR_PARSE, "%s: particle %zu: expected '(x y z) celli'",
                            foam_tok_where(t, nt, i < nt ? i : nt, f->path, w, sizeof w), k);
        }
        for (int c = 0; c < 3; c++) {
            const foam_token *q = &t[i + 1 + (size_t)c];
            if (q->type == FOAM_TOK_SCALAR)
                p[3 * k + (size_t)c] = q->v.scalar;
            else if (q->type == FOAM_TOK_LABEL)
                p[3 * k + (size_t)c] = (double)q->v.label;
            else {
                free(p);
                free(cl);
                return UMP_FAIL(err, UMP_ERR_PARSE, "%s: particle %zu: expected a coordinate",
                                foam_tok_where(t, nt, i + 1 + (size_t)c, f->path, w, sizeof w), k);
            }
        }
        int64_t ci = t[i + 5].v.label;
        cl[k] = ci >= 0 && ci <= UMP_IDX_MAX ? (ump_idx)ci : -1;
        i += 6;
    }
    if (i >= nt || !is_punct(&t[i], ')') || i + 1 != nt) {
        free(p);
        free(cl);
        return UMP_FAIL(err, UMP_ERR_PARSE, "%s: expected ')' closing the positions list",
                        foam_tok_where(t, nt, i < nt ? i : nt, f->path, w, sizeof w));
    }
    *n = cnt;
    *pos = p;
    *cell = cl;
    return UMP_OK;
}

ump_status fio_read_cloud_field(const char *dir, const char *cloud, const char *name, int ncomp, size_t n,
                                double **v, ump_err *err)
{
    char path[4400];
    foam_file *f = NULL;
    size_t nv = 0, pos_i = 0;
    *v = NULL;
    snprintf(path, sizeof path, "%s/lagrangian/%s/%s", dir, cloud, name);
    UMP_CALL(foam_file_read(path, &f, err));
    ump_status rc = foam_tok_scalar_list(f->body, f->nbody, &pos_i, ncomp, v, &nv, name, err);
    if (rc == UMP_OK && nv != n)
        rc = UMP_FAIL(err, UMP_ERR_INPUT, "%s: %zu values for %zu particles", f->path, nv, n);
    foam_file_free(&f);
    if (rc != UMP_OK) {
        free(*v);
        *v = NULL;
    }
    return rc;
}

ump_status fio_read_cloud(const char *dir, const char *cloud, size_t *n, double **pos, double **vel,
                          int64_t **id, ump_idx **cell, ump_err *err)
{
    char path[4400];
    foam_file *f = NULL;
    *pos = *vel = NULL;
    *id = NULL;
    *cell = NULL;
    *n = 0;
    snprintf(path, sizeof path, "%s/lagrangian/%s/positions", dir, cloud);
    ump_status rc = foam_file_read(path, &f, err);
    if (rc == UMP_ERR_UNSUPPORTED && strstr(err->msg, "binary files of class")) {
        /* foamFormatConvert with writeFormat binary writes the cloud so */
        const char *tn = strrchr(dir, '/') ? strrchr(dir, '/') + 1 : dir;
        return UMP_FAIL(err, UMP_ERR_UNSUPPORTED, "%s: a binary cloud (as foamFormatConvert writes it with "
                        "writeFormat binary) is not read by %s: set writeFormat ascii in system/controlDict and "
                        "run 'foamFormatConvert -time %s' to convert it back, or run with -reseed to seed new "
                        "particles from the fields", path, ump_solver, tn);
    }
    UMP_CALL(rc);
    rc = parse_positions(f, n, pos, cell, err);
    foam_file_free(&f);
    if (rc != UMP_OK)
        return rc;
    size_t pos_i = 0;
    if ((rc = fio_read_cloud_field(dir, cloud, "U", 3, *n, vel, err)) != UMP_OK)
        goto fail;
    *id = ump_alloc_array(*n, sizeof **id);
    if (!*id) {
        rc = UMP_FAIL(err, UMP_ERR_NOMEM, "%s: out of memory", path);
        goto fail;
    }
    for (size_t i = 0; i < *n; i++)
        (*id)[i] = -1;
    snprintf(path, sizeof path, "%s/lagrangian/%s/origId", dir, cloud);
    if (foam_file_exists(path)) {
        ump_idx *ids = NULL;
        size_t ni = 0;
        pos_i = 0;
        if ((rc = foam_file_read(path, &f, err)) != UMP_OK)
            goto fail;
        rc = foam_tok_label_list(f->body, f->nbody, &pos_i, &ids, &ni, "origId", err);
        if (rc == UMP_OK && ni != *n)
            rc = UMP_FAIL(err, UMP_ERR_INPUT, "%s: %zu ids for %zu particles", f->path, ni, *n);
        foam_file_free(&f);
        if (rc == UMP_OK)
            for (size_t i = 0; i < *n; i++)
                (*id)[i] = ids[i];
        free(ids);
        if (rc != UMP_OK)
            goto fail;
    }
    return UMP_OK;
fail:
    free(*pos);
    free(*vel);
    free(*id);
    free(*cell);
    *pos = *vel = NULL;
    *id = NULL;
    *cell = NULL;
    *n = 0;
    return rc;
}
