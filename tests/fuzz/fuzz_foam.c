/* SPDX-License-Identifier: GPL-3.0-or-later
 * fuzz_foam.c -- libFuzzer harness for the FoamFile reader: parses the
 * input (file access for #include disabled), then runs the getters and the
 * list decoders over whatever was parsed, and frees everything.
 *   make BUILD=build/fuzz build/fuzz/fuzz_foam
 *   ./build/fuzz/fuzz_foam -max_total_time=300 tests/fuzz/corpus
 */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "umppm/foam.h"

/* A uniform list "N{v}" expands to N elements: the decoders honour it, so
 * skip arrays whose expansion would only measure the machine's memory. */
static int huge_uniform(const foam_token *t, size_t nt)
{
    for (size_t i = 0; i + 1 < nt; i++)
        if (t[i].type == FOAM_TOK_LABEL && t[i].v.label > (1 << 16) &&
            t[i + 1].type == FOAM_TOK_PUNCT && t[i + 1].v.punct == '{')
            return 1;
    return 0;
}

static void decode_at(const foam_token *t, size_t nt, size_t pos)
{
    ump_err err;
    size_t p, n;
    double *d, x;
    ump_idx *l, *o, *it;
    for (int nc = 1; nc <= 3; nc += 2) {
        p = pos;
        if (foam_tok_scalar_list(t, nt, &p, nc, &d, &n, "fuzz", &err) == UMP_OK)
            free(d);
    }
    p = pos;
    if (foam_tok_label_list(t, nt, &p, &l, &n, "fuzz", &err) == UMP_OK)
        free(l);
    p = pos;
    if (foam_tok_labellist_list(t, nt, &p, &o, &it, &n, "fuzz", &err) == UMP_OK) {
        free(o);
        free(it);
    }
    p = pos;
    (void)foam_tok_scalar(t, nt, &p, &x, "fuzz", &err);
    char buf[256];
    (void)foam_tok_where(t, nt, pos, "fuzz", buf, sizeof buf);
    if (pos < nt)
        (void)foam_tok_str(&t[pos], buf, sizeof buf);
}

static void walk_dict(const foam_dict *d, int depth);

static void walk_tokens(const foam_token *t, size_t nt, int depth)
{
    if (!huge_uniform(t, nt)) {
        /* list starts: the first few positions, and after the words that
         * precede lists in fields */
        for (size_t i = 0; i < nt; i++) {
            int start = i < 4;
            if (i > 0 && t[i - 1].type == FOAM_TOK_WORD &&
                (strcmp(t[i - 1].v.str, "nonuniform") == 0 ||
                 strncmp(t[i - 1].v.str, "List<", 5) == 0))
                start = 1;
            if (start)
                decode_at(t, nt, i);
        }
    }
    for (size_t i = 0; i < nt; i++)
        if (t[i].type == FOAM_TOK_DICT && depth < 8)
            walk_dict(t[i].v.dict, depth + 1);
}

static void walk_dict(const foam_dict *d, int depth)
{
    ump_err err;
    double x, v[3], dims[7];
    int64_t l;
    const char *w;
    int b;
    char path[256];
    (void)foam_dict_path(d, path, sizeof path);
    for (size_t i = 0; i < d->n && i < 64; i++) {
        const foam_entry *e = &d->e[i];
        const char *k = e->key;
        (void)foam_get_scalar(d, k, &x, &err);
        (void)foam_get_scalar_or(d, k, 1, &x, &err);
        (void)foam_get_label(d, k, &l, &err);
        (void)foam_get_label_or(d, k, 1, &l, &err);
        (void)foam_get_word(d, k, &w, &err);
        (void)foam_get_word_or(d, k, "x", &w, &err);
        (void)foam_get_bool_or(d, k, 0, &b, &err);
        (void)foam_get_vector(d, k, v, &err);
        (void)foam_get_dimensioned(d, k, &x, dims, &err);
        (void)foam_dict_sub(d, k);
        (void)foam_dict_find(d, k, 1);
        if (e->dict && depth < 8)
            walk_dict(e->dict, depth + 1);
        else if (!e->dict)
            walk_tokens(e->tok, e->ntok, depth);
    }
    /* pattern keys get a look-up that only they can match */
    (void)foam_dict_find(d, "fuzzPatch", 1);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    foam_file *f = NULL;
    ump_err err;
    if (foam_file_parse_ex("fuzz", (const char *)data, size, FOAM_PARSE_NO_INCLUDE, &f, &err) !=
        UMP_OK)
        return 0;
    if (f->header)
        walk_dict(f->header, 0);
    walk_dict(f->dict, 0);
    if (f->body)
        walk_tokens(f->body, f->nbody, 0);
    foam_file_free(&f);
    return 0;
}
