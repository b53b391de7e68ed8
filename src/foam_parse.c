/* SPDX-License-Identifier: GPL-3.0-or-later
 * foam_parse.c -- FoamFile structure: header, dictionaries, primitive
 * entries, list bodies, macro ($var) expansion and #directives, resolved in
 * file order while parsing as OpenFOAM v1912 does.
 *
 * Tokens of the entry being read are collected on one scratch stack (a
 * growable array owned by the parser) and copied into the arena when the
 * entry is complete, so nothing is allocated per token. Variable look-up
 * follows v1912 (tested with foamDictionary -expand): plain $a searches the
 * current dictionary then its parents; $a.b starts in the current one; each
 * extra leading '.' goes one scope up; $:a.b starts at the top; look-ups are
 * literal (pattern keys never match a variable).
 */
#include "foam_internal.h"

#include <limits.h>
#include <regex.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

/* Nesting limits keep hostile input from exhausting the C stack. */
enum { MAX_DICT_DEPTH = 200, MAX_INCLUDE_DEPTH = 32, MAX_PAREN_DEPTH = 256 };

typedef struct parser {
    foam_file *f;
    foam_arena *a;
    ump_err *err;
    unsigned flags;
    foam_token *stk;   /* scratch tokens of the entries being read */
    size_t nstk, capstk;
    size_t budget;     /* tokens/entries that macro copies may still create */
    int depth;         /* dictionary + include nesting */
    int incl_depth;
} parser;

enum { MODE_ENTRY, MODE_EOF };

static ump_status parse_entries(parser *p, foam_lexer *lx, foam_dict *d, int until_brace,
                                int is_include, int open_line);
static int pattern_compile(const char *pattern, regex_t *rx);
static ump_status parse_tokens(parser *p, foam_lexer *lx, foam_dict *ctx, int mode,
                               const char *key, int keyline);

static ump_status oom(parser *p, const char *file, int line)
{
    return FOAM_FAIL(p->err, UMP_ERR_NOMEM, "%s:%d: out of memory", file, line);
}

static void tokstr(const foam_token *t, char *buf, size_t len)
{
    if (foam_lex_is_eof(t))
        snprintf(buf, len, "end of file");
    else
        foam_tok_str(t, buf, len);
}

static ump_status spend(parser *p, size_t n, const foam_token *where)
{
    if (n > p->budget)
        return FOAM_FAIL(p->err, UMP_ERR_INPUT,
                        "%s:%d: macro expansion too large (recursive or exponential $var use?)",
                        where->file, where->line);
    p->budget -= n;
    return UMP_OK;
}

static ump_status push_tok(parser *p, const foam_token *t)
{
    if (p->nstk == p->capstk) {
        size_t nc = p->capstk ? p->capstk * 2 : 256;
        foam_token *n = ump_realloc_array(p->stk, nc, sizeof *n);
        if (!n)
            return oom(p, t->file, t->line);
        p->stk = n;
        p->capstk = nc;
    }
    p->stk[p->nstk++] = *t;
    return UMP_OK;
}

/* ---- dictionaries ---------------------------------------------------------- */

static uint32_t hash_key(const char *s, size_t n)
{
    uint32_t h = 2166136261u;
    for (size_t i = 0; i < n; i++) {
        h ^= (unsigned char)s[i];
        h *= 16777619u;
    }
    return h;
}

static foam_dict *new_dict(parser *p, foam_dict *parent, const char *name, const char *file,
                           int line)
{
    foam_dict_impl *di = foam_arena_alloc(p->a, 1, sizeof *di);
    if (!di)
        return NULL;
    di->pub.parent = parent;
    di->pub.name = name ? name : "";
    di->pub.file = file;
    di->pub.line = line;
    return &di->pub;
}

static int key_eq(const char *key, const char *s, size_t n)
{
    return strncmp(key, s, n) == 0 && key[n] == '\0';
}

/* Index of the entry with exactly this key (pattern keys compared as text,
 * as OpenFOAM's hashed look-up does), or -1. */
static long find_exact_n(const foam_dict *d, const char *s, size_t n)
{
    const foam_dict_impl *di = (const foam_dict_impl *)d;
    if (di->hcap) {
        size_t m = di->hcap - 1, h = hash_key(s, n) & m;
        while (di->hidx[h]) {
            size_t i = di->hidx[h] - 1;
            if (key_eq(d->e[i].key, s, n))
                return (long)i;
            h = (h + 1) & m;
        }
        return -1;
    }
    for (size_t i = 0; i < d->n; i++)
        if (key_eq(d->e[i].key, s, n))
            return (long)i;
    return -1;
}

static long find_exact(const foam_dict *d, const char *key)
{
    return find_exact_n(d, key, strlen(key));
}

/* (Re)build the hash index once a dictionary is big enough to need one. */
static int rebuild_index(parser *p, foam_dict_impl *di)
{
    foam_dict *d = &di->pub;
    if (d->n < 8) {
        di->hcap = 0;
        di->hidx = NULL;
        return 1;
    }
    size_t cap = 16;
    while (cap < d->n * 2)
        cap *= 2;
    uint32_t *h = foam_arena_alloc(p->a, cap, sizeof *h);
    if (!h)
        return 0;
    for (size_t i = 0; i < d->n; i++) {
        size_t k = hash_key(d->e[i].key, strlen(d->e[i].key)) & (cap - 1);
        while (h[k])
            k = (k + 1) & (cap - 1);
        h[k] = (uint32_t)(i + 1);
    }
    di->hidx = h;
    di->hcap = cap;
    return 1;
}

/* Append without checking for an existing key. */
static void free_regex(void *q)
{
    regfree(q);
    free(q);
}

/* A pattern key compiled once, kept with the file (e->rx); left NULL when
 * it cannot be compiled (it then matches nothing, as before) or memory is
 * short (it is then compiled at each match). */
static void compile_key(parser *p, foam_entry *e)
{
    if (!e->is_pattern || e->rx)
        return;
    regex_t *rx = ump_alloc_array(1, sizeof *rx);
    if (rx && pattern_compile(e->key, rx)) {
        if (foam_arena_adopt(p->a, rx, free_regex))
            e->rx = rx;
        return;
    }
    free(rx);
}

static ump_status dict_append(parser *p, foam_dict *d, const foam_entry *e)
{
    foam_dict_impl *di = (foam_dict_impl *)d;
    if (d->n >= UINT32_MAX - 1)
        return FOAM_FAIL(p->err, UMP_ERR_INPUT, "%s:%d: too many entries", e->file, e->line);
    if (d->n == d->cap) {
        size_t nc = d->cap ? d->cap * 2 : 8;
        foam_entry *ne = foam_arena_alloc(p->a, nc, sizeof *ne);
        if (!ne)
            return oom(p, e->file, e->line);
        if (d->n)
            memcpy(ne, d->e, d->n * sizeof *ne);
        d->e = ne;
        d->cap = nc;
    }
    d->e[d->n] = *e;
    compile_key(p, &d->e[d->n]);
    d->n++;
    if (e->is_pattern)
        di->npat++;
    if (di->hcap && d->n * 2 <= di->hcap) {
        size_t m = di->hcap - 1, k = hash_key(e->key, strlen(e->key)) & m;
        while (di->hidx[k])
            k = (k + 1) & m;
        di->hidx[k] = (uint32_t)d->n;
    } else if (!rebuild_index(p, di)) {
        return oom(p, e->file, e->line);
    }
    return UMP_OK;
}


static ump_status dict_merge(parser *p, foam_dict *dst, foam_dict *src);

/* Add e to d with OpenFOAM's default "merge" input mode: a new key is
 * appended; an existing key is replaced in place, except that a dictionary
 * given again for a dictionary is merged into it. e->dict, if any, must be
 * a fresh dictionary that d may take over. */
static ump_status dict_add(parser *p, foam_dict *d, foam_entry *e)
{
    long i = find_exact(d, e->key);
    if (i < 0) {
        if (e->dict)
            e->dict->parent = d;
        return dict_append(p, d, e);
    }
    foam_entry *old = &d->e[i];
    if (old->dict && e->dict)
        return dict_merge(p, old->dict, e->dict);
    foam_dict_impl *di = (foam_dict_impl *)d;
    di->npat -= (size_t)old->is_pattern;
    di->npat += (size_t)e->is_pattern;
    if (e->dict)
        e->dict->parent = d;
    compile_key(p, e);
    *old = *e;
    return UMP_OK;
}

/* Merge the entries of src (a fresh dictionary) into dst. */
static ump_status dict_merge(parser *p, foam_dict *dst, foam_dict *src)
{
    if (++p->depth > MAX_DICT_DEPTH)
        return FOAM_FAIL(p->err, UMP_ERR_INPUT, "%s:%d: dictionaries nested too deeply",
                        src->file, src->line);
    for (size_t i = 0; i < src->n; i++) {
        foam_entry e = src->e[i];
        ump_status rc = dict_add(p, dst, &e);
        if (rc != UMP_OK)
            return rc;
    }
    p->depth--;
    return UMP_OK;
}

/* Deep copy of src's sub-dictionaries (primitive token arrays are shared:
 * they never change once made). Used by $var so that a later merge into
 * the original cannot alter the copy, nor create a cycle. */
static foam_dict *dict_copy(parser *p, const foam_dict *src, foam_dict *parent,
                            const foam_token *where, ump_status *rc)
{
    *rc = UMP_OK;
    if (++p->depth > MAX_DICT_DEPTH) {
        *rc = FOAM_FAIL(p->err, UMP_ERR_INPUT, "%s:%d: dictionaries nested too deeply",
                       where->file, where->line);
        return NULL;
    }
    if ((*rc = spend(p, src->n + 1, where)) != UMP_OK)
        return NULL;
    foam_dict *d = new_dict(p, parent, src->name, src->file, src->line);
    foam_entry *e = src->n ? foam_arena_alloc(p->a, src->n, sizeof *e) : NULL;
    if (!d || (src->n && !e)) {
        *rc = oom(p, where->file, where->line);
        return NULL;
    }
    for (size_t i = 0; i < src->n; i++) {
        e[i] = src->e[i];
        if (e[i].dict) {
            e[i].dict = dict_copy(p, src->e[i].dict, d, where, rc);
            if (!e[i].dict)
                return NULL;
        }
    }
    d->e = e;
    d->n = d->cap = src->n;
    foam_dict_impl *di = (foam_dict_impl *)d;
    di->npat = ((const foam_dict_impl *)src)->npat;
    if (!rebuild_index(p, di)) {
        *rc = oom(p, where->file, where->line);
        return NULL;
    }
    p->depth--;
    return d;
}

static const foam_dict *dict_top(const foam_dict *d)
{
    while (d->parent)
        d = d->parent;
    return d;
}

/* ---- variables ------------------------------------------------------------- */

/* Entry named s[0..n) in d, optionally searching the parents. Pattern
 * keys match only when pat is set: v1912 expands "$var" in a value
 * literally but resolves a "$var;" keyword with regular expressions too. */
static const foam_entry *find_var_n(const foam_dict *d, const char *s, size_t n, int recursive,
                                    int pat)
{
    for (; d; d = recursive ? d->parent : NULL) {
        long i = find_exact_n(d, s, n);
        if (i >= 0)
            return &d->e[i];
        if (pat && ((const foam_dict_impl *)d)->npat && n < 1024) {
            char key[1024];
            memcpy(key, s, n);
            key[n] = '\0';
            for (size_t k = d->n; k-- > 0;)
                if (d->e[k].is_pattern && foam_entry_match(&d->e[k], key))
                    return &d->e[k];
        }
    }
    return NULL;
}

/* a.b.c relative to d; leading dots go up one scope per extra dot. */
static const foam_entry *find_dot_scoped(const foam_dict *d, const char *s, int pat)
{
    for (;;) {
        if (!d || !*s)
            return NULL;
        if (*s == '.') {
            size_t k = 0;
            while (s[k] == '.')
                k++;
            for (size_t i = 1; i < k; i++) {
                d = d->parent;
                if (!d)
                    return NULL;
            }
            s += k;
            continue;
        }
        const char *dot = strchr(s, '.');
        if (!dot)
            return find_var_n(d, s, strlen(s), 0, pat);
        const foam_entry *e = find_var_n(d, s, (size_t)(dot - s), 0, pat);
        /* fall back to keys that contain dots: a.b, a.b.c, ... */
        while (!(e && e->dict)) {
            dot = strchr(dot + 1, '.');
            if (!dot)
                return find_var_n(d, s, strlen(s), 0, pat);
            e = find_var_n(d, s, (size_t)(dot - s), 0, pat);
        }
        d = e->dict;
        s = dot; /* ".rest": one dot, no scope change */
    }
}

/* a/b, /a/b, ../a : slash-separated path of sub-dictionaries. */
static const foam_entry *find_slash_scoped(const foam_dict *d, const char *s, int pat)
{
    if (*s == '/') {
        d = dict_top(d);
        while (*s == '/')
            s++;
    }
    for (;;) {
        const char *sl = strchr(s, '/');
        size_t n = sl ? (size_t)(sl - s) : strlen(s);
        if (!sl) {
            if (n == 0 || (n == 1 && s[0] == '.') || (n == 2 && s[0] == '.' && s[1] == '.'))
                return NULL;
            return find_var_n(d, s, n, 0, pat);
        }
        if (n == 0 || (n == 1 && s[0] == '.')) {
            /* stay */
        } else if (n == 2 && s[0] == '.' && s[1] == '.') {
            d = d->parent;
            if (!d)
                return NULL;
        } else {
            const foam_entry *e = find_var_n(d, s, n, 0, pat);
            if (!e || !e->dict)
                return NULL;
            d = e->dict;
        }
        s = sl + 1;
    }
}

static const foam_entry *resolve_var(const foam_dict *ctx, const char *name, int pat)
{
    if (strchr(name, '/'))
        return find_slash_scoped(ctx, name, pat);
    if (name[0] == ':' || name[0] == '^')
        return find_dot_scoped(dict_top(ctx), name + 1, pat);
    if (strchr(name, '.'))
        return find_dot_scoped(ctx, name, pat);
    return find_var_n(ctx, name, strlen(name), 1, pat);
}

static const foam_entry *resolve_var(const foam_dict *ctx, const char *name, int pat);

/* Text of a primitive entry's single word/string/number token, for the
 * recursive substitution ${..$x..}. */
static int entry_word(const foam_entry *e, char *buf, size_t len)
{
    if (!e || e->dict || e->ntok != 1)
        return 0;
    const foam_token *t = &e->tok[0];
    if (t->type == FOAM_TOK_WORD || t->type == FOAM_TOK_STRING)
        snprintf(buf, len, "%s", t->v.str);
    else if (t->type == FOAM_TOK_LABEL)
        snprintf(buf, len, "%lld", (long long)t->v.label);
    else
        return 0;
    return 1;
}

/* Variable name of a $ token into buf ("$a" -> "a", "${a.b}" -> "a.b").
 * Inside ${...}, $x and ${x} are replaced first (v1912 recursive
 * substitution, e.g. ${:$LESModel}). */
static ump_status var_name(parser *p, foam_dict *ctx, const foam_token *t, char *buf,
                           size_t len)
{
    const char *s = t->v.str + 1;
    size_t n = strlen(s);
    int braces = s[0] == '{';
    if (braces) {
        if (s[1] == '{')
            return FOAM_FAIL(p->err, UMP_ERR_UNSUPPORTED,
                            "%s:%d: expressions ${{...}} are not supported", t->file, t->line);
        s++;
        n -= 2; /* lexer guarantees the closing '}' */
    }
    if (n == 0 || n >= len)
        return FOAM_FAIL(p->err, UMP_ERR_PARSE, "%s:%d: bad variable name '%s'", t->file,
                        t->line, t->v.str);
    if (!braces || !memchr(s, '$', n)) {
        memcpy(buf, s, n);
        buf[n] = '\0';
        return UMP_OK;
    }
    size_t o = 0, i = 0;
    while (i < n) {
        if (s[i] != '$') {
            if (o + 1 >= len)
                goto toolong;
            buf[o++] = s[i++];
            continue;
        }
        char inner[256], val[1024];
        size_t k = 0;
        i++;
        int br = i < n && s[i] == '{';
        if (br)
            i++;
        while (i < n && k + 1 < sizeof inner &&
               (br ? s[i] != '}' : (s[i] != '$' && s[i] != '{' && s[i] != '}')))
            inner[k++] = s[i++];
        if (br && i < n && s[i] == '}')
            i++;
        inner[k] = '\0';
        const foam_entry *e = k ? resolve_var(ctx, inner, 0) : NULL;
        const char *env = !e && k ? getenv(inner) : NULL;
        if (e && !entry_word(e, val, sizeof val))
            return FOAM_FAIL(p->err, UMP_ERR_PARSE,
                            "%s:%d: variable $%s in %s is not a single word", t->file, t->line,
                            inner, t->v.str);
        /* undefined: empty, as stringOps::inplaceExpand (then the outer
         * look-up fails: an error in a value, ignored as a keyword) */
        if (!e)
            snprintf(val, sizeof val, "%s", env ? env : "");
        size_t vl = strlen(val);
        if (o + vl >= len)
            goto toolong;
        memcpy(buf + o, val, vl);
        o += vl;
    }
    buf[o] = '\0';
    return UMP_OK;
toolong:
    return FOAM_FAIL(p->err, UMP_ERR_PARSE, "%s:%d: variable name too long in '%s'", t->file,
                    t->line, t->v.str);
}

static int env_name_ok(const char *s)
{
    if (!*s)
        return 0;
    for (; *s; s++)
        if (!((*s >= 'a' && *s <= 'z') || (*s >= 'A' && *s <= 'Z') ||
              (*s >= '0' && *s <= '9') || *s == '_'))
            return 0;
    return 1;
}

/* $var inside a value: the tokens of var (a dictionary becomes one
 * FOAM_TOK_DICT token, a copy), else an environment variable's value. */
static ump_status expand_var(parser *p, foam_dict *ctx, const foam_token *t)
{
    char name[1024];
    UMP_CALL(var_name(p, ctx, t, name, sizeof name));
    const foam_entry *e = resolve_var(ctx, name, 0);
    if (e && e->dict) {
        ump_status rc;
        foam_dict *c = dict_copy(p, e->dict, ctx, t, &rc);
        if (!c)
            return rc;
        foam_token dt = *t;
        dt.type = FOAM_TOK_DICT;
        dt.v.dict = c;
        return push_tok(p, &dt);
    }
    if (e) {
        UMP_CALL(spend(p, e->ntok, t));
        for (size_t i = 0; i < e->ntok; i++)
            UMP_CALL(push_tok(p, &e->tok[i]));
        return UMP_OK;
    }
    const char *env = env_name_ok(name) ? getenv(name) : NULL;
    if (!env || !*env)
        return FOAM_FAIL(p->err, UMP_ERR_PARSE, "%s:%d: undefined variable $%s", t->file,
                        t->line, name);
    /* OpenFOAM tokenizes the environment value */
    foam_lexer el;
    foam_lex_init(&el, env, strlen(env), t->file, p->a, p->err);
    for (;;) {
        foam_token et;
        UMP_CALL(foam_lex_next(&el, &et));
        if (foam_lex_is_eof(&et))
            break;
        UMP_CALL(spend(p, 1, t));
        et.line = t->line;
        UMP_CALL(push_tok(p, &et));
    }
    return UMP_OK;
}

/* ---- file names for #include ------------------------------------------------ */

static int is_dir(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && S_ISDIR(st.st_mode);
}

/* dst = a + b + c; 0 (dst empty) when it does not fit. */
static int pcat(char *dst, size_t len, const char *a, const char *b, const char *c)
{
    size_t na = strlen(a), nb = strlen(b), nc = strlen(c);
    if (na + nb + nc >= len) {
        dst[0] = '\0';
        return 0;
    }
    memmove(dst, a, na);
    memcpy(dst + na, b, nb);
    memcpy(dst + na + nb, c, nc + 1);
    return 1;
}

/* Directory part of path ("." when none). */
static void dir_of(const char *path, char *buf, size_t len)
{
    const char *sl = strrchr(path, '/');
    if (!sl)
        snprintf(buf, len, ".");
    else if (sl == path)
        snprintf(buf, len, "/");
    else
        snprintf(buf, len, "%.*s", (int)(sl - path), path);
}

/* Case directory: $FOAM_CASE, else the nearest ancestor of the top file that
 * has a system/ directory, else two levels up. */
static void case_dir(const parser *p, char *buf, size_t len)
{
    const char *env = getenv("FOAM_CASE");
    if (env && *env) {
        snprintf(buf, len, "%s", env);
        return;
    }
    char d[4096], probe[4200];
    dir_of(p->f->path, d, sizeof d);
    char first[4096];
    snprintf(first, sizeof first, "%s", d);
    for (int up = 0; up < 4; up++) {
        pcat(probe, sizeof probe, d, "/system", "");
        if (is_dir(probe)) {
            snprintf(buf, len, "%s", d);
            return;
        }
        if (!pcat(d, sizeof d, d, "/..", ""))
            break;
    }
    pcat(buf, len, first, "/..", "");
}

/* Expand <case> <system> <constant> ~ $VAR ${VAR} in an include name. */
static ump_status expand_name(parser *p, foam_dict *ctx, const foam_token *t, char *out,
                              size_t len)
{
    const char *s = t->v.str;
    char cd[4096];
    size_t o = 0;
    out[0] = '\0';
#define APPEND(str_, n_) do { \
        size_t n__ = (n_); \
        if (o + n__ >= len) \
            return FOAM_FAIL(p->err, UMP_ERR_INPUT, "%s:%d: file name too long", \
                             t->file, t->line); \
        memcpy(out + o, (str_), n__); o += n__; out[o] = '\0'; \
    } while (0)
    static const char *const tags[] = {"<case>", "<system>", "<constant>"};
    for (int k = 0; k < 3; k++) {
        size_t tl = strlen(tags[k]);
        if (strncmp(s, tags[k], tl) == 0) {
            case_dir(p, cd, sizeof cd);
            APPEND(cd, strlen(cd));
            if (k == 1)
                APPEND("/system", 7);
            else if (k == 2)
                APPEND("/constant", 9);
            s += tl;
            break;
        }
    }
    if (s[0] == '~' && (s[1] == '/' || s[1] == '\0')) {
        const char *home = getenv("HOME");
        if (home)
            APPEND(home, strlen(home));
        s++;
    }
    while (*s) {
        if (*s != '$') {
            APPEND(s, 1);
            s++;
            continue;
        }
        const char *nm = s + 1;
        size_t n = 0;
        int braces = nm[0] == '{';
        if (braces) {
            nm++;
            while (nm[n] && nm[n] != '}')
                n++;
            if (!nm[n])
                return FOAM_FAIL(p->err, UMP_ERR_PARSE, "%s:%d: expected '}' in file name '%s'",
                                t->file, t->line, t->v.str);
        } else {
            while ((nm[n] >= 'a' && nm[n] <= 'z') || (nm[n] >= 'A' && nm[n] <= 'Z') ||
                   (nm[n] >= '0' && nm[n] <= '9') || nm[n] == '_')
                n++;
        }
        if (n == 0 || n >= 256) {
            APPEND("$", 1);
            s++;
            continue;
        }
        char name[256];
        memcpy(name, nm, n);
        name[n] = '\0';
        s = nm + n + (braces ? 1 : 0);
        if (strcmp(name, "FOAM_CASE") == 0) {
            case_dir(p, cd, sizeof cd);
            APPEND(cd, strlen(cd));
            continue;
        }
        const foam_entry *e = resolve_var(ctx, name, 0);
        if (e && !e->dict && e->ntok == 1 &&
            (e->tok[0].type == FOAM_TOK_WORD || e->tok[0].type == FOAM_TOK_STRING)) {
            APPEND(e->tok[0].v.str, strlen(e->tok[0].v.str));
            continue;
        }
        const char *env = getenv(name);
        if (!env)
            return FOAM_FAIL(p->err, UMP_ERR_INPUT,
                            "%s:%d: undefined variable $%s in file name '%s'", t->file, t->line,
                            name, t->v.str);
        APPEND(env, strlen(env));
    }
#undef APPEND
    return UMP_OK;
}

/* Resolve an #include / #includeEtc name to an existing file (malloc'd), or
 * NULL when none exists (message in *what for the caller). */
static ump_status include_path(parser *p, foam_dict *ctx, const foam_token *dir_tok,
                               const foam_token *name_tok, int etc, char **found, char *tried,
                               size_t tlen)
{
    char name[4096], full[8300];
    *found = NULL;
    UMP_CALL(expand_name(p, ctx, name_tok, name, sizeof name));
    if (!etc || name[0] == '/') {
        if (name[0] == '/') {
            snprintf(full, sizeof full, "%s", name);
        } else {
            char d[4096];
            dir_of(dir_tok->file, d, sizeof d);
            pcat(full, sizeof full, d, "/", name);
        }
        snprintf(tried, tlen, "%s", full);
        *found = foam_resolve_gz(full);
        return UMP_OK;
    }
    /* #includeEtc: the OpenFOAM etc directories, in order */
    const char *fe = getenv("FOAM_ETC"), *wm = getenv("WM_PROJECT_DIR");
    char dirs[3][4200];
    int nd = 0;
    if (fe && *fe && pcat(dirs[nd], sizeof dirs[0], fe, "", ""))
        nd++;
    if (wm && *wm && pcat(dirs[nd], sizeof dirs[0], wm, "/etc", ""))
        nd++;
    pcat(dirs[nd++], sizeof dirs[0], "/usr/share/openfoam/etc", "", "");
    for (int i = 0; i < nd && !*found; i++) {
        if (pcat(full, sizeof full, dirs[i], "/", name))
            *found = foam_resolve_gz(full);
    }
    snprintf(tried, tlen, "'%s' in $FOAM_ETC, $WM_PROJECT_DIR/etc and /usr/share/openfoam/etc",
             name);
    return UMP_OK;
}

typedef struct include_src {
    char *buf;
    size_t len;
    const char *file; /* arena */
} include_src;

/* Shared part of #include handling: reads the named file. *src->buf NULL
 * and UMP_OK means "absent, skip" (#includeIfPresent). */
static ump_status include_open(parser *p, foam_lexer *lx, foam_dict *ctx,
                               const foam_token *dtok, include_src *src)
{
    const char *dn = dtok->v.str;
    int etc = strcmp(dn, "#includeEtc") == 0;
    int optional = strcmp(dn, "#includeIfPresent") == 0 || strcmp(dn, "#sinclude") == 0;
    memset(src, 0, sizeof *src);
    foam_token nt;
    UMP_CALL(foam_lex_next(lx, &nt));
    if (nt.type != FOAM_TOK_STRING && nt.type != FOAM_TOK_WORD) {
        char tb[128];
        tokstr(&nt, tb, sizeof tb);
        return FOAM_FAIL(p->err, UMP_ERR_PARSE, "%s:%d: expected a file name after %s, found %s",
                        dtok->file, dtok->line, dn, tb);
    }
    if (p->flags & FOAM_PARSE_NO_INCLUDE)
        return FOAM_FAIL(p->err, UMP_ERR_UNSUPPORTED, "%s:%d: %s is disabled here", dtok->file,
                        dtok->line, dn);
    if (p->incl_depth >= MAX_INCLUDE_DEPTH)
        return FOAM_FAIL(p->err, UMP_ERR_INPUT,
                        "%s:%d: %s \"%s\": includes nested too deeply (recursive include?)",
                        dtok->file, dtok->line, dn, nt.v.str);
    char tried[8400];
    char *path = NULL;
    UMP_CALL(include_path(p, ctx, dtok, &nt, etc, &path, tried, sizeof tried));
    if (!path) {
        if (optional)
            return UMP_OK;
        if (etc)
            return FOAM_FAIL(p->err, UMP_ERR_IO, "%s:%d: #includeEtc: cannot find %s",
                            dtok->file, dtok->line, tried);
        return FOAM_FAIL(p->err, UMP_ERR_IO, "%s:%d: %s: cannot open %s (nor %s.gz)",
                        dtok->file, dtok->line, dn, tried, tried);
    }
    src->file = foam_arena_strndup(p->a, path, strlen(path));
    if (!src->file) {
        free(path);
        return oom(p, dtok->file, dtok->line);
    }
    ump_err sub;
    memset(&sub, 0, sizeof sub);
    ump_status rc = foam_read_whole_file(path, &src->buf, &src->len, &sub);
    free(path);
    if (rc != UMP_OK)
        return FOAM_FAIL(p->err, rc, "%s:%d: %s: %s", dtok->file, dtok->line, dn, sub.msg);
    size_t extra = src->len > SIZE_MAX / 32 ? SIZE_MAX / 2 : src->len * 16;
    p->budget = p->budget > SIZE_MAX - extra ? SIZE_MAX : p->budget + extra;
    return UMP_OK;
}

/* #include family inside a dictionary: the file's entries join ctx. */
static ump_status include_entries(parser *p, foam_lexer *lx, foam_dict *ctx,
                                  const foam_token *dtok)
{
    include_src src;
    UMP_CALL(include_open(p, lx, ctx, dtok, &src));
    if (!src.buf)
        return UMP_OK;
    foam_lexer il;
    foam_lex_init(&il, src.buf, src.len, src.file, p->a, p->err);
    p->incl_depth++;
    ump_status rc = parse_entries(p, &il, ctx, 0, 1, 0);
    p->incl_depth--;
    free(src.buf);
    return rc;
}

/* #include family inside a value: the file's tokens are inserted. */
static ump_status include_tokens(parser *p, foam_lexer *lx, foam_dict *ctx,
                                 const foam_token *dtok)
{
    include_src src;
    UMP_CALL(include_open(p, lx, ctx, dtok, &src));
    if (!src.buf)
        return UMP_OK;
    foam_lexer il;
    foam_lex_init(&il, src.buf, src.len, src.file, p->a, p->err);
    p->incl_depth++;
    ump_status rc = parse_tokens(p, &il, ctx, MODE_EOF, dtok->v.str, dtok->line);
    p->incl_depth--;
    free(src.buf);
    return rc;
}

static int is_include_directive(const char *s)
{
    return strcmp(s, "#include") == 0 || strcmp(s, "#includeIfPresent") == 0 ||
           strcmp(s, "#sinclude") == 0 || strcmp(s, "#includeEtc") == 0;
}

static ump_status unsupported_directive(parser *p, const foam_token *t)
{
    return FOAM_FAIL(p->err, UMP_ERR_UNSUPPORTED,
                    "%s:%d: directive %s is not supported (%s evaluates no code "
                    "or expressions)",
                    t->file, t->line, t->v.str, ump_solver);
}

/* ---- values -------------------------------------------------------------------- */

static ump_status parse_block(parser *p, foam_lexer *lx, foam_dict *parent, const char *name,
                              int line, foam_dict **out)
{
    if (p->depth >= MAX_DICT_DEPTH)
        return FOAM_FAIL(p->err, UMP_ERR_INPUT, "%s:%d: dictionaries nested too deeply",
                        lx->file, line);
    foam_dict *d = new_dict(p, parent, name, lx->file, line);
    if (!d)
        return oom(p, lx->file, line);
    p->depth++;
    ump_status rc = parse_entries(p, lx, d, 1, 0, line);
    p->depth--;
    *out = d;
    return rc;
}

/* Read tokens onto the scratch stack until ';' at nesting level 0
 * (MODE_ENTRY) or end of input (MODE_EOF), expanding $var and #include,
 * turning "name { ... }" into FOAM_TOK_DICT and, in binary streams, the
 * count after List<T> into FOAM_TOK_BLOB. */
static ump_status parse_tokens(parser *p, foam_lexer *lx, foam_dict *ctx, int mode,
                               const char *key, int keyline)
{
    char open[MAX_PAREN_DEPTH];
    int openline[MAX_PAREN_DEPTH];
    int depth = 0;
    size_t base = p->nstk;
    for (;;) {
        foam_token t;
        UMP_CALL(foam_lex_next(lx, &t));
        if (foam_lex_is_eof(&t)) {
            if (depth > 0)
                return FOAM_FAIL(p->err, UMP_ERR_PARSE,
                                "%s:%d: expected '%c' closing '%c' opened at line %d, found end "
                                "of file",
                                lx->file, t.line, open[depth - 1] == '(' ? ')' : '}',
                                open[depth - 1], openline[depth - 1]);
            if (mode == MODE_ENTRY)
                return FOAM_FAIL(p->err, UMP_ERR_PARSE,
                                "%s:%d: expected ';' ending entry '%s' (line %d), found end "
                                "of file",
                                lx->file, t.line, key, keyline);
            return UMP_OK;
        }
        if (t.type == FOAM_TOK_PUNCT) {
            char c = t.v.punct;
            if (c == ';' && depth == 0 && mode == MODE_ENTRY)
                return UMP_OK;
            if (c == '(' ||
                (c == '{' && p->nstk > base && p->stk[p->nstk - 1].type == FOAM_TOK_LABEL)) {
                /* '{' after a count: uniform list N{v} */
                if (depth >= MAX_PAREN_DEPTH)
                    return FOAM_FAIL(p->err, UMP_ERR_INPUT, "%s:%d: lists nested too deeply",
                                    t.file, t.line);
                open[depth] = c;
                openline[depth++] = t.line;
            } else if (c == '{') {
                const char *nm = "";
                if (p->nstk > base && p->stk[p->nstk - 1].type == FOAM_TOK_WORD)
                    nm = p->stk[p->nstk - 1].v.str;
                foam_dict *sub;
                UMP_CALL(parse_block(p, lx, ctx, nm, t.line, &sub));
                t.type = FOAM_TOK_DICT;
                t.v.dict = sub;
            } else if (c == ')' || c == '}') {
                /* like v1912's primitiveEntry, only ( ) and { } must balance */
                char want = c == ')' ? '(' : '{';
                if (depth == 0 || open[depth - 1] != want) {
                    if (depth == 0 && c == '}' && mode == MODE_ENTRY)
                        return FOAM_FAIL(p->err, UMP_ERR_PARSE,
                                        "%s:%d: expected ';' ending entry '%s' (line %d), "
                                        "found '}'",
                                        t.file, t.line, key, keyline);
                    if (depth == 0)
                        return FOAM_FAIL(p->err, UMP_ERR_PARSE,
                                        "%s:%d: unexpected '%c' (no matching '%c')", t.file,
                                        t.line, c, want);
                    return FOAM_FAIL(p->err, UMP_ERR_PARSE,
                                    "%s:%d: expected '%c' closing '%c' opened at line %d, "
                                    "found '%c'",
                                    t.file, t.line,
                                    open[depth - 1] == '(' ? ')' : '}',
                                    open[depth - 1], openline[depth - 1], c);
                }
                depth--;
            }
            UMP_CALL(push_tok(p, &t));
            continue;
        }
        if (t.type == FOAM_TOK_WORD && t.v.str[0] == '$') {
            UMP_CALL(expand_var(p, ctx, &t));
            continue;
        }
        if (t.type == FOAM_TOK_WORD && t.v.str[0] == '#') {
            if (is_include_directive(t.v.str)) {
                UMP_CALL(include_tokens(p, lx, ctx, &t));
                continue;
            }
            return unsupported_directive(p, &t);
        }
        if (t.type == FOAM_TOK_LABEL && lx->binary && p->nstk > base &&
            p->stk[p->nstk - 1].type == FOAM_TOK_WORD) {
            int is_label = 0;
            int ncomp = foam_list_type_ncomp(p->stk[p->nstk - 1].v.str, &is_label);
            int nc;
            if (ncomp > 0)
                UMP_CALL(foam_lex_peek_char(lx, &nc));
            if (ncomp > 0 && nc != '{') {
                foam_token bt;
                UMP_CALL(foam_lex_blob(lx, t.v.label, ncomp, is_label, t.line, &bt));
                UMP_CALL(push_tok(p, &bt));
                continue;
            }
        }
        UMP_CALL(push_tok(p, &t));
    }
}

/* Copy the scratch tokens from base into the arena as an entry's value. */
static ump_status take_tokens(parser *p, size_t base, foam_entry *e)
{
    size_t n = p->nstk - base;
    e->ntok = n;
    e->tok = NULL;
    if (n) {
        e->tok = foam_arena_alloc(p->a, n, sizeof *e->tok);
        if (!e->tok)
            return oom(p, e->file, e->line);
        memcpy(e->tok, p->stk + base, n * sizeof *e->tok);
    }
    p->nstk = base;
    return UMP_OK;
}

/* ---- directives in a dictionary --------------------------------------------- */

/* Remove every entry whose key equals text or, for a quoted name, matches
 * it as a pattern: one pass and one index rebuild, whatever the count. */
static void remove_keys(parser *p, foam_dict *d, const char *text, int is_pattern)
{
    regex_t rx;
    int have_rx = is_pattern && pattern_compile(text, &rx);
    size_t o = 0;
    foam_dict_impl *di = (foam_dict_impl *)d;
    for (size_t i = 0; i < d->n; i++) {
        const char *k = d->e[i].key;
        int gone = strcmp(k, text) == 0 || (have_rx && regexec(&rx, k, 0, NULL, 0) == 0);
        if (gone) {
            if (d->e[i].is_pattern)
                di->npat--;
            continue;
        }
        d->e[o++] = d->e[i];
    }
    if (have_rx)
        regfree(&rx);
    if (o != d->n) {
        d->n = o;
        if (!rebuild_index(p, di))
            di->hcap = 0; /* fall back to linear search */
    }
}

static ump_status directive_remove(parser *p, foam_lexer *lx, foam_dict *d)
{
    foam_token t;
    UMP_CALL(foam_lex_next(lx, &t));
    int list = t.type == FOAM_TOK_PUNCT && t.v.punct == '(';
    for (;;) {
        if (list) {
            UMP_CALL(foam_lex_next(lx, &t));
            if (t.type == FOAM_TOK_PUNCT && t.v.punct == ')')
                return UMP_OK;
        }
        if (t.type != FOAM_TOK_WORD && t.type != FOAM_TOK_STRING) {
            char tb[128];
            tokstr(&t, tb, sizeof tb);
            return FOAM_FAIL(p->err, UMP_ERR_PARSE,
                            "%s:%d: #remove: expected a keyword%s, found %s", t.file, t.line,
                            list ? " or ')'" : " or '('", tb);
        }
        remove_keys(p, d, t.v.str, t.type == FOAM_TOK_STRING);
        if (!list)
            return UMP_OK;
    }
}

static ump_status directive_dict(parser *p, foam_lexer *lx, foam_dict *d, const foam_token *t)
{
    const char *dn = t->v.str;
    if (is_include_directive(dn))
        return include_entries(p, lx, d, t);
    if (strcmp(dn, "#remove") == 0)
        return directive_remove(p, lx, d);
    if (strcmp(dn, "#inputMode") == 0) {
        foam_token m;
        UMP_CALL(foam_lex_next(lx, &m));
        if (m.type != FOAM_TOK_WORD) {
            char tb[128];
            tokstr(&m, tb, sizeof tb);
            return FOAM_FAIL(p->err, UMP_ERR_PARSE, "%s:%d: #inputMode: expected a mode, found %s",
                            t->file, t->line, tb);
        }
        return UMP_OK;
    }
    if (strcmp(dn, "#includeFunc") == 0 || strcmp(dn, "#includeFunction") == 0) {
        foam_token a;
        UMP_CALL(foam_lex_next(lx, &a));
        if (a.type != FOAM_TOK_WORD && a.type != FOAM_TOK_STRING) {
            char tb[128];
            tokstr(&a, tb, sizeof tb);
            return FOAM_FAIL(p->err, UMP_ERR_PARSE,
                            "%s:%d: %s: expected a function name, found %s", t->file, t->line,
                            dn, tb);
        }
        foam_entry e;
        memset(&e, 0, sizeof e);
        e.key = "#includeFunc";
        e.file = t->file;
        e.line = t->line;
        e.tok = foam_arena_alloc(p->a, 1, sizeof *e.tok);
        if (!e.tok)
            return oom(p, t->file, t->line);
        e.tok[0] = a;
        e.ntok = 1;
        /* several functions may be included: keep them all */
        return dict_append(p, d, &e);
    }
    return unsupported_directive(p, t);
}

/* $var as a keyword: "$var;" merges var's entries; "$var { }" uses var's
 * value as the keyword. An undefined "$var;" is ignored, as in v1912. */
static ump_status var_keyword(parser *p, foam_lexer *lx, foam_dict *d, const foam_token *t)
{
    char name[1024];
    UMP_CALL(var_name(p, d, t, name, sizeof name));
    const foam_entry *e = resolve_var(d, name, 1);
    foam_token nt;
    UMP_CALL(foam_lex_peek(lx, &nt));
    if (nt.type == FOAM_TOK_PUNCT && nt.v.punct == '{') {
        if (!e || e->dict || e->ntok < 1 ||
            (e->tok[0].type != FOAM_TOK_WORD && e->tok[0].type != FOAM_TOK_STRING))
            return FOAM_FAIL(p->err, UMP_ERR_PARSE,
                            "%s:%d: $%s used as a keyword must name a word entry", t->file,
                            t->line, name);
        (void)foam_lex_next(lx, &nt);
        foam_entry ne;
        memset(&ne, 0, sizeof ne);
        ne.key = e->tok[0].v.str;
        ne.is_pattern = e->tok[0].type == FOAM_TOK_STRING;
        ne.file = t->file;
        ne.line = t->line;
        UMP_CALL(parse_block(p, lx, d, ne.key, nt.line, &ne.dict));
        return dict_add(p, d, &ne);
    }
    if (!e)
        return UMP_OK;
    if (!e->dict)
        return FOAM_FAIL(p->err, UMP_ERR_PARSE,
                        "%s:%d: $%s; merges a dictionary, but %s is a primitive entry "
                        "(%s:%d)",
                        t->file, t->line, name, name, e->file, e->line);
    ump_status rc;
    foam_dict *c = dict_copy(p, e->dict, d, t, &rc);
    if (!c)
        return rc;
    return dict_merge(p, d, c);
}

/* Entries of d until '}' (until_brace) or end of input. */
static ump_status parse_entries(parser *p, foam_lexer *lx, foam_dict *d, int until_brace,
                                int is_include, int open_line)
{
    char tb[128];
    for (;;) {
        foam_token t;
        UMP_CALL(foam_lex_next(lx, &t));
        if (foam_lex_is_eof(&t)) {
            if (until_brace)
                return FOAM_FAIL(p->err, UMP_ERR_PARSE,
                                "%s:%d: expected '}' closing dictionary '%s' opened at line %d, "
                                "found end of file",
                                lx->file, t.line, d->name, open_line);
            return UMP_OK;
        }
        if (t.type == FOAM_TOK_PUNCT && t.v.punct == '}') {
            if (until_brace)
                return UMP_OK;
            return FOAM_FAIL(p->err, UMP_ERR_PARSE,
                            "%s:%d: expected a keyword, found '}' (no matching '{')", t.file,
                            t.line);
        }
        if (t.type == FOAM_TOK_PUNCT && t.v.punct == ';')
            continue; /* stray ';' is allowed */
        if (t.type == FOAM_TOK_WORD && t.v.str[0] == '#') {
            UMP_CALL(directive_dict(p, lx, d, &t));
            continue;
        }
        if (t.type == FOAM_TOK_WORD && t.v.str[0] == '$') {
            UMP_CALL(var_keyword(p, lx, d, &t));
            continue;
        }
        if (t.type != FOAM_TOK_WORD && t.type != FOAM_TOK_STRING) {
            tokstr(&t, tb, sizeof tb);
            return FOAM_FAIL(p->err, UMP_ERR_PARSE, "%s:%d: expected a keyword%s, found %s",
                            t.file, t.line, until_brace ? " or '}'" : "", tb);
        }
        foam_entry e;
        memset(&e, 0, sizeof e);
        e.key = t.v.str;
        e.is_pattern = t.type == FOAM_TOK_STRING;
        e.file = t.file;
        e.line = t.line;
        foam_token nt;
        UMP_CALL(foam_lex_peek(lx, &nt));
        if (nt.type == FOAM_TOK_PUNCT && nt.v.punct == '{') {
            (void)foam_lex_next(lx, &nt);
            UMP_CALL(parse_block(p, lx, d, e.key, nt.line, &e.dict));
        } else {
            size_t base = p->nstk;
            UMP_CALL(parse_tokens(p, lx, d, MODE_ENTRY, e.key, e.line));
            UMP_CALL(take_tokens(p, base, &e));
        }
        /* the header of an included file (or a repeated one) is dropped */
        if ((is_include || !d->parent) && strcmp(e.key, "FoamFile") == 0 && e.dict)
            continue;
        UMP_CALL(dict_add(p, d, &e));
    }
}

/* ---- header and body ------------------------------------------------------------- */

static const char *entry_text(const foam_dict *h, const char *key)
{
    long i = find_exact(h, key);
    if (i < 0 || h->e[i].dict || h->e[i].ntok != 1)
        return NULL;
    const foam_token *t = &h->e[i].tok[0];
    return t->type == FOAM_TOK_WORD || t->type == FOAM_TOK_STRING ? t->v.str : NULL;
}

/* "LSB;label=32;scalar=64" */
static ump_status parse_arch(parser *p, const char *arch, const foam_entry *e)
{
    const char *s = arch;
    while (*s) {
        const char *semi = strchr(s, ';');
        size_t n = semi ? (size_t)(semi - s) : strlen(s);
        char item[64];
        if (n >= sizeof item)
            n = sizeof item - 1;
        memcpy(item, s, n);
        item[n] = '\0';
        if (strcmp(item, "MSB") == 0)
            return FOAM_FAIL(p->err, UMP_ERR_UNSUPPORTED,
                            "%s:%d: big-endian (MSB) binary files are not supported", e->file,
                            e->line);
        if (strncmp(item, "label=", 6) == 0 || strncmp(item, "scalar=", 7) == 0) {
            int is_label = item[0] == 'l';
            const char *v = item + (is_label ? 6 : 7);
            int bits = strcmp(v, "32") == 0 ? 32 : strcmp(v, "64") == 0 ? 64 : 0;
            if (!bits)
                return FOAM_FAIL(p->err, UMP_ERR_UNSUPPORTED,
                                "%s:%d: arch \"%s\": expected %s=32 or %s=64", e->file, e->line,
                                arch, is_label ? "label" : "scalar", is_label ? "label" : "scalar");
            if (is_label)
                p->f->label_bytes = bits / 8;
            else
                p->f->scalar_bytes = bits / 8;
        }
        if (!semi)
            break;
        s = semi + 1;
    }
    return UMP_OK;
}

static ump_status read_header(parser *p, foam_dict *h)
{
    foam_file *f = p->f;
    const char *fmt = entry_text(h, "format");
    long fi = find_exact(h, "format");
    if (fi >= 0) {
        if (!fmt || (strcmp(fmt, "ascii") != 0 && strcmp(fmt, "binary") != 0))
            return FOAM_FAIL(p->err, UMP_ERR_PARSE,
                            "%s:%d: FoamFile format: expected ascii or binary", h->e[fi].file,
                            h->e[fi].line);
        f->binary = strcmp(fmt, "binary") == 0;
    }
    const char *s;
    if ((s = entry_text(h, "class")) != NULL)
        f->class_name = (char *)s;
    if ((s = entry_text(h, "object")) != NULL)
        f->object = (char *)s;
    if ((s = entry_text(h, "location")) != NULL)
        f->location = (char *)s;
    long ai = find_exact(h, "arch");
    if (ai >= 0 && f->binary) {
        const char *arch = entry_text(h, "arch");
        if (!arch)
            return FOAM_FAIL(p->err, UMP_ERR_PARSE, "%s:%d: FoamFile arch: expected a string",
                            h->e[ai].file, h->e[ai].line);
        UMP_CALL(parse_arch(p, arch, &h->e[ai]));
    }
    return UMP_OK;
}

/* Binary body classes whose content is one (or two) contiguous lists. */
static int body_blob_class(const char *cls, int *ncomp, int *is_label, int *nlists)
{
    static const struct { const char *name; int ncomp, label, nlists; } cl[] = {
        {"labelList", 1, 1, 1},        {"labelField", 1, 1, 1},
        {"scalarField", 1, 0, 1},      {"scalarList", 1, 0, 1},
        {"vectorField", 3, 0, 1},      {"vectorList", 3, 0, 1},
        {"sphericalTensorField", 1, 0, 1}, {"symmTensorField", 6, 0, 1},
        {"tensorField", 9, 0, 1},      {"faceCompactList", 1, 1, 2},
    };
    for (size_t i = 0; i < sizeof cl / sizeof cl[0]; i++)
        if (strcmp(cls, cl[i].name) == 0) {
            *ncomp = cl[i].ncomp;
            *is_label = cl[i].label;
            *nlists = cl[i].nlists;
            return 1;
        }
    return 0;
}

/* Binary bodies that are text apart from List<T> entries or inner label
 * lists: these are tokenized normally. */
static int body_text_class(const char *cls, int *inner_labels)
{
    static const char *const text[] = {"polyBoundaryMesh", "cellZoneMesh", "faceZoneMesh",
                                       "pointZoneMesh", "regIOobject", "dictionary"};
    *inner_labels = strcmp(cls, "faceList") == 0 || strcmp(cls, "labelListList") == 0 ||
                    strcmp(cls, "cellList") == 0;
    if (*inner_labels)
        return 1;
    for (size_t i = 0; i < sizeof text / sizeof text[0]; i++)
        if (strcmp(cls, text[i]) == 0)
            return 1;
    return 0;
}

static ump_status expect_count(parser *p, foam_lexer *lx, foam_token *t, const char *what)
{
    UMP_CALL(foam_lex_next(lx, t));
    if (t->type != FOAM_TOK_LABEL || t->v.label < 0) {
        char tb[128];
        tokstr(t, tb, sizeof tb);
        return FOAM_FAIL(p->err, foam_lex_is_eof(t) ? UMP_ERR_IO : UMP_ERR_PARSE,
                        "%s:%d: expected the size of %s, found %s", lx->file, t->line, what, tb);
    }
    return UMP_OK;
}

static ump_status parse_body(parser *p, foam_lexer *lx)
{
    foam_file *f = p->f;
    if (f->binary) {
        int ncomp = 0, is_label = 0, nlists = 0, inner = 0;
        if (body_blob_class(f->class_name, &ncomp, &is_label, &nlists)) {
            for (int k = 0; k < nlists; k++) {
                foam_token t, bt;
                UMP_CALL(expect_count(p, lx, &t, "binary list"));
                UMP_CALL(foam_lex_blob(lx, t.v.label, ncomp, is_label, t.line, &bt));
                UMP_CALL(push_tok(p, &bt));
            }
        } else if (body_text_class(f->class_name, &inner)) {
            if (inner) {
                /* N ( M(raw) M(raw) ... ) */
                foam_token t, o;
                UMP_CALL(expect_count(p, lx, &t, "list"));
                UMP_CALL(push_tok(p, &t));
                UMP_CALL(foam_lex_next(lx, &o));
                if (!(o.type == FOAM_TOK_PUNCT && o.v.punct == '(')) {
                    char tb[128];
                    tokstr(&o, tb, sizeof tb);
                    return FOAM_FAIL(p->err, UMP_ERR_PARSE, "%s:%d: expected '(', found %s",
                                    lx->file, o.line, tb);
                }
                UMP_CALL(push_tok(p, &o));
                for (int64_t i = 0; i < t.v.label; i++) {
                    foam_token c, bt;
                    UMP_CALL(expect_count(p, lx, &c, "binary label list"));
                    UMP_CALL(foam_lex_blob(lx, c.v.label, 1, 1, c.line, &bt));
                    UMP_CALL(push_tok(p, &bt));
                }
                UMP_CALL(foam_lex_next(lx, &o));
                if (!(o.type == FOAM_TOK_PUNCT && o.v.punct == ')')) {
                    char tb[128];
                    tokstr(&o, tb, sizeof tb);
                    return FOAM_FAIL(p->err, foam_lex_is_eof(&o) ? UMP_ERR_IO : UMP_ERR_PARSE,
                                    "%s:%d: expected ')' after %lld lists, found %s", lx->file,
                                    o.line, (long long)t.v.label, tb);
                }
                UMP_CALL(push_tok(p, &o));
            }
        } else {
            return FOAM_FAIL(p->err, UMP_ERR_UNSUPPORTED,
                            "%s: binary files of class '%s' are not supported", f->path,
                            f->class_name);
        }
    } else {
        int shape = strcmp(f->class_name, "labelList") == 0    ? FOAM_ASCII_LABELS
                    : strcmp(f->class_name, "vectorField") == 0 ? FOAM_ASCII_VECTORS
                    : strcmp(f->class_name, "faceList") == 0    ? FOAM_ASCII_FACES
                                                                : 0;
        foam_token bt[2];
        int nb = 0;
        if (shape)
            UMP_CALL(foam_lex_ascii_list(lx, shape, bt, &nb));
        for (int k = 0; k < nb; k++)
            UMP_CALL(push_tok(p, &bt[k]));
    }
    UMP_CALL(parse_tokens(p, lx, f->dict, MODE_EOF, "", 0));
    return UMP_OK;
}

static void free_ptr(void *q) { free(q); }

static ump_status parse_file(parser *p, const char *buf, size_t len)
{
    foam_file *f = p->f;
    foam_lexer lx;
    foam_lex_init(&lx, buf, len, f->path, p->a, p->err);
    foam_token t;
    UMP_CALL(foam_lex_peek(&lx, &t));
    if (t.type == FOAM_TOK_WORD && strcmp(t.v.str, "FoamFile") == 0) {
        (void)foam_lex_next(&lx, &t);
        foam_token o;
        UMP_CALL(foam_lex_next(&lx, &o));
        if (!(o.type == FOAM_TOK_PUNCT && o.v.punct == '{')) {
            char tb[128];
            tokstr(&o, tb, sizeof tb);
            return FOAM_FAIL(p->err, UMP_ERR_PARSE, "%s:%d: expected '{' after FoamFile, found %s",
                            f->path, o.line, tb);
        }
        UMP_CALL(parse_block(p, &lx, NULL, "FoamFile", o.line, &f->header));
        UMP_CALL(read_header(p, f->header));
        lx.binary = f->binary;
        lx.label_bytes = f->label_bytes;
        lx.scalar_bytes = f->scalar_bytes;
        UMP_CALL(foam_lex_peek(&lx, &t));
    }
    if (t.type == FOAM_TOK_LABEL || (t.type == FOAM_TOK_PUNCT && t.v.punct == '(')) {
        UMP_CALL(parse_body(p, &lx));
        /* hand the scratch stack over as the body (no copy) */
        f->nbody = p->nstk;
        if (p->nstk == 0) {
            f->body = foam_arena_alloc(p->a, 1, sizeof *f->body);
            if (!f->body)
                return oom(p, f->path, 0);
        } else {
            foam_token *b = ump_realloc_array(p->stk, p->nstk, sizeof *b);
            if (b)
                p->stk = b;
            f->body = p->stk;
            p->stk = NULL;
            p->nstk = p->capstk = 0;
            if (!foam_arena_adopt(p->a, f->body, free_ptr)) {
                f->body = NULL;
                f->nbody = 0;
                return oom(p, f->path, 0);
            }
        }
        return UMP_OK;
    }
    return parse_entries(p, &lx, f->dict, 0, 0, 0);
}

ump_status foam_file_parse_ex(const char *name, const char *buf, size_t len, unsigned flags,
                              foam_file **out, ump_err *err)
{
    *out = NULL;
    if (!name)
        name = "(buffer)";
    if (!buf && len)
        return FOAM_FAIL(err, UMP_ERR_INPUT, "%s: no data", name);
    foam_file *f = ump_alloc_array(1, sizeof *f);
    foam_arena *a = f ? foam_arena_new() : NULL;
    if (!a) {
        free(f);
        return FOAM_FAIL(err, UMP_ERR_NOMEM, "%s: out of memory", name);
    }
    f->arena = a;
    f->label_bytes = 4;
    f->scalar_bytes = 8;
    f->path = foam_arena_strndup(a, name, strlen(name));
    f->class_name = foam_arena_strndup(a, "", 0);
    f->object = f->class_name;
    if (!f->path || !f->class_name) {
        foam_file_free(&f);
        return FOAM_FAIL(err, UMP_ERR_NOMEM, "%s: out of memory", name);
    }
    parser p;
    memset(&p, 0, sizeof p);
    p.f = f;
    p.a = a;
    p.err = err;
    p.flags = flags;
    p.budget = (size_t)1 << 20;
    p.budget += len > SIZE_MAX / 32 ? SIZE_MAX / 4 : len * 16;
    f->dict = new_dict(&p, NULL, "", f->path, 1);
    ump_status rc = f->dict ? parse_file(&p, buf ? buf : "", len)
                            : FOAM_FAIL(err, UMP_ERR_NOMEM, "%s: out of memory", name);
    free(p.stk);
    if (rc != UMP_OK) {
        foam_file_free(&f);
        return rc;
    }
    *out = f;
    return UMP_OK;
}

ump_status foam_file_parse(const char *name, const char *buf, size_t len, foam_file **out,
                           ump_err *err)
{
    return foam_file_parse_ex(name, buf, len, 0, out, err);
}

ump_status foam_file_read(const char *path, foam_file **out, ump_err *err)
{
    *out = NULL;
    if (!path)
        return FOAM_FAIL(err, UMP_ERR_IO, "cannot open (null path)");
    char *real = foam_resolve_gz(path);
    if (!real)
        return FOAM_FAIL(err, UMP_ERR_IO, "cannot open %s (nor %s.gz)", path, path);
    char *buf;
    size_t len;
    ump_status rc = foam_read_whole_file(real, &buf, &len, err);
    if (rc == UMP_OK) {
        rc = foam_file_parse_ex(real, buf, len, 0, out, err);
        free(buf);
    }
    free(real);
    return rc;
}

ump_status foam_read_text(const char *path, char **buf, size_t *len, ump_err *err)
{
    *buf = NULL;
    *len = 0;
    char *real = path ? foam_resolve_gz(path) : NULL;
    if (!real)
        return FOAM_FAIL(err, UMP_ERR_IO, "cannot open %s (nor %s.gz)", path ? path : "(null path)",
                         path ? path : "");
    ump_status rc = foam_read_whole_file(real, buf, len, err);
    free(real);
    return rc;
}

void foam_file_free(foam_file **fp)
{
    if (!fp || !*fp)
        return;
    foam_arena_free((*fp)->arena);
    free(*fp);
    *fp = NULL;
}

/* glibc's regcomp copies the tree of an atom for every '+' and interval
 * applied to it, so "a++++..." or (a{100}){100} build exponentially large
 * automata. Estimate that size (atoms, doubled by '+', times n+1 by {m,n})
 * and refuse costly patterns, and back-references (backtracking), treating
 * them as matching nothing: real OpenFOAM keys never need them. */
static int pattern_too_costly(const char *pat, size_t n)
{
    enum { MAXDEPTH = 32 };
    const double limit = 4096;
    double outer[MAXDEPTH], cur = 0, last = 0;
    int sp = 0;
    if (n > 1024)
        return 1;
    for (size_t i = 0; i < n; i++) {
        char c = pat[i];
        if (c == '\\') {
            if (i + 1 < n && pat[i + 1] >= '1' && pat[i + 1] <= '9')
                return 1;
            i++;
            last = 1;
            cur += 1;
        } else if (c == '[') {
            size_t j = i + 1;
            if (j < n && pat[j] == '^')
                j++;
            if (j < n && pat[j] == ']')
                j++;
            while (j < n && pat[j] != ']')
                j++;
            i = j;
            last = 1;
            cur += 1;
        } else if (c == '(') {
            if (sp == MAXDEPTH)
                return 1;
            outer[sp++] = cur;
            cur = 0;
            last = 0;
        } else if (c == ')' && sp > 0) {
            last = cur;
            cur = outer[--sp] + last;
        } else if (c == '|') {
            last = 0;
        } else if (c == '+') {
            cur += last;
            last *= 2;
        } else if (c == '{') {
            long hi = 0;
            size_t j = i + 1;
            while (j < n && pat[j] != '}') {
                long v = 0;
                while (j < n && pat[j] >= '0' && pat[j] <= '9' && v < 100000)
                    v = v * 10 + (pat[j++] - '0');
                if (v > hi)
                    hi = v;
                if (j < n && pat[j] != '}' && !(pat[j] >= '0' && pat[j] <= '9'))
                    j++;
            }
            i = j;
            cur += last * (double)hi;
            last *= (double)(hi + 1);
        } else if (c == '*' || c == '?') {
            /* no copy */
        } else {
            last = 1;
            cur += 1;
        }
        double total = cur;
        for (int k = 0; k < sp; k++)
            total += outer[k];
        if (total > limit || last > limit)
            return 1;
    }
    return 0;
}

/* Compile a key pattern for whole-string matching, as OpenFOAM's
 * regExp::match; 0 when it cannot be used (then it matches nothing). */
static int pattern_compile(const char *pattern, regex_t *rx)
{
    size_t n = strlen(pattern);
    if (pattern_too_costly(pattern, n))
        return 0;
    char *re = ump_alloc_array(n + 5, 1);
    if (!re)
        return 0;
    re[0] = '^';
    re[1] = '(';
    memcpy(re + 2, pattern, n);
    memcpy(re + 2 + n, ")$", 3);
    int ok = regcomp(rx, re, REG_EXTENDED | REG_NOSUB) == 0;
    free(re);
    return ok;
}

int foam_entry_match(const foam_entry *e, const char *key)
{
    if (e->rx)
        return regexec(e->rx, key, 0, NULL, 0) == 0;
    return foam_pattern_match(e->key, key);
}

int foam_pattern_match(const char *pattern, const char *key)
{
    regex_t rx;
    if (!pattern_compile(pattern, &rx))
        return 0;
    int m = regexec(&rx, key, 0, NULL, 0) == 0;
    regfree(&rx);
    return m;
}
