/* SPDX-License-Identifier: GPL-3.0-or-later
 * case.c -- system/controlDict, constant/transportProperties,
 * system/fvSolution and the time directories of an OpenFOAM case.
 *
 * Defaults are OpenFOAM v1912's (Time.C, TimeIO.C, icoFoam's createFields.H,
 * setDeltaT.H): startFrom startTime, stopAt endTime, writeControl timeStep,
 * purgeWrite 0, writeFormat ascii, writePrecision 6, writeCompression off,
 * timeFormat general, timePrecision 6, adjustTimeStep no, maxCo 1,
 * maxDeltaT great, pRefCell 0, pRefValue 0.
 */
#include "umppm/case.h"
#include "umppm/foam.h"

#include <dirent.h>
#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

typedef struct word_enum {
    const char *word;
    int value;
} word_enum;

/* Map the word of key to an enum value; unknown words are an error listing
 * the valid ones. Absent key gives dflt. */
static ump_status get_enum(const foam_dict *d, const char *key, const word_enum *tab, int ntab,
                           int dflt, int *out, ump_err *err)
{
    const char *w = NULL;
    UMP_CALL(foam_get_word_or(d, key, NULL, &w, err));
    if (!w) {
        *out = dflt;
        return UMP_OK;
    }
    for (int i = 0; i < ntab; i++)
        if (strcmp(tab[i].word, w) == 0) {
            *out = tab[i].value;
            return UMP_OK;
        }
    const foam_entry *e = foam_dict_find(d, key, 0);
    char valid[512] = "";
    for (int i = 0; i < ntab; i++) {
        strncat(valid, i ? " " : "", sizeof valid - strlen(valid) - 1);
        strncat(valid, tab[i].word, sizeof valid - strlen(valid) - 1);
    }
    return UMP_FAIL(err, UMP_ERR_INPUT, "%s:%d: %s '%s' is not one of: %s",
                    e ? e->file : "?", e ? e->line : 0, key, w, valid);
}

static ump_status get_positive(const foam_dict *d, const char *key, double *v, ump_err *err)
{
    UMP_CALL(foam_get_scalar(d, key, v, err));
    const foam_entry *e = foam_dict_find(d, key, 0);
    if (!(*v > 0))
        return UMP_FAIL(err, UMP_ERR_INPUT, "%s:%d: %s must be positive, found %g",
                        e->file, e->line, key, *v);
    return UMP_OK;
}

/* startTime, endTime, deltaT, writeInterval (and maxCo, maxDeltaT) must be
 * finite numbers: `endTime nan` would end the run before its first step
 * and `endTime 1e400` (inf) never; deltaT and writeInterval > 0 (checked by
 * get_positive); endTime >= startTime. endTime only counts with stopAt
 * endTime (Time::readDict reads it for no other stopAt). */
static ump_status check_times(const foam_dict *d, const case_control *c, ump_err *err)
{
    const int use_end = c->stop_at == CASE_STOP_ENDTIME;
    const struct {
        const char *key;
        double v;
    } t[] = {{"startTime", c->start_time}, {"endTime", use_end ? c->end_time : 0}, {"deltaT", c->delta_t},
             {"writeInterval", c->write_interval}, {"maxCo", c->max_co}};
    for (size_t i = 0; i < sizeof t / sizeof t[0]; i++)
        if (!isfinite(t[i].v)) {
            const foam_entry *e = foam_dict_find(d, t[i].key, 0);
            return UMP_FAIL(err, UMP_ERR_INPUT, "%s:%d: %s must be a finite number, found %g", e ? e->file : "?",
                            e ? e->line : 0, t[i].key, t[i].v);
        }
    if (!(c->max_delta_t > 0)) {
        const foam_entry *e = foam_dict_find(d, "maxDeltaT", 0);
        return UMP_FAIL(err, UMP_ERR_INPUT, "%s:%d: maxDeltaT must be positive, found %g", e ? e->file : "?",
                        e ? e->line : 0, c->max_delta_t);
    }
    if (use_end && c->start_from == CASE_START_STARTTIME && c->end_time < c->start_time) {
        const foam_entry *e = foam_dict_find(d, "endTime", 0);
        return UMP_FAIL(err, UMP_ERR_INPUT, "%s:%d: endTime %g is before startTime %g: nothing to run",
                        e ? e->file : "?", e ? e->line : 0, c->end_time, c->start_time);
    }
    return UMP_OK;
}

ump_status case_read_control(const char *case_dir, case_control *c, ump_err *err)
{
    static const word_enum start_from[] = {
        {"startTime", CASE_START_STARTTIME}, {"latestTime", CASE_START_LATESTTIME},
        {"firstTime", CASE_START_FIRSTTIME}};
    static const word_enum stop_at[] = {
        {"endTime", CASE_STOP_ENDTIME}, {"writeNow", CASE_STOP_WRITENOW},
        {"noWriteNow", CASE_STOP_NOWRITENOW}, {"nextWrite", CASE_STOP_NEXTWRITE}};
    static const word_enum write_control[] = {
        {"timeStep", CASE_WRITE_TIMESTEP}, {"runTime", CASE_WRITE_RUNTIME},
        {"adjustableRunTime", CASE_WRITE_ADJUSTABLERUNTIME}, {"adjustable", CASE_WRITE_ADJUSTABLERUNTIME},
        {"cpuTime", CASE_WRITE_CPUTIME}, {"clockTime", CASE_WRITE_CLOCKTIME}};
    static const word_enum formats[] = {{"ascii", 0}, {"binary", 1}};
    static const word_enum compression[] = {
        {"off", 0}, {"no", 0}, {"false", 0}, {"uncompressed", 0},
        {"on", 1}, {"yes", 1}, {"true", 1}, {"compressed", 1}};
    static const word_enum time_format[] = {{"general", 0}, {"fixed", 1}, {"scientific", 2}};

    char path[4096];
    snprintf(path, sizeof path, "%s/system/controlDict", case_dir);
    foam_file *f = NULL;
    UMP_CALL(foam_file_read(path, &f, err));
    const foam_dict *d = f->dict;
    memset(c, 0, sizeof *c);
    ump_status rc;
    const char *app = NULL;
    int e1, e2, e3, e4, e5, e6;
    int64_t purge = 0, wprec = 6, tprec = 6;
    if ((rc = foam_get_word_or(d, "application", "", &app, err)) != UMP_OK ||
        (rc = get_enum(d, "startFrom", start_from, 3, CASE_START_STARTTIME, &e1, err)) != UMP_OK ||
        (rc = get_enum(d, "stopAt", stop_at, 4, CASE_STOP_ENDTIME, &e2, err)) != UMP_OK ||
        (rc = get_enum(d, "writeControl", write_control, 6, CASE_WRITE_TIMESTEP, &e3, err)) != UMP_OK ||
        (rc = get_enum(d, "writeFormat", formats, 2, 0, &e4, err)) != UMP_OK ||
        (rc = get_enum(d, "writeCompression", compression, 8, 0, &e5, err)) != UMP_OK ||
        (rc = get_enum(d, "timeFormat", time_format, 3, 0, &e6, err)) != UMP_OK)
        goto done;
    snprintf(c->application, sizeof c->application, "%s", app);
    c->start_from = (case_start_from)e1;
    c->stop_at = (case_stop_at)e2;
    c->write_control = (case_write_control)e3;
    c->write_binary = e4;
    c->write_compression = e5;
    c->time_format_fixed = e6;
    if (c->start_from == CASE_START_STARTTIME) {
        if ((rc = foam_get_scalar(d, "startTime", &c->start_time, err)) != UMP_OK)
            goto done;
    } else if ((rc = foam_get_scalar_or(d, "startTime", 0, &c->start_time, err)) != UMP_OK) {
        goto done;
    }
    /* stopAt writeNow, noWriteNow, nextWrite: endTime is not read (it is
     * GREAT, Time::readDict), so it may be absent */
    if (c->stop_at == CASE_STOP_ENDTIME)
        rc = foam_get_scalar(d, "endTime", &c->end_time, err);
    else
        rc = foam_get_scalar_or(d, "endTime", 1e15, &c->end_time, err);
    if (rc != UMP_OK ||
        (rc = get_positive(d, "deltaT", &c->delta_t, err)) != UMP_OK ||
        (rc = get_positive(d, "writeInterval", &c->write_interval, err)) != UMP_OK ||
        (rc = foam_get_label_or(d, "purgeWrite", 0, &purge, err)) != UMP_OK ||
        (rc = foam_get_label_or(d, "writePrecision", 6, &wprec, err)) != UMP_OK ||
        (rc = foam_get_label_or(d, "timePrecision", 6, &tprec, err)) != UMP_OK ||
        (rc = foam_get_bool_or(d, "adjustTimeStep", 0, &c->adjust_time_step, err)) != UMP_OK ||
        (rc = foam_get_scalar_or(d, "maxCo", 1.0, &c->max_co, err)) != UMP_OK ||
        (rc = foam_get_scalar_or(d, "maxDeltaT", DBL_MAX, &c->max_delta_t, err)) != UMP_OK ||
        (rc = foam_get_bool_or(d, "runTimeModifiable", 1, &c->run_time_modifiable, err)) != UMP_OK)
        goto done;
    /* each bad value named with its file and line */
    const char *badkey = purge < 0 ? "purgeWrite" : wprec < 1 || wprec > 30 ? "writePrecision"
                       : tprec < 1 || tprec > 30 ? "timePrecision" : !(c->max_co > 0) ? "maxCo" : NULL;
    if (badkey) {
        const foam_entry *e = foam_dict_find(d, badkey, 0);
        int is_purge = purge < 0, is_co = !is_purge && badkey[0] == 'm';
        double v = is_purge ? (double)purge : badkey[0] == 'w' ? (double)wprec
                 : badkey[0] == 't' ? (double)tprec : c->max_co;
        rc = UMP_FAIL(err, UMP_ERR_INPUT, "%s:%d: %s %g: must be %s", f->path, e ? e->line : 0, badkey, v,
                      is_purge ? ">= 0 (0: keep every time)" : is_co ? "positive" : "in 1..30");
        goto done;
    }
    /* OpenFOAM clamps writePrecision silently to what a double can carry */
    c->purge_write = (int)purge;
    c->write_precision = (int)wprec;
    c->time_precision = (int)tprec;
    if ((rc = check_times(d, c, err)) != UMP_OK)
        goto done;
    if (c->write_control == CASE_WRITE_TIMESTEP && c->write_interval < 1) {
        rc = UMP_FAIL(err, UMP_ERR_INPUT, "%s: writeControl timeStep needs writeInterval >= 1", f->path);
        goto done;
    }
done:
    foam_file_free(&f);
    return rc;
}

/* A dimensioned transport constant: the dimensions, if given, must be
 * `want` (or all zero); value >= lo. *has = 0 when absent and !required. */
static ump_status get_transport_constant(const foam_dict *d, const char *key, const double want[7],
                                         const char *units, double lo, int required, double *v, int *has,
                                         ump_err *err)
{
    *has = 0;
    const foam_entry *e = foam_dict_find(d, key, 0);
    if (!e && !required)
        return UMP_OK;
    double dims[7];
    UMP_CALL(foam_get_dimensioned(d, key, v, dims, err));
    int dimensionless = 1, ok = 1;
    for (int k = 0; k < 7; k++) {
        dimensionless &= dims[k] == 0;
        ok &= dims[k] == want[k];
    }
    if (!ok && !dimensionless)
        return UMP_FAIL(err, UMP_ERR_INPUT, "%s:%d: %s must have dimensions [%g %g %g %g %g %g %g] (%s)",
                        e->file, e->line, key, want[0], want[1], want[2], want[3], want[4], want[5],
                        want[6], units);
    if (!(*v >= lo))
        return UMP_FAIL(err, UMP_ERR_INPUT, "%s:%d: %s must be >= %g, found %g", e->file, e->line, key, lo,
                        *v);
    *has = 1;
    return UMP_OK;
}

ump_status case_read_transport(const char *case_dir, case_transport *t, ump_err *err)
{
    static const double d_nu[7] = {0, 2, -1, 0, 0, 0, 0}, d_beta[7] = {0, 0, 0, -1, 0, 0, 0},
                        d_T[7] = {0, 0, 0, 1, 0, 0, 0}, d_none[7] = {0};
    char path[4096];
    snprintf(path, sizeof path, "%s/constant/transportProperties", case_dir);
    foam_file *f = NULL;
    UMP_CALL(foam_file_read(path, &f, err));
    memset(t, 0, sizeof *t);
    const foam_dict *d = f->dict;
    int has_prt = 0;
    ump_status rc;
    if ((rc = get_transport_constant(d, "nu", d_nu, "m^2/s", 0, 1, &t->nu, &t->has_nu, err)) == UMP_OK &&
        (rc = get_transport_constant(d, "beta", d_beta, "1/K", -INFINITY, 0, &t->beta, &t->has_beta,
                                     err)) == UMP_OK &&
        (rc = get_transport_constant(d, "TRef", d_T, "K", -INFINITY, 0, &t->TRef, &t->has_TRef, err)) ==
            UMP_OK &&
        (rc = get_transport_constant(d, "Pr", d_none, "dimensionless", 0, 0, &t->Pr, &t->has_Pr, err)) ==
            UMP_OK &&
        (rc = get_transport_constant(d, "Prt", d_none, "dimensionless", 0, 0, &t->Prt, &has_prt, err)) ==
            UMP_OK &&
        t->has_Pr && !(t->Pr > 0)) {
        const foam_entry *e = foam_dict_find(d, "Pr", 0);
        rc = UMP_FAIL(err, UMP_ERR_INPUT, "%s:%d: Pr must be positive, found %g", e->file, e->line, t->Pr);
    }
    foam_file_free(&f);
    return rc;
}

ump_status case_require_boussinesq(const char *case_dir, const case_transport *t, ump_err *err)
{
    const char *miss = !t->has_beta ? "beta" : !t->has_TRef ? "TRef" : !t->has_Pr ? "Pr" : NULL;
    if (miss)
        return UMP_FAIL(err, UMP_ERR_INPUT,
                        "%s/constant/transportProperties: keyword '%s' is missing; a buoyant case "
                        "(constant/g present) needs nu, beta, TRef and Pr as buoyantBoussinesqPimpleFoam",
                        case_dir, miss);
    return UMP_OK;
}

/* constant/g and constant/hRef (uniformDimensionedVectorField and
 * uniformDimensionedScalarField): their "value". */
ump_status case_read_buoyancy(const char *case_dir, case_buoyancy *b, ump_err *err)
{
    char path[4096];
    memset(b, 0, sizeof *b);
    snprintf(path, sizeof path, "%s/constant/g", case_dir);
    if (!foam_file_exists(path))
        return UMP_OK;
    foam_file *f = NULL;
    UMP_CALL(foam_file_read(path, &f, err));
    ump_status rc = foam_get_vector(f->dict, "value", b->g, err);
    foam_file_free(&f);
    if (rc != UMP_OK)
        return rc;
    b->on = 1;
    snprintf(path, sizeof path, "%s/constant/hRef", case_dir);
    if (!foam_file_exists(path))
        return UMP_OK;
    UMP_CALL(foam_file_read(path, &f, err));
    rc = foam_get_scalar(f->dict, "value", &b->h_ref, err);
    b->has_h_ref = rc == UMP_OK;
    foam_file_free(&f);
    return rc;
}

ump_status case_read_solution(const char *case_dir, case_solution *s, ump_err *err)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/system/fvSolution", case_dir);
    foam_file *f = NULL;
    UMP_CALL(foam_file_read(path, &f, err));
    memset(s, 0, sizeof *s);
    static const char *algo[] = {"PISO", "PIMPLE", "SIMPLE"};
    const foam_dict *a = NULL;
    for (int i = 0; i < 3 && !a; i++)
        if ((a = foam_dict_sub(f->dict, algo[i])) != NULL)
            snprintf(s->algo, sizeof s->algo, "%s", algo[i]);
    ump_status rc = UMP_OK;
    /* icoFoam: "keyword PISO is undefined in dictionary .../system/fvSolution" */
    if (!a) {
        const foam_entry *e = NULL;
        for (int i = 0; i < 3 && !e; i++)
            e = foam_dict_find(f->dict, algo[i], 0);
        if (e)
            rc = UMP_FAIL(err, UMP_ERR_INPUT, "%s:%d: %s must be a dictionary { ... }", e->file, e->line, e->key);
        else
            rc = UMP_FAIL(err, UMP_ERR_INPUT, "%s: keyword PISO is undefined (a PISO, PIMPLE or SIMPLE "
                          "dictionary is required, as icoFoam's PISO { nCorrectors 2; pRefCell 0; pRefValue 0; })",
                          f->path);
    }
    int64_t cell = 0;
    if (a && rc == UMP_OK) {
        s->has_p_ref_cell = foam_dict_find(a, "pRefCell", 0) != NULL;
        s->has_p_ref_value = foam_dict_find(a, "pRefValue", 0) != NULL;
        if ((rc = foam_get_label_or(a, "pRefCell", 0, &cell, err)) == UMP_OK &&
            (rc = foam_get_scalar_or(a, "pRefValue", 0, &s->p_ref_value, err)) == UMP_OK &&
            foam_dict_find(a, "pRefPoint", 0)) {
            rc = foam_get_vector(a, "pRefPoint", s->p_ref_point, err);
            s->has_p_ref_point = 1;
        }
    }
    s->p_ref_cell = (long)cell;
    foam_file_free(&f);
    return rc;
}

static int is_dir(const char *case_dir, const char *name)
{
    char path[4096];
    struct stat st;
    snprintf(path, sizeof path, "%s/%s", case_dir, name);
    return stat(path, &st) == 0 && S_ISDIR(st.st_mode);
}

typedef struct time_ent {
    char *name;
    double value;
} time_ent;

static int cmp_time(const void *a, const void *b)
{
    double x = ((const time_ent *)a)->value, y = ((const time_ent *)b)->value;
    return (x > y) - (x < y);
}

ump_status case_list_times(const char *case_dir, char ***names, double **values, int *n, ump_err *err)
{
    *names = NULL;
    *values = NULL;
    *n = 0;
    DIR *dp = opendir(case_dir);
    if (!dp)
        return UMP_FAIL(err, UMP_ERR_IO, "%s: cannot open the case directory", case_dir);
    time_ent *t = NULL;
    int cnt = 0, cap = 0;
    struct dirent *de;
    ump_status rc = UMP_OK;
    while ((de = readdir(dp)) != NULL) {
        char *end;
        if (de->d_name[0] == '.' || de->d_name[0] == '\0')
            continue;
        double v = strtod(de->d_name, &end);
        if (*end != '\0' || !is_dir(case_dir, de->d_name))
            continue;
        if (cnt == cap) {
            cap = cap ? 2 * cap : 16;
            time_ent *nt = ump_realloc_array(t, (size_t)cap, sizeof *t);
            if (!nt) {
                rc = UMP_FAIL(err, UMP_ERR_NOMEM, "%s: out of memory listing times", case_dir);
                break;
            }
            t = nt;
        }
        t[cnt].value = v;
        if (!(t[cnt].name = ump_strdup(de->d_name))) {
            rc = UMP_FAIL(err, UMP_ERR_NOMEM, "%s: out of memory listing times", case_dir);
            break;
        }
        cnt++;
    }
    closedir(dp);
    if (rc == UMP_OK && cnt > 0) {
        qsort(t, (size_t)cnt, sizeof *t, cmp_time);
        *names = ump_alloc_array((size_t)cnt, sizeof **names);
        *values = ump_alloc_array((size_t)cnt, sizeof **values);
        if (!*names || !*values) {
            free(*names);
            free(*values);
            *names = NULL;
            *values = NULL;
            rc = UMP_FAIL(err, UMP_ERR_NOMEM, "%s: out of memory listing times", case_dir);
        } else {
            for (int i = 0; i < cnt; i++) {
                (*names)[i] = t[i].name;
                (*values)[i] = t[i].value;
            }
            *n = cnt;
        }
    }
    if (rc != UMP_OK)
        for (int i = 0; i < cnt; i++)
            free(t[i].name);
    free(t);
    return rc;
}

void case_free_times(char **names, double *values, int n)
{
    for (int i = 0; i < n; i++)
        free(names[i]);
    free(names);
    free(values);
}

ump_status case_start_dir(const char *case_dir, const case_control *c, char *name, size_t len,
                          double *value, ump_err *err)
{
    char **names;
    double *vals;
    int n;
    UMP_CALL(case_list_times(case_dir, &names, &vals, &n, err));
    int pick = -1;
    if (c->start_from == CASE_START_LATESTTIME)
        pick = n - 1;
    else if (c->start_from == CASE_START_FIRSTTIME)
        pick = n > 0 ? 0 : -1;
    else
        for (int i = 0; i < n; i++) {
            double tol = 1e-12 * (fabs(c->start_time) > 1 ? fabs(c->start_time) : 1);
            if (vals[i] - c->start_time <= tol && c->start_time - vals[i] <= tol)
                pick = i;
        }
    ump_status rc = UMP_OK;
    if (pick < 0) {
        if (c->start_from == CASE_START_STARTTIME)
            rc = UMP_FAIL(err, UMP_ERR_IO, "%s/system/controlDict: startTime %g has no time directory in %s",
                          case_dir, c->start_time, case_dir);
        else
            rc = UMP_FAIL(err, UMP_ERR_IO, "%s: no time directory (e.g. 0/) to start from", case_dir);
    } else {
        snprintf(name, len, "%s", names[pick]);
        *value = vals[pick];
    }
    case_free_times(names, vals, n);
    return rc;
}

/* ---- the UMPPM sub-dictionary of system/fvSolution ------------------------ */

/* variant: auto (-1, decided by the mesh and the flow, app.c) or a variant */
static const char *const variant_words[] = {"auto", "UMPPM", "UMPPMstar", "UMPPM*", NULL};
static const int variant_values[] = {-1, 0, 1, 1};
static const char *const laplacian_words[] = {"auto", "CPM", "MPS", "IPS", "PS", "CPM4", NULL};
static const char *const ppe_words[] = {"auto", "UMFPACK", "KLU", "CHOLMOD", NULL};
static const char *const pc_words[] = {"ILU0", "Jacobi", "none", NULL};
static const char *const buoyancy_words[] = {"source", "balanced", NULL};
static const int buoyancy_values[] = {0, 1};
/* anisotropicCells: auto (-1, decided by the mesh, app.c) or an OpenFOAM Switch */
static const char *const aniso_words[] = {"auto", "yes", "no", "on", "off", "true", "false",
                                          "y", "n", "t", "f", "none", NULL};
static const int aniso_values[] = {-1, 1, 0, 1, 0, 1, 0, 1, 0, 1, 0, 0};
/* interpolationError: auto (-1, decided by the mesh and the flow, app.c) */
static const char *const qerr_words[] = {"auto", "transpose", "gradient", NULL};
static const int qerr_values[] = {-1, 1, 0};
static const char *const refill_words[] = {"auto", "centroid", "carried", NULL};
static const int refill_values[] = {-1, 0, 1};
static const char *const refill_weight_words[] = {"increment", "distance", NULL};
static const int refill_weight_values[] = {1, 0};

#define UM_FIELD(f) offsetof(case_umppm, f), sizeof(((case_umppm *)0)->f)
#define UM_NORANGE {0, 0, 0, 0, 0, 0, 0, 0}
/* has_lo, has_hi, lo_open, hi_open, lo, hi, or_zero, or_auto */
#define UM_OPEN01 {1, 1, 1, 1, 0, 1, 0, 0}
#define UM_ZERO_OR_1TO4 {1, 1, 0, 0, 1, 4, 1, 0}
#define UM_GT(x) {1, 0, 1, 0, (x), 0, 0, 0}
#define UM_GE(x) {1, 0, 0, 0, (x), 0, 0, 0}
#define UM_1TO16 {1, 1, 0, 0, 1, 16, 0, 0}
#define UM_AUTO_OR_0TOHALF {1, 1, 0, 0, 0, 0.5, 0, 1}
#define UM_AUTO_OR_ZERO_OR_1TO4 {1, 1, 0, 0, 1, 4, 1, 1}

static const case_option umppm_options[] = {
    {"variant", CASE_OPT_CHOICE, "auto", -1, variant_words, variant_values, UM_NORANGE,
     "UMPPM (adaptive), UMPPMstar (1 per cell); auto: UMPPM on non-square quads",
     UM_FIELD(variant_star)},
    {"alpha", CASE_OPT_SCALAR, "0.09", 0.09, NULL, NULL, UM_OPEN01,
     "UMPPM: delete one of two particles closer than sqrt(alpha) d_c",
     UM_FIELD(alpha)},
    {"laplacian", CASE_OPT_CHOICE, "auto", 0, laplacian_words, NULL, UM_NORANGE,
     "predictor's Laplacian; auto: CPM4 if no wall, inlet or outlet, else CPM",
     UM_FIELD(laplacian)},
    {"reFactor", CASE_OPT_SCALAR, "0", 0, NULL, NULL, UM_ZERO_OR_1TO4,
     "r_e / particle spacing of IPS, PS, MPS; 0: the model's (2; MPS 2.1)",
     UM_FIELD(re_factor)},
    {"writeQuality", CASE_OPT_BOOL, "no", 0, NULL, NULL, UM_NORANGE,
     "also write the particle fields uN and tau into the cloud", UM_FIELD(write_quality)},
    {"ppeSolver", CASE_OPT_CHOICE, "auto", 0, ppe_words, NULL, UM_NORANGE,
     "direct pressure solver; auto: CHOLMOD if symmetric, else UMFPACK",
     UM_FIELD(ppe_solver)},
    {"predictorSolver.preconditioner", CASE_OPT_CHOICE, "Jacobi", 0, pc_words, NULL, UM_NORANGE,
     "preconditioner of the BiCGSTAB predictor", UM_FIELD(pred_pc)},
    {"predictorSolver.tolerance", CASE_OPT_SCALAR, "1e-12", 1e-12, NULL, NULL, UM_GT(0),
     "relative tolerance of the BiCGSTAB predictor", UM_FIELD(pred_tol)},
    {"predictorSolver.maxIter", CASE_OPT_LABEL, "500", 500, NULL, NULL, UM_GE(1),
     "iteration limit of the BiCGSTAB predictor", UM_FIELD(pred_maxit)},
    {"cloudName", CASE_OPT_WORD, "umppmCloud", 0, NULL, NULL, UM_NORANGE,
     "name of the particle cloud under <time>/lagrangian/", UM_FIELD(cloud_name)},
    {"sortInterval", CASE_OPT_LABEL, "1", 1, NULL, NULL, UM_GE(0),
     "re-sort the particles by cell every N steps; 0: never", UM_FIELD(sort_interval)},
    {"refill", CASE_OPT_CHOICE, "auto", -1, refill_words, refill_values, UM_NORANGE,
     "refilled particle: carried, u_P (centroid, Eq. 36); auto: by variant",
     UM_FIELD(refill_carried)},
    {"refillParticles", CASE_OPT_LABEL, "4", 4, NULL, NULL, UM_1TO16,
     "refill carried: how many nearest particles lend their values", UM_FIELD(refill_k)},
    {"refillWeights", CASE_OPT_CHOICE, "increment", 1, refill_weight_words, refill_weight_values, UM_NORANGE,
     "refill carried: weights 1/(increment^2 + noise(d)), or 1/d^2 (distance)",
     UM_FIELD(refill_increment)},
    {"mlsSupport", CASE_OPT_SCALAR, "2", 2, NULL, NULL, UM_ZERO_OR_1TO4,
     "MLS weight support in cell extents; 0: Eq. 35's scales (farthest sample)",
     UM_FIELD(mls_support)},
    {"faceSupport", CASE_OPT_SCALAR, "auto", -1, NULL, NULL, UM_AUTO_OR_ZERO_OR_1TO4,
     "support of the face fits of u*; auto: 3 beside triangles, else mlsSupport",
     UM_FIELD(face_support)},
    {"pressureTheta", CASE_OPT_SCALAR, "auto", -1, NULL, NULL, UM_AUTO_OR_0TOHALF,
     "old grad p share at r^n; auto: 0.5 if no boundaries or closed triangles",
     UM_FIELD(p_theta)},
    {"positiveRows", CASE_OPT_BOOL, "yes", 1, NULL, NULL, UM_NORANGE,
     "CPM rows that lose diagonal dominance made positive; no: the paper's CPM",
     UM_FIELD(positive_rows)},
    {"boundedFits", CASE_OPT_BOOL, "yes", 1, NULL, NULL, UM_NORANGE,
     "MLS values and refills kept near their samples' range; no: the paper's",
     UM_FIELD(bounded_fits)},
    {"anisotropicCells", CASE_OPT_CHOICE, "auto", -1, aniso_words, aniso_values, UM_NORANGE,
     "stretched-cell operators; auto: yes if a cell is stretched beyond 20:1",
     UM_FIELD(anisotropic)},
    {"interpolationError", CASE_OPT_CHOICE, "auto", -1, qerr_words, qerr_values, UM_NORANGE,
     "its pressure to particles by the fits' transpose or Eq. 10's gradient",
     UM_FIELD(q_transpose)},
    {"buoyancy", CASE_OPT_CHOICE, "balanced", 1, buoyancy_words, buoyancy_values, UM_NORANGE,
     "buoyant: force in the predictor less its balancing pressure",
     UM_FIELD(buoyancy_balanced)},
    {"maxVelocity", CASE_OPT_SCALAR, "0", 0, NULL, NULL, UM_GE(0),
     "stop above this |U|; 0: 100 x the speed scale, 2 x if wall-driven",
     UM_FIELD(max_velocity)},
};

#define UM_NOPT (sizeof umppm_options / sizeof umppm_options[0])

static const case_opt_table umppm_table = {"UMPPM", umppm_options, UM_NOPT};

const case_option *case_umppm_options(size_t *n)
{
    if (n)
        *n = UM_NOPT;
    return umppm_options;
}

/* Append to buf (always NUL-terminated, truncating). */
static void cat(char *buf, size_t len, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
static void cat(char *buf, size_t len, const char *fmt, ...)
{
    size_t o = strlen(buf);
    if (o + 1 >= len)
        return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf + o, len - o, fmt, ap);
    va_end(ap);
}

const char *case_option_allowed(const case_option *o, char *buf, size_t len)
{
    if (!buf || len == 0)
        return buf;
    buf[0] = '\0';
    const case_opt_range *r = &o->range;
    switch (o->type) {
    case CASE_OPT_CHOICE: {
        /* a choice that also takes an OpenFOAM Switch (its words hold
         * "yes": anisotropicCells auto or yes/no) lists its own words and
         * "or yes/no", as a CASE_OPT_BOOL says "yes/no" for all of them */
        int any = 0, nsw = 0, has_yes = 0;
        for (size_t i = 0; o->choices && o->choices[i]; i++)
            has_yes |= strcmp(o->choices[i], "yes") == 0;
        for (size_t i = 0; o->choices && o->choices[i]; i++) {
            if (has_yes && foam_switch_value(o->choices[i]) >= 0)
                nsw++;
            else
                cat(buf, len, "%s%s", any++ ? " " : "", o->choices[i]);
        }
        if (nsw)
            cat(buf, len, "%syes/no", any ? " or " : "");
        break;
    }
    case CASE_OPT_BOOL:
        cat(buf, len, "yes/no");
        break;
    case CASE_OPT_WORD:
        cat(buf, len, "word");
        break;
    case CASE_OPT_SCALAR:
    case CASE_OPT_LABEL:
        if (r->or_auto)
            cat(buf, len, "auto or ");
        if (r->or_zero)
            cat(buf, len, "0 or ");
        if (r->has_lo && r->has_hi)
            cat(buf, len, "%c%.15g, %.15g%c", r->lo_open ? '(' : '[', r->lo, r->hi, r->hi_open ? ')' : ']');
        else if (r->has_lo)
            cat(buf, len, "%s %.15g", r->lo_open ? ">" : ">=", r->lo);
        else if (r->has_hi)
            cat(buf, len, "%s %.15g", r->hi_open ? "<" : "<=", r->hi);
        else
            cat(buf, len, o->type == CASE_OPT_LABEL ? "integer" : "number");
        break;
    }
    return buf;
}

static int in_range(const case_opt_range *r, double v)
{
    if (isnan(v))
        return 0;
    if (r->or_zero && v == 0)
        return 1;
    if (r->has_lo && !(r->lo_open ? v > r->lo : v >= r->lo))
        return 0;
    if (r->has_hi && !(r->hi_open ? v < r->hi : v <= r->hi))
        return 0;
    return 1;
}

/* Store the value of o into its field of u: v (scalar), l (label, bool),
 * choices[choice] or its value (choice), w (word). */
static void store(const case_option *o, void *u, double v, long l, int choice, const char *w)
{
    char *p = (char *)u + o->offset;
    switch (o->type) {
    case CASE_OPT_CHOICE:
        if (o->choice_values)
            *(int *)(void *)p = o->choice_values[choice];
        else
            snprintf(p, o->size, "%s", o->choices[choice]);
        break;
    case CASE_OPT_SCALAR:
        *(double *)(void *)p = v;
        break;
    case CASE_OPT_LABEL:
        *(long *)(void *)p = l;
        break;
    case CASE_OPT_BOOL:
        *(int *)(void *)p = l != 0;
        break;
    case CASE_OPT_WORD:
        snprintf(p, o->size, "%s", w);
        break;
    }
}

static int choice_index(const case_option *o, const char *w)
{
    for (int i = 0; o->choices[i]; i++)
        if (strcmp(o->choices[i], w) == 0)
            return i;
    return -1;
}

/* Every field of dst (a struct of the table's options) set to its default. */
static void table_defaults(const case_opt_table *t, void *dst)
{
    for (size_t i = 0; i < t->n; i++) {
        const case_option *o = &t->opt[i];
        int c = o->type == CASE_OPT_CHOICE ? choice_index(o, o->default_text) : 0;
        store(o, dst, o->default_value, (long)o->default_value, c < 0 ? 0 : c, o->default_text);
    }
}

void case_umppm_defaults(case_umppm *u)
{
    memset(u, 0, sizeof *u);
    table_defaults(&umppm_table, u);
}

/* Length of the first component of key (up to '.' or the end). */
static size_t comp_len(const char *key)
{
    const char *dot = strchr(key, '.');
    return dot ? (size_t)(dot - key) : strlen(key);
}

/* "UMPPM" or "UMPPM predictorSolver" for a dictionary at prefix "" or
 * "predictorSolver." */
static void dict_label(const case_opt_table *t, const char *prefix, char *buf, size_t len)
{
    size_t n = strlen(prefix);
    snprintf(buf, len, "%s%s%.*s", t->dict, n ? " " : "", n ? (int)(n - 1) : 0, prefix);
}

/* Refuse entries of d (the dictionary at prefix) that no option reads, and
 * a non-dictionary where the table has a sub-dictionary. */
static ump_status check_keys(const case_opt_table *t, const foam_dict *d, const char *prefix, ump_err *err)
{
    size_t np = strlen(prefix);
    for (size_t i = 0; i < d->n; i++) {
        const foam_entry *e = &d->e[i];
        int known = 0;
        for (size_t k = 0; k < t->n; k++) {
            const char *key = t->opt[k].key;
            if (strncmp(key, prefix, np) != 0)
                continue;
            const char *rest = key + np;
            char comp[64];
            snprintf(comp, sizeof comp, "%.*s", (int)comp_len(rest), rest);
            if (strcmp(e->key, comp) != 0 && !(e->is_pattern && foam_dict_find(d, comp, 0) == e))
                continue;
            known = 1;
            if (rest[strlen(comp)] != '.')
                continue;
            /* a sub-dictionary of the table */
            char sub[128], where[128];
            snprintf(sub, sizeof sub, "%s%s.", prefix, comp);
            if (!e->dict) {
                char tk[128];
                dict_label(t, sub, where, sizeof where);
                if (e->ntok)
                    foam_tok_str(&e->tok[0], tk, sizeof tk);
                else
                    snprintf(tk, sizeof tk, "nothing");
                return UMP_FAIL(err, UMP_ERR_INPUT, "%s:%d: %s must be a dictionary { ... }, found %s%s",
                                e->file, e->line, where, tk, e->ntok > 1 ? " ..." : "");
            }
            UMP_CALL(check_keys(t, e->dict, sub, err));
            break;
        }
        if (known)
            continue;
        char names[512] = "", where[128];
        for (size_t k = 0; k < t->n; k++) {
            const char *key = t->opt[k].key;
            if (strncmp(key, prefix, np) != 0)
                continue;
            size_t cl = comp_len(key + np);
            int seen = 0;
            for (size_t j = 0; j < k && !seen; j++)
                seen = strncmp(t->opt[j].key, prefix, np) == 0 &&
                       comp_len(t->opt[j].key + np) == cl &&
                       strncmp(t->opt[j].key + np, key + np, cl) == 0;
            if (!seen)
                cat(names, sizeof names, "%s%.*s", names[0] ? " " : "", (int)cl, key + np);
        }
        dict_label(t, prefix, where, sizeof where);
        return UMP_FAIL(err, UMP_ERR_INPUT, "%s:%d: %s: unknown key '%s'; known keys: %s", e->file, e->line,
                        where, e->key, names);
    }
    return UMP_OK;
}

/* What a value of type t must look like, for messages. */
static const char *type_text(case_opt_type t)
{
    switch (t) {
    case CASE_OPT_SCALAR:
        return "a number";
    case CASE_OPT_LABEL:
        return "an integer";
    case CASE_OPT_BOOL:
        return "a switch (yes/no, on/off, true/false, 1/0)";
    case CASE_OPT_CHOICE:
    case CASE_OPT_WORD:
        break;
    }
    return "one word";
}

/* Read option o from the UMPPM dictionary d (NULL: absent) into u, which
 * holds the defaults. */
static ump_status read_option(const case_opt_table *t, const foam_dict *d, const case_option *o, void *u,
                              ump_err *err)
{
    /* walk the sub-dictionaries of the key's path (check_keys made sure
     * they are dictionaries) */
    const char *leaf = o->key;
    while (d && strchr(leaf, '.')) {
        char comp[64];
        snprintf(comp, sizeof comp, "%.*s", (int)comp_len(leaf), leaf);
        d = foam_dict_sub(d, comp);
        leaf += strlen(comp) + 1;
    }
    const foam_entry *e = d ? foam_dict_find(d, leaf, 0) : NULL;
    if (!e)
        return UMP_OK; /* u holds the defaults */
    char allowed[256];
    case_option_allowed(o, allowed, sizeof allowed);
    double v = 0;
    int64_t l = 0;
    int b = 0;
    const char *w = NULL;
    ump_err ignored;
    ump_status rc = UMP_OK;
    /* a scalar that may be auto: stored as -1, the caller decides */
    if (o->type == CASE_OPT_SCALAR && o->range.or_auto &&
        foam_get_word_or(d, leaf, NULL, &w, &ignored) == UMP_OK && strcmp(w, "auto") == 0) {
        store(o, u, -1, 0, 0, NULL);
        return UMP_OK;
    }
    switch (o->type) {
    case CASE_OPT_SCALAR:
        rc = foam_get_scalar_or(d, leaf, 0, &v, &ignored);
        break;
    case CASE_OPT_LABEL:
        rc = foam_get_label_or(d, leaf, 0, &l, &ignored);
        v = (double)l;
        break;
    case CASE_OPT_BOOL:
        rc = foam_get_bool_or(d, leaf, 0, &b, &ignored);
        break;
    case CASE_OPT_CHOICE:
    case CASE_OPT_WORD:
        rc = foam_get_word_or(d, leaf, NULL, &w, &ignored);
        break;
    }
    if (rc != UMP_OK) {
        char tk[128];
        if (e->dict)
            snprintf(tk, sizeof tk, "a dictionary");
        else if (e->ntok == 0)
            snprintf(tk, sizeof tk, "nothing");
        else
            foam_tok_str(&e->tok[0], tk, sizeof tk);
        int with_allowed = o->type != CASE_OPT_BOOL && o->type != CASE_OPT_WORD;
        return UMP_FAIL(err, rc, "%s:%d: %s %s: expected %s, found %s%s%s%s", e->file, e->line, t->dict, o->key,
                        type_text(o->type), tk, e->ntok > 1 ? " ..." : "", with_allowed ? "; allowed " : "",
                        with_allowed ? allowed : "");
    }
    switch (o->type) {
    case CASE_OPT_CHOICE: {
        int c = choice_index(o, w);
        if (c < 0)
            return UMP_FAIL(err, UMP_ERR_INPUT, "%s:%d: %s %s '%s' is not one of: %s", e->file, e->line,
                            t->dict, o->key, w, allowed);
        store(o, u, 0, 0, c, NULL);
        break;
    }
    case CASE_OPT_WORD:
        if (strlen(w) >= o->size)
            return UMP_FAIL(err, UMP_ERR_INPUT, "%s:%d: %s %s '%.40s...' is too long: at most %zu characters",
                            e->file, e->line, t->dict, o->key, w, o->size - 1);
        store(o, u, 0, 0, 0, w);
        break;
    case CASE_OPT_BOOL:
        store(o, u, 0, b, 0, NULL);
        break;
    case CASE_OPT_SCALAR:
    case CASE_OPT_LABEL:
        if (!in_range(&o->range, v)) {
            if (o->type == CASE_OPT_LABEL)
                return UMP_FAIL(err, UMP_ERR_INPUT, "%s:%d: %s %s %lld is out of range: allowed %s", e->file,
                                e->line, t->dict, o->key, (long long)l, allowed);
            return UMP_FAIL(err, UMP_ERR_INPUT, "%s:%d: %s %s %.15g is out of range: allowed %s", e->file,
                            e->line, t->dict, o->key, v, allowed);
        }
        store(o, u, v, (long)l, 0, NULL); /* labels: int64 = long (LP64) */
        break;
    }
    return UMP_OK;
}

static size_t table_help(const case_opt_table *t, char *buf, size_t len)
{
    char text[8192] = ""; /* the whole text (about 2 kB) */
    cat(text, sizeof text,
        "%s dictionary (system/fvSolution)\n"
        "  All keys are optional; unknown keys are refused. sub.KEY is KEY\n"
        "  in the sub-dictionary %s { sub { KEY value; } }.\n\n"
        "  %-32s %-11s %s\n", t->dict, t->dict, "key", "default", "allowed");
    for (size_t i = 0; i < t->n; i++) {
        const case_option *o = &t->opt[i];
        char allowed[256];
        case_option_allowed(o, allowed, sizeof allowed);
        cat(text, sizeof text, "  %-32s %-11s %s\n      %s\n", o->key, o->default_text, allowed, o->help);
    }
    size_t n = strlen(text);
    if (buf && len > 0)
        snprintf(buf, len, "%s", text);
    return n;
}

size_t case_umppm_help(char *buf, size_t len) { return table_help(&umppm_table, buf, len); }

/* Read the sub-dictionary t->dict of <case>/system/fvSolution into dst
 * (defaults first; absent: all defaults). */
static ump_status table_read(const case_opt_table *t, const char *case_dir, void *dst, foam_file **fout,
                             ump_err *err)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/system/fvSolution", case_dir);
    foam_file *f = NULL;
    UMP_CALL(foam_file_read(path, &f, err));
    table_defaults(t, dst);
    ump_status rc = UMP_OK;
    const foam_entry *top = foam_dict_find(f->dict, t->dict, 0);
    const foam_dict *d = top ? top->dict : NULL;
    if (top && !d) {
        char w[128];
        if (top->ntok)
            foam_tok_str(&top->tok[0], w, sizeof w);
        else
            snprintf(w, sizeof w, "nothing");
        rc = UMP_FAIL(err, UMP_ERR_INPUT, "%s:%d: %s must be a dictionary { ... }, found %s%s", top->file,
                      top->line, t->dict, w, top->ntok > 1 ? " ..." : "");
    }
    if (rc == UMP_OK && d)
        rc = check_keys(t, d, "", err);
    for (size_t i = 0; i < t->n && rc == UMP_OK; i++)
        rc = read_option(t, d, &t->opt[i], dst, err);
    if (rc != UMP_OK || !fout)
        foam_file_free(&f);
    else
        *fout = f;
    return rc;
}

ump_status case_read_umppm(const char *case_dir, case_umppm *u, ump_err *err)
{
    memset(u, 0, sizeof *u);
    foam_file *f = NULL;
    UMP_CALL(table_read(&umppm_table, case_dir, u, &f, err));
    ump_status rc = UMP_OK;
    if (!case_name_is_safe(u->cloud_name)) {
        const foam_entry *top = foam_dict_find(f->dict, "UMPPM", 0);
        const foam_entry *e = top && top->dict ? foam_dict_find(top->dict, "cloudName", 0) : NULL;
        rc = UMP_FAIL(err, UMP_ERR_INPUT, "%s:%d: UMPPM cloudName '%s' is not a plain name: it becomes the "
                      "directory <time>/lagrangian/<cloudName>, so it must be non-empty without '/' or '..'",
                      e ? e->file : "system/fvSolution", e ? e->line : 0, u->cloud_name);
    }
    foam_file_free(&f);
    return rc;
}

/* ---- meshlessFoam ----------------------------------------------------------- */

static const char *const method_words[] = {"MPS", "FPM", NULL};
static const char *const weight_words[] = {"spline", "exponential", NULL};
static const int weight_values[] = {5, 4};
static const char *const source_words[] = {"density", "mixed", NULL};
static const int source_values[] = {0, 1};

#define ML_FIELD(f) offsetof(case_meshless, f), sizeof(((case_meshless *)0)->f)
#define ML_RANGE(lo, hi) {1, 1, 1, 0, (lo), (hi), 0, 0}       /* (lo, hi] */
#define ML_CLOSED(lo, hi) {1, 1, 0, 0, (lo), (hi), 0, 0}      /* [lo, hi] */

static const case_option meshless_options[] = {
    {"method", CASE_OPT_CHOICE, "MPS", 0, method_words, NULL, UM_NORANGE,
     "particle method: MPS (fully implicit moving particle semi-implicit) or FPM (finite particle method)",
     ML_FIELD(method)},
    {"spacing", CASE_OPT_SCALAR, "0", 0, NULL, NULL, UM_GE(0),
     "particle spacing l0 [m]; 0: half the median cell size of the mesh", ML_FIELD(spacing)},
    {"reNumberDensity", CASE_OPT_SCALAR, "3.1", 3.1, NULL, NULL, ML_RANGE(1, 6),
     "MPS: r_e of number density, gradient and collisions / l0 (Eqs. 3-5)", ML_FIELD(re_n)},
    {"reLaplacian", CASE_OPT_SCALAR, "3.1", 3.1, NULL, NULL, ML_RANGE(1, 8),
     "MPS: r_e of the Laplacian / l0 (Eqs. 6-7), >= reNumberDensity", ML_FIELD(re_lap)},
    {"beta", CASE_OPT_SCALAR, "0.98", 0.98, NULL, NULL, UM_OPEN01,
     "MPS: free surface: particles with n* < beta n0 get p = 0", ML_FIELD(beta)},
    {"lambda", CASE_OPT_SCALAR, "0", 0, NULL, NULL, UM_GE(0),
     "MPS: Laplacian parameter lambda [m^2]; 0: Eq. 7 on the initial lattice", ML_FIELD(lambda)},
    {"sourceTerm", CASE_OPT_CHOICE, "mixed", 1, source_words, source_values, UM_NORANGE,
     "MPS: pressure source: density (Eq. 18) or mixed (div u* + gamma density)", ML_FIELD(source_mixed)},
    {"gamma", CASE_OPT_SCALAR, "0.1", 0.1, NULL, NULL, ML_CLOSED(0, 1),
     "MPS: weight of the density deviation in the mixed source", ML_FIELD(gamma)},
    {"collisionDistance", CASE_OPT_SCALAR, "0.5", 0.5, NULL, NULL, ML_CLOSED(0, 1),
     "MPS: collision model below this distance / l0; 0: off", ML_FIELD(collision)},
    {"restitution", CASE_OPT_SCALAR, "0.2", 0.2, NULL, NULL, ML_CLOSED(0, 1),
     "MPS: coefficient of restitution of the collision model", ML_FIELD(restitution)},
    {"maxCo", CASE_OPT_SCALAR, "0.2", 0.2, NULL, NULL, ML_RANGE(0, 1),
     "MPS: Courant number |U| dt / l0 kept by adjustTimeStep", ML_FIELD(max_co)},
    {"pressureTolerance", CASE_OPT_SCALAR, "1e-8", 1e-8, NULL, NULL, UM_GT(0),
     "relative tolerance of the pressure CG", ML_FIELD(p_tol)},
    {"velocityTolerance", CASE_OPT_SCALAR, "1e-10", 1e-10, NULL, NULL, UM_GT(0),
     "MPS: relative tolerance of the viscous CG", ML_FIELD(u_tol)},
    {"maxIter", CASE_OPT_LABEL, "5000", 5000, NULL, NULL, UM_GE(1),
     "iteration limit of the linear solvers (pressure; MPS: also viscosity)", ML_FIELD(maxit)},
    {"cloudName", CASE_OPT_WORD, "meshlessCloud", 0, NULL, NULL, UM_NORANGE,
     "name of the particle cloud under <time>/lagrangian/", ML_FIELD(cloud_name)},
    {"maxVelocity", CASE_OPT_SCALAR, "0", 0, NULL, NULL, UM_GE(0),
     "stop when a particle |U| exceeds it; 0: max(10 sqrt(2 |g| H), 10 |U0|max, 1 m/s)", ML_FIELD(max_velocity)},
    {"supportRadius", CASE_OPT_SCALAR, "3", 3, NULL, NULL, ML_CLOSED(2, 6),
     "FPM: support radius h0 of the MLS weights / l0", ML_FIELD(support)},
    {"weightFunction", CASE_OPT_CHOICE, "spline", 5, weight_words, weight_values, UM_NORANGE,
     "FPM: MLS weight, spline (Eq. 5) or exponential (Eq. 4)", ML_FIELD(weight)},
    {"courantFPM", CASE_OPT_SCALAR, "0.12", 0.12, NULL, NULL, ML_RANGE(0, 1),
     "FPM: dt <= courantFPM h0 / |U|max (Eq. 26), with adjustTimeStep", ML_FIELD(fpm_co)},
    {"gravityStepFPM", CASE_OPT_SCALAR, "0.24", 0.24, NULL, NULL, ML_RANGE(0, 1),
     "FPM: dt <= gravityStepFPM sqrt(h0 / |g|) (Eq. 27), with adjustTimeStep", ML_FIELD(fpm_cg)},
    {"surfaceRadius", CASE_OPT_SCALAR, "3", 3, NULL, NULL, ML_RANGE(1, 4),
     "FPM: radius / l0 of the number density of the free-surface test", ML_FIELD(re_s)},
    {"surfaceBeta", CASE_OPT_SCALAR, "0.8", 0.8, NULL, NULL, UM_OPEN01,
     "FPM: free surface where the number density < surfaceBeta n0", ML_FIELD(beta_s)},
    {"surfaceShift", CASE_OPT_SCALAR, "0.2", 0.2, NULL, NULL, UM_GT(0),
     "FPM: ... or where the neighbours' centroid is off by > surfaceShift l0", ML_FIELD(shift_s)},
    {"densitySourceFPM", CASE_OPT_SCALAR, "0.02", 0.02, NULL, NULL, ML_CLOSED(0, 1),
     "FPM: weight of the density deviation added to Eq. 24's source (0: the paper's alone)", ML_FIELD(gamma_fpm)},
    {"laplacianStabilization", CASE_OPT_SCALAR, "1", 1, NULL, NULL, ML_CLOSED(0, 1),
     "FPM: weight of the positive Laplacian of the quadratic fit's residual added to the pressure equation's "
     "MLS Laplacian (0: Eq. 24's alone, which diverges in violent flows)", ML_FIELD(stab_fpm)},
    {"surfaceDampingFPM", CASE_OPT_SCALAR, "0.1", 0.1, NULL, NULL, ML_CLOSED(0, 1),
     "FPM: damping of free-surface particles' velocity towards their fluid neighbours', nu_s = surfaceDampingFPM l0 "
     "sqrt(|g| l0) (0: off; without it the surface row's motion grows from about 1 s in a gentle standing wave)",
     ML_FIELD(surf_damp_fpm)},
    {"wallDistance", CASE_OPT_SCALAR, "0.25", 0.25, NULL, NULL, ML_CLOSED(0, 0.5),
     "FPM: fluid particles closer to a wall go back to this distance / l0; 0: off", ML_FIELD(d_wall)},
    {"mergeDistance", CASE_OPT_SCALAR, "0.5", 0.5, NULL, NULL, ML_CLOSED(0, 0.9),
     "FPM: pairs closer than this / l0 are merged; 0: off", ML_FIELD(d_min)},
    {"holeRadius", CASE_OPT_SCALAR, "1.2", 1.2, NULL, NULL, UM_GE(0),
     "FPM: a particle is inserted in Voronoi holes of radius > this / l0; 0: off", ML_FIELD(r_hole)},
    {"particleShifting", CASE_OPT_SCALAR, "0", 0, NULL, NULL, ML_CLOSED(0, 10),
     "FPM: particle shifting coefficient A (dr = -A (r_s/2) |u| dt grad C, Skillen et al. 2013); 0: off",
     ML_FIELD(shift_a)},
    {"pairRepulsion", CASE_OPT_SCALAR, "0.8", 0.8, NULL, NULL, ML_CLOSED(0, 0.95),
     "FPM: fluid pairs closer than this / l0 collide (restitution 0.2) and are pushed apart; 0: off",
     ML_FIELD(d_rep)},
    {"pairRepulsionCoeff", CASE_OPT_SCALAR, "0.25", 0.25, NULL, NULL, ML_CLOSED(0, 0.5),
     "FPM: pairRepulsion's shift dr_i = coeff sum_j (d - r_ij) e_ij (at most 0.2 l0 per step)", ML_FIELD(c_rep)},
    {"maxParticleLoss", CASE_OPT_SCALAR, "0.2", 0.2, NULL, NULL, ML_CLOSED(0, 1),
     "FPM: stop when merging net of insertion has removed this fraction of the liquid's particles (1: never)",
     ML_FIELD(max_loss)},
    {"maxParticleGain", CASE_OPT_SCALAR, "0.2", 0.2, NULL, NULL, UM_GT(0),
     "FPM: stop when insertion net of merging has added this fraction to the liquid's particles (a large value: never)",
     ML_FIELD(max_gain)},
    {"manageInterval", CASE_OPT_LABEL, "1", 1, NULL, NULL, UM_GE(1),
     "FPM: steps between hole searches (qhull, insertion); merging and the wall distance act every step",
     ML_FIELD(manage_interval)},
};

static const case_opt_table meshless_table = {"meshless", meshless_options,
                                              sizeof meshless_options / sizeof meshless_options[0]};

const case_option *case_meshless_options(size_t *n)
{
    if (n)
        *n = meshless_table.n;
    return meshless_options;
}

void case_meshless_defaults(case_meshless *u)
{
    memset(u, 0, sizeof *u);
    table_defaults(&meshless_table, u);
}

size_t case_meshless_help(char *buf, size_t len) { return table_help(&meshless_table, buf, len); }

ump_status case_read_meshless(const char *case_dir, case_meshless *u, ump_err *err)
{
    memset(u, 0, sizeof *u);
    foam_file *f = NULL;
    UMP_CALL(table_read(&meshless_table, case_dir, u, &f, err));
    const foam_entry *top = foam_dict_find(f->dict, "meshless", 0);
    const foam_dict *d = top ? top->dict : NULL;
    const foam_entry *e = NULL;
    ump_status rc = UMP_OK;
    if (u->re_lap < u->re_n) {
        e = d ? foam_dict_find(d, "reLaplacian", 0) : NULL;
        rc = UMP_FAIL(err, UMP_ERR_INPUT, "%s:%d: meshless reLaplacian %g is smaller than reNumberDensity %g",
                      e ? e->file : "system/fvSolution", e ? e->line : 0, u->re_lap, u->re_n);
    } else if (!case_name_is_safe(u->cloud_name)) {
        e = d ? foam_dict_find(d, "cloudName", 0) : NULL;
        rc = UMP_FAIL(err, UMP_ERR_INPUT, "%s:%d: meshless cloudName '%s' is not a plain name: it becomes the "
                      "directory <time>/lagrangian/<cloudName>, so it must be non-empty without '/' or '..'",
                      e ? e->file : "system/fvSolution", e ? e->line : 0, u->cloud_name);
    }
    /* a key of the other method would have no effect: refused by name
     * (the help text of a method's own keys starts with its name) */
    const char *other = strcmp(u->method, "FPM") == 0 ? "MPS:" : "FPM:";
    for (size_t k = 0; rc == UMP_OK && d && k < meshless_table.n; k++) {
        const case_option *o = &meshless_options[k];
        if (strncmp(o->help, other, 4) != 0 || !(e = foam_dict_find(d, o->key, 0)))
            continue;
        rc = UMP_FAIL(err, UMP_ERR_INPUT, "%s:%d: meshless %s serves method %.3s; with method %s it has no effect: "
                      "remove it, or set method %.3s", e->file, e->line, o->key, other, u->method, other);
    }
    foam_file_free(&f);
    return rc;
}

/* One phase's dictionary: transportModel Newtonian (or absent), nu, rho. */
static ump_status read_phase(const foam_dict *top, const char *path, const char *name, double *nu, double *rho,
                             ump_err *err)
{
    static const double d_nu[7] = {0, 2, -1, 0, 0, 0, 0}, d_rho[7] = {1, -3, 0, 0, 0, 0, 0};
    const foam_entry *pe = foam_dict_find(top, name, 0);
    if (!pe || !pe->dict)
        return UMP_FAIL(err, UMP_ERR_INPUT, "%s: phase '%s' of 'phases' has no dictionary %s { transportModel "
                        "Newtonian; nu ...; rho ...; }", path, name, name);
    const foam_dict *d = pe->dict;
    const foam_entry *tm = foam_dict_find(d, "transportModel", 0);
    if (tm) {
        const char *w = NULL;
        UMP_CALL(foam_get_word(d, "transportModel", &w, err));
        if (strcmp(w, "Newtonian") != 0)
            return UMP_FAIL(err, UMP_ERR_UNSUPPORTED, "%s:%d: %s { transportModel %s; }: non-Newtonian "
                            "viscosity is not implemented by meshlessFoam (Newtonian nu only); use interFoam",
                            tm->file, tm->line, name, w);
    }
    int has;
    UMP_CALL(get_transport_constant(d, "nu", d_nu, "m^2/s", 0, 1, nu, &has, err));
    UMP_CALL(get_transport_constant(d, "rho", d_rho, "kg/m^3", 0, 1, rho, &has, err));
    if (!(*rho > 0)) {
        const foam_entry *e = foam_dict_find(d, "rho", 0);
        return UMP_FAIL(err, UMP_ERR_INPUT, "%s:%d: %s rho must be positive, found %g", e->file, e->line, name,
                        *rho);
    }
    return UMP_OK;
}

ump_status case_read_phases(const char *case_dir, case_phases *ph, ump_err *err)
{
    static const double d_sigma[7] = {1, 0, -2, 0, 0, 0, 0};
    char path[4096];
    snprintf(path, sizeof path, "%s/constant/transportProperties", case_dir);
    foam_file *f = NULL;
    UMP_CALL(foam_file_read(path, &f, err));
    memset(ph, 0, sizeof *ph);
    const foam_dict *d = f->dict;
    ump_status rc = UMP_OK;
    const foam_entry *e = foam_dict_find(d, "phases", 0);
    /* phases (water air): '(' word word ')' */
    int nw = 0;
    if (e && !e->dict && e->ntok == 4 && e->tok[0].type == FOAM_TOK_PUNCT && e->tok[0].v.punct == '(' &&
        e->tok[3].type == FOAM_TOK_PUNCT && e->tok[3].v.punct == ')')
        for (int k = 1; k < 3; k++)
            if (e->tok[k].type == FOAM_TOK_WORD && strlen(e->tok[k].v.str) < sizeof ph->name[0])
                snprintf(ph->name[nw++], sizeof ph->name[0], "%s", e->tok[k].v.str);
    if (!e)
        rc = UMP_FAIL(err, UMP_ERR_INPUT, "%s: no 'phases (liquid gas);' entry: meshlessFoam runs interFoam's "
                      "two-phase cases (phases (water air); water { nu ...; rho ...; } air { ... })", path);
    else if (nw != 2)
        rc = UMP_FAIL(err, UMP_ERR_UNSUPPORTED, "%s:%d: phases: expected two phases, (liquid gas) as interFoam; "
                      "more phases (multiphaseInterFoam) are not implemented by meshlessFoam", e->file, e->line);
    for (int k = 0; k < 2 && rc == UMP_OK; k++)
        rc = read_phase(d, path, ph->name[k], &ph->nu[k], &ph->rho[k], err);
    /* the first phase is the one simulated (interFoam's alpha.<first>): as
     * particles it must be the liquid (phases (air water) had simulated the
     * air as the liquid and the water as the void) */
    if (rc == UMP_OK && ph->rho[0] < ph->rho[1])
        rc = UMP_FAIL(err, UMP_ERR_UNSUPPORTED,
                      "%s:%d: phases (%s %s): meshlessFoam simulates the first phase as the liquid (particles) and "
                      "the second as a void, but '%s' (rho %g) is lighter than '%s' (rho %g); list the liquid "
                      "first, phases (%s %s), with its alpha.%s field, as interFoam's tutorials do",
                      e->file, e->line, ph->name[0], ph->name[1], ph->name[0], ph->rho[0], ph->name[1], ph->rho[1],
                      ph->name[1], ph->name[0], ph->name[1]);
    /* sigma: a value, or v1912's surfaceTensionModel dictionary
     * sigma { type constant; sigma 0.07; } (or another model by type) */
    const foam_dict *sd = rc == UMP_OK ? foam_dict_sub(d, "sigma") : NULL;
    if (sd) {
        const char *type = NULL;
        rc = foam_get_word(sd, "type", &type, err);
        if (rc == UMP_OK && strcmp(type, "constant") == 0)
            rc = get_transport_constant(sd, "sigma", d_sigma, "kg/s^2", 0, 1, &ph->sigma, &ph->has_sigma, err);
        else if (rc == UMP_OK)
            snprintf(ph->sigma_model, sizeof ph->sigma_model, "%s", type);
    } else if (rc == UMP_OK) {
        rc = get_transport_constant(d, "sigma", d_sigma, "kg/s^2", 0, 0, &ph->sigma, &ph->has_sigma, err);
    }
    foam_file_free(&f);
    return rc;
}

ump_status case_read_time_delta_t(const char *case_dir, const char *tname, double *delta_t, int *has,
                                  ump_err *err)
{
    char path[4400];
    snprintf(path, sizeof path, "%s/%s/uniform/time", case_dir, tname);
    *has = 0;
    if (!foam_file_exists(path))
        return UMP_OK;
    foam_file *f = NULL;
    UMP_CALL(foam_file_read(path, &f, err));
    ump_status rc = UMP_OK;
    if (foam_dict_find(f->dict, "deltaT", 0)) {
        rc = foam_get_scalar(f->dict, "deltaT", delta_t, err);
        *has = rc == UMP_OK;
    }
    foam_file_free(&f);
    return rc;
}

/* runTimeModifiable (README "Running"): the words of the enumerations, for
 * the log. */
static const char *const stop_at_word[] = {"endTime", "writeNow", "noWriteNow", "nextWrite"};
static const char *const write_control_word[] = {"timeStep", "runTime", "adjustableRunTime", "cpuTime",
                                                 "clockTime"};
static const char *const time_format_word[] = {"general", "fixed", "scientific"};
static const char *const on_off[] = {"off", "on"};

/* Append ", key old -> new" to buf. */
static void note_change(char *buf, size_t len, const char *key, const char *was, const char *now)
{
    size_t n = strlen(buf);
    snprintf(buf + n, len - n, "%s%s %s -> %s", n ? ", " : "", key, was, now);
}

static void note_number(char *buf, size_t len, const char *key, double was, double now)
{
    char w[32], v[32];
    snprintf(w, sizeof w, "%.15g", was);
    snprintf(v, sizeof v, "%.15g", now);
    if (was != now)
        note_change(buf, len, key, w, v);
}

static void note_word(char *buf, size_t len, const char *key, const char *was, const char *now)
{
    if (strcmp(was, now) != 0)
        note_change(buf, len, key, was, now);
}

/* The settings of o that c changes, "endTime 0.5 -> 0.3, deltaT ...". */
void case_control_changes(const case_control *o, const case_control *c, int delta_t_fixed, char *buf,
                          size_t len)
{
    buf[0] = '\0';
    note_word(buf, len, "stopAt", stop_at_word[o->stop_at], stop_at_word[c->stop_at]);
    if (c->stop_at == CASE_STOP_ENDTIME)
        note_number(buf, len, "endTime", o->stop_at == CASE_STOP_ENDTIME ? o->end_time : 1e15, c->end_time);
    note_number(buf, len, delta_t_fixed ? "deltaT (not used: adjustTimeStep has set the step)" : "deltaT",
                o->delta_t, c->delta_t);
    note_word(buf, len, "writeControl", write_control_word[o->write_control], write_control_word[c->write_control]);
    note_number(buf, len, "writeInterval", o->write_interval, c->write_interval);
    note_number(buf, len, "purgeWrite", o->purge_write, c->purge_write);
    note_word(buf, len, "writeFormat", o->write_binary ? "binary" : "ascii", c->write_binary ? "binary" : "ascii");
    note_number(buf, len, "writePrecision", o->write_precision, c->write_precision);
    note_word(buf, len, "writeCompression", on_off[o->write_compression], on_off[c->write_compression]);
    note_word(buf, len, "timeFormat", time_format_word[o->time_format_fixed], time_format_word[c->time_format_fixed]);
    note_number(buf, len, "timePrecision", o->time_precision, c->time_precision);
    note_word(buf, len, "adjustTimeStep", on_off[o->adjust_time_step], on_off[c->adjust_time_step]);
    note_number(buf, len, "maxCo", o->max_co, c->max_co);
    note_number(buf, len, "maxDeltaT", o->max_delta_t, c->max_delta_t);
    note_word(buf, len, "runTimeModifiable", o->run_time_modifiable ? "true" : "false",
              c->run_time_modifiable ? "true" : "false");
}

const char *case_stop_at_name(int stop_at)
{
    return stop_at >= 0 && stop_at < 4 ? stop_at_word[stop_at] : "?";
}

int case_name_is_safe(const char *name)
{
    return name && name[0] != '\0' && !strchr(name, '/') && !strstr(name, "..");
}

ump_status case_check_start(const char *case_dir, const case_control *c, const char *tname, double t0,
                            ump_err *err)
{
    if (c->stop_at == CASE_STOP_ENDTIME && c->end_time < t0 && !(fabs(c->end_time - t0) <= 1e-12 * fabs(t0)))
        return UMP_FAIL(err, UMP_ERR_INPUT, "%s/system/controlDict: endTime %g is before the start time %s: "
                        "nothing to run", case_dir, c->end_time, tname);
    return UMP_OK;
}

int case_file_stamp(const char *path, case_stamp *s)
{
    struct stat st;
    memset(s, 0, sizeof *s);
    if (stat(path, &st) != 0)
        return -1;
    s->dev = (unsigned long long)st.st_dev;
    s->ino = (unsigned long long)st.st_ino;
    s->size = (long long)st.st_size;
    s->mtime_sec = (long long)st.st_mtim.tv_sec;
    s->mtime_nsec = (long)st.st_mtim.tv_nsec;
    s->ctime_sec = (long long)st.st_ctim.tv_sec;
    s->ctime_nsec = (long)st.st_ctim.tv_nsec;
    return 0;
}

int case_stamp_equal(const case_stamp *a, const case_stamp *b)
{
    return a->dev == b->dev && a->ino == b->ino && a->size == b->size && a->mtime_sec == b->mtime_sec &&
           a->mtime_nsec == b->mtime_nsec && a->ctime_sec == b->ctime_sec && a->ctime_nsec == b->ctime_nsec;
}

/* ---- meshlessFoam: the moving container --------------------------------------- */

/* The word of a primitive entry, NULL when absent or not one word. */
static const char *word_of_entry(const foam_entry *e)
{
    if (!e || e->dict || e->ntok < 1 || (e->tok[0].type != FOAM_TOK_WORD && e->tok[0].type != FOAM_TOK_STRING))
        return NULL;
    return e->tok[0].v.str;
}

ump_status case_read_motion(const char *case_dir, case_motion *mo, ump_err *err)
{
    memset(mo, 0, sizeof *mo);
    char path[4096];
    snprintf(path, sizeof path, "%s/constant/dynamicMeshDict", case_dir);
    if (!foam_file_exists(path))
        return UMP_OK;
    foam_file *f = NULL;
    UMP_CALL(foam_file_read(path, &f, err));
    const foam_dict *d = f->dict;
    ump_status rc = UMP_OK;
    const char *w = NULL;
    const foam_entry *e = foam_dict_find(d, "dynamicFvMesh", 0);
    if (!e)
        goto done; /* OpenFOAM's default: staticFvMesh */
    if ((rc = foam_get_word(d, "dynamicFvMesh", &w, err)) != UMP_OK)
        goto done;
    if (strcmp(w, "staticFvMesh") == 0)
        goto done;
    if (strcmp(w, "dynamicMotionSolverFvMesh") != 0) {
        rc = UMP_FAIL(err, UMP_ERR_UNSUPPORTED, "%s:%d: dynamicFvMesh %s: meshlessFoam implements a container in "
                      "rigid motion only (dynamicMotionSolverFvMesh with motionSolver solidBody and "
                      "solidBodyMotionFunction oscillatingLinearMotion); use interFoam", e->file, e->line, w);
        goto done;
    }
    const char *solver = NULL;
    e = foam_dict_find(d, "motionSolver", 0);
    if (!e)
        e = foam_dict_find(d, "solver", 0);
    if (e && !e->dict && e->ntok > 0 && e->tok[0].type == FOAM_TOK_WORD)
        solver = e->tok[0].v.str;
    if (solver && strcmp(solver, "displacementLaplacian") == 0) {
        mo->deform = 1; /* the walls' motion: 0/pointDisplacement (mlapp.c) */
        goto done;
    }
    if (!solver || strcmp(solver, "solidBody") != 0) {
        rc = UMP_FAIL(err, UMP_ERR_UNSUPPORTED, "%s: motionSolver %s: meshlessFoam implements the solidBody motion "
                      "of the whole mesh (a moving container) and wall patches moved by displacementLaplacian's "
                      "0/pointDisplacement (wave makers); other mesh motion solvers are not implemented; use "
                      "interFoam", path,
                      solver ? solver : "(none)");
        goto done;
    }
    const foam_dict *c = d;
    const foam_entry *sc = foam_dict_find(d, "solidBodyCoeffs", 0);
    if (sc && sc->dict && foam_dict_find(sc->dict, "solidBodyMotionFunction", 0))
        c = sc->dict;
    static const char *const part[] = {"cellZone", "cellSet"};
    for (int k = 0; k < 2; k++) {
        const foam_entry *z = foam_dict_find(c, part[k], 0);
        const char *zw = word_of_entry(z);
        if (z && !(zw && strcmp(zw, "none") == 0)) {
            rc = UMP_FAIL(err, UMP_ERR_UNSUPPORTED, "%s:%d: %s: the motion of part of the mesh is not implemented "
                          "by meshlessFoam (the whole container moves); use interFoam", z->file, z->line, part[k]);
            goto done;
        }
    }
    const char *fn = NULL;
    if ((rc = foam_get_word(c, "solidBodyMotionFunction", &fn, err)) != UMP_OK)
        goto done;
    if (strcmp(fn, "oscillatingLinearMotion") != 0) {
        e = foam_dict_find(c, "solidBodyMotionFunction", 0);
        rc = UMP_FAIL(err, UMP_ERR_UNSUPPORTED, "%s:%d: solidBodyMotionFunction %s is not implemented by "
                      "meshlessFoam (oscillatingLinearMotion only); use interFoam", e->file, e->line, fn);
        goto done;
    }
    e = foam_dict_find(c, "oscillatingLinearMotionCoeffs", 0);
    if (!e || !e->dict) {
        rc = UMP_FAIL(err, UMP_ERR_INPUT, "%s: solidBodyMotionFunction oscillatingLinearMotion needs "
                      "oscillatingLinearMotionCoeffs { amplitude (x y z); omega w; }", path);
        goto done;
    }
    if ((rc = foam_get_vector(e->dict, "amplitude", mo->amplitude, err)) != UMP_OK ||
        (rc = foam_get_scalar(e->dict, "omega", &mo->omega, err)) != UMP_OK)
        goto done;
    mo->on = 1;
done:
    foam_file_free(&f);
    return rc;
}
