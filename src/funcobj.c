/* SPDX-License-Identifier: GPL-3.0-or-later
 * funcobj.c -- the controlDict function objects umppmFoam runs (funcobj.h).
 */
#include "umppm/funcobj.h"
#include "umppm/case.h"
#include "umppm/fieldio.h"
#include "umppm/foam.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

static void note_ignored(fob_list *L, const char *name, const char *type)
{
    size_t len = strlen(L->ignored);
    snprintf(L->ignored + len, sizeof L->ignored - len, "%s%s (%s)", len ? ", " : "", name, type);
}

/* A primitive entry of functions: `#includeFunc mag(U)` is named by its
 * function ("mag(U) (#includeFunc)"). */
static void note_primitive(fob_list *L, const foam_entry *e)
{
    if (strcmp(e->key, "#includeFunc") == 0 && e->ntok > 0 && e->tok[0].type == FOAM_TOK_WORD)
        note_ignored(L, e->tok[0].v.str, "#includeFunc");
    else if (strcmp(e->key, "#includeFunc") == 0 && e->ntok > 0 && e->tok[0].type == FOAM_TOK_STRING)
        note_ignored(L, e->tok[0].v.str, "#includeFunc");
    else
        note_ignored(L, e->key, "not a dictionary");
}

/* name, patch (key `patch` or, for surfaceFieldValue, `name`),
 * writeControl, writeInterval. */
static ump_status read_common(const foam_dict *d, const char *name, const char *patch_key, fob_common *c,
                              ump_err *err)
{
    snprintf(c->name, sizeof c->name, "%s", name);
    const char *patch = NULL, *wc = NULL;
    int64_t interval = 1;
    UMP_CALL(foam_get_word(d, patch_key, &patch, err));
    snprintf(c->patch, sizeof c->patch, "%s", patch);
    UMP_CALL(foam_get_word_or(d, "writeControl", "timeStep", &wc, err));
    if (strcmp(wc, "timeStep") != 0 && strcmp(wc, "writeTime") != 0 && strcmp(wc, "outputTime") != 0) {
        const foam_entry *e = foam_dict_find(d, "writeControl", 0);
        return UMP_FAIL(err, UMP_ERR_INPUT, "%s:%d: writeControl '%s' is not one of: timeStep writeTime",
                        e->file, e->line, wc);
    }
    c->on_write_time = strcmp(wc, "timeStep") != 0;
    UMP_CALL(foam_get_label_or(d, "writeInterval", 1, &interval, err));
    if (interval < 1) {
        const foam_entry *e = foam_dict_find(d, "writeInterval", 0);
        return UMP_FAIL(err, UMP_ERR_INPUT, "%s:%d: writeInterval must be >= 1", e->file, e->line);
    }
    c->interval = (long)interval;
    return UMP_OK;
}

static ump_status read_nusselt(const foam_dict *d, const char *name, fob_nusselt *f, ump_err *err)
{
    memset(f, 0, sizeof *f);
    const char *grad = NULL;
    UMP_CALL(read_common(d, name, "patch", &f->c, err));
    UMP_CALL(foam_get_scalar(d, "length", &f->length, err));
    UMP_CALL(foam_get_scalar(d, "kappa", &f->kappa, err));
    if (!(f->length > 0) || !(f->kappa > 0))
        return UMP_FAIL(err, UMP_ERR_INPUT, "%s:%d: function object '%s': length and kappa must be positive",
                        d->file, d->line, name);
    f->has_T1 = foam_dict_find(d, "T1", 0) != NULL;
    f->has_T2 = foam_dict_find(d, "T2", 0) != NULL;
    if (f->has_T1)
        UMP_CALL(foam_get_scalar(d, "T1", &f->T1, err));
    if (f->has_T2)
        UMP_CALL(foam_get_scalar(d, "T2", &f->T2, err));
    UMP_CALL(foam_get_word_or(d, "gradient", "mls", &grad, err));
    if (strcmp(grad, "mls") != 0 && strcmp(grad, "snGrad") != 0) {
        const foam_entry *e = foam_dict_find(d, "gradient", 0);
        return UMP_FAIL(err, UMP_ERR_INPUT, "%s:%d: gradient '%s' is not one of: mls snGrad", e->file,
                        e->line, grad);
    }
    f->snGrad = strcmp(grad, "snGrad") == 0;
    return UMP_OK;
}

static const char *const op_names[] = {"none", "sum", "average", "areaAverage", "areaIntegrate", "min", "max"};

const char *fob_op_name(fob_op op)
{
    return op_names[op];
}

static const char *const field_names[] = {"U", "p", "T", "p_rgh"};

const char *fob_field_name(fob_field f)
{
    return field_names[f];
}

static ump_status read_sfv(const foam_dict *d, const char *name, fob_sfv *f, ump_err *err)
{
    memset(f, 0, sizeof *f);
    const char *rt = NULL, *op = NULL;
    int wf = 0;
    UMP_CALL(foam_get_word(d, "regionType", &rt, err));
    if (strcmp(rt, "patch") != 0) {
        const foam_entry *e = foam_dict_find(d, "regionType", 0);
        return UMP_FAIL(err, UMP_ERR_INPUT, "%s:%d: function object '%s': regionType '%s' is not supported "
                        "by %s (only: patch)", e->file, e->line, name, rt, ump_solver);
    }
    UMP_CALL(read_common(d, name, "name", &f->c, err));
    UMP_CALL(foam_get_word(d, "operation", &op, err));
    size_t k = 0;
    while (k < sizeof op_names / sizeof *op_names && strcmp(op, op_names[k]) != 0)
        k++;
    if (k == sizeof op_names / sizeof *op_names) {
        const foam_entry *e = foam_dict_find(d, "operation", 0);
        return UMP_FAIL(err, UMP_ERR_INPUT, "%s:%d: function object '%s': operation '%s' is not one of: "
                        "none sum average areaAverage areaIntegrate min max", e->file, e->line, name, op);
    }
    f->op = (fob_op)k;
    UMP_CALL(foam_get_bool_or(d, "writeFields", 0, &wf, err));
    if (wf) {
        const foam_entry *e = foam_dict_find(d, "writeFields", 0);
        return UMP_FAIL(err, UMP_ERR_INPUT, "%s:%d: function object '%s': writeFields true is not supported "
                        "by %s (set it false)", e->file, e->line, name, ump_solver);
    }
    const foam_entry *e = foam_dict_find(d, "fields", 0);
    if (!e || e->dict)
        return UMP_FAIL(err, UMP_ERR_INPUT, "%s:%d: function object '%s': expected 'fields (f1 f2 ...);'",
                        d->file, d->line, name);
    /* fields ( w w ... ) */
    size_t i = 0;
    if (e->ntok >= 2 && e->tok[0].type == FOAM_TOK_PUNCT && e->tok[0].v.punct == '(')
        for (i = 1; i < e->ntok && e->tok[i].type == FOAM_TOK_WORD; i++) {
            if (f->nfields == FOB_MAX_FIELDS)
                return UMP_FAIL(err, UMP_ERR_INPUT, "%s:%d: function object '%s': more than %d fields",
                                e->file, e->line, name, FOB_MAX_FIELDS);
            size_t j = 0;
            while (j < sizeof field_names / sizeof *field_names && strcmp(e->tok[i].v.str, field_names[j]) != 0)
                j++;
            if (j == sizeof field_names / sizeof *field_names)
                return UMP_FAIL(err, UMP_ERR_INPUT, "%s:%d: function object '%s': field '%s' is not one of: "
                                "U p T p_rgh", e->file, e->tok[i].line, name, e->tok[i].v.str);
            f->field[f->nfields++] = (fob_field)j;
        }
    if (e->ntok < 2 || i != e->ntok - 1 || e->tok[i].type != FOAM_TOK_PUNCT || e->tok[i].v.punct != ')' ||
        f->nfields == 0)
        return UMP_FAIL(err, UMP_ERR_INPUT, "%s:%d: function object '%s': expected 'fields (f1 f2 ...);'",
                        e->file, e->line, name);
    return UMP_OK;
}

/* Append one element to an array of function objects. */
static void *grow(void *arr, int n, size_t size)
{
    return ump_realloc_array(arr, (size_t)n + 1, size);
}

/* <case>/system/controlDict read (path gets its path) and its functions
 * dictionary (*fd NULL where there is none). */
static ump_status read_functions(const char *case_dir, char path[4096], foam_file **file, const foam_dict **fd,
                                 ump_err *err)
{
    snprintf(path, 4096, "%s/system/controlDict", case_dir);
    *file = NULL;
    UMP_CALL(foam_file_read(path, file, err));
    *fd = foam_dict_sub((*file)->dict, "functions");
    return UMP_OK;
}

ump_status fob_read(const char *case_dir, fob_list *L, ump_err *err)
{
    memset(L, 0, sizeof *L);
    char path[4096];
    foam_file *file;
    const foam_dict *fd;
    UMP_CALL(read_functions(case_dir, path, &file, &fd, err));
    ump_status rc = UMP_OK;
    for (size_t i = 0; fd && i < fd->n; i++) {
        const foam_entry *e = &fd->e[i];
        if (!e->dict) { /* #includeFunc and other primitive entries */
            note_primitive(L, e);
            continue;
        }
        if (!case_name_is_safe(e->key)) { /* postProcessing/<name>/... */
            rc = UMP_FAIL(err, UMP_ERR_INPUT, "%s:%d: function object name '%s' is not a plain name: it becomes "
                          "the directory postProcessing/<name>, so it must be non-empty without '/' or '..'",
                          e->file, e->line, e->key);
            break;
        }
        const char *type = NULL;
        int enabled = 1;
        if ((rc = foam_get_word(e->dict, "type", &type, err)) != UMP_OK ||
            (rc = foam_get_bool_or(e->dict, "enabled", 1, &enabled, err)) != UMP_OK)
            break;
        if (!enabled)
            continue;
        if (strcmp(type, "nusseltNumber") == 0) {
            fob_nusselt *q = grow(L->nu, L->n, sizeof *q);
            if (!q) {
                rc = UMP_FAIL(err, UMP_ERR_NOMEM, "%s: out of memory", path);
                break;
            }
            L->nu = q;
            if ((rc = read_nusselt(e->dict, e->key, &L->nu[L->n], err)) != UMP_OK)
                break;
            L->n++;
        } else if (strcmp(type, "surfaceFieldValue") == 0) {
            fob_sfv *q = grow(L->sf, L->nsf, sizeof *q);
            if (!q) {
                rc = UMP_FAIL(err, UMP_ERR_NOMEM, "%s: out of memory", path);
                break;
            }
            L->sf = q;
            if ((rc = read_sfv(e->dict, e->key, &L->sf[L->nsf], err)) != UMP_OK)
                break;
            L->nsf++;
        } else {
            note_ignored(L, e->key, type);
        }
    }
    foam_file_free(&file);
    if (rc != UMP_OK)
        fob_free(L);
    return rc;
}

ump_status fob_names(const char *case_dir, char *buf, size_t size, ump_err *err)
{
    fob_list L; /* only its list of names is used */
    memset(&L, 0, sizeof L);
    char path[4096];
    foam_file *file;
    const foam_dict *fd;
    UMP_CALL(read_functions(case_dir, path, &file, &fd, err));
    ump_status rc = UMP_OK;
    for (size_t i = 0; fd && i < fd->n && rc == UMP_OK; i++) {
        const foam_entry *e = &fd->e[i];
        const char *type = NULL;
        int enabled = 1;
        if (!e->dict)
            note_primitive(&L, e);
        else if ((rc = foam_get_word(e->dict, "type", &type, err)) == UMP_OK &&
                 (rc = foam_get_bool_or(e->dict, "enabled", 1, &enabled, err)) == UMP_OK && enabled)
            note_ignored(&L, e->key, type);
    }
    foam_file_free(&file);
    snprintf(buf, size, "%s", rc == UMP_OK ? L.ignored : "");
    return rc;
}

static void free_common(fob_common *c)
{
    if (c->fp)
        fclose(c->fp);
    free(c->face);
    free(c->area);
    free(c->x3);
    c->fp = NULL;
    c->face = NULL;
    c->area = c->x3 = NULL;
}

void fob_free(fob_list *L)
{
    for (int i = 0; i < L->n; i++)
        free_common(&L->nu[i].c);
    for (int i = 0; i < L->nsf; i++)
        free_common(&L->sf[i].c);
    free(L->nu);
    free(L->sf);
    L->nu = NULL;
    L->sf = NULL;
    L->n = L->nsf = 0;
}

/* Move c's open series to n (and nothing else). */
static void move_series(fob_common *n, fob_common *c)
{
    n->fp = c->fp;
    snprintf(n->path, sizeof n->path, "%s", c->path);
    snprintf(n->suffix, sizeof n->suffix, "%s", c->suffix);
    n->continued = 1;
    c->fp = NULL;
}

void fob_take_over(fob_list *nw, fob_list *old, const char *time_name)
{
    for (int i = 0; i < nw->n; i++) {
        fob_nusselt *n = &nw->nu[i];
        snprintf(n->c.suffix, sizeof n->c.suffix, "%s", time_name);
        for (int j = 0; j < old->n; j++) {
            const fob_nusselt *o = &old->nu[j];
            if (strcmp(n->c.name, o->c.name) == 0 && strcmp(n->c.patch, o->c.patch) == 0 &&
                n->length == o->length && n->kappa == o->kappa && n->has_T1 == o->has_T1 &&
                n->has_T2 == o->has_T2 && (!n->has_T1 || n->T1 == o->T1) && (!n->has_T2 || n->T2 == o->T2) &&
                n->snGrad == o->snGrad)
                move_series(&n->c, &old->nu[j].c);
        }
    }
    for (int i = 0; i < nw->nsf; i++) {
        fob_sfv *n = &nw->sf[i];
        snprintf(n->c.suffix, sizeof n->c.suffix, "%s", time_name);
        for (int j = 0; j < old->nsf; j++) {
            const fob_sfv *o = &old->sf[j];
            if (strcmp(n->c.name, o->c.name) == 0 && strcmp(n->c.patch, o->c.patch) == 0 && n->op == o->op &&
                n->nfields == o->nfields && memcmp(n->field, o->field, (size_t)n->nfields * sizeof n->field[0]) == 0)
                move_series(&n->c, &old->sf[j].c);
        }
    }
}

ump_status fob_set_faces(fob_common *c, size_t n, const ump_idx *face, const double *area, const double *x3,
                         ump_err *err)
{
    free(c->face);
    free(c->area);
    free(c->x3);
    c->face = ump_alloc_array(n, sizeof *c->face);
    c->area = ump_alloc_array(n, sizeof *c->area);
    c->x3 = ump_alloc_array(3 * n, sizeof *c->x3);
    if (!c->face || !c->area || !c->x3)
        return UMP_FAIL(err, UMP_ERR_NOMEM, "function object '%s': out of memory", c->name);
    memcpy(c->face, face, n * sizeof *face);
    memcpy(c->area, area, n * sizeof *area);
    memcpy(c->x3, x3, 3 * n * sizeof *x3);
    c->nface = n;
    return UMP_OK;
}

fob_result fob_nusselt_eval(const fob_nusselt *f, const fob_faces *d, double t_ref)
{
    fob_result r;
    double A = 0, sT = 0, sg = 0;
    for (size_t i = 0; i < d->n; i++) {
        A += d->area[i];
        sT += d->area[i] * d->Tf[i];
        sg += d->area[i] * d->dTdn[i];
    }
    r.T1 = f->has_T1 ? f->T1 : sT / A;
    r.T2 = f->has_T2 ? f->T2 : t_ref;
    double dT = r.T1 - r.T2;
    /* Ng, Sheu & Hwang (2016) Eq. 43: q = k dT/dn; Eq. 44: h = q / (T1 - T2);
     * Eq. 45: Nu = h S / k */
    r.q_avg = f->kappa * sg / A;
    r.h_avg = r.q_avg / dT;
    r.Nu_avg = r.h_avg * f->length / f->kappa;
    r.Nu_min = INFINITY;
    r.Nu_max = -INFINITY;
    for (size_t i = 0; i < d->n; i++) {
        double Nu = d->dTdn[i] * f->length / dT;
        r.Nu_min = fmin(r.Nu_min, Nu);
        r.Nu_max = fmax(r.Nu_max, Nu);
    }
    return r;
}

int fob_due(const fob_common *f, long step, int write_time)
{
    return f->on_write_time ? write_time : step % f->interval == 0;
}

/* Open postProcessing/<name>/<start_time>/<base>.dat (an existing file of an
 * earlier run is kept: the new one gets the suffix _<start_time>, as
 * OpenFOAM's writeFile does). */
static ump_status open_series(fob_common *f, const char *case_dir, const char *start_time, const char *base,
                              ump_err *err)
{
    char dir[4200];
    snprintf(dir, sizeof dir, "%s/postProcessing/%s/%s", case_dir, f->name, start_time);
    UMP_CALL(fio_mkdir_p(dir, err));
    snprintf(f->path, sizeof f->path, "%s/%s.dat", dir, base);
    struct stat sb;
    if (stat(f->path, &sb) == 0)
        snprintf(f->path, sizeof f->path, "%s/%s_%s.dat", dir, base, f->suffix[0] ? f->suffix : start_time);
    f->fp = fopen(f->path, "w");
    if (!f->fp)
        return UMP_FAIL(err, UMP_ERR_IO, "%s: cannot create: %s", f->path, strerror(errno));
    return UMP_OK;
}

static ump_status flush_series(fob_common *f, ump_err *err)
{
    if (fflush(f->fp) != 0 || ferror(f->fp))
        return UMP_FAIL(err, UMP_ERR_IO, "%s: write failed: %s", f->path, strerror(errno));
    return UMP_OK;
}

ump_status fob_nusselt_append(fob_nusselt *f, const char *case_dir, const char *start_time, double t,
                              const fob_result *r, int precision, ump_err *err)
{
    FILE *fp = f->c.fp;
    if (!fp) {
        UMP_CALL(open_series(&f->c, case_dir, start_time, "nusseltNumber", err));
        fp = f->c.fp;
        fprintf(fp, "# Nusselt number (umppmFoam nusseltNumber; Eqs. 43-45 of Ng, Sheu & Hwang 2016)\n"
                       "# patch    : %s\n# length   : %.*g\n# kappa    : %.*g\n# T1 - T2  : %.*g - %.*g\n"
                       "# gradient : %s\n# Time\tNu_avg\th_avg\tq_avg\tNu_min\tNu_max\n",
                f->c.patch, precision, f->length, precision, f->kappa, precision, r->T1, precision, r->T2,
                f->snGrad ? "snGrad" : "mls");
    }
    fprintf(fp, "%.*g\t%.*g\t%.*g\t%.*g\t%.*g\t%.*g\n", precision, t, precision, r->Nu_avg, precision,
            r->h_avg, precision, r->q_avg, precision, r->Nu_min, precision, r->Nu_max);
    return flush_series(&f->c, err);
}

void fob_sfv_eval(const fob_sfv *f, const fob_patch_field *d, double *out)
{
    int nc = d->ncomp;
    double A = 0;
    for (int k = 0; k < nc; k++)
        out[k] = f->op == FOB_MIN ? INFINITY : f->op == FOB_MAX ? -INFINITY : 0;
    for (size_t i = 0; i < d->n; i++) {
        A += d->area[i];
        for (int k = 0; k < nc; k++) {
            double v = d->v[i * (size_t)nc + (size_t)k];
            switch (f->op) {
            case FOB_MIN: out[k] = fmin(out[k], v); break;
            case FOB_MAX: out[k] = fmax(out[k], v); break;
            case FOB_AREA_AVERAGE:
            case FOB_AREA_INTEGRATE: out[k] += d->area[i] * v; break;
            default: out[k] += v; break;
            }
        }
    }
    for (int k = 0; k < nc; k++)
        if (f->op == FOB_AREA_AVERAGE)
            out[k] /= A;
        else if (f->op == FOB_AVERAGE)
            out[k] /= (double)d->n;
}

static void put_value(FILE *fp, int nc, const double *v, int precision)
{
    if (nc == 1) {
        fprintf(fp, "\t%.*g", precision, v[0]);
        return;
    }
    fprintf(fp, "\t(");
    for (int k = 0; k < nc; k++)
        fprintf(fp, "%s%.*g", k ? " " : "", precision, v[k]);
    fprintf(fp, ")");
}

ump_status fob_sfv_append(fob_sfv *f, const char *case_dir, const char *start_time, double t,
                          const fob_patch_field *vals, int precision, ump_err *err)
{
    FILE *fp = f->c.fp;
    if (!fp) {
        UMP_CALL(open_series(&f->c, case_dir, start_time, "surfaceFieldValue", err));
        fp = f->c.fp;
        double A = 0;
        for (size_t i = 0; i < vals[0].n; i++)
            A += vals[0].area[i];
        fprintf(fp, "# Region type : patch %s\n# Faces       : %zu\n# Area        : %.*g\n"
                    "# Scale factor: 1\n# Time        ",
                f->c.patch, vals[0].n, precision, A);
        for (int k = 0; k < f->nfields; k++)
            fprintf(fp, "\t%s(%s)", fob_op_name(f->op), fob_field_name(f->field[k]));
        fprintf(fp, "\n");
    }
    fprintf(fp, "%-14.*g", precision, t);
    for (int k = 0; k < f->nfields; k++) {
        double out[3];
        if (f->op == FOB_NONE)
            continue;
        fob_sfv_eval(f, &vals[k], out);
        put_value(fp, vals[k].ncomp, out, precision);
    }
    fprintf(fp, "\n");
    return flush_series(&f->c, err);
}

ump_status fob_nusselt_local(const fob_nusselt *f, const char *case_dir, const char *time_name,
                             const fob_faces *d, const fob_result *r, int precision, ump_err *err)
{
    char dir[4200], path[4400], tmp[4500];
    snprintf(dir, sizeof dir, "%s/postProcessing/%s/%s", case_dir, f->c.name, time_name);
    UMP_CALL(fio_mkdir_p(dir, err));
    snprintf(path, sizeof path, "%s/%s.dat", dir, f->c.patch);
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    FILE *fp = fopen(tmp, "w");
    if (!fp)
        return UMP_FAIL(err, UMP_ERR_IO, "%s: cannot create: %s", tmp, strerror(errno));
    double dT = r->T1 - r->T2;
    fprintf(fp, "# local heat transfer on patch %s at time %s (Eqs. 43-45; T1 - T2 = %.*g)\n"
                "# x\ty\tz\tdTdn\tq\th\tNu\n", f->c.patch, time_name, precision, dT);
    for (size_t i = 0; i < d->n; i++) {
        double q = f->kappa * d->dTdn[i], h = q / dT;
        fprintf(fp, "%.*g\t%.*g\t%.*g\t%.*g\t%.*g\t%.*g\t%.*g\n", precision, d->x3[3 * i], precision,
                d->x3[3 * i + 1], precision, d->x3[3 * i + 2], precision, d->dTdn[i], precision, q,
                precision, h, precision, h * f->length / f->kappa);
    }
    if (fclose(fp) != 0 || rename(tmp, path) != 0) {
        remove(tmp);
        return UMP_FAIL(err, UMP_ERR_IO, "%s: write failed: %s", path, strerror(errno));
    }
    return UMP_OK;
}
