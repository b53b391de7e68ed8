/* SPDX-License-Identifier: GPL-3.0-or-later
 * foam_lex.c -- FoamFile tokenizer: storage arena, OpenFOAM v1912 lexical
 * rules (ISstream), binary contiguous blocks, and reading plain or gzip
 * files through zlib.
 *
 * The tokenizer works on an in-memory buffer and produces one token at a
 * time; strings go into the arena, so tokens never need freeing.
 */
#include "foam_internal.h"

#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <zlib.h>

ump_status foam_oneline(ump_err *err, ump_status rc)
{
    if (err && rc != UMP_OK)
        for (char *c = err->msg; *c; c++)
            if ((unsigned char)*c < 32 || *c == 127)
                *c = ' ';
    return rc;
}

/* ---- arena --------------------------------------------------------------- */

/* Blocks are allocated with this many bytes of payload; larger requests get
 * a block of their own so that a big list never wastes a partial block. */
enum { ARENA_BLOCK = 64 * 1024, ARENA_ALIGN = 16 };

typedef struct arena_blk {
    struct arena_blk *next;
    size_t cap, used;
} arena_blk;

typedef struct arena_cleanup {
    struct arena_cleanup *next;
    void *p;
    void (*fn)(void *);
} arena_cleanup;

struct foam_arena {
    arena_blk *head;        /* current bump block first */
    arena_cleanup *clean;
};

/* Header size rounded so that the payload is ARENA_ALIGN aligned. */
#define BLK_HDR (((sizeof(arena_blk) + ARENA_ALIGN - 1) / ARENA_ALIGN) * ARENA_ALIGN)

foam_arena *foam_arena_new(void)
{
    return ump_alloc_array(1, sizeof(foam_arena));
}

void foam_arena_free(foam_arena *a)
{
    if (!a)
        return;
    /* cleanup records live in the arena blocks: run them before freeing */
    for (arena_cleanup *c = a->clean; c; c = c->next)
        c->fn(c->p);
    arena_blk *b = a->head;
    while (b) {
        arena_blk *nx = b->next;
        free(b);
        b = nx;
    }
    free(a);
}

void *foam_arena_alloc(foam_arena *a, size_t n, size_t size)
{
    if (size != 0 && n > SIZE_MAX / size)
        return NULL;
    size_t bytes = n * size;
    if (bytes > SIZE_MAX - ARENA_ALIGN - BLK_HDR)
        return NULL;
    bytes = (bytes + ARENA_ALIGN - 1) / ARENA_ALIGN * ARENA_ALIGN;
    if (bytes == 0)
        bytes = ARENA_ALIGN;
    if (bytes > ARENA_BLOCK / 4) {
        /* dedicated block, linked behind the current bump block */
        arena_blk *b = ump_alloc_array(1, BLK_HDR + bytes);
        if (!b)
            return NULL;
        b->cap = b->used = bytes;
        if (a->head) {
            b->next = a->head->next;
            a->head->next = b;
        } else {
            a->head = b;
        }
        return (char *)b + BLK_HDR;
    }
    arena_blk *h = a->head;
    if (!h || h->cap - h->used < bytes) {
        h = ump_realloc_array(NULL, 1, BLK_HDR + ARENA_BLOCK);
        if (!h)
            return NULL;
        h->cap = ARENA_BLOCK;
        h->used = 0;
        h->next = a->head;
        a->head = h;
    }
    void *p = (char *)h + BLK_HDR + h->used;
    h->used += bytes;
    memset(p, 0, bytes);
    return p;
}

char *foam_arena_strndup(foam_arena *a, const char *s, size_t n)
{
    char *d = foam_arena_alloc(a, n + 1, 1);
    if (d) {
        if (n)
            memcpy(d, s, n);
        d[n] = '\0';
    }
    return d;
}

int foam_arena_adopt(foam_arena *a, void *p, void (*fn)(void *))
{
    arena_cleanup *c = foam_arena_alloc(a, 1, sizeof *c);
    if (!c) {
        fn(p);
        return 0;
    }
    c->p = p;
    c->fn = fn;
    c->next = a->clean;
    a->clean = c;
    return 1;
}

/* ---- character classes (ISstream / word::valid of v1912) ----------------- */

static int is_blank(int c)
{
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f';
}

/* word::valid(): anything but blanks, quotes, '/', ';', '{', '}' */
static int is_word_char(int c)
{
    return !is_blank(c) && c != '"' && c != '\'' && c != '/' && c != ';' &&
           c != '{' && c != '}';
}

/* Punctuation that is a token of its own when it starts a token. '-' is
 * punctuation only when no number follows (handled with numbers). */
static int is_punct_start(int c)
{
    return c == ';' || c == '(' || c == ')' || c == '[' || c == ']' || c == '{' ||
           c == '}' || c == ':' || c == ',' || c == '=' || c == '+' || c == '*' ||
           c == '/';
}

static int is_number_char(int c)
{
    return (c >= '0' && c <= '9') || c == '+' || c == '-' || c == '.' || c == 'e' ||
           c == 'E';
}

/* ---- lexer ----------------------------------------------------------------- */

void foam_lex_init(foam_lexer *lx, const char *buf, size_t len, const char *file,
              foam_arena *a, ump_err *err)
{
    memset(lx, 0, sizeof *lx);
    lx->buf = buf;
    lx->len = len;
    lx->line = 1;
    lx->file = file;
    lx->label_bytes = 4;
    lx->scalar_bytes = 8;
    lx->arena = a;
    lx->err = err;
}

int foam_lex_is_eof(const foam_token *t)
{
    return t->type == FOAM_TOK_PUNCT && t->v.punct == 0;
}

/* Skip blanks and comments. A '/' that starts no comment is left alone. */
static ump_status skip_blank(foam_lexer *lx)
{
    const char *b = lx->buf;
    size_t n = lx->len, i = lx->pos;
    int line = lx->line;
    for (;;) {
        while (i < n && is_blank((unsigned char)b[i])) {
            if (b[i] == '\n')
                line++;
            i++;
        }
        if (i + 1 < n && b[i] == '/' && b[i + 1] == '/') {
            i += 2;
            while (i < n && b[i] != '\n')
                i++;
            continue;
        }
        if (i + 1 < n && b[i] == '/' && b[i + 1] == '*') {
            int start = line;
            i += 2;
            for (;;) {
                if (i + 1 >= n) {
                    lx->pos = n;
                    lx->line = line;
                    return FOAM_FAIL(lx->err, UMP_ERR_PARSE,
                                    "%s:%d: unterminated /* comment, found end of file",
                                    lx->file, start);
                }
                if (b[i] == '*' && b[i + 1] == '/') {
                    i += 2;
                    break;
                }
                if (b[i] == '\n')
                    line++;
                i++;
            }
            continue;
        }
        break;
    }
    lx->pos = i;
    lx->line = line;
    return UMP_OK;
}

static ump_status nomem(foam_lexer *lx)
{
    return FOAM_FAIL(lx->err, UMP_ERR_NOMEM, "%s:%d: out of memory", lx->file, lx->line);
}

static ump_status make_word(foam_lexer *lx, size_t start, size_t end, foam_token *t)
{
    t->type = FOAM_TOK_WORD;
    t->v.str = foam_arena_strndup(lx->arena, lx->buf + start, end - start);
    return t->v.str ? UMP_OK : nomem(lx);
}

/* A word: word characters, keeping balanced '(' ')' (div(phi,U)); an
 * unmatched ')' ends it, and so does a ']' outside parentheses (ISstream
 * keeps it, but then "[kg/m^3]" would leave the ']' inside the word "m^3]";
 * OpenFOAM's dimensionSet reader splits it off again). Returns the end. */
static size_t scan_word(const foam_lexer *lx, size_t i, int allow_slash)
{
    const char *b = lx->buf;
    int depth = 0;
    while (i < lx->len) {
        int c = (unsigned char)b[i];
        if (!is_word_char(c) && !(allow_slash && c == '/'))
            break;
        if (c == '(')
            depth++;
        else if (c == ']' && depth == 0)
            break; /* closes a dimension set: [kg/m^3] */
        else if (c == ')') {
            if (depth == 0)
                break;
            depth--;
        }
        i++;
    }
    return i;
}

/* "quoted string": \" becomes ", a backslash-newline becomes a newline,
 * other backslashes stay (OpenFOAM keeps them); an unescaped newline is an
 * error. */
static ump_status lex_string(foam_lexer *lx, foam_token *t)
{
    const char *b = lx->buf;
    size_t i = lx->pos + 1, n = lx->len;
    int escaped = 0, start_line = lx->line;
    size_t end = 0;
    int found = 0;
    for (; i < n; i++) {
        char c = b[i];
        if (c == '\\') {
            escaped = !escaped;
        } else if (c == '"') {
            if (!escaped) {
                end = i;
                found = 1;
                break;
            }
            escaped = 0;
        } else if (c == '\n') {
            if (!escaped)
                return FOAM_FAIL(lx->err, UMP_ERR_PARSE,
                                "%s:%d: unterminated string (newline inside \"...\")",
                                lx->file, start_line);
            escaped = 0;
        } else {
            escaped = 0;
        }
    }
    if (!found)
        return FOAM_FAIL(lx->err, UMP_ERR_PARSE,
                        "%s:%d: unterminated string, found end of file", lx->file,
                        start_line);
    char *s = foam_arena_alloc(lx->arena, end - lx->pos, 1);
    if (!s)
        return nomem(lx);
    size_t o = 0;
    escaped = 0;
    for (i = lx->pos + 1; i < end; i++) {
        char c = b[i];
        if (c == '\\') {
            escaped = !escaped;
            s[o++] = c;
        } else if ((c == '"' || c == '\n') && escaped) {
            s[o - 1] = c; /* overwrite the backslash */
            escaped = 0;
            if (c == '\n')
                lx->line++;
        } else {
            escaped = 0;
            s[o++] = c;
        }
    }
    s[o] = '\0';
    t->type = FOAM_TOK_STRING;
    t->v.str = s;
    lx->pos = end + 1;
    return UMP_OK;
}

/* #{ verbatim text #} -> string token (used by coded boundary conditions) */
static ump_status lex_verbatim(foam_lexer *lx, foam_token *t)
{
    const char *b = lx->buf;
    size_t i = lx->pos + 2, n = lx->len;
    int line = lx->line;
    for (; i + 1 < n; i++) {
        if (b[i] == '#' && b[i + 1] == '}') {
            t->type = FOAM_TOK_STRING;
            t->v.str = foam_arena_strndup(lx->arena, b + lx->pos + 2, i - lx->pos - 2);
            if (!t->v.str)
                return nomem(lx);
            lx->pos = i + 2;
            lx->line = line;
            return UMP_OK;
        }
        if (b[i] == '\n')
            line++;
    }
    return FOAM_FAIL(lx->err, UMP_ERR_PARSE,
                    "%s:%d: unterminated #{ verbatim block, found end of file", lx->file,
                    lx->line);
}

/* Decimal text -> double without strtod for the common case (Clinger's
 * fast path, W. D. Clinger, "How to read floating point numbers
 * accurately", PLDI 1990): when the significant digits form an integer
 * m < 2^53 and the power of ten k has |k| <= 22, both m and 10^|k| are
 * exact doubles and one multiplication or division rounds correctly -- the
 * value strtod returns. Form: [-]digits[.digits][(e|E)[+|-]digits], at
 * least one mantissa digit, all of s[0..len). Returns 0 for anything else
 * (then strtod decides, as before). */
static int fast_scalar(const char *s, size_t len, double *out)
{
    static const double p10[23] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                   1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                   1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
    size_t i = 0;
    int neg = s[0] == '-', nd = 0, any = 0, k = 0;
    i += (size_t)neg;
    uint64_t m = 0;
    for (int frac = 0; i < len; i++) {
        char c = s[i];
        if (c == '.' && !frac) {
            frac = 1;
            continue;
        }
        if (c < '0' || c > '9')
            break;
        any = 1;
        if (m == 0 && c == '0') { /* leading zeros carry no digit */
            k -= frac;
            continue;
        }
        if (++nd > 19)
            return 0;
        m = m * 10 + (uint64_t)(c - '0');
        k -= frac;
    }
    if (!any)
        return 0;
    if (i < len) {
        if (s[i] != 'e' && s[i] != 'E')
            return 0;
        i++;
        int eneg = 0, e = 0, ed = 0;
        if (i < len && (s[i] == '+' || s[i] == '-'))
            eneg = s[i++] == '-';
        for (; i < len && s[i] >= '0' && s[i] <= '9'; i++, ed++)
            if (e < 10000)
                e = e * 10 + (s[i] - '0');
        if (ed == 0 || i < len)
            return 0;
        k += eneg ? -e : e;
    }
    double v;
    if (m == 0)
        v = 0.0;
    else if (m > (UINT64_C(1) << 53) || k < -22 || k > 22)
        return 0;
    else
        v = k >= 0 ? (double)m * p10[k] : (double)m / p10[-k];
    *out = neg ? -v : v;
    return 1;
}

/* Number: the run of [0-9+-.eE] as ISstream collects it. Digits only (with
 * an optional leading '-') -> label, or scalar when it overflows int64;
 * otherwise scalar when strtod takes the whole run; otherwise a word. */
static ump_status lex_number(foam_lexer *lx, foam_token *t)
{
    const char *b = lx->buf;
    size_t s = lx->pos, i = s + 1;
    while (i < lx->len && is_number_char((unsigned char)b[i]))
        i++;
    size_t len = i - s;
    if (len == 1 && b[s] == '-') {
        t->type = FOAM_TOK_PUNCT;
        t->v.punct = '-';
        lx->pos = i;
        return UMP_OK;
    }
    if (len >= 128)
        return FOAM_FAIL(lx->err, UMP_ERR_PARSE, "%s:%d: number too long (%zu characters)",
                        lx->file, lx->line, len);
    int neg = b[s] == '-';
    int aslabel = b[s] != '.' && len > (size_t)neg;
    for (size_t k = s + 1; k < i && aslabel; k++)
        aslabel = b[k] >= '0' && b[k] <= '9';
    lx->pos = i;
    if (aslabel && len - (size_t)neg <= 18) { /* below 10^18: cannot overflow int64 */
        int64_t v = 0;
        for (size_t k = s + (size_t)neg; k < i; k++)
            v = v * 10 + (b[k] - '0');
        t->type = FOAM_TOK_LABEL;
        t->v.label = neg ? -v : v;
        return UMP_OK;
    }
    if (!aslabel) {
        double d;
        if (fast_scalar(b + s, len, &d)) {
            t->type = FOAM_TOK_SCALAR;
            t->v.scalar = d;
            return UMP_OK;
        }
    }
    if (aslabel) {
        uint64_t v = 0, lim = neg ? (uint64_t)INT64_MAX + 1u : (uint64_t)INT64_MAX;
        int ok = 1;
        for (size_t k = s + (size_t)neg; k < i; k++) {
            unsigned d = (unsigned)(b[k] - '0');
            if (v > (lim - d) / 10) {
                ok = 0;
                break;
            }
            v = v * 10 + d;
        }
        if (ok) {
            t->type = FOAM_TOK_LABEL;
            if (neg)
                t->v.label = v == (uint64_t)INT64_MAX + 1u ? INT64_MIN : -(int64_t)v;
            else
                t->v.label = (int64_t)v;
            return UMP_OK;
        }
    }
    char nb[128];
    memcpy(nb, b + s, len);
    nb[len] = '\0';
    char *endp;
    errno = 0;
    double d = strtod(nb, &endp);
    if (endp == nb + len) {
        t->type = FOAM_TOK_SCALAR;
        t->v.scalar = d;
        return UMP_OK;
    }
    return make_word(lx, s, i, t);
}

ump_status foam_lex_next(foam_lexer *lx, foam_token *t)
{
    if (lx->has_back) {
        *t = lx->back;
        lx->has_back = 0;
        return UMP_OK;
    }
    memset(t, 0, sizeof *t);
    UMP_CALL(skip_blank(lx));
    t->file = lx->file;
    t->line = lx->line;
    t->type = FOAM_TOK_PUNCT;
    if (lx->pos >= lx->len) {
        t->v.punct = 0; /* end of input */
        return UMP_OK;
    }
    const char *b = lx->buf;
    size_t p = lx->pos;
    int c = (unsigned char)b[p];
    int next = p + 1 < lx->len ? (unsigned char)b[p + 1] : -1;
    if (is_punct_start(c)) {
        t->v.punct = (char)c;
        lx->pos++;
        return UMP_OK;
    }
    if (c == '"')
        return lex_string(lx, t);
    if (c == '-' || c == '.' || (c >= '0' && c <= '9'))
        return lex_number(lx, t);
    if (c == '#') {
        if (next == '{')
            return lex_verbatim(lx, t);
        /* ISstream reads the next non-blank character: "# include" works */
        lx->pos++;
        UMP_CALL(skip_blank(lx));
        size_t q = lx->pos;
        int nc = q < lx->len ? (unsigned char)b[q] : -1;
        if (nc < 0 || !is_word_char(nc) || nc == '#')
            return FOAM_FAIL(lx->err, UMP_ERR_PARSE,
                            "%s:%d: expected a directive name after '#'", lx->file, t->line);
        size_t e = scan_word(lx, q, 0);
        char *w = foam_arena_alloc(lx->arena, e - q + 2, 1);
        if (!w)
            return nomem(lx);
        w[0] = '#';
        memcpy(w + 1, b + q, e - q);
        w[e - q + 1] = '\0';
        t->type = FOAM_TOK_WORD;
        t->v.str = w;
        lx->pos = e;
        return UMP_OK;
    }
    if (c == '$') {
        if (next == '{') {
            /* ${var} or ${{expr}}: up to the matching '}' */
            int depth = 0;
            size_t i = p + 1;
            for (; i < lx->len; i++) {
                if (b[i] == '{')
                    depth++;
                else if (b[i] == '}' && --depth == 0)
                    break;
                else if (b[i] == '\n')
                    break;
            }
            if (i >= lx->len || b[i] != '}')
                return FOAM_FAIL(lx->err, UMP_ERR_PARSE,
                                "%s:%d: expected '}' closing '${', found %s", lx->file,
                                lx->line, i >= lx->len ? "end of file" : "end of line");
            lx->pos = i + 1;
            return make_word(lx, p, i + 1, t);
        }
        if (next < 0 || !(is_word_char(next) || next == '/'))
            return FOAM_FAIL(lx->err, UMP_ERR_PARSE,
                            "%s:%d: expected a variable name after '$'", lx->file, lx->line);
        size_t e = scan_word(lx, p + 1, 1);
        if (e == p + 1)
            return FOAM_FAIL(lx->err, UMP_ERR_PARSE,
                            "%s:%d: expected a variable name after '$'", lx->file, lx->line);
        lx->pos = e;
        return make_word(lx, p, e, t);
    }
    if (!is_word_char(c))
        return FOAM_FAIL(lx->err, UMP_ERR_PARSE, "%s:%d: unexpected character '%c'",
                        lx->file, lx->line, c);
    size_t e = scan_word(lx, p, 0);
    lx->pos = e;
    return make_word(lx, p, e, t);
}

ump_status foam_lex_peek(foam_lexer *lx, foam_token *t)
{
    if (lx->has_back) {
        *t = lx->back;
        return UMP_OK;
    }
    UMP_CALL(foam_lex_next(lx, t));
    lx->back = *t;
    lx->has_back = 1;
    return UMP_OK;
}

void foam_lex_unget(foam_lexer *lx, const foam_token *t)
{
    lx->back = *t;
    lx->has_back = 1;
}

ump_status foam_lex_peek_char(foam_lexer *lx, int *c)
{
    UMP_CALL(skip_blank(lx));
    *c = lx->pos < lx->len ? (unsigned char)lx->buf[lx->pos] : -1;
    return UMP_OK;
}

/* ---- ascii lists in one pass ------------------------------------------------ */

/* Token by token, the faces of the 160^2 cavity took 0.16 s (about 220 ns
 * per token) of a 0.35 s start-up. This reads the same characters once,
 * taking only what the token reader would read to the same values:
 * blanks between items (no comments), decimal labels of at most 18 digits
 * between 0 and UMP_IDX_MAX, each followed by a blank or the one
 * parenthesis that may follow it, scalars as lex_number reads them, and
 * counts that match. Anything else gives up (returns NULL) and the token
 * reader takes over from the start. The cursor is a local pointer: kept in
 * a struct, every int64 store of the output would make the compiler reload
 * it (int64_t and size_t may alias). */
static inline const char *as_blank(const char *p, const char *e, int *line)
{
    while (p < e && is_blank((unsigned char)*p)) {
        *line += *p == '\n';
        p++;
    }
    return p;
}

static inline const char *as_char(const char *p, const char *e, int *line, char c)
{
    p = as_blank(p, e, line);
    return p < e && *p == c ? p + 1 : NULL;
}

/* A label, then a blank or endc (not consumed). */
static inline const char *as_label(const char *p, const char *e, int *line, char endc, int64_t *v)
{
    p = as_blank(p, e, line);
    const char *d0 = p;
    uint64_t x = 0; /* wraps harmlessly past 19 digits: refused below */
    for (; p < e && (unsigned)(*p - '0') < 10u; p++)
        x = x * 10 + (uint64_t)(*p - '0');
    if (p == d0 || p - d0 > 18 || p >= e || x > (uint64_t)UMP_IDX_MAX ||
        !(is_blank((unsigned char)*p) || *p == endc))
        return NULL;
    *v = (int64_t)x;
    return p;
}

/* A scalar as lex_number reads it (a label-like run as the double of that
 * label), then a blank or ')'. */
static const char *as_scalar(const char *p, const char *e, int *line, double *v)
{
    p = as_blank(p, e, line);
    const char *r = p;
    if (p >= e || !(*p == '-' || *p == '.' || (*p >= '0' && *p <= '9')))
        return NULL;
    while (p < e && is_number_char((unsigned char)*p))
        p++;
    size_t len = (size_t)(p - r);
    if (p >= e || !(is_blank((unsigned char)*p) || *p == ')') || len >= 128 || (len == 1 && *r == '-'))
        return NULL;
    int neg = r[0] == '-';
    int aslabel = r[0] != '.' && len > (size_t)neg;
    for (size_t k = 1; k < len && aslabel; k++)
        aslabel = r[k] >= '0' && r[k] <= '9';
    if (aslabel) {
        if (len - (size_t)neg > 18)
            return NULL;
        int64_t x = 0;
        for (size_t k = (size_t)neg; k < len; k++)
            x = x * 10 + (r[k] - '0');
        *v = (double)(neg ? -x : x); /* as the label token converted */
    } else if (!fast_scalar(r, len, v)) {
        char nb[128];
        memcpy(nb, r, len);
        nb[len] = '\0';
        char *endp;
        *v = strtod(nb, &endp);
        if (endp != nb + len)
            return NULL; /* a word to the token reader */
    }
    return p;
}

static void as_free(void *p) { free(p); }

/* A FOAM_TOK_BLOB token (also for the binary lists below). */
static void as_blob(foam_token *t, const foam_lexer *lx, int line, size_t n, int ncomp, int is_label,
                    void *data)
{
    memset(t, 0, sizeof *t);
    t->type = FOAM_TOK_BLOB;
    t->file = lx->file;
    t->line = line;
    t->v.blob.n = n;
    t->v.blob.ncomp = ncomp;
    t->v.blob.is_label = is_label;
    t->v.blob.data = data;
}

ump_status foam_lex_ascii_list(foam_lexer *lx, int shape, foam_token out[2], int *nout)
{
    *nout = 0;
    if (!lx->has_back || lx->back.type != FOAM_TOK_LABEL || lx->back.v.label <= 0 ||
        lx->back.v.label > UMP_IDX_MAX || shape < FOAM_ASCII_LABELS || shape > FOAM_ASCII_FACES)
        return UMP_OK;
    size_t n = (size_t)lx->back.v.label;
    const char *p = lx->buf + lx->pos, *e = lx->buf + lx->len;
    int line = lx->line;
    /* an item takes at least two characters: a larger count is cut short */
    size_t most = (size_t)(e - p) / 2 + 1;
    if (n > most || !(p = as_char(p, e, &line, '(')))
        return UMP_OK;
    /* exact sizes, but for the labels of faces: at most one per two
     * characters (untouched pages cost nothing), shrunk at the end */
    size_t na = shape == FOAM_ASCII_VECTORS ? 3 * n : shape == FOAM_ASCII_FACES ? n + 1 : n;
    size_t nb = shape == FOAM_ASCII_FACES ? most : 0;
    int64_t *a = ump_realloc_array(NULL, na, sizeof *a), *b = NULL;
    if (!a || (nb && !(b = ump_realloc_array(NULL, nb, sizeof *b)))) {
        free(a);
        return nomem(lx);
    }
    size_t nitem = 0;
    if (shape == FOAM_ASCII_LABELS) {
        for (size_t k = 0; p && k < n; k++)
            p = as_label(p, e, &line, ')', &a[k]);
    } else if (shape == FOAM_ASCII_VECTORS) {
        double x[3];
        for (size_t k = 0; p && k < n; k++) {
            if ((p = as_char(p, e, &line, '(')) && (p = as_scalar(p, e, &line, &x[0])) &&
                (p = as_scalar(p, e, &line, &x[1])) && (p = as_scalar(p, e, &line, &x[2])) &&
                (p = as_char(p, e, &line, ')')))
                memcpy(&a[3 * k], x, sizeof x); /* doubles kept in the int64 buffer */
        }
    } else {
        a[0] = 0;
        for (size_t k = 0; p && k < n; k++) {
            int64_t m;
            if (!(p = as_label(p, e, &line, '(', &m)) || !(p = as_char(p, e, &line, '(')) ||
                (uint64_t)m > nb - nitem)
                p = NULL;
            for (int64_t j = 0; p && j < m; j++)
                p = as_label(p, e, &line, ')', &b[nitem++]);
            if (p && (p = as_char(p, e, &line, ')')))
                a[k + 1] = (int64_t)nitem;
        }
        if (p && nitem > (size_t)UMP_IDX_MAX)
            p = NULL;
    }
    if (p)
        p = as_char(p, e, &line, ')');
    if (!p) {
        free(a);
        free(b);
        return UMP_OK;
    }
    if (b) {
        int64_t *q = ump_realloc_array(b, nitem ? nitem : 1, sizeof *b);
        if (q)
            b = q;
    }
    /* a failed adopt frees its block */
    if (!foam_arena_adopt(lx->arena, a, as_free)) {
        free(b);
        return nomem(lx);
    }
    if (b && !foam_arena_adopt(lx->arena, b, as_free))
        return nomem(lx);
    int l0 = lx->back.line;
    if (shape == FOAM_ASCII_FACES) {
        as_blob(&out[0], lx, l0, n + 1, 1, 1, a);
        as_blob(&out[1], lx, l0, nitem, 1, 1, b);
        *nout = 2;
    } else {
        as_blob(&out[0], lx, l0, n, shape == FOAM_ASCII_VECTORS ? 3 : 1, shape == FOAM_ASCII_LABELS, a);
        *nout = 1;
    }
    lx->has_back = 0;
    lx->pos = (size_t)(p - lx->buf);
    lx->line = line;
    return UMP_OK;
}

/* ---- binary blocks ---------------------------------------------------------- */

static uint64_t get_le(const unsigned char *p, int nb)
{
    uint64_t v = 0;
    for (int i = nb - 1; i >= 0; i--)
        v = (v << 8) | p[i];
    return v;
}

static int host_is_le(void)
{
    const uint16_t one = 1;
    unsigned char c;
    memcpy(&c, &one, 1);
    return c == 1;
}

ump_status foam_lex_blob(foam_lexer *lx, int64_t n, int ncomp, int is_label, int line,
                    foam_token *out)
{
    if (lx->has_back)
        return FOAM_FAIL(lx->err, UMP_ERR_PARSE,
                        "%s:%d: internal error: binary list after look-ahead", lx->file, line);
    if (n < 0)
        return FOAM_FAIL(lx->err, UMP_ERR_PARSE, "%s:%d: negative list size %lld",
                        lx->file, line, (long long)n);
    as_blob(out, lx, line, 0, ncomp, is_label, NULL);
    int c;
    UMP_CALL(foam_lex_peek_char(lx, &c));
    if (n == 0) {
        /* "0" alone, or "0 ( )" / "0()" */
        out->v.blob.data = foam_arena_alloc(lx->arena, 1, sizeof(double));
        if (!out->v.blob.data)
            return nomem(lx);
        if (c == '(') {
            lx->pos++;
            UMP_CALL(foam_lex_peek_char(lx, &c));
            if (c != ')')
                return FOAM_FAIL(lx->err, UMP_ERR_PARSE,
                                "%s:%d: expected ')' closing empty list, found %s",
                                lx->file, lx->line, c < 0 ? "end of file" : "other data");
            lx->pos++;
        }
        return UMP_OK;
    }
    if (c != '(')
        return FOAM_FAIL(lx->err, c < 0 ? UMP_ERR_IO : UMP_ERR_PARSE,
                        "%s:%d: expected '(' starting binary list of %lld elements, found %s",
                        lx->file, lx->line, (long long)n,
                        c < 0 ? "end of file (file cut short)" : "other data");
    lx->pos++;
    int csize = is_label ? lx->label_bytes : lx->scalar_bytes;
    size_t avail = lx->len - lx->pos;
    size_t per = (size_t)csize * (size_t)ncomp;
    if ((uint64_t)n > (uint64_t)(avail / per))
        return FOAM_FAIL(lx->err, UMP_ERR_IO,
                        "%s:%d: binary list of %lld elements cut short (%zu bytes left, "
                        "%d-byte components)",
                        lx->file, line, (long long)n, avail, csize);
    size_t cnt = (size_t)n * (size_t)ncomp;
    const unsigned char *src = (const unsigned char *)lx->buf + lx->pos;
    void *data = foam_arena_alloc(lx->arena, cnt, 8);
    if (!data)
        return nomem(lx);
    int le = host_is_le();
    if (is_label) {
        int64_t *d = data;
        if (csize == 8 && le) {
            memcpy(d, src, cnt * 8);
        } else {
            for (size_t k = 0; k < cnt; k++) {
                uint64_t u = get_le(src + k * (size_t)csize, csize);
                if (csize == 4) {
                    d[k] = (int32_t)(uint32_t)u;
                } else {
                    int64_t s;
                    memcpy(&s, &u, 8);
                    d[k] = s;
                }
            }
        }
    } else {
        double *d = data;
        if (csize == 8 && le) {
            memcpy(d, src, cnt * 8);
        } else {
            for (size_t k = 0; k < cnt; k++) {
                uint64_t u = get_le(src + k * (size_t)csize, csize);
                if (csize == 4) {
                    uint32_t u32 = (uint32_t)u;
                    float f;
                    memcpy(&f, &u32, 4);
                    d[k] = f;
                } else {
                    memcpy(&d[k], &u, 8);
                }
            }
        }
    }
    lx->pos += cnt * (size_t)csize;
    out->v.blob.n = (size_t)n;
    out->v.blob.data = data;
    UMP_CALL(foam_lex_peek_char(lx, &c));
    if (c != ')')
        return FOAM_FAIL(lx->err, c < 0 ? UMP_ERR_IO : UMP_ERR_PARSE,
                        "%s:%d: expected ')' after binary list of %lld elements, found %s",
                        lx->file, lx->line, (long long)n,
                        c < 0 ? "end of file (file cut short)" : "other data");
    lx->pos++;
    return UMP_OK;
}

int foam_list_type_ncomp(const char *w, int *is_label)
{
    static const struct { const char *name; int ncomp, label; } types[] = {
        {"List<label>", 1, 1},         {"List<scalar>", 1, 0},
        {"List<vector>", 3, 0},        {"List<sphericalTensor>", 1, 0},
        {"List<symmTensor>", 6, 0},    {"List<tensor>", 9, 0},
        {"List<vector2D>", 2, 0},      {"List<symmTensor2D>", 3, 0},
        {"List<tensor2D>", 4, 0},      {"List<sphericalTensor2D>", 1, 0},
    };
    for (size_t i = 0; i < sizeof types / sizeof types[0]; i++)
        if (strcmp(w, types[i].name) == 0) {
            if (is_label)
                *is_label = types[i].label;
            return types[i].ncomp;
        }
    return 0;
}

/* ---- files ----------------------------------------------------------------- */

static int is_regular(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0 && S_ISREG(st.st_mode);
}

char *foam_resolve_gz(const char *path)
{
    if (is_regular(path))
        return ump_strdup(path);
    size_t n = strlen(path);
    char *gz = ump_alloc_array(n + 4, 1);
    if (!gz)
        return NULL;
    memcpy(gz, path, n);
    memcpy(gz + n, ".gz", 4);
    if (is_regular(gz))
        return gz;
    free(gz);
    return NULL;
}

int foam_file_exists(const char *path)
{
    char *p = path ? foam_resolve_gz(path) : NULL;
    free(p);
    return p != NULL;
}

/* zlib's gzread passes plain files through unchanged, so one reader serves
 * both NAME and NAME.gz. */
ump_status foam_read_whole_file(const char *path, char **out, size_t *outlen, ump_err *err)
{
    *out = NULL;
    *outlen = 0;
    gzFile gz = gzopen(path, "rb");
    if (!gz)
        return FOAM_FAIL(err, UMP_ERR_IO, "cannot open %s: %s", path,
                        errno ? strerror(errno) : "gzopen failed");
    /* not zeroed (gzread fills it): a zeroed 64 KiB start was 36 % of the
     * instructions of reading a small file */
    size_t cap = 1 << 12, len = 0;
    char *buf = ump_realloc_array(NULL, cap, 1);
    if (!buf) {
        gzclose(gz);
        return FOAM_FAIL(err, UMP_ERR_NOMEM, "%s: out of memory", path);
    }
    for (;;) {
        if (cap - len < 2) {
            if (cap > SIZE_MAX / 2) {
                free(buf);
                gzclose(gz);
                return FOAM_FAIL(err, UMP_ERR_NOMEM, "%s: file too large", path);
            }
            char *nb = ump_realloc_array(buf, cap * 2, 1);
            if (!nb) {
                free(buf);
                gzclose(gz);
                return FOAM_FAIL(err, UMP_ERR_NOMEM, "%s: out of memory", path);
            }
            buf = nb;
            cap *= 2;
        }
        size_t want = cap - len - 1;
        if (want > (size_t)INT_MAX / 2)
            want = (size_t)INT_MAX / 2;
        int got = gzread(gz, buf + len, (unsigned)want);
        if (got < 0) {
            int zerr;
            const char *msg = gzerror(gz, &zerr);
            ump_status rc = FOAM_FAIL(err, UMP_ERR_IO, "cannot read %s: %s", path,
                                      zerr == Z_ERRNO ? strerror(errno) : msg);
            free(buf);
            gzclose(gz);
            return rc;
        }
        if (got == 0)
            break;
        len += (size_t)got;
    }
    /* gzread reports a truncated gzip stream as end of file; gzclose_r
     * then returns Z_BUF_ERROR. */
    int zerr = 0;
    (void)gzerror(gz, &zerr);
    int rc = gzclose_r(gz);
    if ((zerr != Z_OK && zerr != Z_STREAM_END) || rc == Z_BUF_ERROR || rc == Z_ERRNO) {
        free(buf);
        return FOAM_FAIL(err, UMP_ERR_IO, "cannot read %s: %s", path,
                        rc == Z_BUF_ERROR ? "compressed data cut short" : "read error");
    }
    buf[len] = '\0';
    *out = buf;
    *outlen = len;
    return UMP_OK;
}
