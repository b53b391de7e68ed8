/* SPDX-License-Identifier: GPL-3.0-or-later
 * foam.h -- reader for OpenFOAM "FoamFile" files (module prefix foam_).
 *
 * Reads one file (plain, or NAME.gz when NAME is absent, as OpenFOAM's
 * IFstream does) into memory, parses the FoamFile header, and then either
 *   - a top-level dictionary (controlDict, fields, transportProperties...), or
 *   - a top-level token "body" (points, faces, owner, neighbour, boundary,
 *     lagrangian fields): files whose content starts with a count or '('.
 *
 * Lexical rules follow OpenFOAM v1912 ISstream: // and block comments,
 * punctuation ; ( ) { } [ ] : , = + * / (a '-' starts a number when a digit
 * or '.' follows), "quoted strings" (a quoted key is a regular expression),
 * words (anything else; balanced parentheses inside a word are kept, so
 * div(phi,U) is one word; a ']' outside parentheses ends a word, so that
 * [kg/m^3] gives '[' kg '/' m^3 ']'), numbers (the run of [0-9.eE+-]:
 * digits only: label (scalar if it overflows int64); otherwise scalar when
 * strtod consumes the whole run; otherwise word), #{ verbatim #} (a string).
 * As in v1912 only ( ) and { } must balance inside an entry.
 *
 * Dictionaries: a redefined key replaces the entry in place, except that a
 * dictionary given again for a dictionary is merged into it (v1912's
 * default "merge" input mode). A FoamFile entry in an included file is
 * dropped. Inside a value, "name { ... }" becomes FOAM_TOK_DICT, except
 * after a count, where "N{v}" stays tokens (uniform list).
 *
 * Directives and macros are resolved WHILE parsing, in file order, as
 * OpenFOAM does:
 *   $var ${var}      value of var, searched in this dict then its parents
 *                    (then the environment); undefined is an error
 *   $..var           one scope up per extra '.' (no search of parents there)
 *   $:a.b            absolute scope: top-level a, then b inside it
 *   $a.b / $a/b      scoped: sub-dictionary a of the current scope, then b
 *   ${..$x..}        $x inside braces is substituted first
 *   Value look-ups are literal (pattern keys never match), as in v1912. In a
 *   value, $d naming a dictionary gives one FOAM_TOK_DICT token (a copy).
 *   "$var;" as an entry inside a dictionary merges var's entries (var a dict;
 *                    this look-up also matches pattern keys, as v1912 does,
 *                    and an undefined var is ignored, as v1912 does)
 *   #include "f"     relative to the including file's directory; $FOAM_CASE,
 *                    <case>, <system>, <constant> and $ENV are expanded
 *   #includeIfPresent "f"  as #include, silently skipped when absent
 *   #includeEtc "f"  searched in $FOAM_ETC, $WM_PROJECT_DIR/etc,
 *                    /usr/share/openfoam/etc; clear error when none has it
 *   #includeFunc w   kept as an entry with key "#includeFunc" and one token
 *   #remove key|(k1 k2)  removes entries; #inputMode ... is ignored
 *   #calc #codeStream #eval #if ... : refused (UMP_ERR_UNSUPPORTED) naming
 *                    file and line.
 * Included files may be gzipped; includes nest at most 32 deep, and macro
 * copies are bounded (about 16 tokens per input byte) so that exponential
 * $var use fails with UMP_ERR_INPUT instead of exhausting memory.
 *
 * Binary files ("format binary;"): the "arch" entry ("LSB;label=32;scalar=64")
 * gives label and scalar sizes (32 or 64 bits each; MSB refused). Contiguous
 * lists are "N\n(" + raw bytes + ")". They are recognised in two places:
 *   - in a dictionary entry, a count directly after a word List<T>, T one of
 *     label scalar vector sphericalTensor symmTensor tensor (and the 2D
 *     vector2D symmTensor2D tensor2D sphericalTensor2D);
 *   - in a file body, by the header class: labelList, scalarField/List,
 *     vectorField/List, faceCompactList (two label lists), labelField,
 *     scalarField, vectorField, sphericalTensorField, symmTensorField,
 *     tensorField; faceList, labelListList, cellList ("N(" then one binary
 *     label list per item, then ")"). Bodies that are text even in binary
 *     files are tokenized normally: polyBoundaryMesh, cellZoneMesh,
 *     faceZoneMesh, pointZoneMesh, regIOobject, dictionary. A binary body of
 *     another class (e.g. Cloud<...> positions) is refused
 *     (UMP_ERR_UNSUPPORTED).
 * Raw data is converted to native int64/double and kept as a FOAM_TOK_BLOB
 * token (line = line of the count). "0" alone, "0()" and "0 ( )" give an
 * empty blob. Anything cut short is an error naming the file.
 *
 * Memory: a foam_file owns everything reachable from it; foam_file_free()
 * releases it all. Strings and tokens are borrowed from it.
 */
#ifndef UMPPM_FOAM_H
#define UMPPM_FOAM_H

#include <stdint.h>
#include <stddef.h>
#include "umppm/ump.h"

typedef enum foam_tok_type {
    FOAM_TOK_PUNCT,  /* v.punct: one of ; ( ) { } [ ] : , = + - * / */
    FOAM_TOK_WORD,   /* v.str: bare word, e.g. uniform, List<vector>, div(phi,U) */
    FOAM_TOK_STRING, /* v.str: contents of a "quoted string" (escapes resolved) */
    FOAM_TOK_LABEL,  /* v.label: integer */
    FOAM_TOK_SCALAR, /* v.scalar: floating point */
    FOAM_TOK_BLOB,   /* v.blob: binary contiguous list, converted to native */
    FOAM_TOK_DICT    /* v.dict: a { ... } block inside a list or entry value */
} foam_tok_type;

struct foam_dict;

typedef struct foam_blob {
    size_t n;      /* number of list elements (the N of "N(") */
    int ncomp;     /* components per element: 1 label/scalar, 3 vector, 6, 9 */
    int is_label;  /* 1: data is int64_t[n*ncomp]; 0: data is double[n*ncomp] */
    void *data;
} foam_blob;

typedef struct foam_token {
    foam_tok_type type;
    int line;          /* 1-based line in the file the token came from */
    const char *file;  /* that file's path (borrowed from the foam_file) */
    union {
        char punct;
        char *str;
        int64_t label;
        double scalar;
        foam_blob blob;
        struct foam_dict *dict;
    } v;
} foam_token;

/* A dictionary entry: either a sub-dictionary or a primitive entry (the
 * tokens between the key and the terminating ';', macros already expanded). */
typedef struct foam_entry {
    char *key;
    int is_pattern;        /* key was "quoted": a POSIX extended regex */
    const void *rx;         /* that regex compiled once by the reader (owned by
                               the foam_file), or NULL: compiled at each match */
    int line;
    const char *file;
    struct foam_dict *dict; /* non-NULL: sub-dictionary entry */
    foam_token *tok;        /* primitive entry tokens (dict == NULL) */
    size_t ntok;
} foam_entry;

typedef struct foam_dict {
    struct foam_dict *parent; /* NULL at top level */
    const char *name;         /* key of this dict in its parent ("" at top) */
    const char *file;
    int line;                 /* line of the opening '{' */
    foam_entry *e;            /* entries in file order (a redefined key
                                 replaces the earlier entry in place) */
    size_t n, cap;
} foam_dict;

typedef struct foam_file {
    char *path;          /* path actually opened (ends in .gz if compressed) */
    int binary;          /* header format binary */
    int label_bytes;     /* 4 or 8 (from arch; native 4 when absent) */
    int scalar_bytes;    /* 4 or 8 (from arch; native 8 when absent) */
    char *class_name;    /* header class ("" when no header) */
    char *object;        /* header object ("" when no header) */
    char *location;      /* header location or NULL */
    foam_dict *header;   /* the FoamFile dict, or NULL */
    foam_dict *dict;     /* top-level entries (never NULL; empty for a body file) */
    foam_token *body;    /* top-level tokens of a list file, else NULL */
    size_t nbody;
    void *arena;         /* implementation-owned storage */
} foam_file;

/* Read and parse path (tries path, then path.gz). */
ump_status foam_file_read(const char *path, foam_file **out, ump_err *err);
/* Parse an in-memory buffer (name used in messages and for #include paths). */
ump_status foam_file_parse(const char *name, const char *buf, size_t len,
                           foam_file **out, ump_err *err);
/* As foam_file_parse, with FOAM_PARSE_* flags. FOAM_PARSE_NO_INCLUDE makes
 * every #include* directive fail (UMP_ERR_UNSUPPORTED) without touching the
 * file system (used by the fuzz harness). */
#define FOAM_PARSE_NO_INCLUDE 1u
ump_status foam_file_parse_ex(const char *name, const char *buf, size_t len,
                              unsigned flags, foam_file **out, ump_err *err);
void foam_file_free(foam_file **f);

/* 1 if path or path.gz exists (as a regular file). */
int foam_file_exists(const char *path);

/* The bytes of path (or of path.gz, uncompressed) in *buf (malloc'ed, NUL
 * after the *len bytes). */
ump_status foam_read_text(const char *path, char **buf, size_t *len, ump_err *err);

/* ---- dictionary look-up ------------------------------------------------ */
/* Look up key in d: exact key first, then pattern keys (latest first, as
 * OpenFOAM). With recursive != 0, continue in the parent dictionaries.
 * Returns NULL when absent. */
const foam_entry *foam_dict_find(const foam_dict *d, const char *key, int recursive);
/* Sub-dictionary key of d, or NULL when absent or not a dictionary. */
const foam_dict *foam_dict_sub(const foam_dict *d, const char *key);
/* "a/b/c" style path of d for messages (static buffer inside d's file arena
 * is NOT used: writes into buf, returns buf). */
const char *foam_dict_path(const foam_dict *d, char *buf, size_t len);

/* Typed getters: non-recursive look-up (pattern keys match); the value must
 * be exactly the expected tokens. Each fails (UMP_ERR_INPUT / UMP_ERR_PARSE)
 * with a message "<file>:<line>: ..." when the key is missing or of the
 * wrong form; the
 *  *_or variants return the default when the key is absent but still fail on
 *  a malformed value. */
ump_status foam_get_scalar(const foam_dict *d, const char *key, double *out, ump_err *err);
ump_status foam_get_scalar_or(const foam_dict *d, const char *key, double dflt, double *out, ump_err *err);
ump_status foam_get_label(const foam_dict *d, const char *key, int64_t *out, ump_err *err);
ump_status foam_get_label_or(const foam_dict *d, const char *key, int64_t dflt, int64_t *out, ump_err *err);
/* word or string; *out borrowed from the file */
ump_status foam_get_word(const foam_dict *d, const char *key, const char **out, ump_err *err);
ump_status foam_get_word_or(const foam_dict *d, const char *key, const char *dflt, const char **out, ump_err *err);
/* An OpenFOAM Switch word (yes/no on/off true/false y/n t/f none): its
 * value 1 or 0; -1 for any other word */
int foam_switch_value(const char *w);
/* yes/no on/off true/false y/n t/f none, or a label 0/1 */
ump_status foam_get_bool_or(const foam_dict *d, const char *key, int dflt, int *out, ump_err *err);
/* (x y z) */
ump_status foam_get_vector(const foam_dict *d, const char *key, double out[3], ump_err *err);
/* Dimensioned scalar, any of:  key 0.01;  key [0 2 -1 0 0 0 0] 0.01;
 * key key [0 2 -1 0 0 0 0] 0.01;  key name 0.01;  dims (7 entries) may be
 * NULL. Dimensions are 7 (or 5) numbers or SI unit names with factor 1
 * (kg m s K mol A cd N Pa J W Hz C V, "^n" powers, '/' divides; [m^2/s]
 * [W/m/K] [1/K]); dims absent -> all 0. */
ump_status foam_get_dimensioned(const foam_dict *d, const char *key, double *value,
                                double dims[7], ump_err *err);

/* ---- decoding token streams -------------------------------------------- */
/* All decoders read from tok[*pos] (tok has nt tokens), advance *pos past
 * what they consumed and report malformed input as "<file>:<line>: ...".
 * 'what' names the thing being read in messages (e.g. "points"). */

/* One scalar (label or scalar token, or nan/inf). */
ump_status foam_tok_scalar(const foam_token *tok, size_t nt, size_t *pos,
                           double *out, const char *what, ump_err *err);
/* A list of n elements of ncomp scalars each, any OpenFOAM form:
 *   N ( a b c )     N ( (x y z) (x y z) )    N { v }    N { (x y z) }
 *   ( a b c )       blob (binary)            0 ( )   0()
 * and a lone "0" (binary writers emit "nonuniform 0;").
 * ncomp == 1: elements are plain numbers; ncomp > 1: "(c1 .. cn)". Numbers
 * are labels, scalars, or words nan/inf (also "-" inf). A blob must have
 * ncomp components (a label blob is converted). Sizes are limited to
 * UMP_IDX_MAX elements; N is checked against the tokens present before
 * anything is allocated, and the item count must equal N. A token array
 * with no tokens has no file name to report.
 * *out is allocated (caller frees with free()), *n its element count;
 * on failure *out is NULL and *pos unchanged (the same for all decoders). */
ump_status foam_tok_scalar_list(const foam_token *tok, size_t nt, size_t *pos,
                                int ncomp, double **out, size_t *n,
                                const char *what, ump_err *err);
/* A list of labels (same forms, label tokens only); values checked to fit
 * ump_idx (INT32_MIN..UMP_IDX_MAX: negative labels are allowed). */
ump_status foam_tok_label_list(const foam_token *tok, size_t nt, size_t *pos,
                               ump_idx **out, size_t *n, const char *what, ump_err *err);
/* A list of label lists, e.g. faces "N( 4(a b c d) 3(e f g) ... )", or the
 * compact form (faceCompactList: a list of n+1 offsets starting at 0, then
 * the items; two blobs in binary, two label lists in ASCII), into CSR:
 * *offs has *n+1 entries, *items offs[n] entries (both caller-freed). */
ump_status foam_tok_labellist_list(const foam_token *tok, size_t nt, size_t *pos,
                                   ump_idx **offs, ump_idx **items, size_t *n,
                                   const char *what, ump_err *err);

/* Message prefix for a token: "<file>:<line>" (or "<file>" at end of input). */
const char *foam_tok_where(const foam_token *tok, size_t nt, size_t pos,
                           const char *fallback_file, char *buf, size_t len);
/* Short printable form of a token for messages ("')'", "word 'uniform'", ...). */
const char *foam_tok_str(const foam_token *t, char *buf, size_t len);

#endif
