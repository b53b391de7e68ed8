/* SPDX-License-Identifier: GPL-3.0-or-later
 * test_foam.c -- unit tests of the FoamFile reader (foam.h): tokenizer,
 * dictionaries, every list form, macros and directives (expected values
 * checked against OpenFOAM v1912 foamDictionary -expand), binary files with
 * 32/64-bit labels and scalars, gzip, getters, decoders and malformed input.
 */
#include "testutil.h"

#include <errno.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>
#include <zlib.h>

#include "umppm/foam.h"

#define HDR(cls) "FoamFile { version 2.0; format ascii; class " cls "; object x; }\n"

static foam_file *parse_ok(const char *text)
{
    foam_file *f = NULL;
    ump_err err;
    memset(&err, 0, sizeof err);
    ump_status rc = foam_file_parse("test.dict", text, strlen(text), &f, &err);
    if (rc != UMP_OK)
        fail_msg("parse failed (%d): %s", rc, err.msg);
    assert_non_null(f);
    return f;
}

static ump_status parse_err(const char *name, const char *text, ump_err *err)
{
    foam_file *f = NULL;
    memset(err, 0, sizeof *err);
    ump_status rc = foam_file_parse(name, text, strlen(text), &f, err);
    if (rc == UMP_OK)
        foam_file_free(&f);
    else
        assert_null(f);
    return rc;
}

static const foam_entry *E(const foam_dict *d, const char *key)
{
    const foam_entry *e = foam_dict_find(d, key, 0);
    if (!e)
        fail_msg("no entry '%s'", key);
    return e;
}

/* The single token of a primitive entry. */
static const foam_token *T1(const foam_dict *d, const char *key)
{
    const foam_entry *e = E(d, key);
    assert_null(e->dict);
    if (e->ntok != 1)
        fail_msg("entry '%s' has %zu tokens", key, e->ntok);
    return &e->tok[0];
}

static void assert_word(const foam_token *t, const char *w)
{
    assert_int_equal(t->type, FOAM_TOK_WORD);
    assert_string_equal(t->v.str, w);
}

static void assert_label(const foam_token *t, int64_t v)
{
    assert_int_equal(t->type, FOAM_TOK_LABEL);
    assert_true(t->v.label == v);
}

static void assert_punct(const foam_token *t, char c)
{
    assert_int_equal(t->type, FOAM_TOK_PUNCT);
    assert_int_equal(t->v.punct, c);
}

static double num(const foam_token *t)
{
    if (t->type == FOAM_TOK_LABEL)
        return (double)t->v.label;
    assert_int_equal(t->type, FOAM_TOK_SCALAR);
    return t->v.scalar;
}

/* ---- tokenizer ------------------------------------------------------------ */

static void test_tokens(void **state)
{
    (void)state;
    foam_file *f = parse_ok(
        "a 1 -2 3.5 -.5 1e-05 -1E+3 .5e1 word div(phi,U) List<vector> \"s t\" ( ) [ ] - + * : , = ;\n"
        "b 99999999999999999999 1.2.3 1e 12abc --5;\n"
        "c \"esc\\\"aped\\\\n\" nan;\n"
        "d a,b x=y f(a(b)c) (g(h)) ;\n");
    const foam_entry *a = E(f->dict, "a");
    assert_int_equal(a->ntok, 21);
    assert_label(&a->tok[0], 1);
    assert_label(&a->tok[1], -2);
    assert_int_equal(a->tok[2].type, FOAM_TOK_SCALAR);
    TU_CLOSE(a->tok[2].v.scalar, 3.5, 0);
    TU_CLOSE(num(&a->tok[3]), -0.5, 0);
    TU_CLOSE(num(&a->tok[4]), 1e-5, 0);
    TU_CLOSE(num(&a->tok[5]), -1000, 0);
    TU_CLOSE(num(&a->tok[6]), 5, 0);
    assert_word(&a->tok[7], "word");
    assert_word(&a->tok[8], "div(phi,U)");
    assert_word(&a->tok[9], "List<vector>");
    assert_int_equal(a->tok[10].type, FOAM_TOK_STRING);
    assert_string_equal(a->tok[10].v.str, "s t");
    const char *p = "()[]-+*:,=";
    for (int i = 0; p[i]; i++)
        assert_punct(&a->tok[11 + i], p[i]);
    assert_punct(&a->tok[20], '=');
    assert_int_equal(a->line, 1);

    const foam_entry *b = E(f->dict, "b");
    /* label overflow -> scalar; not a number -> word (ISstream splits 12abc) */
    assert_int_equal(b->tok[0].type, FOAM_TOK_SCALAR);
    TU_CLOSE(b->tok[0].v.scalar, 1e20, 1e-15);
    assert_word(&b->tok[1], "1.2.3");
    assert_word(&b->tok[2], "1e");
    assert_label(&b->tok[3], 12);
    assert_word(&b->tok[4], "abc");
    assert_word(&b->tok[5], "--5");
    assert_int_equal(b->tok[0].line, 2);

    const foam_entry *c = E(f->dict, "c");
    assert_int_equal(c->tok[0].type, FOAM_TOK_STRING);
    /* \" becomes ", other backslashes stay as OpenFOAM keeps them */
    assert_string_equal(c->tok[0].v.str, "esc\"aped\\\\n");
    assert_word(&c->tok[1], "nan");

    const foam_entry *d = E(f->dict, "d");
    assert_int_equal(d->ntok, 6);
    assert_word(&d->tok[0], "a,b");
    assert_word(&d->tok[1], "x=y");
    assert_word(&d->tok[2], "f(a(b)c)");
    assert_punct(&d->tok[3], '(');
    assert_word(&d->tok[4], "g(h)");
    /* unmatched ')' ends the word and stands alone */
    assert_punct(&d->tok[5], ')');
    foam_file_free(&f);
    assert_null(f);
}

static void test_comments_lines(void **state)
{
    (void)state;
    foam_file *f = parse_ok(
        "/*--------------------------------*- C++ -*----------------------------------*\\\n"
        "  banner\n"
        "\\*---------------------------------------------------------------------------*/\n"
        HDR("dictionary")
        "// * * * //\n"
        "a 1; // trailing\n"
        "b /* inline */ 2;\n"
        "c /* multi\n"
        "line\n"
        "comment */ 3 / 4;\n"
        "d \"two\\\n"
        "lines\" 5;\n"
        "e 6;");
    assert_string_equal(f->class_name, "dictionary");
    assert_string_equal(f->object, "x");
    assert_null(f->location);
    assert_int_equal(f->binary, 0);
    assert_int_equal(E(f->dict, "a")->line, 6);
    assert_label(T1(f->dict, "b"), 2);
    assert_int_equal(T1(f->dict, "b")->line, 7);
    const foam_entry *c = E(f->dict, "c");
    assert_int_equal(c->ntok, 3);
    assert_int_equal(c->tok[0].line, 10);
    assert_punct(&c->tok[1], '/');
    const foam_entry *d = E(f->dict, "d");
    assert_string_equal(d->tok[0].v.str, "two\nlines");
    assert_int_equal(d->tok[1].line, 12);
    assert_int_equal(E(f->dict, "e")->line, 13);
    assert_string_equal(E(f->dict, "e")->file, "test.dict");
    foam_file_free(&f);
}

static void test_header_and_empty(void **state)
{
    (void)state;
    foam_file *f = parse_ok("");
    assert_int_equal(f->dict->n, 0);
    assert_null(f->header);
    assert_null(f->body);
    assert_string_equal(f->class_name, "");
    foam_file_free(&f);
    f = parse_ok("FoamFile\n{\n version 2.0;\n format ascii;\n class volScalarField;\n"
                 " location \"0.1\";\n object p;\n}\n");
    assert_non_null(f->header);
    assert_string_equal(f->location, "0.1");
    assert_string_equal(f->class_name, "volScalarField");
    assert_int_equal(f->dict->n, 0);
    assert_int_equal(f->label_bytes, 4);
    assert_int_equal(f->scalar_bytes, 8);
    foam_file_free(&f);
}

/* ---- dictionaries ---------------------------------------------------------- */

static void test_nested_dicts(void **state)
{
    (void)state;
    foam_file *f = parse_ok(HDR("dictionary")
        "a { b { c { d 1; } } e 2; }\n"
        "x 1; y { z 1; w 2; } x 3;\n"
        "y { w 5; v 6; }\n"
        "q 1; q { r 1; }\n"
        ";; s 7;;\n"
        "empty { }\n"
        "k;\n");
    const foam_dict *a = foam_dict_sub(f->dict, "a");
    assert_non_null(a);
    assert_string_equal(a->name, "a");
    assert_ptr_equal(a->parent, f->dict);
    const foam_dict *c = foam_dict_sub(foam_dict_sub(a, "b"), "c");
    assert_non_null(c);
    char buf[64];
    assert_string_equal(foam_dict_path(c, buf, sizeof buf), "a/b/c");
    /* recursive find goes up */
    assert_non_null(foam_dict_find(c, "e", 1));
    assert_null(foam_dict_find(c, "e", 0));
    /* redefinition: primitive replaced in place, dict merged */
    assert_string_equal(f->dict->e[1].key, "x");
    assert_label(T1(f->dict, "x"), 3);
    const foam_dict *y = foam_dict_sub(f->dict, "y");
    assert_int_equal(y->n, 3);
    assert_label(T1(y, "z"), 1);
    assert_label(T1(y, "w"), 5);
    assert_label(T1(y, "v"), 6);
    /* primitive replaced by a dict in place */
    assert_string_equal(f->dict->e[3].key, "q");
    assert_non_null(f->dict->e[3].dict);
    assert_label(T1(f->dict, "s"), 7);
    assert_int_equal(foam_dict_sub(f->dict, "empty")->n, 0);
    assert_int_equal(E(f->dict, "k")->ntok, 0);
    assert_null(foam_dict_sub(f->dict, "s"));
    assert_null(foam_dict_find(f->dict, "nope", 1));
    foam_file_free(&f);
}

static void test_regex_keys(void **state)
{
    (void)state;
    foam_file *f = parse_ok(HDR("dictionary")
        "\".*\" { t any; }\n"
        "\"(left|right)\" { t lr; }\n"
        "\"left.*\" { t leftish; }\n"
        "left { t exact; }\n"
        "\"wall\" 3;\n");
    const char *w;
    ump_err err;
    assert_int_equal(foam_get_word(foam_dict_sub(f->dict, "left"), "t", &w, &err), UMP_OK);
    assert_string_equal(w, "exact");
    assert_int_equal(foam_get_word(foam_dict_sub(f->dict, "right"), "t", &w, &err), UMP_OK);
    assert_string_equal(w, "lr");
    /* latest pattern first */
    assert_int_equal(foam_get_word(foam_dict_sub(f->dict, "leftWall"), "t", &w, &err), UMP_OK);
    assert_string_equal(w, "leftish");
    assert_int_equal(foam_get_word(foam_dict_sub(f->dict, "top"), "t", &w, &err), UMP_OK);
    assert_string_equal(w, "any");
    /* whole-string match only */
    assert_null(foam_dict_find(foam_dict_sub(f->dict, "left"), "xt", 0));
    const foam_entry *e = foam_dict_find(f->dict, "wall", 0);
    assert_non_null(e);
    assert_true(e->is_pattern);
    /* "wallx" is not matched by "wall", but by ".*" */
    assert_ptr_equal(foam_dict_find(f->dict, "wallx", 0), &f->dict->e[0]);
    foam_file_free(&f);

    /* patterns whose automaton would explode (found by fuzzing) or that
     * need backtracking match nothing, quickly */
    f = parse_ok("\"a++++++++++++++++++++++++++++++++++++++++\" 1;\n"
                 "\"((a{100}){100}){100}\" 2;\n\"(a)\\1\" 3;\n"
                 "#remove \"(b{1000}){1000}\"\n");
    assert_int_equal(f->dict->n, 3);
    assert_null(foam_dict_find(f->dict, "aaaa", 0));
    assert_null(foam_dict_find(f->dict, "aa", 0));
    foam_file_free(&f);
}

/* ---- lists ---------------------------------------------------------------------- */

static void check_list(const foam_entry *e, size_t start, int ncomp, const double *want,
                       size_t nwant)
{
    double *v;
    size_t n, pos = start;
    ump_err err;
    ump_status rc = foam_tok_scalar_list(e->tok, e->ntok, &pos, ncomp, &v, &n, e->key, &err);
    if (rc != UMP_OK)
        fail_msg("%s: %s", e->key, err.msg);
    assert_int_equal(n, nwant);
    assert_int_equal(pos, e->ntok);
    for (size_t i = 0; i < nwant * (size_t)ncomp; i++) {
        if (isinf(want[i]))
            assert_true(v[i] == want[i]);
        else
            TU_CLOSE(v[i], want[i], 1e-15);
    }
    free(v);
}

static void test_list_forms(void **state)
{
    (void)state;
    foam_file *f = parse_ok(HDR("dictionary")
        "oneline 3(1 2 3.5);\n"
        "long\n4\n(\n1\n2\n3\n4\n)\n;\n"
        "uni 3{-1};\n"
        "univ 2{(1 2 3)};\n"
        "empty 0();\n"
        "empty2 0 ( );\n"
        "bare ( 1 2 );\n"
        "vecs 2((1 0 0) (0 1 -inf));\n"
        "bvecs ((1 2 3));\n"
        "field nonuniform List<scalar> 2(5 6);\n"
        "zero nonuniform 0;\n");
    check_list(E(f->dict, "oneline"), 0, 1, (double[]){1, 2, 3.5}, 3);
    check_list(E(f->dict, "long"), 0, 1, (double[]){1, 2, 3, 4}, 4);
    check_list(E(f->dict, "uni"), 0, 1, (double[]){-1, -1, -1}, 3);
    check_list(E(f->dict, "univ"), 0, 3, (double[]){1, 2, 3, 1, 2, 3}, 2);
    check_list(E(f->dict, "empty"), 0, 1, NULL, 0);
    check_list(E(f->dict, "empty2"), 0, 3, NULL, 0);
    check_list(E(f->dict, "bare"), 0, 1, (double[]){1, 2}, 2);
    check_list(E(f->dict, "vecs"), 0, 3, (double[]){1, 0, 0, 0, 1, -INFINITY}, 2);
    check_list(E(f->dict, "bvecs"), 0, 3, (double[]){1, 2, 3}, 1);
    check_list(E(f->dict, "field"), 2, 1, (double[]){5, 6}, 2);
    check_list(E(f->dict, "zero"), 1, 1, NULL, 0);
    /* the long list keeps one line per item */
    const foam_entry *l = E(f->dict, "long");
    assert_int_equal(l->line, 3);
    assert_int_equal(l->tok[0].line, 4);
    assert_int_equal(l->tok[2].line, 6);

    /* labels */
    ump_idx *lab;
    size_t n, pos = 0;
    ump_err err;
    const foam_entry *o = E(f->dict, "oneline");
    assert_int_equal(foam_tok_label_list(o->tok, o->ntok, &pos, &lab, &n, "x", &err),
                     UMP_ERR_PARSE);
    assert_non_null(strstr(err.msg, "test.dict:2"));
    assert_non_null(strstr(err.msg, "expected a label"));
    assert_null(lab);
    const foam_entry *u = E(f->dict, "uni");
    pos = 0;
    assert_int_equal(foam_tok_label_list(u->tok, u->ntok, &pos, &lab, &n, "x", &err), UMP_OK);
    assert_int_equal(n, 3);
    assert_int_equal(lab[2], -1);
    free(lab);
    foam_file_free(&f);
}

static void test_list_of_lists(void **state)
{
    (void)state;
    foam_file *f = parse_ok(HDR("faceList")
        "\n5\n(\n4(0 1 2 3)\n3(4 5 6)\n(7 8)\n0()\n2{9}\n)\n");
    assert_non_null(f->body);
    ump_idx *offs, *items;
    size_t n, pos = 0;
    ump_err err;
    assert_int_equal(foam_tok_labellist_list(f->body, f->nbody, &pos, &offs, &items, &n,
                                             "faces", &err), UMP_OK);
    assert_int_equal(n, 5);
    assert_int_equal(pos, f->nbody);
    ump_idx wo[] = {0, 4, 7, 9, 9, 11};
    ump_idx wi[] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 9};
    for (int i = 0; i < 6; i++)
        assert_int_equal(offs[i], wo[i]);
    for (int i = 0; i < 11; i++)
        assert_int_equal(items[i], wi[i]);
    free(offs);
    free(items);
    foam_file_free(&f);

    /* ASCII faceCompactList: offsets then labels */
    f = parse_ok(HDR("faceCompactList") "3(0 3 7)\n7(0 1 2 3 4 5 6)\n");
    pos = 0;
    assert_int_equal(foam_tok_labellist_list(f->body, f->nbody, &pos, &offs, &items, &n,
                                             "faces", &err), UMP_OK);
    assert_int_equal(n, 2);
    assert_int_equal(offs[2], 7);
    assert_int_equal(items[6], 6);
    free(offs);
    free(items);
    foam_file_free(&f);

    /* empty */
    f = parse_ok(HDR("faceList") "0()\n");
    pos = 0;
    assert_int_equal(foam_tok_labellist_list(f->body, f->nbody, &pos, &offs, &items, &n,
                                             "faces", &err), UMP_OK);
    assert_int_equal(n, 0);
    assert_int_equal(offs[0], 0);
    free(offs);
    free(items);
    foam_file_free(&f);
}

static void test_boundary_body(void **state)
{
    (void)state;
    foam_file *f = parse_ok(
        "FoamFile { version 2.0; format ascii; class polyBoundaryMesh;"
        " location \"constant/polyMesh\"; object boundary; }\n"
        "3\n(\n"
        "    movingWall\n    {\n        type wall;\n        inGroups 1(wall);\n"
        "        nFaces 20;\n        startFace 760;\n    }\n"
        "    fixedWalls { type wall; inGroups List<word> 1(wall); nFaces 60; startFace 780; }\n"
        "    frontAndBack { type empty; inGroups 1(empty); nFaces 800; startFace 840; }\n"
        ")\n");
    assert_string_equal(f->location, "constant/polyMesh");
    assert_int_equal(f->nbody, 9);
    assert_label(&f->body[0], 3);
    assert_punct(&f->body[1], '(');
    assert_word(&f->body[2], "movingWall");
    assert_int_equal(f->body[3].type, FOAM_TOK_DICT);
    const foam_dict *mw = f->body[3].v.dict;
    assert_string_equal(mw->name, "movingWall");
    assert_int_equal(mw->line, 5);
    int64_t nf;
    ump_err err;
    assert_int_equal(foam_get_label(mw, "startFace", &nf, &err), UMP_OK);
    assert_true(nf == 760);
    const foam_entry *g = E(mw, "inGroups");
    assert_int_equal(g->ntok, 4);
    assert_word(&g->tok[2], "wall");
    assert_word(&f->body[6], "frontAndBack");
    assert_int_equal(f->body[7].v.dict->n, 4);
    assert_punct(&f->body[8], ')');
    assert_int_equal(f->dict->n, 0);
    foam_file_free(&f);
}

/* blockMeshDict-like dictionaries inside a list entry */
static void test_dict_in_list_entry(void **state)
{
    (void)state;
    foam_file *f = parse_ok(HDR("dictionary")
        "w 2;\n"
        "boundary\n(\n  left { type cyclic; n $w; faces ((0 4 7 3)); }\n"
        "  right { type empty; }\n);\n");
    const foam_entry *b = E(f->dict, "boundary");
    assert_int_equal(b->ntok, 6);
    assert_int_equal(b->tok[2].type, FOAM_TOK_DICT);
    const foam_dict *l = b->tok[2].v.dict;
    assert_ptr_equal(l->parent, f->dict);
    assert_label(T1(l, "n"), 2);
    assert_int_equal(E(l, "faces")->ntok, 8);
    foam_file_free(&f);
}

/* ---- macros (expected values verified with foamDictionary -expand) ------------ */

static void test_macros(void **state)
{
    (void)state;
    foam_file *f = parse_ok(HDR("dictionary")
        "a 1;\n"
        "b { c 2; d $a; e $..a; g ${a}; }\n"
        "p { solver PCG; tol 1e-6; sub { x 1; } }\n"
        "pFinal { $p; tol 0; }\n"
        "f { g { h $:b.c; j ${:b.c}; } bb { c 5; } i $bb.c; k $bb/c; l $../a; m $/a; }\n"
        "top $b.c;\n"
        "internalField uniform 300;\n"
        "boundaryField { wall { value $internalField; } }\n"
        "z 5; deep { g 4; mid { h { k $...g; } } }\n");
    const foam_dict *b = foam_dict_sub(f->dict, "b");
    assert_label(T1(b, "d"), 1);
    assert_label(T1(b, "e"), 1);
    assert_label(T1(b, "g"), 1);
    const foam_dict *pf = foam_dict_sub(f->dict, "pFinal");
    assert_int_equal(pf->n, 3);
    assert_string_equal(pf->e[0].key, "solver");
    assert_string_equal(pf->e[1].key, "tol");
    assert_label(T1(pf, "tol"), 0);
    assert_word(T1(pf, "solver"), "PCG");
    /* the merged sub-dictionary is a copy */
    const foam_dict *sub = foam_dict_sub(pf, "sub");
    assert_non_null(sub);
    assert_ptr_not_equal(sub, foam_dict_sub(foam_dict_sub(f->dict, "p"), "sub"));
    assert_ptr_equal(sub->parent, pf);
    const foam_dict *fd = foam_dict_sub(f->dict, "f");
    assert_label(T1(foam_dict_sub(fd, "g"), "h"), 2);
    assert_label(T1(foam_dict_sub(fd, "g"), "j"), 2);
    assert_label(T1(fd, "i"), 5);
    assert_label(T1(fd, "k"), 5);
    assert_label(T1(fd, "l"), 1);
    assert_label(T1(fd, "m"), 1);
    assert_label(T1(f->dict, "top"), 2);
    const foam_entry *v = E(foam_dict_sub(foam_dict_sub(f->dict, "boundaryField"), "wall"),
                            "value");
    assert_int_equal(v->ntok, 2);
    assert_word(&v->tok[0], "uniform");
    assert_label(&v->tok[1], 300);
    /* $...g from h: two scopes up (deep) */
    const foam_dict *h = foam_dict_sub(foam_dict_sub(foam_dict_sub(f->dict, "deep"), "mid"), "h");
    assert_label(T1(h, "k"), 4);
    foam_file_free(&f);

    /* "$T;" resolves through a pattern key; value $x does not */
    f = parse_ok(HDR("dictionary")
        "solvers { \"(U|T)\" { solver PBiCGStab; relTol 0.01; }\n"
        "          \"(U|T)Final\" { $T; relTol 0; } }\n"
        "LESModel kEqn; kEqn { delta cube; } LES { ${:$LESModel} }\n");
    const foam_dict *fin = foam_dict_sub(foam_dict_sub(f->dict, "solvers"), "UFinal");
    assert_non_null(fin);
    assert_int_equal(fin->n, 2);
    assert_word(T1(fin, "solver"), "PBiCGStab");
    assert_label(T1(fin, "relTol"), 0);
    assert_word(T1(foam_dict_sub(f->dict, "LES"), "delta"), "cube");
    foam_file_free(&f);

    /* an undefined "$x;" keyword is ignored, as in v1912 */
    f = parse_ok("x { $nothing; y 1; }\n");
    assert_int_equal(foam_dict_sub(f->dict, "x")->n, 1);
    foam_file_free(&f);

    ump_err err;
    assert_int_equal(parse_err("m.dict", "a 1;\nb $q;\n", &err), UMP_ERR_PARSE);
    assert_non_null(strstr(err.msg, "m.dict:2"));
    assert_non_null(strstr(err.msg, "$q"));
    /* value look-up is literal: pattern keys never match */
    assert_int_equal(parse_err("m.dict", "\"x.*\" 3;\ni $xa;\n", &err), UMP_ERR_PARSE);
    /* $a.b starts in the current dictionary (v1912) */
    assert_int_equal(parse_err("m.dict", "b { c 2; }\nf { i $b.c; }\n", &err), UMP_ERR_PARSE);
    assert_int_equal(parse_err("m.dict", "a 1;\nx { $a; }\n", &err), UMP_ERR_PARSE);
    assert_non_null(strstr(err.msg, "m.dict:2"));
    assert_int_equal(parse_err("m.dict", "a ${{ 1 + 2 }};\n", &err), UMP_ERR_UNSUPPORTED);
}

static void test_macro_blowup(void **state)
{
    (void)state;
    /* each level doubles: must stop with an error, not exhaust memory */
    char buf[4096];
    size_t o = 0;
    o += (size_t)snprintf(buf + o, sizeof buf - o, "l0 (1 2 3 4 5 6 7 8);\n");
    for (int i = 1; i < 60; i++)
        o += (size_t)snprintf(buf + o, sizeof buf - o, "l%d ($l%d $l%d $l%d);\n", i, i - 1,
                              i - 1, i - 1);
    ump_err err;
    assert_int_equal(parse_err("blow.dict", buf, &err), UMP_ERR_INPUT);
    assert_non_null(strstr(err.msg, "blow.dict:"));
    o = 0;
    o += (size_t)snprintf(buf + o, sizeof buf - o, "d0 { a 1; b 2; }\n");
    for (int i = 1; i < 60; i++)
        o += (size_t)snprintf(buf + o, sizeof buf - o, "d%d { x { $d%d; } y { $d%d; } }\n", i,
                              i - 1, i - 1);
    assert_int_equal(parse_err("blow.dict", buf, &err), UMP_ERR_INPUT);
}

/* ---- directives ------------------------------------------------------------------ */

static void test_include(void **state)
{
    (void)state;
    char dir[64], path[256];
    tu_tmpdir(dir, sizeof dir);
    char sub[300];
    snprintf(sub, sizeof sub, "%s/system", dir);
    assert_int_equal(mkdir(sub, 0755), 0);
    tu_write(dir, "system/inc.h", "FoamFile { version 2.0; format ascii; class dictionary; object inc; }\n"
                                  "incA 1;\nincB { c 2; }\n#include \"nested/n.h\"\n");
    snprintf(sub, sizeof sub, "%s/system/nested", dir);
    assert_int_equal(mkdir(sub, 0755), 0);
    tu_write(dir, "system/nested/n.h", "nestedC $incA;\n");
    tu_write(dir, "system/vals", "(1 2 3)");
    tu_write(dir, "system/main",
             HDR("dictionary")
             "before 0;\n"
             "#include \"inc.h\"\n"
             "#includeIfPresent \"absent.h\"\n"
             "sub { #include \"<system>/inc.h\" }\n"
             "list #include \"vals\";\n"
             "functions\n{\n    #includeFunc residuals\n    #includeFunc streamlines\n}\n"
             "#inputMode merge\n"
             "r1 1; r2 2; r3 3; rx 4;\n"
             "#remove r1\n"
             "#remove (r2 \"r[x]\")\n"
             "after $incB.c;\n");
    snprintf(path, sizeof path, "%s/system/main", dir);
    foam_file *f;
    ump_err err;
    ump_status rc = foam_file_read(path, &f, &err);
    if (rc != UMP_OK)
        fail_msg("%s", err.msg);
    assert_null(foam_dict_find(f->dict, "FoamFile", 0));
    assert_label(T1(f->dict, "incA"), 1);
    assert_label(T1(f->dict, "nestedC"), 1);
    assert_non_null(strstr(T1(f->dict, "nestedC")->file, "inc.h"));
    const foam_entry *ia = E(f->dict, "incA");
    assert_non_null(strstr(ia->file, "system/inc.h"));
    assert_int_equal(ia->line, 2);
    assert_label(T1(foam_dict_sub(f->dict, "sub"), "incA"), 1);
    check_list(E(f->dict, "list"), 0, 1, (double[]){1, 2, 3}, 3);
    const foam_dict *fn = foam_dict_sub(f->dict, "functions");
    assert_int_equal(fn->n, 2);
    assert_string_equal(fn->e[0].key, "#includeFunc");
    assert_word(&fn->e[0].tok[0], "residuals");
    assert_word(&fn->e[1].tok[0], "streamlines");
    assert_null(foam_dict_find(f->dict, "r1", 0));
    assert_null(foam_dict_find(f->dict, "r2", 0));
    assert_null(foam_dict_find(f->dict, "rx", 0));
    assert_label(T1(f->dict, "r3"), 3);
    assert_label(T1(f->dict, "after"), 2);
    foam_file_free(&f);

    /* missing include: error names the including file and line */
    tu_write(dir, "system/bad", "a 1;\n\n#include \"nothere.h\"\n");
    snprintf(path, sizeof path, "%s/system/bad", dir);
    assert_int_equal(foam_file_read(path, &f, &err), UMP_ERR_IO);
    assert_non_null(strstr(err.msg, "system/bad:3"));
    assert_non_null(strstr(err.msg, "nothere.h"));

    /* recursive include stops */
    tu_write(dir, "system/self", "a 1;\n#include \"self\"\n");
    snprintf(path, sizeof path, "%s/system/self", dir);
    assert_int_equal(foam_file_read(path, &f, &err), UMP_ERR_INPUT);
    assert_non_null(strstr(err.msg, "self:2"));

    /* parse_ex can forbid file access */
    const char *txt = "#include \"x\"\n";
    assert_int_equal(foam_file_parse_ex("n.dict", txt, strlen(txt), FOAM_PARSE_NO_INCLUDE, &f,
                                        &err), UMP_ERR_UNSUPPORTED);
    assert_non_null(strstr(err.msg, "n.dict:1"));
    tu_rmtree(dir);
}

static void test_include_etc(void **state)
{
    (void)state;
    char dir[64], path[256], etc[300];
    tu_tmpdir(dir, sizeof dir);
    snprintf(etc, sizeof etc, "%s/etc", dir);
    assert_int_equal(mkdir(etc, 0755), 0);
    snprintf(path, sizeof path, "%s/etc/caseDicts", dir);
    assert_int_equal(mkdir(path, 0755), 0);
    /* an abridged copy of v1912 etc/caseDicts/setConstraintTypes */
    tu_write(dir, "etc/caseDicts/setConstraintTypes",
             "cyclic { type cyclic; }\nempty { type empty; }\n"
             "processor { type processor; value $internalField; }\n");
    const char *old = getenv("FOAM_ETC");
    char *saved = old ? strdup(old) : NULL;
    setenv("FOAM_ETC", etc, 1);
    foam_file *f = parse_ok(HDR("volScalarField")
        "internalField uniform 300;\n"
        "boundaryField\n{\n    wall { type zeroGradient; }\n"
        "    #includeEtc \"caseDicts/setConstraintTypes\"\n}\n");
    const foam_dict *bf = foam_dict_sub(f->dict, "boundaryField");
    assert_int_equal(bf->n, 4);
    assert_word(T1(foam_dict_sub(bf, "empty"), "type"), "empty");
    const foam_entry *v = E(foam_dict_sub(bf, "processor"), "value");
    assert_int_equal(v->ntok, 2);
    assert_label(&v->tok[1], 300);
    foam_file_free(&f);
    ump_err err;
    assert_int_equal(parse_err("etc.dict", "a 1;\n#includeEtc \"caseDicts/noSuchFile\"\n", &err),
                     UMP_ERR_IO);
    assert_non_null(strstr(err.msg, "etc.dict:2"));
    assert_non_null(strstr(err.msg, "caseDicts/noSuchFile"));
    if (saved) {
        setenv("FOAM_ETC", saved, 1);
        free(saved);
    } else {
        unsetenv("FOAM_ETC");
    }
    tu_rmtree(dir);

    /* the installed OpenFOAM file, when present */
    if (access("/usr/share/openfoam/etc/caseDicts/setConstraintTypes", R_OK) == 0 &&
        !getenv("FOAM_ETC")) {
        f = parse_ok("internalField uniform 1;\n"
                     "bf { #includeEtc \"caseDicts/setConstraintTypes\" }\n");
        const foam_dict *b = foam_dict_sub(f->dict, "bf");
        assert_non_null(foam_dict_sub(b, "cyclic"));
        assert_non_null(foam_dict_sub(b, "processorCyclic"));
        foam_file_free(&f);
    }
}

static void test_unsupported_directives(void **state)
{
    (void)state;
    static const char *const cases[] = {
        "a 1;\n#calc \"$a + 1\";\n",
        "a 1;\nb #calc \"$a + 1\";\n",
        "a 1;\nb #codeStream { code #{ os << 1; #}; };\n",
        "a 1;\nb #eval{ 2*$a };\n",
        "a 1;\n#if 1\n#endif\n",
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        ump_err err;
        assert_int_equal(parse_err("u.dict", cases[i], &err), UMP_ERR_UNSUPPORTED);
        assert_non_null(strstr(err.msg, "u.dict:2"));
    }
}

/* ---- getters ----------------------------------------------------------------------- */

static void test_getters(void **state)
{
    (void)state;
    foam_file *f = parse_ok(HDR("dictionary")
        "dt 0.005; n 20; w icoFoam; s \"str\"; on yes; off off; one 1; t true;\n"
        "v (1 2 -3.5); vbad (1 2); nu [0 2 -1 0 0 0 0] 0.01; nu2 nu [0 2 -1 0 0 0 0] 1e-05;\n"
        "nu3 1.5e-5; nu4 [m^2/s] 0.1; beta [1/K] 3e-3; rho rho [kg/m^3] 1.2; k [W/m/K] 2;\n"
        "bad abc; two 1 2; sd { } big 1e300; lbl 3.0; nanv nan;\n");
    const foam_dict *d = f->dict;
    ump_err err;
    double x;
    int64_t l;
    const char *w;
    int b;
    assert_int_equal(foam_get_scalar(d, "dt", &x, &err), UMP_OK);
    TU_CLOSE(x, 0.005, 0);
    assert_int_equal(foam_get_scalar(d, "n", &x, &err), UMP_OK);
    TU_CLOSE(x, 20, 0);
    assert_int_equal(foam_get_scalar(d, "nanv", &x, &err), UMP_OK);
    assert_true(isnan(x));
    assert_int_equal(foam_get_scalar(d, "bad", &x, &err), UMP_ERR_PARSE);
    assert_non_null(strstr(err.msg, "test.dict:5"));
    assert_non_null(strstr(err.msg, "'bad'"));
    assert_int_equal(foam_get_scalar(d, "two", &x, &err), UMP_ERR_PARSE);
    assert_int_equal(foam_get_scalar(d, "sd", &x, &err), UMP_ERR_PARSE);
    assert_int_equal(foam_get_scalar(d, "missing", &x, &err), UMP_ERR_INPUT);
    assert_non_null(strstr(err.msg, "test.dict:"));
    assert_non_null(strstr(err.msg, "missing"));
    assert_int_equal(foam_get_scalar_or(d, "missing", 7.5, &x, &err), UMP_OK);
    TU_CLOSE(x, 7.5, 0);
    assert_int_equal(foam_get_scalar_or(d, "bad", 7.5, &x, &err), UMP_ERR_PARSE);
    assert_int_equal(foam_get_label(d, "n", &l, &err), UMP_OK);
    assert_true(l == 20);
    assert_int_equal(foam_get_label(d, "lbl", &l, &err), UMP_ERR_PARSE);
    assert_int_equal(foam_get_label(d, "dt", &l, &err), UMP_ERR_PARSE);
    assert_int_equal(foam_get_label_or(d, "zz", -4, &l, &err), UMP_OK);
    assert_true(l == -4);
    assert_int_equal(foam_get_label_or(d, "w", -4, &l, &err), UMP_ERR_PARSE);
    assert_int_equal(foam_get_word(d, "w", &w, &err), UMP_OK);
    assert_string_equal(w, "icoFoam");
    assert_int_equal(foam_get_word(d, "s", &w, &err), UMP_OK);
    assert_string_equal(w, "str");
    assert_int_equal(foam_get_word(d, "n", &w, &err), UMP_ERR_PARSE);
    assert_int_equal(foam_get_word_or(d, "zz", "dflt", &w, &err), UMP_OK);
    assert_string_equal(w, "dflt");
    assert_int_equal(foam_get_bool_or(d, "on", 0, &b, &err), UMP_OK);
    assert_int_equal(b, 1);
    assert_int_equal(foam_get_bool_or(d, "off", 1, &b, &err), UMP_OK);
    assert_int_equal(b, 0);
    assert_int_equal(foam_get_bool_or(d, "one", 0, &b, &err), UMP_OK);
    assert_int_equal(b, 1);
    assert_int_equal(foam_get_bool_or(d, "t", 0, &b, &err), UMP_OK);
    assert_int_equal(b, 1);
    assert_int_equal(foam_get_bool_or(d, "zz", 1, &b, &err), UMP_OK);
    assert_int_equal(b, 1);
    assert_int_equal(foam_get_bool_or(d, "w", 1, &b, &err), UMP_ERR_PARSE);
    double v[3];
    assert_int_equal(foam_get_vector(d, "v", v, &err), UMP_OK);
    TU_CLOSE(v[2], -3.5, 0);
    assert_int_equal(foam_get_vector(d, "vbad", v, &err), UMP_ERR_PARSE);
    assert_non_null(strstr(err.msg, "test.dict:3"));
    double dims[7];
    assert_int_equal(foam_get_dimensioned(d, "nu", &x, dims, &err), UMP_OK);
    TU_CLOSE(x, 0.01, 0);
    TU_CLOSE(dims[1], 2, 0);
    TU_CLOSE(dims[2], -1, 0);
    assert_int_equal(foam_get_dimensioned(d, "nu2", &x, dims, &err), UMP_OK);
    TU_CLOSE(x, 1e-5, 0);
    TU_CLOSE(dims[1], 2, 0);
    assert_int_equal(foam_get_dimensioned(d, "nu3", &x, NULL, &err), UMP_OK);
    TU_CLOSE(x, 1.5e-5, 0);
    assert_int_equal(foam_get_dimensioned(d, "nu4", &x, dims, &err), UMP_OK);
    TU_CLOSE(x, 0.1, 0);
    double wnu[7] = {0, 2, -1, 0, 0, 0, 0};
    for (int i = 0; i < 7; i++)
        TU_CLOSE(dims[i], wnu[i], 0);
    assert_int_equal(foam_get_dimensioned(d, "beta", &x, dims, &err), UMP_OK);
    TU_CLOSE(dims[3], -1, 0);
    assert_int_equal(foam_get_dimensioned(d, "rho", &x, dims, &err), UMP_OK);
    TU_CLOSE(x, 1.2, 0);
    TU_CLOSE(dims[0], 1, 0);
    TU_CLOSE(dims[1], -3, 0);
    assert_int_equal(foam_get_dimensioned(d, "k", &x, dims, &err), UMP_OK);
    double wk[7] = {1, 1, -3, -1, 0, 0, 0};
    for (int i = 0; i < 7; i++)
        TU_CLOSE(dims[i], wk[i], 0);
    assert_int_equal(foam_get_dimensioned(d, "v", &x, dims, &err), UMP_ERR_PARSE);
    assert_int_equal(foam_get_dimensioned(d, "zz", &x, dims, &err), UMP_ERR_INPUT);
    foam_file_free(&f);
}

/* ---- binary ---------------------------------------------------------------------------- */

typedef struct bbuf { char *p; size_t n, cap; } bbuf;

static void bput(bbuf *b, const void *d, size_t n)
{
    if (b->n + n > b->cap) {
        b->cap = (b->n + n) * 2 + 64;
        b->p = realloc(b->p, b->cap);
        assert_non_null(b->p);
    }
    memcpy(b->p + b->n, d, n);
    b->n += n;
}

static void bstr(bbuf *b, const char *s) { bput(b, s, strlen(s)); }

/* little-endian integer of nb bytes */
static void ble(bbuf *b, uint64_t v, int nb)
{
    unsigned char c[8];
    for (int i = 0; i < nb; i++)
        c[i] = (unsigned char)(v >> (8 * i));
    bput(b, c, (size_t)nb);
}

static void bdbl(bbuf *b, double d, int nb)
{
    if (nb == 8) {
        uint64_t u;
        memcpy(&u, &d, 8);
        ble(b, u, 8);
    } else {
        float fl = (float)d;
        uint32_t u;
        memcpy(&u, &fl, 4);
        ble(b, u, 4);
    }
}

static void bheader(bbuf *b, const char *cls, int lbits, int sbits)
{
    char h[256];
    if (lbits)
        snprintf(h, sizeof h, "FoamFile\n{\n    version 2.0;\n    format binary;\n    class %s;\n"
                 "    arch \"LSB;label=%d;scalar=%d\";\n    object x;\n}\n"
                 "// * * * //\n\n", cls, lbits, sbits);
    else
        snprintf(h, sizeof h, "FoamFile { version 2.0; format binary; class %s; object x; }\n",
                 cls);
    bstr(b, h);
}

static foam_file *bparse(bbuf *b, ump_status want, ump_err *err)
{
    foam_file *f = NULL;
    memset(err, 0, sizeof *err);
    ump_status rc = foam_file_parse("bin.dat", b->p, b->n, &f, err);
    if (rc != want)
        fail_msg("binary parse returned %d, wanted %d: %s", rc, want, err->msg);
    return f;
}

static void test_binary_labels(void **state)
{
    (void)state;
    for (int lb = 0; lb <= 64; lb += 32) {
        if (lb == 0)
            continue;
        for (int pass = 0; pass < 2; pass++) {
            int bits = pass ? 64 : 32;
            bbuf b = {0};
            bheader(&b, "labelList", bits, 64);
            bstr(&b, "\n5\n(");
            int64_t vals[5] = {0, 1, -1, 2147483647, -2147483647 - 1};
            for (int i = 0; i < 5; i++)
                ble(&b, (uint64_t)vals[i], bits / 8);
            bstr(&b, ")\n\n// ******* //\n");
            ump_err err;
            foam_file *f = bparse(&b, UMP_OK, &err);
            assert_int_equal(f->label_bytes, bits / 8);
            assert_int_equal(f->nbody, 1);
            assert_int_equal(f->body[0].type, FOAM_TOK_BLOB);
            assert_int_equal(f->body[0].v.blob.n, 5);
            assert_int_equal(f->body[0].v.blob.is_label, 1);
            const int64_t *d = f->body[0].v.blob.data;
            for (int i = 0; i < 5; i++)
                assert_true(d[i] == vals[i]);
            ump_idx *l;
            size_t n, pos = 0;
            assert_int_equal(foam_tok_label_list(f->body, f->nbody, &pos, &l, &n, "owner", &err),
                             UMP_OK);
            assert_int_equal(n, 5);
            assert_int_equal(l[4], INT32_MIN);
            free(l);
            foam_file_free(&f);
            free(b.p);
        }
    }
    /* a 64-bit label that does not fit ump_idx is refused by the decoder */
    bbuf b = {0};
    bheader(&b, "labelList", 64, 64);
    bstr(&b, "1(");
    ble(&b, (uint64_t)1 << 40, 8);
    bstr(&b, ")");
    ump_err err;
    foam_file *f = bparse(&b, UMP_OK, &err);
    ump_idx *l;
    size_t n, pos = 0;
    assert_int_equal(foam_tok_label_list(f->body, f->nbody, &pos, &l, &n, "owner", &err),
                     UMP_ERR_INPUT);
    assert_non_null(strstr(err.msg, "bin.dat"));
    foam_file_free(&f);
    free(b.p);
}

static void test_binary_points(void **state)
{
    (void)state;
    for (int sb = 32; sb <= 64; sb += 32) {
        bbuf b = {0};
        bheader(&b, "vectorField", 32, sb);
        bstr(&b, "\n3\n(");
        double pts[9] = {0, 0, 0, 0.005, 0, 0, 1.5, -2.25, 1e-3};
        for (int i = 0; i < 9; i++)
            bdbl(&b, pts[i], sb / 8);
        bstr(&b, ")\n");
        ump_err err;
        foam_file *f = bparse(&b, UMP_OK, &err);
        assert_int_equal(f->scalar_bytes, sb / 8);
        double *v;
        size_t n, pos = 0;
        assert_int_equal(foam_tok_scalar_list(f->body, f->nbody, &pos, 3, &v, &n, "points", &err),
                         UMP_OK);
        assert_int_equal(n, 3);
        for (int i = 0; i < 9; i++)
            TU_CLOSE(v[i], pts[i], sb == 32 ? 1e-7 : 0);
        free(v);
        /* wrong component count */
        pos = 0;
        assert_int_equal(foam_tok_scalar_list(f->body, f->nbody, &pos, 1, &v, &n, "points", &err),
                         UMP_ERR_PARSE);
        foam_file_free(&f);
        free(b.p);
    }
    /* no arch: label=32 scalar=64 */
    bbuf b = {0};
    bheader(&b, "scalarField", 0, 0);
    bstr(&b, "2(");
    bdbl(&b, 1.25, 8);
    bdbl(&b, -7, 8);
    bstr(&b, ")");
    ump_err err;
    foam_file *f = bparse(&b, UMP_OK, &err);
    assert_int_equal(f->scalar_bytes, 8);
    assert_int_equal(f->label_bytes, 4);
    const double *d = f->body[0].v.blob.data;
    TU_CLOSE(d[1], -7, 0);
    foam_file_free(&f);
    free(b.p);
}

static void test_binary_faces(void **state)
{
    (void)state;
    bbuf b = {0};
    bheader(&b, "faceCompactList", 32, 64);
    bstr(&b, "\n3\n(");
    int off[3] = {0, 4, 7};
    for (int i = 0; i < 3; i++)
        ble(&b, (uint64_t)off[i], 4);
    bstr(&b, ")\n7\n(");
    for (int i = 0; i < 7; i++)
        ble(&b, (uint64_t)(10 + i), 4);
    bstr(&b, ")\n\n// ***** //\n");
    ump_err err;
    foam_file *f = bparse(&b, UMP_OK, &err);
    assert_int_equal(f->nbody, 2);
    ump_idx *offs, *items;
    size_t n, pos = 0;
    assert_int_equal(foam_tok_labellist_list(f->body, f->nbody, &pos, &offs, &items, &n, "faces",
                                             &err), UMP_OK);
    assert_int_equal(n, 2);
    assert_int_equal(pos, 2);
    assert_int_equal(offs[1], 4);
    assert_int_equal(items[6], 16);
    free(offs);
    free(items);
    foam_file_free(&f);
    free(b.p);

    /* binary faceList (each face its own binary list), 64-bit labels */
    memset(&b, 0, sizeof b);
    bheader(&b, "faceList", 64, 64);
    bstr(&b, "\n2\n(\n3(");
    for (int i = 0; i < 3; i++)
        ble(&b, (uint64_t)i, 8);
    bstr(&b, ")\n4(");
    for (int i = 0; i < 4; i++)
        ble(&b, (uint64_t)(5 + i), 8);
    bstr(&b, ")\n)\n");
    f = bparse(&b, UMP_OK, &err);
    pos = 0;
    assert_int_equal(foam_tok_labellist_list(f->body, f->nbody, &pos, &offs, &items, &n, "faces",
                                             &err), UMP_OK);
    assert_int_equal(n, 2);
    assert_int_equal(offs[2], 7);
    assert_int_equal(items[6], 8);
    free(offs);
    free(items);
    foam_file_free(&f);
    free(b.p);

    /* inconsistent offsets */
    memset(&b, 0, sizeof b);
    bheader(&b, "faceCompactList", 32, 64);
    bstr(&b, "2(");
    ble(&b, 0, 4);
    ble(&b, 5, 4);
    bstr(&b, ")3(");
    for (int i = 0; i < 3; i++)
        ble(&b, 1, 4);
    bstr(&b, ")");
    f = bparse(&b, UMP_OK, &err);
    pos = 0;
    assert_int_equal(foam_tok_labellist_list(f->body, f->nbody, &pos, &offs, &items, &n, "faces",
                                             &err), UMP_ERR_INPUT);
    assert_non_null(strstr(err.msg, "bin.dat"));
    foam_file_free(&f);
    free(b.p);
}

static void test_binary_field(void **state)
{
    (void)state;
    bbuf b = {0};
    bheader(&b, "volVectorField", 32, 64);
    bstr(&b, "dimensions [ 0 1 -1 0 0 0 0 ];\n\ninternalField   nonuniform List<vector> \n2\n(");
    for (int i = 0; i < 6; i++)
        bdbl(&b, i * 0.5, 8);
    bstr(&b, ");\nboundaryField\n{\n    a { type fixedValue; value uniform ( 1 0 0 ); }\n"
             "    b { type calculated; value nonuniform List<scalar> \n1\n(");
    bdbl(&b, 42, 8);
    bstr(&b, ");\n    }\n    c { type empty; value nonuniform 0 ( ); }\n"
             "    d { type empty; value nonuniform 0(); }\n"
             "    e { type empty; value nonuniform List<scalar> 0; }\n"
             "    f { type empty; value nonuniform List<scalar> 0(); }\n"
             "    g { type empty; value nonuniform 0; }\n"
             "    h { type x; value nonuniform List<label> 2(");
    ble(&b, 7, 4);
    ble(&b, 8, 4);
    bstr(&b, "); }\n}\n");
    ump_err err;
    foam_file *f = bparse(&b, UMP_OK, &err);
    assert_int_equal(f->binary, 1);
    const foam_entry *in = E(f->dict, "internalField");
    assert_int_equal(in->ntok, 3);
    assert_word(&in->tok[1], "List<vector>");
    assert_int_equal(in->tok[2].type, FOAM_TOK_BLOB);
    assert_int_equal(in->tok[2].line, 14);
    check_list(in, 2, 3, (double[]){0, 0.5, 1, 1.5, 2, 2.5}, 2);
    const foam_dict *bf = foam_dict_sub(f->dict, "boundaryField");
    check_list(E(foam_dict_sub(bf, "b"), "value"), 2, 1, (double[]){42}, 1);
    check_list(E(foam_dict_sub(bf, "c"), "value"), 1, 1, NULL, 0);
    check_list(E(foam_dict_sub(bf, "d"), "value"), 1, 1, NULL, 0);
    check_list(E(foam_dict_sub(bf, "e"), "value"), 2, 1, NULL, 0);
    check_list(E(foam_dict_sub(bf, "f"), "value"), 2, 1, NULL, 0);
    check_list(E(foam_dict_sub(bf, "g"), "value"), 1, 1, NULL, 0);
    const foam_entry *h = E(foam_dict_sub(bf, "h"), "value");
    ump_idx *l;
    size_t n, pos = 2;
    assert_int_equal(foam_tok_label_list(h->tok, h->ntok, &pos, &l, &n, "h", &err), UMP_OK);
    assert_int_equal(n, 2);
    assert_int_equal(l[1], 8);
    free(l);
    const foam_entry *a = E(foam_dict_sub(bf, "a"), "value");
    assert_int_equal(a->ntok, 6);
    foam_file_free(&f);
    free(b.p);
}

static void test_binary_errors(void **state)
{
    (void)state;
    /* cut short in the raw data, before ')', before '(' */
    for (int cut = 0; cut < 4; cut++) {
        bbuf b = {0};
        bheader(&b, "labelList", 32, 64);
        bstr(&b, "4\n(");
        size_t keep = b.n;
        for (int i = 0; i < 4; i++)
            ble(&b, (uint64_t)i, 4);
        if (cut == 0)
            b.n = keep + 7;
        else if (cut == 1)
            (void)0;
        else if (cut == 2)
            b.n = keep - 1;
        else
            bstr(&b, "x");
        ump_err err;
        foam_file *f = NULL;
        ump_status rc = foam_file_parse("cut.bin", b.p, b.n, &f, &err);
        assert_true(rc == UMP_ERR_IO || rc == UMP_ERR_PARSE);
        assert_null(f);
        assert_non_null(strstr(err.msg, "cut.bin"));
        free(b.p);
    }
    /* MSB, odd sizes, unknown binary class */
    static const char *const bad[] = {
        "FoamFile { format binary; class labelList; arch \"MSB;label=32;scalar=64\"; }\n0()",
        "FoamFile { format binary; class labelList; arch \"LSB;label=16;scalar=64\"; }\n0()",
        "FoamFile { format binary; class Cloud<passiveParticle>; }\n0()",
        "FoamFile { format binery; class labelList; }\n0()",
    };
    ump_status want[] = {UMP_ERR_UNSUPPORTED, UMP_ERR_UNSUPPORTED, UMP_ERR_UNSUPPORTED,
                         UMP_ERR_PARSE};
    for (int i = 0; i < 4; i++) {
        ump_err err;
        assert_int_equal(parse_err("h.bin", bad[i], &err), want[i]);
        assert_non_null(strstr(err.msg, "h.bin"));
    }
}

/* ---- files and gzip --------------------------------------------------------------------- */

static void test_files_gzip(void **state)
{
    (void)state;
    char dir[64], path[256];
    tu_tmpdir(dir, sizeof dir);
    const char *text = HDR("labelList") "3(4 5 6)\n";
    /* gzip-compressed copy only: reading "owner" finds "owner.gz" */
    snprintf(path, sizeof path, "%s/owner.gz", dir);
    gzFile gz = gzopen(path, "wb");
    assert_non_null(gz);
    assert_int_equal(gzwrite(gz, text, (unsigned)strlen(text)), (int)strlen(text));
    assert_int_equal(gzclose(gz), Z_OK);
    snprintf(path, sizeof path, "%s/owner", dir);
    assert_true(foam_file_exists(path));
    foam_file *f;
    ump_err err;
    assert_int_equal(foam_file_read(path, &f, &err), UMP_OK);
    assert_non_null(strstr(f->path, "owner.gz"));
    ump_idx *l;
    size_t nl, pos = 0;
    assert_int_equal(foam_tok_label_list(f->body, f->nbody, &pos, &l, &nl, "owner", &err), UMP_OK);
    assert_true(nl == 3 && l[2] == 6 && pos == f->nbody);
    free(l);
    foam_file_free(&f);
    /* plain file wins over .gz */
    tu_write(dir, "owner", HDR("labelList") "1(9)\n");
    assert_int_equal(foam_file_read(path, &f, &err), UMP_OK);
    pos = 0;
    assert_int_equal(foam_tok_label_list(f->body, f->nbody, &pos, &l, &nl, "owner", &err), UMP_OK);
    assert_true(nl == 1 && l[0] == 9);
    free(l);
    assert_string_equal(f->path, path);
    foam_file_free(&f);
    /* truncated gzip */
    char big[4096];
    size_t o = (size_t)snprintf(big, sizeof big, "%s", HDR("labelList") "400(");
    for (int i = 0; i < 400 && o < sizeof big - 8; i++)
        o += (size_t)snprintf(big + o, sizeof big - o, "%d ", i % 10);
    snprintf(path, sizeof path, "%s/trunc.gz", dir);
    gz = gzopen(path, "wb");
    gzwrite(gz, big, (unsigned)o);
    gzclose(gz);
    FILE *fp = fopen(path, "rb");
    char raw[4096];
    size_t nraw = fread(raw, 1, sizeof raw, fp);
    fclose(fp);
    tu_write_bytes(dir, "trunc.gz", raw, nraw / 2);
    snprintf(path, sizeof path, "%s/trunc", dir);
    assert_int_not_equal(foam_file_read(path, &f, &err), UMP_OK);
    assert_non_null(strstr(err.msg, "trunc"));
    /* missing */
    snprintf(path, sizeof path, "%s/nothing", dir);
    assert_false(foam_file_exists(path));
    assert_int_equal(foam_file_read(path, &f, &err), UMP_ERR_IO);
    char want[1024];
    snprintf(want, sizeof want, "cannot open %s (nor %s.gz)", path, path);
    assert_string_equal(err.msg, want);
    assert_null(f);
    /* a directory is not a file */
    assert_false(foam_file_exists(dir));
    tu_rmtree(dir);
}

/* ---- decoders: malformed lists ---------------------------------------------------------- */

static void test_decoder_errors(void **state)
{
    (void)state;
    static const struct { const char *text; int ncomp; int kind; } cases[] = {
        {"a 3(1 2);", 1, 0},
        {"a 2(1 2 3);", 1, 0},
        {"a (1 2 x);", 1, 0},
        {"a 2((1 2 3) (1 2));", 3, 0},
        {"a 2((1 2 3) (1 2 3 4));", 3, 0},
        {"a 2{1};", 3, 0},
        {"a 2{(1 2 3)};", 1, 0},
        {"a 2{1;", 1, 2},
        {"a -1();", 1, 0},
        {"a 3;", 1, 0},
        {"a;", 1, 0},
        {"a word;", 1, 0},
        {"a 3(1 2 3);", 1, 1},   /* label list: fine */
        {"a 2(1 2.5);", 1, 1},
        {"a 2(1 3000000000);", 1, 1},
        {"a 2(4(1 2 3 4) 3(1 2));", 1, 3},
        {"a 2(4(1 2 3 4));", 1, 3},
        {"a 1(4(1 2 3 4) 1(1));", 1, 3},
        {"a 1{4(1 2 3 4)};", 1, 3},
        {"a 2(4(1 2 3 4) x);", 1, 3},
        {"a 2(0 4) 3(1 2 3);", 1, 3},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        ump_err err;
        foam_file *f = NULL;
        memset(&err, 0, sizeof err);
        ump_status rc = foam_file_parse("dec.dict", cases[i].text, strlen(cases[i].text), &f, &err);
        if (rc != UMP_OK) {
            assert_int_equal(cases[i].kind, 2);
            continue;
        }
        const foam_entry *e = E(f->dict, "a");
        size_t pos = 0, n;
        if (cases[i].kind == 0) {
            double *v = NULL;
            rc = foam_tok_scalar_list(e->tok, e->ntok, &pos, cases[i].ncomp, &v, &n, "a", &err);
            assert_null(v);
        } else if (cases[i].kind == 1) {
            ump_idx *v = NULL;
            rc = foam_tok_label_list(e->tok, e->ntok, &pos, &v, &n, "a", &err);
            if (i == 12) {
                assert_int_equal(rc, UMP_OK);
                assert_int_equal(n, 3);
                free(v);
                foam_file_free(&f);
                continue;
            }
            assert_null(v);
        } else {
            ump_idx *o = NULL, *it = NULL;
            rc = foam_tok_labellist_list(e->tok, e->ntok, &pos, &o, &it, &n, "a", &err);
            assert_null(o);
            assert_null(it);
        }
        if (rc == UMP_OK)
            fail_msg("case %zu (%s) accepted", i, cases[i].text);
        if (e->ntok > 0 && !strstr(err.msg, "dec.dict"))
            fail_msg("case %zu: message without file: %s", i, err.msg);
        foam_file_free(&f);
    }
    /* foam_tok_scalar and the message helpers */
    foam_file *f = parse_ok("a 1 x;");
    const foam_entry *e = E(f->dict, "a");
    size_t pos = 0;
    double x;
    ump_err err;
    assert_int_equal(foam_tok_scalar(e->tok, e->ntok, &pos, &x, "a", &err), UMP_OK);
    assert_int_equal(pos, 1);
    assert_int_equal(foam_tok_scalar(e->tok, e->ntok, &pos, &x, "a", &err), UMP_ERR_PARSE);
    assert_non_null(strstr(err.msg, "test.dict:1: a: expected a number, found word 'x'"));
    pos = 2;
    assert_int_equal(foam_tok_scalar(e->tok, e->ntok, &pos, &x, "a", &err), UMP_ERR_PARSE);
    char buf[128];
    assert_string_equal(foam_tok_where(e->tok, e->ntok, 0, "fb", buf, sizeof buf), "test.dict:1");
    assert_string_equal(foam_tok_where(e->tok, e->ntok, 2, "fb", buf, sizeof buf), "fb");
    assert_string_equal(foam_tok_str(&e->tok[1], buf, sizeof buf), "word 'x'");
    assert_string_equal(foam_tok_str(&e->tok[0], buf, sizeof buf), "label 1");
    foam_file_free(&f);
}

/* ---- malformed files ------------------------------------------------------------------- */

static void test_bad_inputs(void **state)
{
    (void)state;
    static const struct { const char *text; int line; } bad[] = {
        {"a \"unterminated;\n", 1},
        {"a 1;\nb \"new\nline\";\n", 2},
        {"a 1;\n/* never closed\n", 2},
        {"a { b 1;\n", 2},
        {"a 1;\n}\n", 2},
        {"a (1 2;\nb 3;\n", 3},
        {"a 1\n", 2},
        {"a 1 }\n", 1},
        {"a (1 2));\n", 1},
        {"a { b 1 }\n", 1},
        {"3 ( 1 2\n", 2},
        {"( 1 } \n", 1},
        {"a 1;\n{ b 1; }\n", 2},
        {"a 1;\n5 6;\n", 2},
        {"a 1;\nb $;\n", 2},
        {"a 1;\nb ${a;\n", 2},
        {"a 1;\n# x\n", 2},
        {"a 1;\nb #{ no end\n", 2},
        {"a 1;\nb 'x';\n", 2},
        {"FoamFile 3;\n", 1},
        {"FoamFile { format binary; class labelList; }\n3(", 2},
        {"FoamFile { format binary; class labelList; }\nx", 2},
        {"a 1;\nb 1234567890123456789012345678901234567890123456789012345678901234567890"
         "1234567890123456789012345678901234567890123456789012345678901234567890;\n", 2},
        {"a 1;\n#remove 5\n", 2},
        {"a 1;\n#include\n", 2},
        {"a 1;\n#includeFunc ;\n", 2},
        {"a $b;\n", 1},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        ump_err err;
        ump_status rc = parse_err("bad.dict", bad[i].text, &err);
        if (rc == UMP_OK)
            fail_msg("bad input %zu accepted: %s", i, bad[i].text);
        char want[64];
        snprintf(want, sizeof want, "bad.dict:%d:", bad[i].line);
        if (!strstr(err.msg, want))
            fail_msg("bad input %zu: wanted '%s' in: %s", i, want, err.msg);
        assert_null(strchr(err.msg, '\n'));
    }
    /* deep nesting is refused, not a stack overflow */
    size_t n = 100000;
    char *deep = malloc(2 * n + 16);
    for (size_t i = 0; i < n; i++)
        memcpy(deep + 2 * i, "a{", 2);
    deep[2 * n] = '\0';
    ump_err err;
    assert_int_not_equal(parse_err("deep.dict", deep, &err), UMP_OK);
    for (size_t i = 0; i < n; i++)
        deep[i] = '(';
    memcpy(deep, "a ", 2);
    deep[n] = '\0';
    assert_int_not_equal(parse_err("deep.dict", deep, &err), UMP_OK);
    free(deep);
    /* NUL bytes and binary junk in an ASCII file do not crash */
    char junk[256];
    for (int i = 0; i < 256; i++)
        junk[i] = (char)(i * 37 + 11);
    foam_file *f = NULL;
    ump_status rc = foam_file_parse("junk", junk, sizeof junk, &f, &err);
    if (rc == UMP_OK)
        foam_file_free(&f);
}

/* Numbers read by the lexer's fast paths (digits-only labels below 10^18
 * without overflow checks; decimal scalars by Clinger's exact fast path)
 * against strtod/strtoll, bit for bit: random doubles written in every
 * printf form and precision, plus the boundary cases of each path. */
static void test_number_fast_paths(void **state)
{
    (void)state;
    static const char *fixed[] = {"0", "-0", "0.0", "-0.0", ".5", "-.5", "5.", "1e5", "1E-5", "1e+22",
                                  "1e23", "1e-22", "1e-23", "9007199254740992", "9007199254740993.0",
                                  "9007199254740993e-3", "123456789012345678", "1234567890123456789",
                                  "12345678901234567890", "-9223372036854775808", "9223372036854775807",
                                  "9223372036854775808", "0.000000000000000000000000001", "1.7976931348623157e308",
                                  "4.9e-324", "2.2250738585072014e-308", "0.1", "0.2", "0.3", "1.5e0",
                                  "00012.5000", "-000", "1e0000000000000000000001", "123.456e-7"};
    size_t nf = sizeof fixed / sizeof fixed[0], nr = 20000, cap = (nf + 8 * nr) * 40 + 256;
    char *text = malloc(cap), **words = malloc(sizeof(char *) * (nf + 8 * nr));
    size_t len = (size_t)snprintf(text, cap, HDR("dictionary") "l (");
    size_t nw = 0;
    for (size_t k = 0; k < nf; k++) {
        words[nw++] = text + len + 1;
        len += (size_t)snprintf(text + len, cap - len, " %s", fixed[k]);
    }
    uint64_t x = 88172645463325252ULL;
    for (size_t k = 0; k < nr; k++) {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        double v = (double)(x >> 11) / 9007199254740992.0 * pow(10.0, (double)((int)(x % 41) - 20));
        if (x & 1)
            v = -v;
        static const char *fmt[] = {"%.*g", "%.*e", "%.*f", "%.*G"};
        for (int q = 0; q < 8; q++) {
            int prec = 1 + (int)((x >> (8 + 4 * q)) % 17);
            words[nw++] = text + len + 1;
            text[len++] = ' ';
            len += (size_t)snprintf(text + len, cap - len, fmt[q % 4], q % 4 == 2 ? prec % 8 : prec, v);
        }
    }
    len += (size_t)snprintf(text + len, cap - len, " );\n");
    foam_file *f = parse_ok(text);
    const foam_entry *e = E(f->dict, "l");
    assert_int_equal(e->ntok, nw + 2);
    for (size_t k = 0; k < nw; k++) {
        const foam_token *t = &e->tok[k + 1];
        char w[64];
        size_t wl = strcspn(words[k], " )");
        memcpy(w, words[k], wl);
        w[wl] = '\0';
        char *end;
        if (t->type == FOAM_TOK_LABEL) {
            errno = 0;
            long long want = strtoll(w, &end, 10);
            assert_int_equal(errno, 0);
            assert_true(*end == '\0' && (long long)t->v.label == want);
        } else {
            assert_int_equal(t->type, FOAM_TOK_SCALAR);
            double want = strtod(w, &end);
            assert_true(*end == '\0');
            if (memcmp(&want, &t->v.scalar, sizeof want) != 0)
                fail_msg("'%s': lexer %.17g, strtod %.17g", w, t->v.scalar, want);
        }
    }
    foam_file_free(&f);
    free(words);
    free(text);
}

/* ---- allocation failures at every point ------------------------------------------------- */

static void test_alloc_failures(void **state)
{
    (void)state;
    const char *text = HDR("dictionary")
        "a 1; b { c $a; d (1 2 3); } p { x 1; } q { $p; y 2; } l 2((1 2 3) (4 5 6));\n"
        "big { k0 0; k1 1; k2 2; k3 3; k4 4; k5 5; k6 6; k7 7; k8 8; k9 9; k10 $b; }\n"
        "\"r.*\" 1; #remove k\n";
    int ok = 0;
    for (long k = 0; k < 2000 && !ok; k++) {
        ump_alloc_fail_after(k);
        foam_file *f = NULL;
        ump_err err;
        ump_status rc = foam_file_parse("alloc.dict", text, strlen(text), &f, &err);
        ump_alloc_fail_after(-1);
        if (rc == UMP_OK) {
            ok = 1;
            const foam_entry *e = E(f->dict, "l");
            for (long j = 0; j < 10; j++) {
                double *v = NULL;
                size_t n, pos = 0;
                ump_alloc_fail_after(j);
                rc = foam_tok_scalar_list(e->tok, e->ntok, &pos, 3, &v, &n, "l", &err);
                ump_alloc_fail_after(-1);
                if (rc == UMP_OK)
                    free(v);
                else
                    assert_int_equal(rc, UMP_ERR_NOMEM);
            }
            foam_file_free(&f);
        } else {
            assert_int_equal(rc, UMP_ERR_NOMEM);
            assert_null(f);
        }
    }
    assert_true(ok);
}

/* ---- a real mesh from OpenFOAM (when installed) and a big ASCII mesh --------------------- */

static void test_openfoam_cavity(void **state)
{
    (void)state;
    const char *src = "/usr/share/doc/openfoam-examples/examples/incompressible/icoFoam/cavity/cavity";
    if (access(src, R_OK) != 0 || system("command -v blockMesh >/dev/null 2>&1") != 0) {
        skip();
        return;
    }
    char dir[64], cmd[1024], path[256];
    tu_tmpdir(dir, sizeof dir);
    snprintf(cmd, sizeof cmd,
             "cp -r %s/. %s/ && cd %s && WM_PROJECT_DIR=/usr/share/openfoam blockMesh "
             ">/dev/null 2>&1 && sed -i 's/^writeFormat .*/writeFormat binary;/' "
             "system/controlDict && mkdir bin && cp -r constant system bin/ && cd bin && "
             "WM_PROJECT_DIR=/usr/share/openfoam foamFormatConvert -constant >/dev/null 2>&1",
             src, dir, dir);
    if (system(cmd) != 0) {
        tu_rmtree(dir);
        skip();
        return;
    }
    for (int bin = 0; bin < 2; bin++) {
        const char *pre = bin ? "bin/" : "";
        foam_file *f;
        ump_err err;
        ump_idx *offs, *items, *own;
        double *pts;
        size_t n, np, no, pos;
        snprintf(path, sizeof path, "%s/%sconstant/polyMesh/points", dir, pre);
        assert_int_equal(foam_file_read(path, &f, &err), UMP_OK);
        assert_int_equal(f->binary, bin);
        pos = 0;
        assert_int_equal(foam_tok_scalar_list(f->body, f->nbody, &pos, 3, &pts, &np, "points",
                                              &err), UMP_OK);
        assert_int_equal(np, 882);
        TU_CLOSE(pts[3], 0.005, 1e-12);
        free(pts);
        foam_file_free(&f);
        snprintf(path, sizeof path, "%s/%sconstant/polyMesh/faces", dir, pre);
        assert_int_equal(foam_file_read(path, &f, &err), UMP_OK);
        pos = 0;
        assert_int_equal(foam_tok_labellist_list(f->body, f->nbody, &pos, &offs, &items, &n,
                                                 "faces", &err), UMP_OK);
        assert_int_equal(n, 1640);
        assert_int_equal(offs[n], 6560);
        assert_int_equal(items[0], 1);
        assert_int_equal(items[1], 22);
        free(offs);
        free(items);
        foam_file_free(&f);
        snprintf(path, sizeof path, "%s/%sconstant/polyMesh/owner", dir, pre);
        assert_int_equal(foam_file_read(path, &f, &err), UMP_OK);
        pos = 0;
        assert_int_equal(foam_tok_label_list(f->body, f->nbody, &pos, &own, &no, "owner", &err),
                         UMP_OK);
        assert_int_equal(no, 1640);
        assert_int_equal(own[2], 1);
        free(own);
        foam_file_free(&f);
        snprintf(path, sizeof path, "%s/%sconstant/polyMesh/boundary", dir, pre);
        assert_int_equal(foam_file_read(path, &f, &err), UMP_OK);
        assert_label(&f->body[0], 3);
        assert_int_equal(f->body[3].type, FOAM_TOK_DICT);
        foam_file_free(&f);
    }
    tu_rmtree(dir);
}

static void test_big_ascii_mesh(void **state)
{
    (void)state;
    /* 300 000 points and 400 000 quad faces, as an ASCII polyMesh would hold */
    const size_t np = 300000, nf = 400000;
    size_t cap = np * 40 + nf * 48 + 1024, o = 0;
    char *buf = malloc(cap);
    assert_non_null(buf);
    o += (size_t)snprintf(buf + o, cap - o, HDR("vectorField") "\n%zu\n(\n", np);
    for (size_t i = 0; i < np; i++)
        o += (size_t)snprintf(buf + o, cap - o, "(%.6g %.6g 0.01)\n", (double)(i % 547) * 0.001,
                              (double)(i / 547) * 0.00125);
    o += (size_t)snprintf(buf + o, cap - o, ")\n");
    clock_t c0 = clock();
    foam_file *f;
    ump_err err;
    assert_int_equal(foam_file_parse("points", buf, o, &f, &err), UMP_OK);
    double *pts;
    size_t n, pos = 0;
    assert_int_equal(foam_tok_scalar_list(f->body, f->nbody, &pos, 3, &pts, &n, "points", &err),
                     UMP_OK);
    assert_int_equal(n, np);
    TU_CLOSE(pts[3 * 548], 0.001, 1e-12);
    free(pts);
    foam_file_free(&f);
    double tp = (double)(clock() - c0) / CLOCKS_PER_SEC;

    o = 0;
    o += (size_t)snprintf(buf + o, cap - o, HDR("faceList") "\n%zu\n(\n", nf);
    for (size_t i = 0; i < nf; i++)
        o += (size_t)snprintf(buf + o, cap - o, "4(%zu %zu %zu %zu)\n", i, i + 1, i + 548, i + 547);
    o += (size_t)snprintf(buf + o, cap - o, ")\n");
    c0 = clock();
    assert_int_equal(foam_file_parse("faces", buf, o, &f, &err), UMP_OK);
    ump_idx *offs, *items;
    pos = 0;
    assert_int_equal(foam_tok_labellist_list(f->body, f->nbody, &pos, &offs, &items, &n, "faces",
                                             &err), UMP_OK);
    assert_int_equal(n, nf);
    assert_int_equal(offs[nf], 4 * (ump_idx)nf);
    assert_int_equal(items[4 * 1000 + 2], 1000 + 548);
    free(offs);
    free(items);
    foam_file_free(&f);
    double tf = (double)(clock() - c0) / CLOCKS_PER_SEC;
    print_message("big ASCII mesh: points %.3f s, faces %.3f s\n", tp, tf);
    free(buf);
}

/* ---- the one-pass ascii list reader against the token reader ---------------- */

/* Parse body under class fast (which takes foam_lex_ascii_list) and under
 * class slow (token by token), read the list with the getter of its shape,
 * and require the same status, message, values (bit for bit) and tokens
 * left after the list. Returns 1 when the fast class read it as a blob. */
static int same_both_ways(const char *fast, const char *slow, int shape, const char *body)
{
    char *text[2];
    const char *cls[2] = {fast, slow};
    ump_status rc[2], grc[2] = {UMP_OK, UMP_OK};
    ump_err err[2], gerr[2];
    foam_file *f[2] = {NULL, NULL};
    ump_idx *a[2] = {NULL, NULL}, *b[2] = {NULL, NULL};
    double *d[2] = {NULL, NULL};
    size_t n[2] = {0, 0}, left[2] = {0, 0};
    int blob = 0;
    for (int k = 0; k < 2; k++) {
        size_t len = strlen(body) + 200;
        text[k] = malloc(len);
        assert_non_null(text[k]);
        snprintf(text[k], len, "FoamFile { version 2.0; format ascii; class %s; object x; }\n%s",
                 cls[k], body);
        memset(&err[k], 0, sizeof err[k]);
        memset(&gerr[k], 0, sizeof gerr[k]);
        rc[k] = foam_file_parse("list", text[k], strlen(text[k]), &f[k], &err[k]);
        if (rc[k] != UMP_OK)
            continue;
        size_t pos = 0;
        if (k == 0)
            blob = f[k]->nbody > 0 && f[k]->body[0].type == FOAM_TOK_BLOB;
        if (shape == 1)
            grc[k] = foam_tok_label_list(f[k]->body, f[k]->nbody, &pos, &a[k], &n[k], "l", &gerr[k]);
        else if (shape == 2)
            grc[k] = foam_tok_scalar_list(f[k]->body, f[k]->nbody, &pos, 3, &d[k], &n[k], "p", &gerr[k]);
        else
            grc[k] = foam_tok_labellist_list(f[k]->body, f[k]->nbody, &pos, &a[k], &b[k], &n[k], "f",
                                             &gerr[k]);
        left[k] = f[k]->nbody - pos;
    }
    if (rc[0] != rc[1] || strcmp(err[0].msg, err[1].msg) != 0 || grc[0] != grc[1] ||
        strcmp(gerr[0].msg, gerr[1].msg) != 0 || n[0] != n[1] || (grc[0] == UMP_OK && left[0] != left[1]))
        fail_msg("%s / %s differ on\n%s\nparse %d '%s' / %d '%s'; get %d '%s' / %d '%s'; n %zu / %zu", fast,
                 slow, body, rc[0], err[0].msg, rc[1], err[1].msg, grc[0], gerr[0].msg, grc[1], gerr[1].msg,
                 n[0], n[1]);
    if (rc[0] == UMP_OK && grc[0] == UMP_OK) {
        if (shape == 2)
            assert_memory_equal(d[0], d[1], 3 * n[0] * sizeof(double));
        else
            assert_memory_equal(a[0], a[1], (shape == 3 ? n[0] + 1 : n[0]) * sizeof(ump_idx));
        if (shape == 3)
            assert_memory_equal(b[0], b[1], (size_t)a[0][n[0]] * sizeof(ump_idx));
    }
    for (int k = 0; k < 2; k++) {
        free(a[k]);
        free(b[k]);
        free(d[k]);
        foam_file_free(&f[k]);
        free(text[k]);
    }
    return blob;
}

static void test_ascii_list_fast_path(void **state)
{
    (void)state;
    static const char *const cls[3][2] = {
        {"labelList", "labelField"}, {"vectorField", "vectorList"}, {"faceList", "labelListList"}};
    static const char *const good[3] = {
        "\n5\n(\n0\n3\n2\n\t7 1\n)\n\n// ****** //\n",
        "\n3\n(\n(0 0 0)\n(1.5e-3 -0.25 .5)\n(-0 1e400 0.10000000000000001)\n)\n",
        "\n3\n(\n4(0 1 5 4)\n3(1 2 5)\n4 ( 2 3 7 6 )\n)\n// end\n"};
    /* well-formed: the fast path takes them, same values */
    for (int s = 0; s < 3; s++)
        assert_true(same_both_ways(cls[s][0], cls[s][1], s + 1, good[s]));
    /* forms left to the token reader (errors named as before) */
    static const char *const other[] = {
        "3 (0 1 /* c */ 2)", "3 (0 1 2 3)", "4 (0 1 2)", "3 (0 -1 2)", "3 (0 1234567890123456789 2)",
        "3 (0 +1 2)", "3{1}", "3 (0 1a 2)", "3 (0 1 2", "3 (0 1 2) junk", "0()", "2 (0 2147483648)",
        "3 (0 1 2)\r\n", "1 (4(0 1 2 3))", "(0 1 2)", "3 (0 1.0 2)"};
    for (size_t k = 0; k < sizeof other / sizeof other[0]; k++)
        for (int s = 0; s < 3; s++)
            (void)same_both_ways(cls[s][0], cls[s][1], s + 1, other[k]);
    /* random edits of the well-formed bodies: the two readers never differ */
    static const char alpha[] = " \n\t()0123456789-.eE+/*{}a;";
    uint64_t x = 0x9E3779B97F4A7C15ULL;
    int taken = 0;
    for (int it = 0; it < 30000; it++) {
        int s = it % 3;
        char body[256];
        size_t len = strlen(good[s]);
        memcpy(body, good[s], len + 1);
        int nedit = 1 + (int)((x >> 5) % 3);
        for (int e = 0; e < nedit && len > 0 && len < sizeof body - 2; e++) {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            size_t at = (size_t)(x % len);
            char c = alpha[(x >> 20) % (sizeof alpha - 1)];
            switch ((x >> 40) % 3) {
            case 0:
                body[at] = c;
                break;
            case 1:
                memmove(body + at + 1, body + at, len - at + 1);
                body[at] = c;
                len++;
                break;
            default:
                memmove(body + at, body + at + 1, len - at);
                len--;
            }
        }
        taken += same_both_ways(cls[s][0], cls[s][1], s + 1, body);
    }
    print_message("ascii lists: %d of 30000 edited bodies read in one pass, all as the token reader\n",
                  taken);
    assert_true(taken > 1000); /* the edits leave many well-formed (e.g. changed digits) */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_tokens),
        cmocka_unit_test(test_number_fast_paths),
        cmocka_unit_test(test_comments_lines),
        cmocka_unit_test(test_header_and_empty),
        cmocka_unit_test(test_nested_dicts),
        cmocka_unit_test(test_regex_keys),
        cmocka_unit_test(test_list_forms),
        cmocka_unit_test(test_list_of_lists),
        cmocka_unit_test(test_boundary_body),
        cmocka_unit_test(test_dict_in_list_entry),
        cmocka_unit_test(test_macros),
        cmocka_unit_test(test_macro_blowup),
        cmocka_unit_test(test_include),
        cmocka_unit_test(test_include_etc),
        cmocka_unit_test(test_unsupported_directives),
        cmocka_unit_test(test_getters),
        cmocka_unit_test(test_binary_labels),
        cmocka_unit_test(test_binary_points),
        cmocka_unit_test(test_binary_faces),
        cmocka_unit_test(test_binary_field),
        cmocka_unit_test(test_binary_errors),
        cmocka_unit_test(test_files_gzip),
        cmocka_unit_test(test_decoder_errors),
        cmocka_unit_test(test_bad_inputs),
        cmocka_unit_test(test_alloc_failures),
        cmocka_unit_test(test_openfoam_cavity),
        cmocka_unit_test(test_big_ascii_mesh),
        cmocka_unit_test(test_ascii_list_fast_path),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
