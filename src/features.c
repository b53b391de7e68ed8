/* SPDX-License-Identifier: GPL-3.0-or-later
 * features.c -- refuse, by name, what an OpenFOAM case asks for and
 * umppmFoam does not implement (see features.h for the list and the form
 * of the messages).
 *
 * The checks run in a fixed order, the most fundamental first, so a case
 * that needs several missing features is refused for the one that matters
 * most: several phases or a free surface (interFoam, the interface-tracking
 * tutorials of pimpleFoam), a moving mesh, finite-area regions, a non-
 * Newtonian or viscoelastic fluid, a turbulence model, then source terms
 * (fvOptions, fvConstraints, porosity, MRF) and last the time scheme.
 * What OpenFOAM v1912 reads is followed: dynamicFvMesh defaults to
 * staticFvMesh (dynamicFvMeshNew.C), laminarModel to Stokes (laminarModel.C),
 * an MRF zone is active unless `active false` (MRFZone.C).
 */
#include "umppm/features.h"
#include "umppm/case.h"
#include "umppm/foam.h"

#include <dirent.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

/* The solver named in the messages, and the OpenFOAM solver to use
 * instead for the general case (set by each entry point; start-up only). */
static const char *feat_solver = "umppmFoam", *feat_instead = "pimpleFoam";

/* Read case_dir/rel if it exists (plain or .gz); *f = NULL when absent. */
static ump_status read_optional(const char *case_dir, const char *rel, foam_file **f, ump_err *err)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/%s", case_dir, rel);
    *f = NULL;
    if (!foam_file_exists(path))
        return UMP_OK;
    return foam_file_read(path, f, err);
}

/* The first token of a primitive entry as text ("nothing" for none). */
static const char *first_word(const foam_entry *e, char *buf, size_t len)
{
    if (e->dict)
        snprintf(buf, len, "a dictionary");
    else if (e->ntok == 0)
        snprintf(buf, len, "nothing");
    else if (e->tok[0].type == FOAM_TOK_WORD || e->tok[0].type == FOAM_TOK_STRING)
        snprintf(buf, len, "%s", e->tok[0].v.str);
    else
        foam_tok_str(&e->tok[0], buf, len);
    return buf;
}

/* The word of key in d, NULL when absent or not one word. */
static const char *word_of(const foam_dict *d, const char *key)
{
    const foam_entry *e = d ? foam_dict_find(d, key, 0) : NULL;
    if (!e || e->dict || e->ntok < 1 || (e->tok[0].type != FOAM_TOK_WORD && e->tok[0].type != FOAM_TOK_STRING))
        return NULL;
    return e->tok[0].v.str;
}

static int is_dir(const char *case_dir, const char *rel)
{
    char path[4096];
    struct stat st;
    snprintf(path, sizeof path, "%s/%s", case_dir, rel);
    return stat(path, &st) == 0 && S_ISDIR(st.st_mode);
}

/* ---- multiphase and free surfaces ---------------------------------------- */

static ump_status check_multiphase(const char *case_dir, const char *tname, ump_err *err)
{
    foam_file *f = NULL;
    UMP_CALL(read_optional(case_dir, "constant/transportProperties", &f, err));
    const foam_entry *e = f ? foam_dict_find(f->dict, "phases", 0) : NULL;
    if (e) {
        char w[256] = "";
        for (size_t i = 0; !e->dict && i < e->ntok && strlen(w) < 120; i++) {
            char t[64];
            const foam_token *k = &e->tok[i];
            if (k->type == FOAM_TOK_WORD || k->type == FOAM_TOK_STRING)
                snprintf(t, sizeof t, "%s", k->v.str);
            else if (k->type == FOAM_TOK_PUNCT)
                snprintf(t, sizeof t, "%c", k->v.punct);
            else
                foam_tok_str(k, t, sizeof t);
            size_t o = strlen(w);
            snprintf(w + o, sizeof w - o, "%s%s", o && k->type != FOAM_TOK_PUNCT && w[o - 1] != '(' ? " " : "", t);
        }
        ump_status rc = UMP_FAIL(err, UMP_ERR_UNSUPPORTED,
                                 "%s:%d: entry 'phases' %s: multiphase flow is not implemented by "
                                 "umppmFoam, which solves one incompressible phase; use interFoam or "
                                 "multiphaseInterFoam", e->file, e->line, e->dict ? "{ ... }" : w);
        foam_file_free(&f);
        return rc;
    }
    foam_file_free(&f);
    /* alpha.<phase> volume fractions in the start time (alphat is the
     * turbulent diffusivity of a buoyant case: no dot) */
    char dir[4096];
    snprintf(dir, sizeof dir, "%s/%s", case_dir, tname);
    DIR *dp = opendir(dir);
    if (dp) {
        struct dirent *de;
        char found[256] = "";
        while ((de = readdir(dp)) != NULL)
            if (strncmp(de->d_name, "alpha.", 6) == 0 && de->d_name[6] != '\0' && !found[0])
                snprintf(found, sizeof found, "%s", de->d_name);
        closedir(dp);
        if (found[0])
            return UMP_FAIL(err, UMP_ERR_UNSUPPORTED,
                            "%s/%s: a phase fraction field: multiphase flow is not implemented by umppmFoam, "
                            "which solves one incompressible phase; use interFoam", dir, found);
    }
    return UMP_OK;
}

/* ---- moving meshes and finite area ---------------------------------------- */

static ump_status check_dynamic_mesh(const char *case_dir, ump_err *err)
{
    foam_file *f = NULL;
    UMP_CALL(read_optional(case_dir, "constant/dynamicMeshDict", &f, err));
    if (!f)
        return UMP_OK;
    const foam_entry *e = foam_dict_find(f->dict, "dynamicFvMesh", 0);
    const char *w = word_of(f->dict, "dynamicFvMesh");
    ump_status rc = UMP_OK;
    if (e && (!w || strcmp(w, "staticFvMesh") != 0)) {
        char t[128];
        first_word(e, t, sizeof t);
        if (w && strcmp(w, "interfaceTrackingFvMesh") == 0)
            rc = UMP_FAIL(err, UMP_ERR_UNSUPPORTED,
                          "%s:%d: dynamicFvMesh interfaceTrackingFvMesh: free-surface (multiphase) flow on an "
                          "interface-tracking moving mesh is not implemented by %s, which solves one "
                          "phase on a static mesh; use pimpleFoam", e->file, e->line, feat_solver);
        else
            rc = UMP_FAIL(err, UMP_ERR_UNSUPPORTED,
                          "%s:%d: dynamicFvMesh %s: moving or topology-changing meshes are not implemented by "
                          "%s (static meshes only); remove the file or set dynamicFvMesh staticFvMesh, "
                          "or use %s", e->file, e->line, t, feat_solver, feat_instead);
    }
    foam_file_free(&f);
    return rc;
}

static ump_status check_finite_area(const char *case_dir, ump_err *err)
{
    static const char *const files[] = {"system/faSchemes", "system/faSolution"};
    char path[4096];
    for (int i = 0; i < 2; i++) {
        snprintf(path, sizeof path, "%s/%s", case_dir, files[i]);
        if (foam_file_exists(path))
            return UMP_FAIL(err, UMP_ERR_UNSUPPORTED,
                            "%s: finite-area (faMesh) regions are not implemented by %s; remove "
                            "system/faSchemes, system/faSolution and constant/faMesh to run the volume flow "
                            "alone", path, feat_solver);
    }
    if (is_dir(case_dir, "constant/faMesh"))
        return UMP_FAIL(err, UMP_ERR_UNSUPPORTED,
                        "%s/constant/faMesh: finite-area (faMesh) regions are not implemented by %s; "
                        "remove constant/faMesh to run the volume flow alone", case_dir, feat_solver);
    return UMP_OK;
}

/* ---- the fluid: viscosity model, laminar model, turbulence ----------------- */

static ump_status check_viscosity(const char *case_dir, ump_err *err)
{
    foam_file *f = NULL;
    UMP_CALL(read_optional(case_dir, "constant/transportProperties", &f, err));
    if (!f)
        return UMP_OK;
    static const char *const keys[] = {"transportModel", "viscosityModel"};
    ump_status rc = UMP_OK;
    for (int k = 0; k < 2 && rc == UMP_OK; k++) {
        const foam_entry *e = foam_dict_find(f->dict, keys[k], 0);
        const char *w = word_of(f->dict, keys[k]);
        if (!e || (w && strcmp(w, "Newtonian") == 0))
            continue;
        char t[128];
        rc = UMP_FAIL(err, UMP_ERR_UNSUPPORTED,
                      "%s:%d: %s %s: non-Newtonian viscosity is not implemented by %s (Newtonian nu "
                      "only: transportModel Newtonian; nu ...;); use %s", e->file, e->line,
                      keys[k], first_word(e, t, sizeof t), feat_solver,
                      strcmp(feat_solver, "umppmFoam") == 0 ? "nonNewtonianIcoFoam" : feat_instead);
    }
    foam_file_free(&f);
    return rc;
}

/* constant/turbulenceProperties (v1912) or constant/momentumTransport
 * (later OpenFOAM): simulationType laminar, laminarModel Stokes. */
static ump_status check_momentum_transport(const char *case_dir, ump_err *err)
{
    static const char *const files[] = {"constant/turbulenceProperties", "constant/momentumTransport"};
    for (int i = 0; i < 2; i++) {
        foam_file *f = NULL;
        UMP_CALL(read_optional(case_dir, files[i], &f, err));
        if (!f)
            continue;
        const char *w = NULL;
        ump_status rc = foam_get_word(f->dict, "simulationType", &w, err);
        if (rc == UMP_OK && strcmp(w, "laminar") != 0) {
            const foam_entry *e = foam_dict_find(f->dict, "simulationType", 0);
            rc = UMP_FAIL(err, UMP_ERR_UNSUPPORTED,
                          "%s:%d: simulationType '%s' is not supported: %s is a laminar solver "
                          "(use simulationType laminar;)", e->file, e->line, w, feat_solver);
        }
        const foam_dict *lam = rc == UMP_OK ? foam_dict_sub(f->dict, "laminar") : NULL;
        /* v1912's laminarModel, and the later momentumTransport's model and
         * viscosityModel (generalisedNewtonian with a Newtonian viscosity is
         * Stokes) */
        const foam_entry *ve = lam ? foam_dict_find(lam, "viscosityModel", 0) : NULL;
        const char *vm = word_of(lam, "viscosityModel");
        int newtonian = vm && strcmp(vm, "Newtonian") == 0;
        static const char *const keys[] = {"laminarModel", "model"};
        for (int k = 0; k < 2 && rc == UMP_OK; k++) {
            const foam_entry *e = lam ? foam_dict_find(lam, keys[k], 0) : NULL;
            const char *m = word_of(lam, keys[k]);
            int gn_ok = k == 1 && m && strcmp(m, "generalisedNewtonian") == 0; /* its viscosityModel below */
            if (e && !gn_ok && (!m || strcmp(m, "Stokes") != 0)) {
                char t[128];
                rc = UMP_FAIL(err, UMP_ERR_UNSUPPORTED,
                              "%s:%d: laminar { %s %s; }: only the Newtonian laminar model Stokes is "
                              "implemented by %s (no viscoelastic stress or generalised-Newtonian viscosity); "
                              "set %s Stokes, or use %s", e->file, e->line, keys[k], first_word(e, t, sizeof t),
                              feat_solver, keys[k], feat_instead);
            }
        }
        if (rc == UMP_OK && ve && !newtonian) { /* (none given: the solver's Newtonian nu) */
            char t[128];
            rc = UMP_FAIL(err, UMP_ERR_UNSUPPORTED,
                          "%s:%d: laminar { viscosityModel %s; }: non-Newtonian viscosity is not implemented by %s",
                          ve->file, ve->line, first_word(ve, t, sizeof t), feat_solver);
        }
        foam_file_free(&f);
        if (rc != UMP_OK)
            return rc;
    }
    return UMP_OK;
}

/* ---- source terms -------------------------------------------------------- */

/* The first entry of a file of named source dictionaries (fvOptions,
 * fvConstraints, porosityProperties, MRFProperties) that is in force;
 * with mrf, entries with `active false` are not. */
static ump_status check_sources(const char *case_dir, const char *rel, const char *what, const char *instead,
                                int mrf, ump_err *err)
{
    foam_file *f = NULL;
    UMP_CALL(read_optional(case_dir, rel, &f, err));
    if (!f)
        return UMP_OK;
    ump_status rc = UMP_OK;
    for (size_t i = 0; i < f->dict->n && rc == UMP_OK; i++) {
        const foam_entry *e = &f->dict->e[i];
        if (mrf && e->dict) {
            int active = 1;
            if ((rc = foam_get_bool_or(e->dict, "active", 1, &active, err)) != UMP_OK || !active)
                continue;
        }
        char type[128] = "";
        const char *w = e->dict ? word_of(e->dict, "type") : NULL;
        if (w)
            snprintf(type, sizeof type, ", type %s", w);
        rc = UMP_FAIL(err, UMP_ERR_UNSUPPORTED,
                      "%s:%d: %s not implemented by %s (entry '%s'%s); remove the file (or empty it) "
                      "to run without it, or use %s", e->file, e->line, what, feat_solver, e->key, type,
                      instead);
    }
    foam_file_free(&f);
    return rc;
}

/* ---- the time scheme ------------------------------------------------------ */

/* Is the ddt scheme of entry e one umppmFoam runs (Euler, backward)? The
 * word goes to w; `default none` is accepted (a per-field entry decides). */
static int ddt_ok(const foam_entry *e, char *w, size_t len)
{
    first_word(e, w, len);
    if (e->dict || e->ntok != 1)
        return 0;
    return strcmp(w, "Euler") == 0 || strcmp(w, "backward") == 0 ||
           (strcmp(e->key, "default") == 0 && strcmp(w, "none") == 0);
}

ump_status feat_ddt_scheme(const char *case_dir, char *buf, size_t len, ump_err *err)
{
    foam_file *f = NULL;
    UMP_CALL(read_optional(case_dir, "system/fvSchemes", &f, err));
    const foam_dict *d = f ? foam_dict_sub(f->dict, "ddtSchemes") : NULL;
    snprintf(buf, len, "Euler (no system/fvSchemes ddtSchemes)");
    ump_status rc = UMP_OK;
    for (size_t i = 0; d && i < d->n && rc == UMP_OK; i++) {
        const foam_entry *e = &d->e[i];
        char w[128];
        if (!ddt_ok(e, w, sizeof w))
            rc = UMP_FAIL(err, UMP_ERR_UNSUPPORTED,
                          "%s:%d: ddtSchemes %s %s%s: umppmFoam runs the transient first-order UMPPM step "
                          "only (allowed: Euler, backward); steady-state and Crank-Nicolson time schemes are "
                          "not implemented (use simpleFoam for steady flow, or set default Euler;)",
                          e->file, e->line, e->key, w, !e->dict && e->ntok > 1 ? " ..." : "");
    }
    if (rc == UMP_OK && d) {
        const foam_entry *e = foam_dict_find(d, "ddt(U)", 0);
        if (!e)
            e = foam_dict_find(d, "default", 0);
        char w[128];
        if (e && ddt_ok(e, w, sizeof w) && strcmp(w, "none") != 0)
            snprintf(buf, len, "%s", w);
        else
            rc = UMP_FAIL(err, UMP_ERR_INPUT, "%s:%d: ddtSchemes has no scheme for U (ddt(U) or default)",
                          d->file, d->line);
    }
    foam_file_free(&f);
    return rc;
}

ump_status feat_check_case(const char *case_dir, const char *tname, ump_err *err)
{
    feat_solver = "umppmFoam";
    feat_instead = "pimpleFoam";
    UMP_CALL(check_multiphase(case_dir, tname, err));
    UMP_CALL(check_dynamic_mesh(case_dir, err));
    UMP_CALL(check_finite_area(case_dir, err));
    UMP_CALL(check_viscosity(case_dir, err));
    UMP_CALL(check_momentum_transport(case_dir, err));
    static const struct {
        const char *rel, *what, *instead;
        int mrf;
    } src[] = {
        {"constant/fvOptions", "fvOptions are", "pimpleFoam", 0},
        {"system/fvOptions", "fvOptions are", "pimpleFoam", 0},
        {"constant/fvConstraints", "fvConstraints are", "pimpleFoam", 0},
        {"system/fvConstraints", "fvConstraints are", "pimpleFoam", 0},
        {"constant/porosityProperties", "porosity zones are", "porousSimpleFoam", 0},
        {"constant/MRFProperties", "MRF (rotating frame) zones are", "pimpleFoam or SRFPimpleFoam", 1},
    };
    for (size_t i = 0; i < sizeof src / sizeof src[0]; i++)
        UMP_CALL(check_sources(case_dir, src[i].rel, src[i].what, src[i].instead, src[i].mrf, err));
    char ddt[128];
    return feat_ddt_scheme(case_dir, ddt, sizeof ddt, err);
}

ump_status feat_check_meshless(const char *case_dir, ump_err *err)
{
    feat_solver = "meshlessFoam";
    feat_instead = "interFoam";
    /* a moving container (case_read_motion) is the one dynamic mesh it runs */
    case_motion mo;
    ump_status rc = case_read_motion(case_dir, &mo, err);
    if (rc == UMP_OK)
        rc = check_finite_area(case_dir, err);
    if (rc == UMP_OK)
        rc = check_momentum_transport(case_dir, err);
    static const char *const files[] = {"constant/fvOptions", "system/fvOptions", "constant/fvConstraints",
                                        "system/fvConstraints", "constant/porosityProperties"};
    static const char *const what[] = {"fvOptions are", "fvOptions are", "fvConstraints are",
                                       "fvConstraints are", "porosity zones are"};
    for (size_t i = 0; rc == UMP_OK && i < sizeof files / sizeof files[0]; i++)
        rc = check_sources(case_dir, files[i], what[i], "interFoam", 0, err);
    if (rc == UMP_OK)
        rc = check_sources(case_dir, "constant/MRFProperties", "MRF (rotating frame) zones are", "interFoam", 1,
                           err);
    feat_solver = "umppmFoam";
    feat_instead = "pimpleFoam";
    return rc;
}
