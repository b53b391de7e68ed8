/* SPDX-License-Identifier: GPL-3.0-or-later
 * function1.c -- OpenFOAM v1912's Function1 (constant, table, sine,
 * square): reading from a FoamFile dictionary, evaluation in time.
 *
 * The reader mirrors v1912's Function1::New (function1.h lists the forms;
 * each was run through the installed v1912 icoFoam to confirm what it
 * accepts and computes). The evaluator is a few arithmetic operations per
 * call and allocates nothing, so a boundary condition evaluates it once per
 * patch and time step.
 */
#include "umppm/function1.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const char *f1_kind_name(f1_kind k)
{
    switch (k) {
    case F1_CONSTANT: return "constant";
    case F1_TABLE: return "table";
    case F1_SINE: return "sine";
    case F1_SQUARE: return "square";
    }
    return "unknown";
}

void f1_free(f1 **pf)
{
    if (!pf || !*pf)
        return;
    f1 *f = *pf;
    free(f->t);
    free(f->v);
    f1_free(&f->amplitude);
    f1_free(&f->frequency);
    f1_free(&f->scale);
    f1_free(&f->level);
    free(f);
    *pf = NULL;
}

/* ---- evaluation ---------------------------------------------------------- */

/* Table: linear interpolation, clamped to the first/last row outside them
 * (v1912's linearInterpolationWeights gives the end value there too). */
static void table_value(const f1 *f, double t, double *out)
{
    size_t n = f->n, nc = (size_t)f->ncomp;
    if (f->bounds == F1_REPEAT && n > 1 && (t < f->t[0] || t > f->t[n - 1])) {
        /* TableBase::checkMin/MaxBounds, REPEAT */
        double span = f->t[n - 1] - f->t[0];
        t = fmod(t - f->t[0], span) + f->t[0];
    }
    if (t <= f->t[0] || n == 1) {
        memcpy(out, f->v, nc * sizeof *out);
        return;
    }
    if (t >= f->t[n - 1]) {
        memcpy(out, f->v + (n - 1) * nc, nc * sizeof *out);
        return;
    }
    /* the row i with t_i <= t < t_{i+1}, by bisection */
    size_t lo = 0, hi = n - 1;
    while (hi - lo > 1) {
        size_t mid = lo + (hi - lo) / 2;
        if (f->t[mid] <= t)
            lo = mid;
        else
            hi = mid;
    }
    double w = (t - f->t[lo]) / (f->t[hi] - f->t[lo]);
    for (size_t k = 0; k < nc; k++)
        out[k] = (1 - w) * f->v[lo * nc + k] + w * f->v[hi * nc + k];
}

void f1_value(const f1 *f, double t, double *out)
{
    switch (f->kind) {
    case F1_CONSTANT:
        memcpy(out, f->value, (size_t)f->ncomp * sizeof *out);
        return;
    case F1_TABLE:
        table_value(f, t, out);
        return;
    case F1_SINE:
    case F1_SQUARE: {
        double a, fr, s[3], l[3], wave;
        f1_value(f->amplitude, t, &a);
        f1_value(f->frequency, t, &fr);
        f1_value(f->scale, t, s);
        f1_value(f->level, t, l);
        if (f->kind == F1_SINE) {
            /* Sine.C: amplitude*sin(twoPi*frequency*(t - t0))*scale + level */
            wave = sin(2 * UMP_PI * fr * (t - f->t0));
        } else {
            /* Square.C: the fraction of the current wave (modf keeps the sign
             * of its argument) against markSpace/(1 + markSpace) */
            double whole, frac = modf(fr * (t - f->t0), &whole);
            wave = frac < f->mark_space / (1.0 + f->mark_space) ? 1.0 : -1.0;
        }
        for (int k = 0; k < f->ncomp; k++)
            out[k] = a * wave * s[k] + l[k];
        return;
    }
    }
}

static double norm(const double *v, int nc)
{
    double s = 0;
    for (int k = 0; k < nc; k++)
        s += v[k] * v[k];
    return sqrt(s);
}

double f1_max_abs(const f1 *f)
{
    switch (f->kind) {
    case F1_CONSTANT:
        return norm(f->value, f->ncomp);
    case F1_TABLE: {
        /* linear interpolation stays inside the rows' values */
        double m = 0;
        for (size_t i = 0; i < f->n; i++)
            m = fmax(m, norm(f->v + i * (size_t)f->ncomp, f->ncomp));
        return m;
    }
    case F1_SINE:
    case F1_SQUARE:
        return f1_max_abs(f->amplitude) * f1_max_abs(f->scale) + f1_max_abs(f->level);
    }
    return 0;
}

/* ---- reading --------------------------------------------------------------- */

static int is_punct(const foam_token *tok, size_t nt, size_t pos, char c)
{
    return pos < nt && tok[pos].type == FOAM_TOK_PUNCT && tok[pos].v.punct == c;
}

/* One value of ncomp components at tok[*pos]: a number, or (x y z). */
static ump_status read_value(const foam_token *tok, size_t nt, size_t *pos, int ncomp, double *out,
                             const char *file, const char *what, ump_err *err)
{
    char w[512], s[128];
    if (ncomp == 1)
        return foam_tok_scalar(tok, nt, pos, out, what, err);
    size_t at = *pos;
    if (!is_punct(tok, nt, *pos, '('))
        return UMP_FAIL(err, UMP_ERR_PARSE, "%s: %s: expected a vector (x y z), found %s",
                        foam_tok_where(tok, nt, at, file, w, sizeof w), what,
                        at < nt ? foam_tok_str(&tok[at], s, sizeof s) : "end of entry");
    (*pos)++;
    for (int k = 0; k < 3; k++)
        UMP_CALL(foam_tok_scalar(tok, nt, pos, &out[k], what, err));
    if (!is_punct(tok, nt, *pos, ')'))
        return UMP_FAIL(err, UMP_ERR_PARSE, "%s: %s: expected a vector of 3 components (x y z)",
                        foam_tok_where(tok, nt, at, file, w, sizeof w), what);
    (*pos)++;
    return UMP_OK;
}

/* Nothing may follow the value of an entry. */
static ump_status expect_end(const foam_token *tok, size_t nt, size_t pos, const char *file, const char *what,
                             ump_err *err)
{
    if (pos >= nt)
        return UMP_OK;
    char w[512], s[128];
    return UMP_FAIL(err, UMP_ERR_PARSE, "%s: %s: unexpected %s after the value",
                    foam_tok_where(tok, nt, pos, file, w, sizeof w), what, foam_tok_str(&tok[pos], s, sizeof s));
}

/* "( (t v) ... )" or "N( ... )": rows into f->t, f->v (TableBase::check:
 * not empty, times strictly increasing). */
static ump_status read_table(const foam_token *tok, size_t nt, size_t *pos, f1 *f, const char *file,
                             const char *what, ump_err *err)
{
    char w[512];
    size_t at = *pos;
    int64_t count = -1;
    if (*pos < nt && tok[*pos].type == FOAM_TOK_LABEL) {
        count = tok[*pos].v.label;
        (*pos)++;
    }
    if (!is_punct(tok, nt, *pos, '('))
        return UMP_FAIL(err, UMP_ERR_PARSE, "%s: %s: expected the table rows ((t0 v0) (t1 v1) ...)",
                        foam_tok_where(tok, nt, at, file, w, sizeof w), what);
    (*pos)++;
    /* rows are at least 4 tokens each: an upper bound before allocating */
    size_t cap = (nt - *pos) / 4 + 1, nc = (size_t)f->ncomp;
    if (!(f->t = ump_alloc_array(cap, sizeof *f->t)) || !(f->v = ump_alloc_array(cap * nc, sizeof *f->v)))
        return UMP_FAIL(err, UMP_ERR_NOMEM, "%s: %s: out of memory", file, what);
    size_t n = 0;
    while (!is_punct(tok, nt, *pos, ')')) {
        size_t row = *pos;
        if (!is_punct(tok, nt, *pos, '(') || n >= cap)
            return UMP_FAIL(err, UMP_ERR_PARSE, "%s: %s: expected a table row (t value) or ')'",
                            foam_tok_where(tok, nt, row, file, w, sizeof w), what);
        (*pos)++;
        UMP_CALL(foam_tok_scalar(tok, nt, pos, &f->t[n], what, err));
        UMP_CALL(read_value(tok, nt, pos, f->ncomp, f->v + n * nc, file, what, err));
        if (!is_punct(tok, nt, *pos, ')'))
            return UMP_FAIL(err, UMP_ERR_PARSE, "%s: %s: a table row is (t value), found more",
                            foam_tok_where(tok, nt, row, file, w, sizeof w), what);
        (*pos)++;
        if (!isfinite(f->t[n]))
            return UMP_FAIL(err, UMP_ERR_INPUT, "%s: %s: table time %g is not a finite number",
                            foam_tok_where(tok, nt, row, file, w, sizeof w), what, f->t[n]);
        if (n > 0 && f->t[n] <= f->t[n - 1])
            return UMP_FAIL(err, UMP_ERR_INPUT, "%s: %s: table times must increase: row %zu has t = %g "
                            "after %g (OpenFOAM: out-of-order value)",
                            foam_tok_where(tok, nt, row, file, w, sizeof w), what, n, f->t[n], f->t[n - 1]);
        n++;
    }
    (*pos)++;
    if (n == 0)
        return UMP_FAIL(err, UMP_ERR_INPUT, "%s: %s: the table is empty (OpenFOAM: invalid (empty))",
                        foam_tok_where(tok, nt, at, file, w, sizeof w), what);
    if (count >= 0 && (size_t)count != n)
        return UMP_FAIL(err, UMP_ERR_PARSE, "%s: %s: the table says %lld rows but has %zu",
                        foam_tok_where(tok, nt, at, file, w, sizeof w), what, (long long)count, n);
    f->n = n;
    return UMP_OK;
}

/* Table options of TableBase, read from coeffs (the dictionary holding the
 * entry, or its <key>Coeffs). */
static ump_status read_table_options(const foam_dict *coeffs, f1 *f, const char *what, ump_err *err)
{
    const char *ob, *is;
    UMP_CALL(foam_get_word_or(coeffs, "outOfBounds", "clamp", &ob, err));
    UMP_CALL(foam_get_word_or(coeffs, "interpolationScheme", "linear", &is, err));
    const foam_entry *e = foam_dict_find(coeffs, "outOfBounds", 0);
    if (strcmp(ob, "clamp") == 0)
        f->bounds = F1_CLAMP;
    else if (strcmp(ob, "repeat") == 0)
        f->bounds = F1_REPEAT;
    else
        return UMP_FAIL(err, UMP_ERR_UNSUPPORTED, "%s:%d: %s: table outOfBounds '%s' is not implemented by "
                        "%s (clamp, the default, or repeat)", e->file, e->line, what, ob, ump_solver);
    if (strcmp(is, "linear") != 0) {
        e = foam_dict_find(coeffs, "interpolationScheme", 0);
        return UMP_FAIL(err, UMP_ERR_UNSUPPORTED, "%s:%d: %s: table interpolationScheme '%s' is not "
                        "implemented by %s (linear, the default)", e->file, e->line, what, is, ump_solver);
    }
    return UMP_OK;
}

/* Nesting limit: `amplitude sine;` without amplitudeCoeffs takes its
 * coefficients from the same dictionary, whose amplitude is that entry
 * again; OpenFOAM recurses until the stack is gone, we stop here. */
#define F1_MAX_DEPTH 8

static ump_status read_f1(const foam_dict *d, const char *key, int ncomp, unsigned flags, const char *what,
                          int depth, f1 **out, ump_err *err);

/* sine and square: coefficients of Sine.C / Square.C. */
static ump_status read_wave(const foam_dict *coeffs, f1 *f, const char *what, int depth, ump_err *err)
{
    const foam_entry *st = foam_dict_find(coeffs, "start", 0);
    if (st)
        return UMP_FAIL(err, UMP_ERR_UNSUPPORTED, "%s:%d: %s: %s: key 'start' is the OpenFOAM Foundation's; "
                        "OpenFOAM v1912 ignores it (its time origin is 't0'): write t0 instead",
                        st->file, st->line, what, f1_kind_name(f->kind));
    UMP_CALL(foam_get_scalar_or(coeffs, "t0", 0.0, &f->t0, err));
    if (f->kind == F1_SQUARE)
        UMP_CALL(foam_get_scalar_or(coeffs, "markSpace", 1.0, &f->mark_space, err));
    static const char *const keys[4] = {"amplitude", "frequency", "scale", "level"};
    f1 **dst[4] = {&f->amplitude, &f->frequency, &f->scale, &f->level};
    for (int k = 0; k < 4; k++) {
        char sub[512];
        snprintf(sub, sizeof sub, "%s: %s %s", what, f1_kind_name(f->kind), keys[k]);
        if (!foam_dict_find(coeffs, keys[k], 0))
            return UMP_FAIL(err, UMP_ERR_INPUT, "%s:%d: %s: %s needs '%s' (OpenFOAM: No Function1 dictionary "
                            "entry: %s)", coeffs->file, coeffs->line, what, f1_kind_name(f->kind), keys[k],
                            keys[k]);
        UMP_CALL(read_f1(coeffs, keys[k], k < 2 ? 1 : f->ncomp, 0, sub, depth + 1, dst[k], err));
    }
    if (!isfinite(f->t0) || !isfinite(f->mark_space) || f->mark_space < 0)
        return UMP_FAIL(err, UMP_ERR_INPUT, "%s:%d: %s: t0 = %g, markSpace = %g: need finite values, "
                        "markSpace >= 0", coeffs->file, coeffs->line, what, f->t0, f->mark_space);
    return UMP_OK;
}

/* The type word w (already known not to be a value) with its coefficient
 * dictionary coeffs. */
static int kind_of(const char *w, f1_kind *k)
{
    if (strcmp(w, "constant") == 0 || strcmp(w, "uniform") == 0)
        *k = F1_CONSTANT;
    else if (strcmp(w, "table") == 0)
        *k = F1_TABLE;
    else if (strcmp(w, "sine") == 0)
        *k = F1_SINE;
    else if (strcmp(w, "square") == 0)
        *k = F1_SQUARE;
    else
        return 0;
    return 1;
}

static ump_status unknown_type(const char *file, int line, const char *what, const char *w, unsigned flags,
                               ump_err *err)
{
    if ((flags & F1_PATCH) && strcmp(w, "nonuniform") == 0)
        return UMP_FAIL(err, UMP_ERR_UNSUPPORTED, "%s:%d: %s: 'nonuniform' (a value per face) is not "
                        "implemented by %s; use fixedValue with a nonuniform value", file, line, what, ump_solver);
    return UMP_FAIL(err, UMP_ERR_UNSUPPORTED, "%s:%d: %s: Function1 type '%s' is not implemented by %s "
                    "(implemented: constant, uniform, table, sine, square, or a bare value)", file, line, what,
                    w, ump_solver);
}

static ump_status read_entry(const foam_dict *d, const char *key, int ncomp, unsigned flags, const char *what,
                             int depth, f1 *f, ump_err *err)
{
    const foam_entry *e = foam_dict_find(d, key, 0);
    if (!e)
        return UMP_FAIL(err, UMP_ERR_INPUT, "%s:%d: %s: keyword '%s' is undefined", d->file, d->line, what, key);
    if (depth > F1_MAX_DEPTH)
        return UMP_FAIL(err, UMP_ERR_INPUT, "%s:%d: %s: Function1s nested more than %d deep (does '%s' refer "
                        "to itself? give it its own %sCoeffs)", e->file, e->line, what, F1_MAX_DEPTH, key, key);
    f->ncomp = ncomp;
    f->mark_space = 1.0;
    if (e->dict) {
        /* key { type ...; coefficients } */
        const char *w;
        UMP_CALL(foam_get_word(e->dict, "type", &w, err));
        if (!kind_of(w, &f->kind))
            return unknown_type(e->file, e->line, what, w, flags, err);
        if (f->kind == F1_CONSTANT || f->kind == F1_TABLE)
            return UMP_FAIL(err, UMP_ERR_INPUT, "%s:%d: %s: OpenFOAM v1912 reads a %s only inline (Entry '%s' "
                            "not found in the dictionary): write '%s %s %s;'", e->file, e->line, what, w, key,
                            key, w, f->kind == F1_TABLE ? "((t0 v0) (t1 v1) ...)" : "value");
        return read_wave(e->dict, f, what, depth, err);
    }
    const foam_token *tok = e->tok;
    size_t nt = e->ntok, pos = 0;
    if (nt == 0)
        return UMP_FAIL(err, UMP_ERR_PARSE, "%s:%d: %s: no value", e->file, e->line, what);
    if (tok[0].type != FOAM_TOK_WORD) { /* a bare value */
        f->kind = F1_CONSTANT;
        UMP_CALL(read_value(tok, nt, &pos, ncomp, f->value, e->file, what, err));
        return expect_end(tok, nt, pos, e->file, what, err);
    }
    const char *w = tok[0].v.str;
    if (!kind_of(w, &f->kind))
        return unknown_type(e->file, e->line, what, w, flags, err);
    pos = 1;
    if (f->kind == F1_CONSTANT) {
        UMP_CALL(read_value(tok, nt, &pos, ncomp, f->value, e->file, what, err));
        return expect_end(tok, nt, pos, e->file, what, err);
    }
    /* Function1::New: the coefficients of `key type;` are <key>Coeffs if
     * present, else the dictionary holding key (optionalSubDict) */
    char ck[256];
    snprintf(ck, sizeof ck, "%sCoeffs", key);
    const foam_dict *coeffs = foam_dict_sub(d, ck);
    if (!coeffs)
        coeffs = d;
    if (f->kind == F1_TABLE) {
        UMP_CALL(read_table(tok, nt, &pos, f, e->file, what, err));
        UMP_CALL(expect_end(tok, nt, pos, e->file, what, err));
        return read_table_options(coeffs, f, what, err);
    }
    UMP_CALL(expect_end(tok, nt, pos, e->file, what, err));
    return read_wave(coeffs, f, what, depth, err);
}

static ump_status read_f1(const foam_dict *d, const char *key, int ncomp, unsigned flags, const char *what,
                          int depth, f1 **out, ump_err *err)
{
    *out = NULL;
    UMP_CHECK(ncomp == 1 || ncomp == 3, err, UMP_ERR_INPUT, "%s: Function1 of %d components", what, ncomp);
    f1 *f = ump_alloc_array(1, sizeof *f);
    if (!f)
        return UMP_FAIL(err, UMP_ERR_NOMEM, "%s: out of memory", what);
    ump_status rc = read_entry(d, key, ncomp, flags, what, depth, f, err);
    if (rc != UMP_OK) {
        f1_free(&f);
        return rc;
    }
    *out = f;
    return UMP_OK;
}

ump_status f1_read(const foam_dict *d, const char *key, int ncomp, unsigned flags, const char *what, f1 **out,
                   ump_err *err)
{
    return read_f1(d, key, ncomp, flags, what, 0, out, err);
}

ump_status f1_copy(const f1 *src, f1 **out, ump_err *err)
{
    *out = NULL;
    if (!src)
        return UMP_OK;
    f1 *f = ump_alloc_array(1, sizeof *f);
    if (!f)
        return UMP_FAIL(err, UMP_ERR_NOMEM, "Function1: out of memory");
    *f = *src;
    f->t = f->v = NULL;
    f->amplitude = f->frequency = f->scale = f->level = NULL;
    ump_status rc = UMP_OK;
    if (src->kind == F1_TABLE) {
        size_t nc = (size_t)src->ncomp;
        if (!(f->t = ump_alloc_array(src->n, sizeof *f->t)) || !(f->v = ump_alloc_array(src->n * nc, sizeof *f->v)))
            rc = UMP_FAIL(err, UMP_ERR_NOMEM, "Function1: out of memory");
        else {
            memcpy(f->t, src->t, src->n * sizeof *f->t);
            memcpy(f->v, src->v, src->n * nc * sizeof *f->v);
        }
    }
    if (rc == UMP_OK && (rc = f1_copy(src->amplitude, &f->amplitude, err)) == UMP_OK &&
        (rc = f1_copy(src->frequency, &f->frequency, err)) == UMP_OK &&
        (rc = f1_copy(src->scale, &f->scale, err)) == UMP_OK)
        rc = f1_copy(src->level, &f->level, err);
    if (rc != UMP_OK) {
        f1_free(&f);
        return rc;
    }
    *out = f;
    return UMP_OK;
}
