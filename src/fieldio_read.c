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
    char *anch = malloc(n + 5);
    if (!anch)
        return 0;
    snprintf(anch, n + 5, "^(%s)$", pattern);
    regex_t re;
    int ok = 0;
    if (regcomp(&re, anch, REG_EXTENDED | REG_NOSUB) == 0) {
        ok = regexec(&re, s, 0, NULL, 0) == 0;
        regfree(&re);
    }
    free(anch);
    return ok;
}

static const foam_entry *match_patch(const foam_dict *bf, const pmesh_patch *p)
{
    for (size_t i = 0; i < bf->n; i++)
        if (!bf->e[i].is_pattern && strcmp(bf->e[i].key, p->name) == 0)
            return &bf->e[i];
    for (size_t i = 0; i < bf->n; i++)
        if (!bf->e[i].is_pattern && pmesh_patch_in_group(p, bf->e[i].key))
            return &bf->e[i];
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

/* Serialise tokens on one line, for keys kept verbatim. */
static void tokens_to_text(const foam_token *t, size_t nt, char *buf, size_t len)
{
    size_t k = 0;
    buf[0] = '\0';
    for (size_t i = 0; i < nt && k + 1 < len; i++) {
        char tmp[256];
        const char *sep = (i == 0) ? "" : " ";
        switch (t[i].type) {
        case FOAM_TOK_PUNCT: snprintf(tmp, sizeof tmp, "%c", t[i].v.punct); break;
        case FOAM_TOK_WORD: snprintf(tmp, sizeof tmp, "%s", t[i].v.str); break;
        case FOAM_TOK_STRING: snprintf(tmp, sizeof tmp, "\"%s\"", t[i].v.str); break;
        case FOAM_TOK_LABEL: snprintf(tmp, sizeof tmp, "%lld", (long long)t[i].v.label); break;
        case FOAM_TOK_SCALAR: snprintf(tmp, sizeof tmp, "%.17g", t[i].v.scalar); break;
        default: snprintf(tmp, sizeof tmp, "%s", "()"); break;
        }
        if (i > 0 && t[i - 1].type == FOAM_TOK_PUNCT && t[i - 1].v.punct == '(')
            sep = "";
        if (t[i].type == FOAM_TOK_PUNCT && t[i].v.punct == ')')
            sep = "";
        k += (size_t)snprintf(buf + k, len - k, "%s%s", sep, tmp);
        if (k >= len)
            k = len - 1;
    }
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
        char list[512] = "";
        for (int k = 0; k < FLD_BC_NTYPES; k++) {
            strncat(list, k ? " " : "", sizeof list - strlen(list) - 1);
            strncat(list, fld_bc_name((fld_bc_type)k), sizeof list - strlen(list) - 1);
        }
        return UMP_FAIL(err, UMP_ERR_UNSUPPORTED,
                        "%s:%d: patch '%s': boundary condition type '%s' is not supported by umppmFoam "
                        "(supported: %s)", te->file, te->line, pp->name, type, list);
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
    /* default face values: the adjacent cell values (zero for noSlip) */
    for (size_t i = 0; i < n; i++)
        for (size_t k = 0; k < nc; k++)
            fp->value[i * nc + k] = fp->type == FLD_BC_NOSLIP
                                        ? 0.0 : fld->internal[(size_t)pm->owner[pp->start + (ump_idx)i] * nc + k];
    int need_value = fp->type == FLD_BC_FIXEDVALUE || fp->type == FLD_BC_MOVINGWALLVELOCITY ||
                     fp->type == FLD_BC_CALCULATED;
    const char *auxkey = fp->type == FLD_BC_INLETOUTLET ? "inletValue"
                         : fp->type == FLD_BC_FIXEDFLUXPRESSURE ? "gradient" : NULL;
    if (fp->type == FLD_BC_NOSLIP && ncomp != 3)
        return UMP_FAIL(err, UMP_ERR_INPUT, "%s:%d: patch '%s': noSlip applies to vector fields only",
                        te->file, te->line, pp->name);
    const foam_entry *ve = foam_dict_find(d, "value", 0);
    if (need_value && !ve)
        return UMP_FAIL(err, UMP_ERR_INPUT, "%s:%d: patch '%s': type %s needs a 'value' entry",
                        te->file, te->line, pp->name, type);
    int use_value = ve && fp->type != FLD_BC_EMPTY && fp->type != FLD_BC_NOSLIP &&
                    fp->type != FLD_BC_ZEROGRADIENT && fp->type != FLD_BC_CYCLIC &&
                    fp->type != FLD_BC_SYMMETRYPLANE && fp->type != FLD_BC_SYMMETRY;
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
        if (fp->type == FLD_BC_INLETOUTLET && !ae)
            return UMP_FAIL(err, UMP_ERR_INPUT, "%s:%d: patch '%s': inletOutlet needs an 'inletValue' entry",
                            te->file, te->line, pp->name);
        fp->aux = ump_alloc_array(n * nc, sizeof *fp->aux);
        if (!fp->aux)
            return UMP_FAIL(err, UMP_ERR_NOMEM, "%s: out of memory", te->file);
        if (ae) {
            if (ae->dict)
                return UMP_FAIL(err, UMP_ERR_PARSE, "%s:%d: patch '%s': %s must be uniform/nonuniform",
                                ae->file, ae->line, pp->name, auxkey);
            size_t pos = 0;
            UMP_CALL(read_values(ae->tok, ae->ntok, &pos, n, ncomp, fp->aux, ae->file, auxkey, err));
        }
    }
    /* keep every other key verbatim */
    for (size_t i = 0; i < d->n; i++) {
        const foam_entry *x = &d->e[i];
        if (strcmp(x->key, "type") == 0 || strcmp(x->key, "value") == 0 ||
            (auxkey && strcmp(x->key, auxkey) == 0) || x->dict)
            continue;
        fld_extra *ne = ump_realloc_array(fp->extra, (size_t)fp->nextra + 1, sizeof *fp->extra);
        if (!ne)
            return UMP_FAIL(err, UMP_ERR_NOMEM, "%s: out of memory", te->file);
        fp->extra = ne;
        char text[1024];
        tokens_to_text(x->tok, x->ntok, text, sizeof text);
        ne[fp->nextra].key = ump_strdup(x->key);
        ne[fp->nextra].text = ump_strdup(text);
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
        const foam_entry *e = match_patch(bf, &pm->patch[p]);
        if (!e)
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
