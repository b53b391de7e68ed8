/* SPDX-License-Identifier: GPL-3.0-or-later
 * fieldio_read.c -- reading volScalarField / volVectorField files.
 *
 * Boundary entries are matched to mesh patches as OpenFOAM's
 * GeometricBoundaryField does: the exact patch name first, then the patch's
 * groups (inGroups, plus its type for wall and constraint types), then
 * regular-expression keys, the latest one first. Constraint patches must
 * carry their own type (an empty patch needs `empty`, a cyclic `cyclic`,
 * ...), and those types are refused on other patches, as OpenFOAM does.
 */
#include "umppm/fieldio.h"
#include "umppm/foam.h"

#include <regex.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Full-string match of a POSIX extended regex (OpenFOAM anchors keys). */
static int regex_match(const char *pattern, const char *s)
{
    size_t n = strlen(pattern);
    char small[256], *anch = n + 5 <= sizeof small ? small : malloc(n + 5);
    if (!anch)
        return 0; /* out of memory for a key of over 250 characters */
    snprintf(anch, n + 5, "^(%s)$", pattern);
    regex_t re;
    int ok = 0;
    if (regcomp(&re, anch, REG_EXTENDED | REG_NOSUB) == 0) {
        ok = regexec(&re, s, 0, NULL, 0) == 0;
        regfree(&re);
    }
    if (anch != small)
        free(anch);
    return ok;
}

/* The entry for patch p, or NULL: with *implicit_empty set where p is an
 * empty patch that no name or group names (OpenFOAM gives it `empty`
 * before it tries the regular expressions). */
static const foam_entry *match_patch(const foam_dict *bf, const pmesh_patch *p, int *implicit_empty)
{
    *implicit_empty = 0;
    for (size_t i = 0; i < bf->n; i++)
        if (!bf->e[i].is_pattern && strcmp(bf->e[i].key, p->name) == 0)
            return &bf->e[i];
    for (size_t i = 0; i < bf->n; i++)
        if (!bf->e[i].is_pattern && pmesh_patch_in_group(p, bf->e[i].key))
            return &bf->e[i];
    if (p->kind == PMESH_EMPTY) {
        *implicit_empty = 1;
        return NULL;
    }
    for (size_t i = bf->n; i-- > 0;)
        if (bf->e[i].is_pattern && regex_match(bf->e[i].key, p->name))
            return &bf->e[i];
    return NULL;
}

/* "uniform v" or "nonuniform List<T> ..." of n elements with ncomp components. */
static ump_status read_values(const foam_token *tok, size_t nt, size_t *pos, size_t n, int ncomp,
                              double *out, const char *file, const char *what, ump_err *err)
{
    char w[512], s[128];
    if (*pos >= nt || tok[*pos].type != FOAM_TOK_WORD)
        return UMP_FAIL(err, UMP_ERR_PARSE, "%s: %s: expected 'uniform' or 'nonuniform', found %s",
                        foam_tok_where(tok, nt, *pos, file, w, sizeof w), what,
                        *pos < nt ? foam_tok_str(&tok[*pos], s, sizeof s) : "end of entry");
    const char *kind = tok[*pos].v.str;
    size_t at = *pos;
    (*pos)++;
    if (strcmp(kind, "uniform") == 0) {
        double v[3];
        if (ncomp == 1) {
            UMP_CALL(foam_tok_scalar(tok, nt, pos, &v[0], what, err));
        } else {
            double *lst = NULL;
            size_t cnt = 0;
            if (*pos < nt && (tok[*pos].type == FOAM_TOK_LABEL || tok[*pos].type == FOAM_TOK_SCALAR))
                return UMP_FAIL(err, UMP_ERR_PARSE, "%s: %s: expected a vector (x y z) after 'uniform', found "
                                "%s", foam_tok_where(tok, nt, at, file, w, sizeof w), what,
                                foam_tok_str(&tok[*pos], s, sizeof s));
            /* "(x y z)" is read as a bare list of 3 scalars */
            UMP_CALL(foam_tok_scalar_list(tok, nt, pos, 1, &lst, &cnt, what, err));
            if (cnt != 3) {
                free(lst);
                return UMP_FAIL(err, UMP_ERR_PARSE, "%s: %s: expected a vector (x y z)",
                                foam_tok_where(tok, nt, at, file, w, sizeof w), what);
            }
            memcpy(v, lst, sizeof v);
            free(lst);
        }
        for (size_t i = 0; i < n; i++)
            for (int k = 0; k < ncomp; k++)
                out[i * (size_t)ncomp + (size_t)k] = v[k];
        return UMP_OK;
    }
    if (strcmp(kind, "nonuniform") != 0)
        return UMP_FAIL(err, UMP_ERR_PARSE, "%s: %s: expected 'uniform' or 'nonuniform', found '%s'",
                        foam_tok_where(tok, nt, at, file, w, sizeof w), what, kind);
    if (*pos < nt && tok[*pos].type == FOAM_TOK_WORD) {
        const char *lt = tok[*pos].v.str;
        const char *want = ncomp == 1 ? "List<scalar>" : "List<vector>";
        if (strcmp(lt, want) != 0)
            return UMP_FAIL(err, UMP_ERR_PARSE, "%s: %s: expected %s, found '%s'",
                            foam_tok_where(tok, nt, *pos, file, w, sizeof w), what, want, lt);
        (*pos)++;
    }
    double *lst = NULL;
    size_t cnt = 0;
    UMP_CALL(foam_tok_scalar_list(tok, nt, pos, ncomp, &lst, &cnt, what, err));
    if (cnt != n) {
        free(lst);
        return UMP_FAIL(err, UMP_ERR_INPUT, "%s: %s: %zu values for %zu %s",
                        foam_tok_where(tok, nt, at, file, w, sizeof w), what, cnt, n,
                        strcmp(what, "internalField") == 0 ? "cells" : "faces");
    }
    memcpy(out, lst, n * (size_t)ncomp * sizeof *out);
    free(lst);
    return UMP_OK;
}

/* ---- keys kept verbatim -------------------------------------------------- */

/* A growable string (the text of a kept key, any length). */
typedef struct sbuf {
    char *s;
    size_t n, cap;
    int failed;
} sbuf;

static void sb_put(sbuf *b, const char *str, size_t len)
{
    if (b->failed)
        return;
    if (b->n + len + 1 > b->cap) {
        size_t cap = b->cap ? b->cap : 256;
        while (cap < b->n + len + 1)
            cap *= 2;
        char *ns = ump_realloc_array(b->s, cap, 1);
        if (!ns) {
            b->failed = 1;
            return;
        }
        b->s = ns;
        b->cap = cap;
    }
    memcpy(b->s + b->n, str, len);
    b->n += len;
    b->s[b->n] = '\0';
}

static void sb_str(sbuf *b, const char *str) { sb_put(b, str, strlen(str)); }

/* The shortest of %.15g..%.17g that reads back as v. */
static void sb_num(sbuf *b, double v)
{
    char tmp[64];
    for (int prec = 15; prec <= 17; prec++) {
        snprintf(tmp, sizeof tmp, "%.*g", prec, v);
        if (strtod(tmp, NULL) == v || prec == 17)
            break;
    }
    sb_str(b, tmp);
}

static void dict_to_text(sbuf *b, const foam_dict *d);

/* Tokens on one line, as OpenFOAM would read them back: no space after '('
 * or before ')'; sub-dictionaries as "{ k v; }"; binary lists as ascii
 * "N(...)". */
static void tokens_to_text(sbuf *b, const foam_token *t, size_t nt)
{
    for (size_t i = 0; i < nt; i++) {
        char tmp[64];
        int nospace = i == 0 || (t[i - 1].type == FOAM_TOK_PUNCT && t[i - 1].v.punct == '(') ||
                      (t[i].type == FOAM_TOK_PUNCT && t[i].v.punct == ')');
        if (!nospace)
            sb_str(b, " ");
        switch (t[i].type) {
        case FOAM_TOK_PUNCT: sb_put(b, &t[i].v.punct, 1); break;
        case FOAM_TOK_WORD: sb_str(b, t[i].v.str); break;
        case FOAM_TOK_STRING: sb_str(b, "\""); sb_str(b, t[i].v.str); sb_str(b, "\""); break;
        case FOAM_TOK_LABEL:
            snprintf(tmp, sizeof tmp, "%lld", (long long)t[i].v.label);
            sb_str(b, tmp);
            break;
        case FOAM_TOK_SCALAR: sb_num(b, t[i].v.scalar); break;
        case FOAM_TOK_DICT: dict_to_text(b, t[i].v.dict); break;
        case FOAM_TOK_BLOB: {
            const foam_blob *bl = &t[i].v.blob;
            snprintf(tmp, sizeof tmp, "%zu(", bl->n);
            sb_str(b, tmp);
            for (size_t e = 0; e < bl->n; e++) {
                if (e)
                    sb_str(b, " ");
                if (bl->ncomp > 1)
                    sb_str(b, "(");
                for (int c = 0; c < bl->ncomp; c++) {
                    size_t k = e * (size_t)bl->ncomp + (size_t)c;
                    if (c)
                        sb_str(b, " ");
                    if (bl->is_label) {
                        snprintf(tmp, sizeof tmp, "%lld", (long long)((const int64_t *)bl->data)[k]);
                        sb_str(b, tmp);
                    } else {
                        sb_num(b, ((const double *)bl->data)[k]);
                    }
                }
                if (bl->ncomp > 1)
                    sb_str(b, ")");
            }
            sb_str(b, ")");
            break;
        }
        }
    }
}

static void dict_to_text(sbuf *b, const foam_dict *d)
{
    sb_str(b, "{");
    for (size_t i = 0; i < d->n; i++) {
        const foam_entry *x = &d->e[i];
        sb_str(b, " ");
        if (x->is_pattern) {
            sb_str(b, "\"");
            sb_str(b, x->key);
            sb_str(b, "\"");
        } else {
            sb_str(b, x->key);
        }
        sb_str(b, " ");
        if (x->dict) {
            dict_to_text(b, x->dict);
        } else {
            tokens_to_text(b, x->tok, x->ntok);
            sb_str(b, ";");
        }
    }
    sb_str(b, " }");
}

/* A word-valued key of a boundary condition that umppmFoam implements only
 * with its default (phi phi; U U; rho rho; psi none): absent or equal to
 * dflt, else refused by name with why. */
static ump_status key_default_word(const foam_dict *d, const char *key, const char *dflt, const char *bc,
                                   const char *patch, const char *why, ump_err *err)
{
    const foam_entry *x = foam_dict_find(d, key, 0);
    if (!x)
        return UMP_OK;
    int ok = !x->dict && x->ntok == 1 && (x->tok[0].type == FOAM_TOK_WORD || x->tok[0].type == FOAM_TOK_STRING) &&
             strcmp(x->tok[0].v.str, dflt) == 0;
    if (ok)
        return UMP_OK;
    sbuf b = {0};
    if (x->dict)
        sb_str(&b, "{...}");
    else
        tokens_to_text(&b, x->tok, x->ntok);
    ump_status rc = UMP_FAIL(err, UMP_ERR_UNSUPPORTED, "%s:%d: patch '%s': %s: '%s %s' is not implemented by "
                             "%s (only %s %s: %s)", x->file, x->line, patch, bc, key,
                             b.s ? b.s : "", ump_solver, key, dflt, why);
    free(b.s);
    return rc;
}

/* A key of the boundary condition that umppmFoam does not implement at all. */
static ump_status key_refused(const foam_dict *d, const char *key, const char *bc, const char *patch,
                              const char *why, ump_err *err)
{
    const foam_entry *x = foam_dict_find(d, key, 0);
    if (!x)
        return UMP_OK;
    return UMP_FAIL(err, UMP_ERR_UNSUPPORTED, "%s:%d: patch '%s': %s: key '%s' is not implemented by %s "
                    "(%s)", x->file, x->line, patch, bc, key, ump_solver, why);
}

#define WHY_PHI "the solver's own face flux"
#define WHY_RHO "kinematic pressure and volumetric flow, no density"

/* The keys of v1912's boundary conditions that the solvers implement only
 * in part: refused by name unless they have the value implemented. */
static ump_status check_bc_keys(const foam_dict *d, fld_bc_type t, const char *type, const char *patch,
                                ump_err *err)
{
    switch (t) {
    case FLD_BC_INLETOUTLET:
    case FLD_BC_OUTLETINLET:
    case FLD_BC_PRESSUREINLETOUTLETVELOCITY:
        return key_default_word(d, "phi", "phi", type, patch, WHY_PHI, err);
    case FLD_BC_TOTALPRESSURE: {
        /* v1912 totalPressure: kinematic pressure (dimensions m^2/s^2)
         * with psi none is p0 - 0.5 (1 - pos0(phi)) |U|^2; rho is used only
         * for a pressure in Pa, gamma only with psi. The pressure's
         * dimensions are the solver's to check (umppmFoam: kinematic, in
         * app.c; meshlessFoam writes interFoam's p_rgh in Pa back as read) */
        UMP_CALL(key_default_word(d, "phi", "phi", type, patch, WHY_PHI, err));
        UMP_CALL(key_default_word(d, "U", "U", type, patch, "the solver's velocity", err));
        UMP_CALL(key_default_word(d, "rho", "rho", type, patch, WHY_RHO, err));
        UMP_CALL(key_default_word(d, "psi", "none", type, patch, "incompressible flow", err));
        const foam_entry *g = foam_dict_find(d, "gamma", 0);
        double gamma = 1;
        if (g && (foam_get_scalar(d, "gamma", &gamma, err) != UMP_OK || gamma != 1))
            return UMP_FAIL(err, UMP_ERR_UNSUPPORTED, "%s:%d: patch '%s': totalPressure: 'gamma %g' is not "
                            "implemented by %s (only gamma 1: incompressible flow, p0 - |U|^2/2)",
                            g->file, g->line, patch, gamma, ump_solver);
        return UMP_OK;
    }
    case FLD_BC_UNIFORMFIXEDVALUE:
        /* v1912's PatchFunction1 rotates uniformValue by a coordinateSystem
         * of the patch dictionary (checked with its icoFoam) */
        return key_refused(d, "coordinateSystem", type, patch,
                           "it rotates uniformValue; give the value in the global axes", err);
    case FLD_BC_FLOWRATEINLETVELOCITY:
        UMP_CALL(key_refused(d, "massFlowRate", type, patch,
                             "it needs the density rho; give volumetricFlowRate instead", err));
        UMP_CALL(key_default_word(d, "rho", "rho", type, patch, WHY_RHO, err));
        UMP_CALL(key_refused(d, "rhoInlet", type, patch, "a density for massFlowRate; only "
                             "volumetricFlowRate is implemented", err));
        {
            int extrapolate = 0;
            UMP_CALL(foam_get_bool_or(d, "extrapolateProfile", 0, &extrapolate, err));
            if (extrapolate) {
                const foam_entry *x = foam_dict_find(d, "extrapolateProfile", 0);
                return UMP_FAIL(err, UMP_ERR_UNSUPPORTED, "%s:%d: patch '%s': flowRateInletVelocity: "
                                "'extrapolateProfile true' is not implemented by %s (only the uniform "
                                "profile, extrapolateProfile false)", x->file, x->line, patch, ump_solver);
            }
        }
        return UMP_OK;
    default:
        return UMP_OK;
    }
}

/* Default face values of patch p: the adjacent cell values (zero for noSlip). */
static void set_default_values(const pmesh *pm, int p, int ncomp, fld_field *fld)
{
    const pmesh_patch *pp = &pm->patch[p];
    fld_patch *fp = &fld->patch[p];
    size_t n = (size_t)pp->n, nc = (size_t)ncomp;
    for (size_t i = 0; i < n; i++)
        for (size_t k = 0; k < nc; k++)
            fp->value[i * nc + k] = fp->type == FLD_BC_NOSLIP
                                        ? 0.0 : fld->internal[(size_t)pm->owner[pp->start + (ump_idx)i] * nc + k];
}

static ump_status read_patch_entry(const foam_entry *e, const pmesh *pm, int p, int ncomp,
                                   fld_field *fld, ump_err *err)
{
    const pmesh_patch *pp = &pm->patch[p];
    fld_patch *fp = &fld->patch[p];
    if (!e->dict)
        return UMP_FAIL(err, UMP_ERR_PARSE, "%s:%d: boundaryField entry for patch '%s' must be a dictionary",
                        e->file, e->line, pp->name);
    const foam_dict *d = e->dict;
    const char *type = NULL;
    UMP_CALL(foam_get_word(d, "type", &type, err));
    int t = fld_bc_parse(type);
    const foam_entry *te = foam_dict_find(d, "type", 0);
    if (t < 0) {
        char list[1024] = "";
        for (int k = 0; k < FLD_BC_NTYPES; k++) {
            strncat(list, k ? " " : "", sizeof list - strlen(list) - 1);
            strncat(list, fld_bc_name((fld_bc_type)k), sizeof list - strlen(list) - 1);
        }
        return UMP_FAIL(err, UMP_ERR_UNSUPPORTED,
                        "%s:%d: patch '%s': boundary condition type '%s' is not supported by %s "
                        "(supported: %s)", te->file, te->line, pp->name, type, ump_solver, list);
    }
    /* constraint types must sit on their own patch type, and only there */
    static const struct { pmesh_patch_kind k; fld_bc_type t; } cons[] = {
        {PMESH_EMPTY, FLD_BC_EMPTY}, {PMESH_CYCLIC, FLD_BC_CYCLIC},
        {PMESH_SYMMETRYPLANE, FLD_BC_SYMMETRYPLANE}, {PMESH_SYMMETRY, FLD_BC_SYMMETRY}};
    for (size_t k = 0; k < sizeof cons / sizeof cons[0]; k++)
        if ((pp->kind == cons[k].k) != (t == (int)cons[k].t))
            return UMP_FAIL(err, UMP_ERR_INPUT,
                            "%s:%d: patch '%s' is of mesh type '%s' but its boundary condition is '%s'",
                            te->file, te->line, pp->name, pp->type, type);
    fp->type = (fld_bc_type)t;
    size_t n = (size_t)pp->n, nc = (size_t)ncomp;
    set_default_values(pm, p, ncomp, fld);
    if ((fp->type == FLD_BC_NOSLIP || fp->type == FLD_BC_FLOWRATEINLETVELOCITY ||
         fp->type == FLD_BC_PRESSUREINLETOUTLETVELOCITY) && ncomp != 3)
        return UMP_FAIL(err, UMP_ERR_INPUT, "%s:%d: patch '%s': %s applies to vector fields only",
                        te->file, te->line, pp->name, type);
    if (fp->type == FLD_BC_TOTALPRESSURE && ncomp != 1)
        return UMP_FAIL(err, UMP_ERR_INPUT, "%s:%d: patch '%s': %s applies to the pressure (a scalar field) only",
                        te->file, te->line, pp->name, type);
    UMP_CALL(check_bc_keys(d, fp->type, type, pp->name, err));
    /* v1912 requires `value` of these (pressureInletOutletVelocity reads it
     * unconditionally) */
    int need_value = fp->type == FLD_BC_FIXEDVALUE || fp->type == FLD_BC_MOVINGWALLVELOCITY ||
                     fp->type == FLD_BC_CALCULATED || fp->type == FLD_BC_PRESSUREINLETOUTLETVELOCITY;
    const char *auxkey = fld_bc_aux_key(fp->type);
    const foam_entry *ve = foam_dict_find(d, "value", 0);
    if (need_value && !ve)
        return UMP_FAIL(err, UMP_ERR_INPUT, "%s:%d: patch '%s': type %s needs a 'value' entry",
                        te->file, te->line, pp->name, type);
    int use_value = ve && fp->type != FLD_BC_EMPTY && fp->type != FLD_BC_NOSLIP &&
                    fp->type != FLD_BC_ZEROGRADIENT && fp->type != FLD_BC_CYCLIC &&
                    fp->type != FLD_BC_SYMMETRYPLANE && fp->type != FLD_BC_SYMMETRY && fp->type != FLD_BC_SLIP;
    if (use_value) {
        if (ve->dict)
            return UMP_FAIL(err, UMP_ERR_PARSE, "%s:%d: patch '%s': value must be uniform/nonuniform",
                            ve->file, ve->line, pp->name);
        size_t pos = 0;
        UMP_CALL(read_values(ve->tok, ve->ntok, &pos, n, ncomp, fp->value, ve->file, "value", err));
        fp->value_given = 1;
    }
    if (auxkey) {
        const foam_entry *ae = foam_dict_find(d, auxkey, 0);
        int required = fp->type == FLD_BC_INLETOUTLET || fp->type == FLD_BC_OUTLETINLET ||
                       fp->type == FLD_BC_TOTALPRESSURE;
        if (required && !ae)
            return UMP_FAIL(err, UMP_ERR_INPUT, "%s:%d: patch '%s': %s needs a '%s' entry",
                            te->file, te->line, pp->name, type, auxkey);
        /* an optional list that is absent: gradient zero (fixedFluxPressure);
         * no tangentialVelocity (pressureInletOutletVelocity: aux stays NULL) */
        if (ae || fp->type == FLD_BC_FIXEDFLUXPRESSURE) {
            fp->aux = ump_alloc_array(n * nc, sizeof *fp->aux);
            if (!fp->aux)
                return UMP_FAIL(err, UMP_ERR_NOMEM, "%s: out of memory", te->file);
        }
        if (ae) {
            if (ae->dict)
                return UMP_FAIL(err, UMP_ERR_PARSE, "%s:%d: patch '%s': %s must be uniform/nonuniform",
                                ae->file, ae->line, pp->name, auxkey);
            size_t pos = 0;
            UMP_CALL(read_values(ae->tok, ae->ntok, &pos, n, ncomp, fp->aux, ae->file, auxkey, err));
        }
        /* v1912: without `value`, totalPressure starts at p0 and outletInlet
         * at outletValue */
        if (!use_value && (fp->type == FLD_BC_TOTALPRESSURE || fp->type == FLD_BC_OUTLETINLET))
            memcpy(fp->value, fp->aux, n * nc * sizeof *fp->value);
    }
    const char *fnkey = fp->type == FLD_BC_UNIFORMFIXEDVALUE       ? "uniformValue"
                        : fp->type == FLD_BC_FLOWRATEINLETVELOCITY ? "volumetricFlowRate"
                                                                   : NULL;
    if (fnkey) {
        char what[512];
        snprintf(what, sizeof what, "patch '%s': %s %s", pp->name, type, fnkey);
        if (!foam_dict_find(d, fnkey, 0))
            return UMP_FAIL(err, UMP_ERR_INPUT, "%s:%d: patch '%s': %s needs a '%s' entry%s", te->file, te->line,
                            pp->name, type, fnkey,
                            fp->type == FLD_BC_FLOWRATEINLETVELOCITY ? " (massFlowRate is not implemented)" : "");
        UMP_CALL(f1_read(d, fnkey, fp->type == FLD_BC_UNIFORMFIXEDVALUE ? ncomp : 1,
                         fp->type == FLD_BC_UNIFORMFIXEDVALUE ? F1_PATCH : 0u, what, &fp->fn, err));
    }
    /* keep every other key verbatim (written back after type) */
    for (size_t i = 0; i < d->n; i++) {
        const foam_entry *x = &d->e[i];
        if (strcmp(x->key, "type") == 0 || strcmp(x->key, "value") == 0 || (auxkey && strcmp(x->key, auxkey) == 0))
            continue;
        fld_extra *ne = ump_realloc_array(fp->extra, (size_t)fp->nextra + 1, sizeof *fp->extra);
        if (!ne)
            return UMP_FAIL(err, UMP_ERR_NOMEM, "%s: out of memory", te->file);
        fp->extra = ne;
        sbuf text = {0};
        if (x->dict)
            dict_to_text(&text, x->dict);
        else
            tokens_to_text(&text, x->tok, x->ntok);
        ne[fp->nextra].key = ump_strdup(x->key);
        ne[fp->nextra].text = text.failed ? NULL : text.s ? text.s : ump_strdup("");
        if (text.failed)
            free(text.s);
        fp->nextra++;
        if (!ne[fp->nextra - 1].key || !ne[fp->nextra - 1].text)
            return UMP_FAIL(err, UMP_ERR_NOMEM, "%s: out of memory", te->file);
    }
    return UMP_OK;
}

static ump_status read_dimensions(const foam_file *f, fld_field *fld, ump_err *err)
{
    const foam_entry *e = foam_dict_find(f->dict, "dimensions", 0);
    if (!e)
        return UMP_FAIL(err, UMP_ERR_PARSE, "%s: keyword 'dimensions' is undefined", f->path);
    size_t i = 0, n = 0;
    if (e->dict || e->ntok < 2 || e->tok[0].type != FOAM_TOK_PUNCT || e->tok[0].v.punct != '[')
        return UMP_FAIL(err, UMP_ERR_PARSE, "%s:%d: dimensions must be [kg m s K mol A cd]", e->file, e->line);
    for (i = 1; i < e->ntok && n < 7; i++) {
        if (e->tok[i].type == FOAM_TOK_LABEL)
            fld->dims[n++] = (double)e->tok[i].v.label;
        else if (e->tok[i].type == FOAM_TOK_SCALAR)
            fld->dims[n++] = e->tok[i].v.scalar;
        else
            break;
    }
    if ((n != 5 && n != 7) || i >= e->ntok || e->tok[i].type != FOAM_TOK_PUNCT || e->tok[i].v.punct != ']')
        return UMP_FAIL(err, UMP_ERR_PARSE, "%s:%d: dimensions must be 5 or 7 numbers in [ ]",
                        e->file, e->line);
    return UMP_OK;
}

ump_status fio_read_field(const char *path, const pmesh *pm, int ncomp, fld_field **out, ump_err *err)
{
    *out = NULL;
    foam_file *f = NULL;
    UMP_CALL(foam_file_read(path, &f, err));
    const char *want = ncomp == 1 ? "volScalarField" : "volVectorField";
    ump_status rc = UMP_OK;
    fld_field *fld = NULL;
    ump_idx *sizes = NULL;
    if (strcmp(f->class_name, want) != 0) {
        rc = UMP_FAIL(err, UMP_ERR_INPUT, "%s: class is '%s', expected %s", f->path, f->class_name, want);
        goto done;
    }
    sizes = ump_alloc_array((size_t)pm->npatches, sizeof *sizes);
    if (!sizes) {
        rc = UMP_FAIL(err, UMP_ERR_NOMEM, "%s: out of memory", f->path);
        goto done;
    }
    for (int p = 0; p < pm->npatches; p++)
        sizes[p] = pm->patch[p].n;
    const char *name = f->object[0] ? f->object : strrchr(path, '/') ? strrchr(path, '/') + 1 : path;
    if ((rc = fld_create(name, ncomp, pm->ncells, pm->npatches, sizes, &fld, err)) != UMP_OK ||
        (rc = read_dimensions(f, fld, err)) != UMP_OK)
        goto done;
    const foam_entry *ie = foam_dict_find(f->dict, "internalField", 0);
    if (!ie || ie->dict) {
        rc = UMP_FAIL(err, UMP_ERR_PARSE, "%s: keyword 'internalField' is undefined or not a value", f->path);
        goto done;
    }
    size_t pos = 0;
    if ((rc = read_values(ie->tok, ie->ntok, &pos, (size_t)pm->ncells, ncomp, fld->internal, ie->file,
                          "internalField", err)) != UMP_OK)
        goto done;
    const foam_dict *bf = foam_dict_sub(f->dict, "boundaryField");
    if (!bf) {
        rc = UMP_FAIL(err, UMP_ERR_PARSE, "%s: boundaryField dictionary is missing", f->path);
        goto done;
    }
    for (int p = 0; p < pm->npatches && rc == UMP_OK; p++) {
        int implicit_empty;
        const foam_entry *e = match_patch(bf, &pm->patch[p], &implicit_empty);
        if (implicit_empty) {
            fld->patch[p].type = FLD_BC_EMPTY; /* as OpenFOAM: an empty patch may be left out */
            set_default_values(pm, p, ncomp, fld);
        } else if (!e)
            rc = UMP_FAIL(err, UMP_ERR_INPUT, "%s:%d: boundaryField has no entry for patch '%s' (type %s)",
                          f->path, bf->line, pm->patch[p].name, pm->patch[p].type);
        else
            rc = read_patch_entry(e, pm, p, ncomp, fld, err);
    }
done:
    free(sizes);
    foam_file_free(&f);
    if (rc == UMP_OK)
        *out = fld;
    else
        fld_free(&fld);
    return rc;
}
