/* SPDX-License-Identifier: GPL-3.0-or-later
 * foam_get.c -- dictionary look-up, typed getters and decoders of token
 * streams (lists in every ASCII form OpenFOAM writes, and binary blobs).
 *
 * Decoders never trust a count before checking it against the tokens that
 * are really there, so a wrong "N(" cannot make them allocate or read past
 * the end.
 */
#include "foam_internal.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- look-up ------------------------------------------------------------------ */

const foam_entry *foam_dict_find(const foam_dict *d, const char *key, int recursive)
{
    if (!key)
        return NULL;
    for (; d; d = recursive ? d->parent : NULL) {
        for (size_t i = 0; i < d->n; i++)
            if (strcmp(d->e[i].key, key) == 0)
                return &d->e[i];
        /* patterns: the latest definition wins, as in OpenFOAM */
        for (size_t i = d->n; i-- > 0;)
            if (d->e[i].is_pattern && foam_entry_match(&d->e[i], key))
                return &d->e[i];
    }
    return NULL;
}

const foam_dict *foam_dict_sub(const foam_dict *d, const char *key)
{
    const foam_entry *e = foam_dict_find(d, key, 0);
    return e ? e->dict : NULL;
}

const char *foam_dict_path(const foam_dict *d, char *buf, size_t len)
{
    if (!buf || len == 0)
        return buf;
    buf[0] = '\0';
    if (!d)
        return buf;
    /* collect names from the leaf up, then write them root first */
    const foam_dict *chain[64];
    int n = 0;
    for (const foam_dict *q = d; q && q->parent && n < 64; q = q->parent)
        chain[n++] = q;
    size_t o = 0;
    for (int i = n - 1; i >= 0; i--) {
        int w = snprintf(buf + o, len - o, "%s%s", o ? "/" : "", chain[i]->name);
        if (w < 0 || (size_t)w >= len - o)
            break;
        o += (size_t)w;
    }
    return buf;
}

/* ---- token printing ------------------------------------------------------------------ */

const char *foam_tok_str(const foam_token *t, char *buf, size_t len)
{
    if (!buf || len == 0)
        return "";
    if (!t) {
        snprintf(buf, len, "end of input");
        return buf;
    }
    switch (t->type) {
    case FOAM_TOK_PUNCT:
        if (t->v.punct == 0)
            snprintf(buf, len, "end of input");
        else
            snprintf(buf, len, "'%c'", t->v.punct);
        break;
    case FOAM_TOK_WORD:
        snprintf(buf, len, "word '%.60s%s'", t->v.str, strlen(t->v.str) > 60 ? "..." : "");
        break;
    case FOAM_TOK_STRING:
        snprintf(buf, len, "string \"%.60s%s\"", t->v.str, strlen(t->v.str) > 60 ? "..." : "");
        break;
    case FOAM_TOK_LABEL:
        snprintf(buf, len, "label %lld", (long long)t->v.label);
        break;
    case FOAM_TOK_SCALAR:
        snprintf(buf, len, "scalar %.17g", t->v.scalar);
        break;
    case FOAM_TOK_BLOB:
        snprintf(buf, len, "binary list of %zu %s", t->v.blob.n,
                 t->v.blob.is_label ? "labels" : t->v.blob.ncomp == 1 ? "scalars" : "tuples");
        break;
    case FOAM_TOK_DICT:
        snprintf(buf, len, "dictionary '%s'", t->v.dict && t->v.dict->name ? t->v.dict->name : "");
        break;
    default:
        snprintf(buf, len, "token of unknown type");
        break;
    }
    for (char *c = buf; *c; c++)
        if ((unsigned char)*c < 32 || *c == 127)
            *c = ' ';
    return buf;
}

const char *foam_tok_where(const foam_token *tok, size_t nt, size_t pos,
                           const char *fallback_file, char *buf, size_t len)
{
    if (!buf || len == 0)
        return "";
    if (tok && pos < nt)
        snprintf(buf, len, "%s:%d", tok[pos].file ? tok[pos].file : "?", tok[pos].line);
    else if (fallback_file)
        snprintf(buf, len, "%s", fallback_file);
    else if (tok && nt > 0)
        snprintf(buf, len, "%s", tok[nt - 1].file ? tok[nt - 1].file : "?");
    else
        snprintf(buf, len, "(input)");
    return buf;
}

/* "<where>: <what>: expected X, found <token>" */
static ump_status fail_at(ump_err *err, ump_status code, const foam_token *tok, size_t nt,
                          size_t pos, const char *what, const char *expected)
{
    char w[512], t[128];
    foam_tok_where(tok, nt, pos, NULL, w, sizeof w);
    if (pos < nt)
        foam_tok_str(&tok[pos], t, sizeof t);
    else if (nt > 0)
        snprintf(t, sizeof t, "end of entry (after line %d)", tok[nt - 1].line);
    else
        snprintf(t, sizeof t, "nothing");
    return FOAM_FAIL(err, code, "%s: %s: expected %s, found %s", w, what ? what : "value",
                    expected, t);
}

static int is_punct(const foam_token *tok, size_t nt, size_t pos, char c)
{
    return pos < nt && tok[pos].type == FOAM_TOK_PUNCT && tok[pos].v.punct == c;
}

/* A word that strtod reads whole: nan, inf, infinity (any case). */
static int word_number(const char *s, double *v)
{
    char *end;
    if (!s[0])
        return 0;
    double d = strtod(s, &end);
    if (*end)
        return 0;
    *v = d;
    return 1;
}

/* One number at *pos: label, scalar, or nan/inf written as a word, with an
 * optional '-' before the word (ISstream splits "-inf"). */
static int read_number(const foam_token *tok, size_t nt, size_t *pos, double *v)
{
    size_t i = *pos;
    if (i >= nt)
        return 0;
    const foam_token *t = &tok[i];
    if (t->type == FOAM_TOK_LABEL) {
        *v = (double)t->v.label;
    } else if (t->type == FOAM_TOK_SCALAR) {
        *v = t->v.scalar;
    } else if (t->type == FOAM_TOK_WORD && word_number(t->v.str, v)) {
        /* nan / inf */
    } else if (t->type == FOAM_TOK_PUNCT && t->v.punct == '-' && i + 1 < nt &&
               tok[i + 1].type == FOAM_TOK_WORD && word_number(tok[i + 1].v.str, v)) {
        *v = -*v;
        i++;
    } else {
        return 0;
    }
    *pos = i + 1;
    return 1;
}

ump_status foam_tok_scalar(const foam_token *tok, size_t nt, size_t *pos, double *out,
                           const char *what, ump_err *err)
{
    if (!read_number(tok, nt, pos, out))
        return fail_at(err, UMP_ERR_PARSE, tok, nt, *pos, what, "a number");
    return UMP_OK;
}

static int read_label(const foam_token *tok, size_t nt, size_t pos, int64_t *v)
{
    if (pos >= nt || tok[pos].type != FOAM_TOK_LABEL)
        return 0;
    *v = tok[pos].v.label;
    return 1;
}

/* ---- growable buffers ---------------------------------------------------------- */

typedef struct dvec { double *v; size_t n, cap; } dvec;
typedef struct ivec { ump_idx *v; size_t n, cap; } ivec;

static int dvec_reserve(dvec *d, size_t extra)
{
    if (extra <= d->cap - d->n)
        return 1;
    if (extra > SIZE_MAX / 2 - d->n)
        return 0;
    size_t nc = d->cap ? d->cap : 16;
    while (nc - d->n < extra)
        nc *= 2;
    double *nv = ump_realloc_array(d->v, nc, sizeof *nv);
    if (!nv)
        return 0;
    d->v = nv;
    d->cap = nc;
    return 1;
}

static int ivec_reserve(ivec *d, size_t extra)
{
    if (extra <= d->cap - d->n)
        return 1;
    if (extra > SIZE_MAX / 2 - d->n)
        return 0;
    size_t nc = d->cap ? d->cap : 16;
    while (nc - d->n < extra)
        nc *= 2;
    ump_idx *nv = ump_realloc_array(d->v, nc, sizeof *nv);
    if (!nv)
        return 0;
    d->v = nv;
    d->cap = nc;
    return 1;
}

static ump_status nomem_at(ump_err *err, const foam_token *tok, size_t nt, size_t pos,
                           const char *what)
{
    char w[512];
    foam_tok_where(tok, nt, pos, NULL, w, sizeof w);
    return FOAM_FAIL(err, UMP_ERR_NOMEM, "%s: %s: out of memory", w, what ? what : "list");
}

/* ---- list headers ------------------------------------------------------------- */

typedef enum { L_BLOB, L_PAREN, L_UNIFORM, L_EMPTY } list_kind;

/* Recognise the start of a list at *pos: N( ... ), N{ v }, ( ... ), blob, or
 * a lone 0 (binary writers emit "nonuniform 0;"). After it *pos is past
 * "N(" / "N{" / "(" / the blob / the 0. count is -1 when not given. */
static ump_status list_start(const foam_token *tok, size_t nt, size_t *pos, list_kind *kind,
                             int64_t *count, const char *what, ump_err *err)
{
    size_t i = *pos;
    if (i < nt && tok[i].type == FOAM_TOK_BLOB) {
        *kind = L_BLOB;
        *count = (int64_t)tok[i].v.blob.n;
        return UMP_OK;
    }
    if (is_punct(tok, nt, i, '(')) {
        *kind = L_PAREN;
        *count = -1;
        *pos = i + 1;
        return UMP_OK;
    }
    int64_t n;
    if (read_label(tok, nt, i, &n)) {
        if (n < 0 || n > UMP_IDX_MAX) {
            char m[96];
            snprintf(m, sizeof m, "a list size between 0 and %d", UMP_IDX_MAX);
            return fail_at(err, UMP_ERR_INPUT, tok, nt, i, what, m);
        }
        *count = n;
        if (is_punct(tok, nt, i + 1, '(')) {
            *kind = L_PAREN;
            *pos = i + 2;
            return UMP_OK;
        }
        if (is_punct(tok, nt, i + 1, '{')) {
            *kind = L_UNIFORM;
            *pos = i + 2;
            return UMP_OK;
        }
        if (n == 0) {
            *kind = L_EMPTY;
            *pos = i + 1;
            return UMP_OK;
        }
        return fail_at(err, UMP_ERR_PARSE, tok, nt, i + 1, what,
                       "'(' or '{' after the list size");
    }
    return fail_at(err, UMP_ERR_PARSE, tok, nt, i, what, "a list: N(...), N{...} or (...)");
}

/* A list ended before its count: say how many items were found. */
static ump_status short_list(const foam_token *tok, size_t nt, size_t pos, const char *what,
                             int64_t count, size_t got, ump_err *err)
{
    char m[128];
    snprintf(m, sizeof m, "%lld items (only %zu given)", (long long)count, got);
    return fail_at(err, UMP_ERR_PARSE, tok, nt, pos, what, m);
}

/* One element of ncomp numbers: a number, or (c1 .. cn). */
static ump_status read_tuple(const foam_token *tok, size_t nt, size_t *pos, int ncomp,
                             double *dst, const char *what, ump_err *err)
{
    if (ncomp == 1)
        return foam_tok_scalar(tok, nt, pos, dst, what, err);
    if (!is_punct(tok, nt, *pos, '('))
        return fail_at(err, UMP_ERR_PARSE, tok, nt, *pos, what, "'(' starting a tuple");
    (*pos)++;
    for (int c = 0; c < ncomp; c++)
        if (!read_number(tok, nt, pos, &dst[c])) {
            char m[64];
            snprintf(m, sizeof m, "%d numbers in (...)", ncomp);
            return fail_at(err, UMP_ERR_PARSE, tok, nt, *pos, what, m);
        }
    if (!is_punct(tok, nt, *pos, ')'))
        return fail_at(err, UMP_ERR_PARSE, tok, nt, *pos, what, "')' closing a tuple");
    (*pos)++;
    return UMP_OK;
}

/* Append a list of ncomp-tuples at *pos to out. */
static ump_status scalars_into(const foam_token *tok, size_t nt, size_t *pos, int ncomp,
                               dvec *out, size_t *nelem, const char *what, ump_err *err)
{
    list_kind kind;
    int64_t count;
    size_t start = *pos;
    UMP_CALL(list_start(tok, nt, pos, &kind, &count, what, err));
    size_t nc = (size_t)ncomp;
    if (kind == L_BLOB) {
        const foam_blob *b = &tok[*pos].v.blob;
        if (b->ncomp != ncomp) {
            char m[64];
            snprintf(m, sizeof m, "a list of %d-component items", ncomp);
            return fail_at(err, UMP_ERR_PARSE, tok, nt, *pos, what, m);
        }
        if (b->n > (size_t)UMP_IDX_MAX || !dvec_reserve(out, b->n * nc))
            return nomem_at(err, tok, nt, *pos, what);
        size_t m = b->n * nc;
        if (b->is_label) {
            const int64_t *s = b->data;
            for (size_t k = 0; k < m; k++)
                out->v[out->n + k] = (double)s[k];
        } else if (m) {
            memcpy(out->v + out->n, b->data, m * sizeof(double));
        }
        out->n += m;
        *nelem = b->n;
        (*pos)++;
        return UMP_OK;
    }
    if (kind == L_EMPTY) {
        *nelem = 0;
        return UMP_OK;
    }
    if (kind == L_UNIFORM) {
        double v[9];
        UMP_CALL(read_tuple(tok, nt, pos, ncomp, v, what, err));
        if (!is_punct(tok, nt, *pos, '}'))
            return fail_at(err, UMP_ERR_PARSE, tok, nt, *pos, what, "'}' closing N{...}");
        (*pos)++;
        if (!dvec_reserve(out, (size_t)count * nc))
            return nomem_at(err, tok, nt, start, what);
        for (int64_t k = 0; k < count; k++)
            for (size_t c = 0; c < nc; c++)
                out->v[out->n++] = v[c];
        *nelem = (size_t)count;
        return UMP_OK;
    }
    /* N( ... ) or ( ... ): never reserve more than the tokens can hold */
    size_t per = ncomp == 1 ? 1 : nc + 2;
    if (count >= 0) {
        size_t avail = (nt - *pos) / per;
        if ((uint64_t)count > avail) {
            /* find where it really ends for the message */
            size_t got = 0, q = *pos;
            double tmp[9];
            ump_err e2;
            while (got < avail && read_tuple(tok, nt, &q, ncomp, tmp, what, &e2) == UMP_OK)
                got++;
            return short_list(tok, nt, q, what, count, got, err);
        }
        if (!dvec_reserve(out, (size_t)count * nc))
            return nomem_at(err, tok, nt, start, what);
    }
    size_t got = 0;
    for (;;) {
        if (is_punct(tok, nt, *pos, ')')) {
            if (count >= 0 && got < (size_t)count)
                return short_list(tok, nt, *pos, what, count, got, err);
            (*pos)++;
            break;
        }
        if (count >= 0 && got == (size_t)count) {
            char m[96];
            snprintf(m, sizeof m, "')' after %lld items", (long long)count);
            return fail_at(err, UMP_ERR_PARSE, tok, nt, *pos, what, m);
        }
        if (*pos >= nt)
            return fail_at(err, UMP_ERR_PARSE, tok, nt, *pos, what, "')' closing the list");
        if (count < 0 && (got >= (size_t)UMP_IDX_MAX || !dvec_reserve(out, nc)))
            return nomem_at(err, tok, nt, *pos, what);
        UMP_CALL(read_tuple(tok, nt, pos, ncomp, out->v + out->n, what, err));
        out->n += nc;
        got++;
    }
    *nelem = got;
    return UMP_OK;
}

ump_status foam_tok_scalar_list(const foam_token *tok, size_t nt, size_t *pos, int ncomp,
                                double **out, size_t *n, const char *what, ump_err *err)
{
    *out = NULL;
    *n = 0;
    if (ncomp < 1 || ncomp > 9)
        return FOAM_FAIL(err, UMP_ERR_INPUT, "%s: bad component count %d", what ? what : "list",
                        ncomp);
    dvec d = {0};
    size_t p = *pos, ne = 0;
    ump_status rc = scalars_into(tok, nt, &p, ncomp, &d, &ne, what, err);
    if (rc != UMP_OK) {
        free(d.v);
        return rc;
    }
    if (!d.v) {
        d.v = ump_alloc_array(0, sizeof(double));
        if (!d.v)
            return nomem_at(err, tok, nt, *pos, what);
    }
    *out = d.v;
    *n = ne;
    *pos = p;
    return UMP_OK;
}

/* ---- label lists ---------------------------------------------------------------- */

static ump_status label_fits(const foam_token *tok, size_t nt, size_t pos, int64_t v,
                             const char *what, ump_err *err)
{
    if (v < INT32_MIN || v > UMP_IDX_MAX) {
        char w[512];
        foam_tok_where(tok, nt, pos, NULL, w, sizeof w);
        return FOAM_FAIL(err, UMP_ERR_INPUT, "%s: %s: label %lld out of range", w,
                        what ? what : "list", (long long)v);
    }
    return UMP_OK;
}

static ump_status one_label(const foam_token *tok, size_t nt, size_t *pos, ump_idx *dst,
                            const char *what, ump_err *err)
{
    int64_t v;
    if (!read_label(tok, nt, *pos, &v))
        return fail_at(err, UMP_ERR_PARSE, tok, nt, *pos, what, "a label");
    UMP_CALL(label_fits(tok, nt, *pos, v, what, err));
    *dst = (ump_idx)v;
    (*pos)++;
    return UMP_OK;
}

static ump_status labels_into(const foam_token *tok, size_t nt, size_t *pos, ivec *out,
                              size_t *nelem, const char *what, ump_err *err)
{
    list_kind kind;
    int64_t count;
    size_t start = *pos;
    UMP_CALL(list_start(tok, nt, pos, &kind, &count, what, err));
    if (kind == L_BLOB) {
        const foam_blob *b = &tok[*pos].v.blob;
        if (!b->is_label || b->ncomp != 1)
            return fail_at(err, UMP_ERR_PARSE, tok, nt, *pos, what, "a list of labels");
        if (b->n > (size_t)UMP_IDX_MAX || !ivec_reserve(out, b->n))
            return nomem_at(err, tok, nt, *pos, what);
        const int64_t *s = b->data;
        for (size_t k = 0; k < b->n; k++) {
            UMP_CALL(label_fits(tok, nt, *pos, s[k], what, err));
            out->v[out->n++] = (ump_idx)s[k];
        }
        *nelem = b->n;
        (*pos)++;
        return UMP_OK;
    }
    if (kind == L_EMPTY) {
        *nelem = 0;
        return UMP_OK;
    }
    if (kind == L_UNIFORM) {
        ump_idx v;
        UMP_CALL(one_label(tok, nt, pos, &v, what, err));
        if (!is_punct(tok, nt, *pos, '}'))
            return fail_at(err, UMP_ERR_PARSE, tok, nt, *pos, what, "'}' closing N{...}");
        (*pos)++;
        if (!ivec_reserve(out, (size_t)count))
            return nomem_at(err, tok, nt, start, what);
        for (int64_t k = 0; k < count; k++)
            out->v[out->n++] = v;
        *nelem = (size_t)count;
        return UMP_OK;
    }
    if (count >= 0) {
        if ((uint64_t)count > nt - *pos) {
            size_t got = 0, q = *pos;
            while (q < nt && tok[q].type == FOAM_TOK_LABEL) {
                q++;
                got++;
            }
            return short_list(tok, nt, q, what, count, got, err);
        }
        if (!ivec_reserve(out, (size_t)count))
            return nomem_at(err, tok, nt, start, what);
    }
    size_t got = 0;
    for (;;) {
        if (is_punct(tok, nt, *pos, ')')) {
            if (count >= 0 && got < (size_t)count)
                return short_list(tok, nt, *pos, what, count, got, err);
            (*pos)++;
            break;
        }
        if (count >= 0 && got == (size_t)count) {
            char m[96];
            snprintf(m, sizeof m, "')' after %lld items", (long long)count);
            return fail_at(err, UMP_ERR_PARSE, tok, nt, *pos, what, m);
        }
        if (*pos >= nt)
            return fail_at(err, UMP_ERR_PARSE, tok, nt, *pos, what, "')' closing the list");
        if (count < 0 && (got >= (size_t)UMP_IDX_MAX || !ivec_reserve(out, 1)))
            return nomem_at(err, tok, nt, *pos, what);
        UMP_CALL(one_label(tok, nt, pos, out->v + out->n, what, err));
        out->n++;
        got++;
    }
    *nelem = got;
    return UMP_OK;
}

ump_status foam_tok_label_list(const foam_token *tok, size_t nt, size_t *pos, ump_idx **out,
                               size_t *n, const char *what, ump_err *err)
{
    *out = NULL;
    *n = 0;
    ivec v = {0};
    size_t p = *pos, ne = 0;
    ump_status rc = labels_into(tok, nt, &p, &v, &ne, what, err);
    if (rc != UMP_OK) {
        free(v.v);
        return rc;
    }
    if (!v.v) {
        v.v = ump_alloc_array(0, sizeof(ump_idx));
        if (!v.v)
            return nomem_at(err, tok, nt, *pos, what);
    }
    *out = v.v;
    *n = ne;
    *pos = p;
    return UMP_OK;
}

/* Compact form: offsets (n+1, from 0, non-decreasing) then items. */
static ump_status compact_lists(const foam_token *tok, size_t nt, size_t *pos, ump_idx **offs,
                                ump_idx **items, size_t *n, const char *what, ump_err *err)
{
    size_t p = *pos, no = 0, ni = 0;
    ump_idx *o = NULL, *it = NULL;
    ump_status rc = foam_tok_label_list(tok, nt, &p, &o, &no, what, err);
    if (rc != UMP_OK)
        return rc;
    size_t p2 = p;
    rc = foam_tok_label_list(tok, nt, &p2, &it, &ni, what, err);
    if (rc != UMP_OK) {
        free(o);
        return rc;
    }
    const char *bad = NULL;
    if (no == 0)
        bad = "at least one offset";
    else if (o[0] != 0)
        bad = "offsets starting at 0";
    for (size_t k = 1; !bad && k < no; k++)
        if (o[k] < o[k - 1])
            bad = "non-decreasing offsets";
    if (!bad && (size_t)o[no - 1] != ni)
        bad = "the last offset to equal the number of items";
    if (bad) {
        free(o);
        free(it);
        char w[512];
        foam_tok_where(tok, nt, *pos, NULL, w, sizeof w);
        return FOAM_FAIL(err, UMP_ERR_INPUT, "%s: %s: compact list: expected %s", w,
                        what ? what : "list", bad);
    }
    *offs = o;
    *items = it;
    *n = no - 1;
    *pos = p2;
    return UMP_OK;
}

ump_status foam_tok_labellist_list(const foam_token *tok, size_t nt, size_t *pos,
                                   ump_idx **offs, ump_idx **items, size_t *n,
                                   const char *what, ump_err *err)
{
    *offs = NULL;
    *items = NULL;
    *n = 0;
    size_t p = *pos;
    if (p < nt && tok[p].type == FOAM_TOK_BLOB)
        return compact_lists(tok, nt, pos, offs, items, n, what, err);
    list_kind kind;
    int64_t count;
    UMP_CALL(list_start(tok, nt, &p, &kind, &count, what, err));
    if (kind == L_UNIFORM)
        return fail_at(err, UMP_ERR_UNSUPPORTED, tok, nt, p - 1, what,
                       "'(' (uniform lists of lists are not supported)");
    /* ASCII compact form: the outer list holds plain labels */
    if (kind == L_PAREN && p < nt && tok[p].type == FOAM_TOK_LABEL &&
        (is_punct(tok, nt, p + 1, ')') || (p + 1 < nt && tok[p + 1].type == FOAM_TOK_LABEL)))
        return compact_lists(tok, nt, pos, offs, items, n, what, err);
    ivec o = {0}, it = {0};
    ump_status rc = UMP_OK;
    size_t got = 0;
    if (count >= 0 && kind == L_PAREN && (uint64_t)count > nt - p) {
        rc = short_list(tok, nt, nt, what, count, 0, err);
        goto fail;
    }
    if (!ivec_reserve(&o, count > 0 ? (size_t)count + 1 : 16)) {
        rc = nomem_at(err, tok, nt, p, what);
        goto fail;
    }
    o.v[o.n++] = 0;
    if (kind == L_PAREN) {
        for (;;) {
            if (is_punct(tok, nt, p, ')')) {
                if (count >= 0 && got < (size_t)count) {
                    rc = short_list(tok, nt, p, what, count, got, err);
                    goto fail;
                }
                p++;
                break;
            }
            if (count >= 0 && got == (size_t)count) {
                char m[96];
                snprintf(m, sizeof m, "')' after %lld lists", (long long)count);
                rc = fail_at(err, UMP_ERR_PARSE, tok, nt, p, what, m);
                goto fail;
            }
            if (p >= nt) {
                rc = fail_at(err, UMP_ERR_PARSE, tok, nt, p, what, "')' closing the list");
                goto fail;
            }
            size_t ne;
            rc = labels_into(tok, nt, &p, &it, &ne, what, err);
            if (rc != UMP_OK)
                goto fail;
            if (it.n > (size_t)UMP_IDX_MAX || got >= (size_t)UMP_IDX_MAX ||
                !ivec_reserve(&o, 1)) {
                rc = nomem_at(err, tok, nt, p, what);
                goto fail;
            }
            o.v[o.n++] = (ump_idx)it.n;
            got++;
        }
    }
    if (!it.v && !(it.v = ump_alloc_array(0, sizeof(ump_idx)))) {
        rc = nomem_at(err, tok, nt, p, what);
        goto fail;
    }
    *offs = o.v;
    *items = it.v;
    *n = got;
    *pos = p;
    return UMP_OK;
fail:
    free(o.v);
    free(it.v);
    return rc;
}

/* ---- typed getters ------------------------------------------------------------- */

static ump_status missing(const foam_dict *d, const char *key, ump_err *err)
{
    char path[512];
    foam_dict_path(d, path, sizeof path);
    return FOAM_FAIL(err, UMP_ERR_INPUT, "%s:%d: keyword '%s' is missing in %s%s%s",
                    d && d->file ? d->file : "?", d ? d->line : 0, key,
                    path[0] ? "dictionary '" : "the top-level dictionary", path,
                    path[0] ? "'" : "");
}

/* The primitive entry for key, or an error; *e NULL when absent. */
static ump_status primitive(const foam_dict *d, const char *key, const foam_entry **e,
                            ump_err *err)
{
    *e = foam_dict_find(d, key, 0);
    if (*e && (*e)->dict)
        return FOAM_FAIL(err, UMP_ERR_PARSE, "%s:%d: keyword '%s': expected a value, found a "
                        "dictionary", (*e)->file, (*e)->line, key);
    return UMP_OK;
}

static ump_status entry_error(const foam_entry *e, const char *key, const char *expected,
                              ump_err *err)
{
    char t[128];
    if (e->ntok == 0)
        snprintf(t, sizeof t, "nothing");
    else
        foam_tok_str(&e->tok[0], t, sizeof t);
    return FOAM_FAIL(err, UMP_ERR_PARSE, "%s:%d: keyword '%s': expected %s, found %s%s", e->file,
                    e->line, key, expected, t, e->ntok > 1 ? " ..." : "");
}

static ump_status scalar_of(const foam_entry *e, const char *key, double *out, ump_err *err)
{
    size_t p = 0;
    double v;
    if (!read_number(e->tok, e->ntok, &p, &v) || p != e->ntok)
        return entry_error(e, key, "one number", err);
    *out = v;
    return UMP_OK;
}

ump_status foam_get_scalar(const foam_dict *d, const char *key, double *out, ump_err *err)
{
    const foam_entry *e;
    UMP_CALL(primitive(d, key, &e, err));
    if (!e)
        return missing(d, key, err);
    return scalar_of(e, key, out, err);
}

ump_status foam_get_scalar_or(const foam_dict *d, const char *key, double dflt, double *out,
                              ump_err *err)
{
    const foam_entry *e;
    UMP_CALL(primitive(d, key, &e, err));
    if (!e) {
        *out = dflt;
        return UMP_OK;
    }
    return scalar_of(e, key, out, err);
}

static ump_status label_of(const foam_entry *e, const char *key, int64_t *out, ump_err *err)
{
    if (e->ntok != 1 || e->tok[0].type != FOAM_TOK_LABEL)
        return entry_error(e, key, "one integer", err);
    *out = e->tok[0].v.label;
    return UMP_OK;
}

ump_status foam_get_label(const foam_dict *d, const char *key, int64_t *out, ump_err *err)
{
    const foam_entry *e;
    UMP_CALL(primitive(d, key, &e, err));
    if (!e)
        return missing(d, key, err);
    return label_of(e, key, out, err);
}

ump_status foam_get_label_or(const foam_dict *d, const char *key, int64_t dflt, int64_t *out,
                             ump_err *err)
{
    const foam_entry *e;
    UMP_CALL(primitive(d, key, &e, err));
    if (!e) {
        *out = dflt;
        return UMP_OK;
    }
    return label_of(e, key, out, err);
}

static ump_status word_of(const foam_entry *e, const char *key, const char **out, ump_err *err)
{
    if (e->ntok != 1 || (e->tok[0].type != FOAM_TOK_WORD && e->tok[0].type != FOAM_TOK_STRING))
        return entry_error(e, key, "one word", err);
    *out = e->tok[0].v.str;
    return UMP_OK;
}

ump_status foam_get_word(const foam_dict *d, const char *key, const char **out, ump_err *err)
{
    const foam_entry *e;
    UMP_CALL(primitive(d, key, &e, err));
    if (!e)
        return missing(d, key, err);
    return word_of(e, key, out, err);
}

ump_status foam_get_word_or(const foam_dict *d, const char *key, const char *dflt,
                            const char **out, ump_err *err)
{
    const foam_entry *e;
    UMP_CALL(primitive(d, key, &e, err));
    if (!e) {
        *out = dflt;
        return UMP_OK;
    }
    return word_of(e, key, out, err);
}

int foam_switch_value(const char *w)
{
    static const struct { const char *w; int v; } sw[] = {
        {"yes", 1}, {"no", 0}, {"on", 1}, {"off", 0}, {"true", 1}, {"false", 0},
        {"y", 1},   {"n", 0},  {"t", 1},  {"f", 0},   {"none", 0},
    };
    for (size_t i = 0; i < sizeof sw / sizeof sw[0]; i++)
        if (strcmp(w, sw[i].w) == 0)
            return sw[i].v;
    return -1;
}

ump_status foam_get_bool_or(const foam_dict *d, const char *key, int dflt, int *out,
                            ump_err *err)
{
    const foam_entry *e;
    UMP_CALL(primitive(d, key, &e, err));
    if (!e) {
        *out = dflt;
        return UMP_OK;
    }
    if (e->ntok == 1 && e->tok[0].type == FOAM_TOK_LABEL &&
        (e->tok[0].v.label == 0 || e->tok[0].v.label == 1)) {
        *out = (int)e->tok[0].v.label;
        return UMP_OK;
    }
    int v = e->ntok == 1 && e->tok[0].type == FOAM_TOK_WORD ? foam_switch_value(e->tok[0].v.str) : -1;
    if (v >= 0) {
        *out = v;
        return UMP_OK;
    }
    return entry_error(e, key, "a switch (yes/no, on/off, true/false, 1/0)", err);
}

ump_status foam_get_vector(const foam_dict *d, const char *key, double out[3], ump_err *err)
{
    const foam_entry *e;
    UMP_CALL(primitive(d, key, &e, err));
    if (!e)
        return missing(d, key, err);
    size_t p = 0;
    double v[3];
    if (read_tuple(e->tok, e->ntok, &p, 3, v, key, err) != UMP_OK || p != e->ntok)
        return entry_error(e, key, "a vector (x y z)", err);
    memcpy(out, v, sizeof v);
    return UMP_OK;
}

/* SI unit names OpenFOAM accepts inside [ ] (those with factor 1 only):
 * exponents of kg m s K mol A cd. */
static int unit_dims(const char *u, double d[7])
{
    static const struct { const char *name; signed char e[7]; } units[] = {
        {"kg", {1, 0, 0, 0, 0, 0, 0}},   {"m", {0, 1, 0, 0, 0, 0, 0}},
        {"s", {0, 0, 1, 0, 0, 0, 0}},    {"K", {0, 0, 0, 1, 0, 0, 0}},
        {"mol", {0, 0, 0, 0, 1, 0, 0}},  {"A", {0, 0, 0, 0, 0, 1, 0}},
        {"cd", {0, 0, 0, 0, 0, 0, 1}},   {"N", {1, 1, -2, 0, 0, 0, 0}},
        {"Pa", {1, -1, -2, 0, 0, 0, 0}}, {"J", {1, 2, -2, 0, 0, 0, 0}},
        {"W", {1, 2, -3, 0, 0, 0, 0}},   {"Hz", {0, 0, -1, 0, 0, 0, 0}},
        {"C", {0, 0, 1, 0, 0, 1, 0}},    {"V", {1, 2, -3, 0, 0, -1, 0}},
    };
    for (size_t i = 0; i < sizeof units / sizeof units[0]; i++)
        if (strcmp(u, units[i].name) == 0) {
            for (int k = 0; k < 7; k++)
                d[k] = units[i].e[k];
            return 1;
        }
    return 0;
}

/* [M L T Theta N I J] (7 or 5 numbers) or unit names such as [kg/m^3],
 * [m s^-1], [W/m/K], [1/K]; *p is just past '['. */
static int read_dims(const foam_token *t, size_t nt, size_t *p, double dv[7])
{
    size_t q = *p;
    int k = 0;
    double x;
    while (k < 7 && read_number(t, nt, &q, &x))
        dv[k++] = x;
    if ((k == 7 || k == 5) && is_punct(t, nt, q, ']')) {
        for (int i = k; i < 7; i++)
            dv[i] = 0;
        *p = q + 1;
        return 1;
    }
    for (int i = 0; i < 7; i++)
        dv[i] = 0;
    q = *p;
    double sign = 1;
    int any = 0;
    for (;;) {
        if (is_punct(t, nt, q, ']')) {
            *p = q + 1;
            return any;
        }
        if (is_punct(t, nt, q, '/')) {
            sign = -1;
            q++;
            continue;
        }
        if (is_punct(t, nt, q, '*')) {
            q++;
            continue;
        }
        if (q < nt && t[q].type == FOAM_TOK_LABEL && t[q].v.label == 1) {
            sign = 1;
            any = 1;
            q++;
            continue;
        }
        if (q >= nt || t[q].type != FOAM_TOK_WORD)
            return 0;
        char name[32];
        const char *w = t[q].v.str, *caret = strchr(w, '^');
        size_t n = caret ? (size_t)(caret - w) : strlen(w);
        if (n == 0 || n >= sizeof name)
            return 0;
        memcpy(name, w, n);
        name[n] = '\0';
        double u[7], e = 1;
        if (!unit_dims(name, u))
            return 0;
        if (caret && !word_number(caret + 1, &e))
            return 0;
        for (int i = 0; i < 7; i++)
            dv[i] += sign * e * u[i];
        sign = 1;
        any = 1;
        q++;
    }
}

ump_status foam_get_dimensioned(const foam_dict *d, const char *key, double *value,
                                double dims[7], ump_err *err)
{
    const foam_entry *e;
    UMP_CALL(primitive(d, key, &e, err));
    if (!e)
        return missing(d, key, err);
    const foam_token *t = e->tok;
    size_t nt = e->ntok, p = 0;
    double dv[7] = {0, 0, 0, 0, 0, 0, 0}, v;
    /* optional name, optional [dims], then the value */
    if (p < nt && (t[p].type == FOAM_TOK_WORD || t[p].type == FOAM_TOK_STRING) &&
        !word_number(t[p].v.str, &v))
        p++;
    if (is_punct(t, nt, p, '[')) {
        p++;
        if (!read_dims(t, nt, &p, dv))
            return entry_error(e, key, "dimensions [M L T Theta N I J] or SI unit names", err);
    }
    if (!read_number(t, nt, &p, &v) || p != nt)
        return entry_error(e, key, "a dimensioned scalar ([dims] value)", err);
    *value = v;
    if (dims)
        memcpy(dims, dv, sizeof dv);
    return UMP_OK;
}
