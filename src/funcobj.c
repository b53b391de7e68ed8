/* SPDX-License-Identifier: GPL-3.0-or-later
 * funcobj.c -- the controlDict function objects umppmFoam runs (funcobj.h).
 */
#include "umppm/funcobj.h"
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

static ump_status read_nusselt(const foam_dict *d, const char *name, fob_nusselt *f, ump_err *err)
{
    memset(f, 0, sizeof *f);
    snprintf(f->name, sizeof f->name, "%s", name);
    const char *patch = NULL, *grad = NULL, *wc = NULL;
    int64_t interval = 1;
    UMP_CALL(foam_get_word(d, "patch", &patch, err));
    snprintf(f->patch, sizeof f->patch, "%s", patch);
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
    UMP_CALL(foam_get_word_or(d, "writeControl", "timeStep", &wc, err));
    if (strcmp(wc, "timeStep") != 0 && strcmp(wc, "writeTime") != 0 && strcmp(wc, "outputTime") != 0) {
        const foam_entry *e = foam_dict_find(d, "writeControl", 0);
        return UMP_FAIL(err, UMP_ERR_INPUT, "%s:%d: writeControl '%s' is not one of: timeStep writeTime",
                        e->file, e->line, wc);
    }
    f->on_write_time = strcmp(wc, "timeStep") != 0;
    UMP_CALL(foam_get_label_or(d, "writeInterval", 1, &interval, err));
    if (interval < 1) {
        const foam_entry *e = foam_dict_find(d, "writeInterval", 0);
        return UMP_FAIL(err, UMP_ERR_INPUT, "%s:%d: writeInterval must be >= 1", e->file, e->line);
    }
    f->interval = (long)interval;
    return UMP_OK;
}

ump_status fob_read(const char *case_dir, fob_list *L, ump_err *err)
{
    memset(L, 0, sizeof *L);
    char path[4096];
    snprintf(path, sizeof path, "%s/system/controlDict", case_dir);
    foam_file *file = NULL;
    UMP_CALL(foam_file_read(path, &file, err));
    ump_status rc = UMP_OK;
    const foam_dict *fd = foam_dict_sub(file->dict, "functions");
    for (size_t i = 0; fd && i < fd->n; i++) {
        const foam_entry *e = &fd->e[i];
        if (!e->dict) { /* #includeFunc and other primitive entries */
            note_ignored(L, e->key, "not a dictionary");
            continue;
        }
        const char *type = NULL;
        int enabled = 1;
        if ((rc = foam_get_word(e->dict, "type", &type, err)) != UMP_OK ||
            (rc = foam_get_bool_or(e->dict, "enabled", 1, &enabled, err)) != UMP_OK)
            break;
        if (!enabled)
            continue;
        if (strcmp(type, "nusseltNumber") != 0) {
            note_ignored(L, e->key, type);
            continue;
        }
        fob_nusselt *q = ump_realloc_array(L->nu, (size_t)L->n + 1, sizeof *q);
        if (!q) {
            rc = UMP_FAIL(err, UMP_ERR_NOMEM, "%s: out of memory", path);
            break;
        }
        L->nu = q;
        if ((rc = read_nusselt(e->dict, e->key, &L->nu[L->n], err)) != UMP_OK)
            break;
        L->n++;
    }
    foam_file_free(&file);
    if (rc != UMP_OK)
        fob_free(L);
    return rc;
}

void fob_free(fob_list *L)
{
    for (int i = 0; i < L->n; i++)
        if (L->nu[i].fp)
            fclose(L->nu[i].fp);
    free(L->nu);
    L->nu = NULL;
    L->n = 0;
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
    /* Eq. 43: q = k dT/dn; Eq. 44: h = q / (T1 - T2); Eq. 45: Nu = h S / k */
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

int fob_due(const fob_nusselt *f, long step, int write_time)
{
    return f->on_write_time ? write_time : step % f->interval == 0;
}

ump_status fob_nusselt_append(fob_nusselt *f, const char *case_dir, const char *start_time, double t,
                              const fob_result *r, int precision, ump_err *err)
{
    if (!f->fp) {
        char dir[4200];
        snprintf(dir, sizeof dir, "%s/postProcessing/%s/%s", case_dir, f->name, start_time);
        UMP_CALL(fio_mkdir_p(dir, err));
        snprintf(f->path, sizeof f->path, "%s/nusseltNumber.dat", dir);
        struct stat sb;
        if (stat(f->path, &sb) == 0)
            snprintf(f->path, sizeof f->path, "%s/nusseltNumber_%s.dat", dir, start_time);
        f->fp = fopen(f->path, "w");
        if (!f->fp)
            return UMP_FAIL(err, UMP_ERR_IO, "%s: cannot create: %s", f->path, strerror(errno));
        fprintf(f->fp, "# Nusselt number (umppmFoam nusseltNumber; Eqs. 43-45 of Ng, Sheu & Hwang 2016)\n"
                       "# patch    : %s\n# length   : %.*g\n# kappa    : %.*g\n# T1 - T2  : %.*g - %.*g\n"
                       "# gradient : %s\n# Time\tNu_avg\th_avg\tq_avg\tNu_min\tNu_max\n",
                f->patch, precision, f->length, precision, f->kappa, precision, r->T1, precision, r->T2,
                f->snGrad ? "snGrad" : "mls");
    }
    fprintf(f->fp, "%.*g\t%.*g\t%.*g\t%.*g\t%.*g\t%.*g\n", precision, t, precision, r->Nu_avg, precision,
            r->h_avg, precision, r->q_avg, precision, r->Nu_min, precision, r->Nu_max);
    if (fflush(f->fp) != 0)
        return UMP_FAIL(err, UMP_ERR_IO, "%s: write failed: %s", f->path, strerror(errno));
    return UMP_OK;
}

ump_status fob_nusselt_local(const fob_nusselt *f, const char *case_dir, const char *time_name,
                             const fob_faces *d, const fob_result *r, int precision, ump_err *err)
{
    char dir[4200], path[4400], tmp[4500];
    snprintf(dir, sizeof dir, "%s/postProcessing/%s/%s", case_dir, f->name, time_name);
    UMP_CALL(fio_mkdir_p(dir, err));
    snprintf(path, sizeof path, "%s/%s.dat", dir, f->patch);
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    FILE *fp = fopen(tmp, "w");
    if (!fp)
        return UMP_FAIL(err, UMP_ERR_IO, "%s: cannot create: %s", tmp, strerror(errno));
    double dT = r->T1 - r->T2;
    fprintf(fp, "# local heat transfer on patch %s at time %s (Eqs. 43-45; T1 - T2 = %.*g)\n"
                "# x\ty\tz\tdTdn\tq\th\tNu\n", f->patch, time_name, precision, dT);
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
