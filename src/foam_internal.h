/* SPDX-License-Identifier: GPL-3.0-or-later
 * foam_internal.h -- private interfaces shared by the FoamFile reader
 * (foam_lex.c, foam_parse.c, foam_get.c). Not part of the public API.
 *
 * These functions are shared between the three files, so they carry the
 * foam_ prefix to stay clear of other modules in libumppm.a.
 *
 * Storage model: everything reachable from a foam_file lives in one arena
 * (a chain of large blocks, bump-allocated), so a parse does no per-token
 * malloc and foam_file_free() releases it all at once.
 */
#ifndef UMPPM_FOAM_INTERNAL_H
#define UMPPM_FOAM_INTERNAL_H

#include <stddef.h>
#include <stdint.h>
#include "umppm/foam.h"

/* Messages quote input (a string may hold an escaped newline): keep them
 * one line by turning control characters into blanks. */
ump_status foam_oneline(ump_err *err, ump_status rc);
#define FOAM_FAIL(err, code, ...) foam_oneline((err), UMP_FAIL((err), (code), __VA_ARGS__))

/* ---- arena --------------------------------------------------------------- */
typedef struct foam_arena foam_arena;

foam_arena *foam_arena_new(void);
void foam_arena_free(foam_arena *a);
/* n*size zeroed bytes aligned for any object; NULL on overflow/failure. */
void *foam_arena_alloc(foam_arena *a, size_t n, size_t size);
char *foam_arena_strndup(foam_arena *a, const char *s, size_t n);
/* Hand a malloc'd block (or an object needing cleanup) to the arena: it is
 * released by fn(p) in foam_arena_free(). On failure fn(p) is called at once and
 * 0 is returned. */
int foam_arena_adopt(foam_arena *a, void *p, void (*fn)(void *));

/* ---- dictionaries ------------------------------------------------------- */
/* Every foam_dict made by the reader is the first member of a foam_dict_impl,
 * which adds a hash index over the keys so that building a dictionary of n
 * entries costs O(n), not O(n^2). Public look-ups use only foam_dict. */
typedef struct foam_dict_impl {
    foam_dict pub;
    uint32_t *hidx;  /* open addressing: entry index + 1, 0 = empty */
    size_t hcap;     /* power of two, or 0 when no index yet */
    size_t npat;     /* number of pattern keys */
} foam_dict_impl;

/* ---- lexer -------------------------------------------------------------- */
/* The token type FOAM_TOK_PUNCT with v.punct == 0 marks end of input. */
typedef struct foam_lexer {
    const char *buf;
    size_t len, pos;
    int line;
    const char *file;      /* arena copy of the file name */
    int binary;            /* this stream's header said format binary */
    int label_bytes, scalar_bytes;
    foam_arena *arena;
    ump_err *err;
    int has_back;          /* one token of push-back */
    foam_token back;
} foam_lexer;

void foam_lex_init(foam_lexer *lx, const char *buf, size_t len, const char *file,
              foam_arena *a, ump_err *err);
ump_status foam_lex_next(foam_lexer *lx, foam_token *t);
ump_status foam_lex_peek(foam_lexer *lx, foam_token *t);
void foam_lex_unget(foam_lexer *lx, const foam_token *t);
int foam_lex_is_eof(const foam_token *t);
/* Binary contiguous list of n elements of ncomp components, positioned just
 * after the count token: skips blanks, expects '(' + raw bytes + ')'. A zero
 * count may be followed by "( )" or by nothing. The token gets file/line. */
ump_status foam_lex_blob(foam_lexer *lx, int64_t n, int ncomp, int is_label,
                    int line, foam_token *out);
/* The ascii body "N ( ... )" of a list file read in one pass over the
 * characters, without a token per number, into FOAM_TOK_BLOB tokens the
 * list getters take as they take binary ones:
 *   FOAM_ASCII_LABELS   N(l l ...)            one blob of N labels
 *   FOAM_ASCII_VECTORS  N((x y z) ...)        one blob of N 3-vectors
 *   FOAM_ASCII_FACES    N(M(l ...) ...)       two blobs: N+1 offsets from 0,
 *                                             then the concatenated labels
 * The lexer must hold the count N as its look-ahead token. Only the plain
 * form OpenFOAM writes is taken (see foam_lex.c); for anything else *nout
 * is 0 and the lexer is left as it was, so that the token reader reads it
 * and reports its errors exactly as before. */
enum { FOAM_ASCII_LABELS = 1, FOAM_ASCII_VECTORS, FOAM_ASCII_FACES };
ump_status foam_lex_ascii_list(foam_lexer *lx, int shape, foam_token out[2], int *nout);
/* Next non-blank character (comments skipped) without consuming it, or -1. */
ump_status foam_lex_peek_char(foam_lexer *lx, int *c);

/* Whole file (plain or gzip) into a malloc'd buffer (NUL-terminated). */
ump_status foam_read_whole_file(const char *path, char **buf, size_t *len, ump_err *err);
/* Resolve path or path.gz (regular files only); returns the malloc'd name
 * that exists, or NULL. */
char *foam_resolve_gz(const char *path);

/* ---- shared helpers ----------------------------------------------------- */
/* Element components of List<T> for the contiguous T we convert, else 0;
 * *is_label set for List<label>. */
int foam_list_type_ncomp(const char *word, int *is_label);
/* POSIX-extended whole-string match of key against pattern (1/0). */
int foam_pattern_match(const char *pattern, const char *key);
/* The same for the key of pattern entry e, with its compiled regex when the
 * reader made one (a fuzzed dictionary spent 99 % of its parse compiling
 * the same patterns again for every $variable look-up). */
int foam_entry_match(const foam_entry *e, const char *key);
#endif
