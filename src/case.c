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
    if ((rc = foam_get_scalar(d, "endTime", &c->end_time, err)) != UMP_OK ||
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
    if (purge < 0 || wprec < 1 || wprec > 30 || tprec < 1 || tprec > 30 || !(c->max_co > 0)) {
        rc = UMP_FAIL(err, UMP_ERR_INPUT,
                      "%s: purgeWrite must be >= 0, writePrecision and timePrecision in 1..30, maxCo > 0",
                      f->path);
        goto done;
    }
    /* OpenFOAM clamps writePrecision silently to what a double can carry */
    c->purge_write = (int)purge;
    c->write_precision = (int)wprec;
    c->time_precision = (int)tprec;
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

ump_status case_check_laminar(const char *case_dir, ump_err *err)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/constant/turbulenceProperties", case_dir);
    if (!foam_file_exists(path))
        return UMP_OK;
    foam_file *f = NULL;
    UMP_CALL(foam_file_read(path, &f, err));
    const char *w = NULL;
    ump_status rc = foam_get_word(f->dict, "simulationType", &w, err);
    if (rc == UMP_OK && strcmp(w, "laminar") != 0) {
        const foam_entry *e = foam_dict_find(f->dict, "simulationType", 0);
        rc = UMP_FAIL(err, UMP_ERR_UNSUPPORTED,
                      "%s:%d: simulationType '%s' is not supported: umppmFoam is a laminar solver "
                      "(use simulationType laminar;)", e->file, e->line, w);
    }
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
        a = foam_dict_sub(f->dict, algo[i]);
    ump_status rc = UMP_OK;
    int64_t cell = 0;
    if (a) {
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

/* Copy a word entry of d into buf after checking it against a list. */
static ump_status get_choice(const foam_dict *d, const char *key, const char *dflt,
                             const char *const *valid, int nvalid, char *buf, size_t len, ump_err *err)
{
    const char *w = NULL;
    UMP_CALL(foam_get_word_or(d, key, dflt, &w, err));
    for (int i = 0; i < nvalid; i++)
        if (strcmp(valid[i], w) == 0) {
            snprintf(buf, len, "%s", w);
            return UMP_OK;
        }
    const foam_entry *e = foam_dict_find(d, key, 0);
    char list[256] = "";
    for (int i = 0; i < nvalid; i++) {
        strncat(list, i ? " " : "", sizeof list - strlen(list) - 1);
        strncat(list, valid[i], sizeof list - strlen(list) - 1);
    }
    return UMP_FAIL(err, UMP_ERR_INPUT, "%s:%d: UMPPM %s '%s' is not one of: %s",
                    e ? e->file : "system/fvSolution", e ? e->line : 0, key, w, list);
}

ump_status case_read_umppm(const char *case_dir, case_umppm *u, ump_err *err)
{
    static const char *const variants[] = {"UMPPM", "UMPPMstar", "UMPPM*"};
    static const char *const laps[] = {"CPM", "MPS", "IPS", "PS"};
    static const char *const ppes[] = {"auto", "UMFPACK", "KLU", "CHOLMOD"};
    static const char *const pcs[] = {"ILU0", "Jacobi", "none"};
    char path[4096], var[16];
    snprintf(path, sizeof path, "%s/system/fvSolution", case_dir);
    foam_file *f = NULL;
    UMP_CALL(foam_file_read(path, &f, err));
    const foam_dict *d = foam_dict_sub(f->dict, "UMPPM");
    static const foam_dict empty = {0};
    if (!d)
        d = &empty;
    const foam_dict *pd = foam_dict_sub(d, "predictorSolver");
    if (!pd)
        pd = &empty;
    int64_t maxit = 500;
    const char *cloud = NULL;
    ump_status rc;
    if ((rc = get_choice(d, "variant", "UMPPMstar", variants, 3, var, sizeof var, err)) != UMP_OK ||
        (rc = foam_get_scalar_or(d, "alpha", 0.09, &u->alpha, err)) != UMP_OK ||
        (rc = get_choice(d, "laplacian", "CPM", laps, 4, u->laplacian, sizeof u->laplacian, err)) != UMP_OK ||
        (rc = foam_get_scalar_or(d, "reFactor", 0, &u->re_factor, err)) != UMP_OK ||
        (rc = foam_get_bool_or(d, "writeQuality", 0, &u->write_quality, err)) != UMP_OK ||
        (rc = get_choice(d, "ppeSolver", "auto", ppes, 4, u->ppe_solver, sizeof u->ppe_solver, err)) != UMP_OK ||
        (rc = get_choice(pd, "preconditioner", "ILU0", pcs, 3, u->pred_pc, sizeof u->pred_pc, err)) != UMP_OK ||
        (rc = foam_get_scalar_or(pd, "tolerance", 1e-12, &u->pred_tol, err)) != UMP_OK ||
        (rc = foam_get_label_or(pd, "maxIter", 500, &maxit, err)) != UMP_OK ||
        (rc = foam_get_word_or(d, "cloudName", "umppmCloud", &cloud, err)) != UMP_OK)
        goto done;
    u->variant_star = strcmp(var, "UMPPM") != 0;
    u->pred_maxit = (long)maxit;
    snprintf(u->cloud_name, sizeof u->cloud_name, "%s", cloud);
    if (!(u->alpha > 0 && u->alpha < 1) || !(u->pred_tol > 0) || maxit < 1)
        rc = UMP_FAIL(err, UMP_ERR_INPUT, "%s: UMPPM alpha must be in (0,1), predictorSolver tolerance > 0 "
                      "and maxIter >= 1", f->path);
    else if (u->re_factor != 0 && !(u->re_factor >= 1 && u->re_factor <= 4))
        rc = UMP_FAIL(err, UMP_ERR_INPUT, "%s: UMPPM reFactor %g: expected 0 (the model's default) or a "
                      "value in [1, 4] (r_e = reFactor x particle spacing)", f->path, u->re_factor);
done:
    foam_file_free(&f);
    return rc;
}
