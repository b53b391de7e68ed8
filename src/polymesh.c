/* SPDX-License-Identifier: GPL-3.0-or-later
 * polymesh.c -- reads an OpenFOAM constant/polyMesh directory.
 *
 * Files (each plain or .gz, ascii or binary, through foam.h): points
 * (vectorField), faces (faceList or faceCompactList), owner and neighbour
 * (labelList), boundary (polyBoundaryMesh: a list of "name { dict }").
 * The number of cells is 1 + the largest owner/neighbour label, as OpenFOAM
 * computes it (bounded by nFaces/2 before any per-cell allocation).
 * pmesh_check() then verifies the topology (the checks of OpenFOAM's
 * checkMesh -allTopology that matter here: vertex labels, duplicate faces,
 * closed cells by edges and by area vectors) so that later
 * stages can index without bounds checks.
 */
#include "umppm/polymesh.h"
#include "umppm/foam.h"

#include <math.h>
#include <omp.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void pmesh_free(pmesh **pp)
{
    if (!pp || !*pp)
        return;
    pmesh *m = *pp;
    for (int i = 0; i < m->npatches; i++) {
        pmesh_patch *p = &m->patch[i];
        free(p->name);
        free(p->type);
        for (int g = 0; g < p->ngroups; g++)
            free(p->groups[g]);
        free(p->groups);
        free(p->neighbour_patch);
        free(p->transform);
    }
    free(m->patch);
    free(m->dir);
    free(m->points);
    free(m->face_off);
    free(m->face_pts);
    free(m->owner);
    free(m->neighbour);
    free(m);
    *pp = NULL;
}

int pmesh_patch_index(const pmesh *m, const char *name)
{
    for (int i = 0; i < m->npatches; i++)
        if (strcmp(m->patch[i].name, name) == 0)
            return i;
    return -1;
}

int pmesh_patch_in_group(const pmesh_patch *p, const char *g)
{
    for (int i = 0; i < p->ngroups; i++)
        if (strcmp(p->groups[i], g) == 0)
            return 1;
    /* constraint types and wall are implicit groups (polyPatch constructors) */
    return p->kind != PMESH_PATCH && strcmp(p->type, g) == 0;
}

static pmesh_patch_kind patch_kind(const char *type)
{
    static const struct { const char *w; pmesh_patch_kind k; } tab[] = {
        {"patch", PMESH_PATCH}, {"wall", PMESH_WALL}, {"empty", PMESH_EMPTY},
        {"symmetryPlane", PMESH_SYMMETRYPLANE}, {"symmetry", PMESH_SYMMETRY},
        {"cyclic", PMESH_CYCLIC}, {"wedge", PMESH_WEDGE},
    };
    for (size_t i = 0; i < sizeof tab / sizeof tab[0]; i++)
        if (strcmp(tab[i].w, type) == 0)
            return tab[i].k;
    return PMESH_OTHER;
}

/* Open dir/name and insist that the body holds one list (or two for
 * faceCompactList); *f is the parsed file. */
static ump_status open_list_file(const char *dir, const char *name, foam_file **f, ump_err *err)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    UMP_CALL(foam_file_read(path, f, err));
    if (!(*f)->body || (*f)->nbody == 0) {
        ump_status rc = UMP_FAIL(err, UMP_ERR_PARSE, "%s: expected a list (N ( ... )) after the header",
                                 (*f)->path);
        foam_file_free(f);
        return rc;
    }
    return UMP_OK;
}

static ump_status expect_end(foam_file *f, size_t pos, ump_err *err)
{
    if (pos != f->nbody) {
        char w[256], t[128];
        return UMP_FAIL(err, UMP_ERR_PARSE, "%s: unexpected %s after the list",
                        foam_tok_where(f->body, f->nbody, pos, f->path, w, sizeof w),
                        foam_tok_str(&f->body[pos], t, sizeof t));
    }
    return UMP_OK;
}

static ump_status read_points(pmesh *m, ump_err *err)
{
    foam_file *f = NULL;
    UMP_CALL(open_list_file(m->dir, "points", &f, err));
    size_t pos = 0, n = 0;
    ump_status rc = foam_tok_scalar_list(f->body, f->nbody, &pos, 3, &m->points, &n, "points", err);
    if (rc == UMP_OK)
        rc = expect_end(f, pos, err);
    if (rc == UMP_OK && n > (size_t)UMP_IDX_MAX)
        rc = UMP_FAIL(err, UMP_ERR_INPUT, "%s: too many points (%zu)", f->path, n);
    if (rc == UMP_OK)
        for (size_t i = 0; i < 3 * n; i++)
            if (!isfinite(m->points[i])) {
                rc = UMP_FAIL(err, UMP_ERR_INPUT, "%s: point %zu has a non-finite coordinate (%g)",
                              f->path, i / 3, m->points[i]);
                break;
            }
    m->npoints = (ump_idx)n;
    foam_file_free(&f);
    return rc;
}

static ump_status read_faces(pmesh *m, ump_err *err)
{
    foam_file *f = NULL;
    UMP_CALL(open_list_file(m->dir, "faces", &f, err));
    size_t pos = 0, n = 0;
    ump_status rc;
    if (strcmp(f->class_name, "faceCompactList") == 0) {
        /* offsets (nFaces+1, from 0) then the concatenated point labels */
        size_t noff = 0, nitem = 0;
        rc = foam_tok_label_list(f->body, f->nbody, &pos, &m->face_off, &noff, "faces offsets", err);
        if (rc == UMP_OK)
            rc = foam_tok_label_list(f->body, f->nbody, &pos, &m->face_pts, &nitem, "faces labels", err);
        if (rc == UMP_OK)
            rc = expect_end(f, pos, err);
        if (rc == UMP_OK && noff == 0)
            rc = UMP_FAIL(err, UMP_ERR_PARSE, "%s: faceCompactList has no offsets", f->path);
        if (rc == UMP_OK) {
            n = noff - 1;
            if (m->face_off[0] != 0 || (size_t)m->face_off[n] != nitem)
                rc = UMP_FAIL(err, UMP_ERR_INPUT,
                              "%s: faceCompactList offsets run from %ld to %ld but there are %zu labels",
                              f->path, (long)m->face_off[0], (long)m->face_off[n], nitem);
            for (size_t i = 0; rc == UMP_OK && i < n; i++)
                if (m->face_off[i + 1] < m->face_off[i])
                    rc = UMP_FAIL(err, UMP_ERR_INPUT, "%s: faceCompactList offsets decrease at face %zu",
                                  f->path, i);
        }
    } else {
        rc = foam_tok_labellist_list(f->body, f->nbody, &pos, &m->face_off, &m->face_pts, &n,
                                     "faces", err);
        if (rc == UMP_OK)
            rc = expect_end(f, pos, err);
    }
    if (rc == UMP_OK && n > (size_t)UMP_IDX_MAX)
        rc = UMP_FAIL(err, UMP_ERR_INPUT, "%s: too many faces (%zu)", f->path, n);
    m->nfaces = (ump_idx)n;
    foam_file_free(&f);
    return rc;
}

/* A label list file. *ncells_note receives nCells from the header's
 * note "nPoints:.. nCells:.. ..." (written by OpenFOAM in owner), else -1. */
static ump_status read_labels(const char *dir, const char *name, ump_idx **out, size_t *n,
                              long *ncells_note, ump_err *err)
{
    foam_file *f = NULL;
    UMP_CALL(open_list_file(dir, name, &f, err));
    size_t pos = 0;
    ump_status rc = foam_tok_label_list(f->body, f->nbody, &pos, out, n, name, err);
    if (rc == UMP_OK)
        rc = expect_end(f, pos, err);
    *ncells_note = -1;
    const foam_entry *e = f->header ? foam_dict_find(f->header, "note", 0) : NULL;
    if (e && e->ntok == 1 && e->tok[0].type == FOAM_TOK_STRING) {
        const char *c = strstr(e->tok[0].v.str, "nCells:");
        if (c)
            *ncells_note = strtol(c + 7, NULL, 10);
    }
    foam_file_free(&f);
    return rc;
}

/* inGroups N(w1 w2 ...) */
static ump_status read_groups(const foam_dict *d, pmesh_patch *p, const char *path, ump_err *err)
{
    const foam_entry *e = foam_dict_find(d, "inGroups", 0);
    if (!e)
        return UMP_OK;
    if (e->dict)
        return UMP_FAIL(err, UMP_ERR_PARSE, "%s:%d: inGroups of patch '%s' must be a list of words",
                        path, e->line, p->name);
    size_t i = 0;
    if (i < e->ntok && e->tok[i].type == FOAM_TOK_LABEL)
        i++;
    if (i >= e->ntok || e->tok[i].type != FOAM_TOK_PUNCT || e->tok[i].v.punct != '(')
        return UMP_FAIL(err, UMP_ERR_PARSE, "%s:%d: inGroups of patch '%s': expected '('",
                        path, e->line, p->name);
    size_t first = ++i;
    while (i < e->ntok && (e->tok[i].type == FOAM_TOK_WORD || e->tok[i].type == FOAM_TOK_STRING))
        i++;
    if (i >= e->ntok || e->tok[i].type != FOAM_TOK_PUNCT || e->tok[i].v.punct != ')')
        return UMP_FAIL(err, UMP_ERR_PARSE, "%s:%d: inGroups of patch '%s': expected words and ')'",
                        path, e->line, p->name);
    p->ngroups = (int)(i - first);
    p->groups = ump_alloc_array((size_t)p->ngroups, sizeof *p->groups);
    if (!p->groups)
        return UMP_FAIL(err, UMP_ERR_NOMEM, "%s: out of memory", path);
    for (int g = 0; g < p->ngroups; g++)
        if (!(p->groups[g] = ump_strdup(e->tok[first + (size_t)g].v.str)))
            return UMP_FAIL(err, UMP_ERR_NOMEM, "%s: out of memory", path);
    return UMP_OK;
}

static ump_status read_patch(const foam_dict *d, const char *name, pmesh_patch *p,
                             const char *path, ump_err *err)
{
    const char *type = NULL;
    int64_t nf = 0, sf = 0;
    p->nbr = -1;
    if (!(p->name = ump_strdup(name)))
        return UMP_FAIL(err, UMP_ERR_NOMEM, "%s: out of memory", path);
    UMP_CALL(foam_get_word(d, "type", &type, err));
    UMP_CALL(foam_get_label(d, "nFaces", &nf, err));
    UMP_CALL(foam_get_label(d, "startFace", &sf, err));
    const char *bad = nf < 0 || nf > UMP_IDX_MAX ? "nFaces" : sf < 0 || sf > UMP_IDX_MAX ? "startFace" : NULL;
    if (bad) {
        const foam_entry *e = foam_dict_find(d, bad, 0);
        return UMP_FAIL(err, UMP_ERR_INPUT, "%s:%d: patch '%s': %s %lld is out of range (0 to %d)",
                        path, e ? e->line : d->line, name, bad, (long long)(bad[0] == 'n' ? nf : sf),
                        UMP_IDX_MAX);
    }
    if (!(p->type = ump_strdup(type)))
        return UMP_FAIL(err, UMP_ERR_NOMEM, "%s: out of memory", path);
    p->kind = patch_kind(type);
    p->n = (ump_idx)nf;
    p->start = (ump_idx)sf;
    UMP_CALL(read_groups(d, p, path, err));
    if (p->kind == PMESH_CYCLIC) {
        const char *nbr = NULL, *tr = NULL;
        UMP_CALL(foam_get_word(d, "neighbourPatch", &nbr, err));
        UMP_CALL(foam_get_word_or(d, "transform", "unknown", &tr, err));
        if (!(p->neighbour_patch = ump_strdup(nbr)) || !(p->transform = ump_strdup(tr)))
            return UMP_FAIL(err, UMP_ERR_NOMEM, "%s: out of memory", path);
        if (foam_dict_find(d, "separationVector", 0)) {
            UMP_CALL(foam_get_vector(d, "separationVector", p->separation, err));
            p->has_separation = 1;
        }
    }
    return UMP_OK;
}

static ump_status read_boundary(pmesh *m, ump_err *err)
{
    foam_file *f = NULL;
    UMP_CALL(open_list_file(m->dir, "boundary", &f, err));
    const foam_token *t = f->body;
    size_t nt = f->nbody, pos = 0;
    char w[256], s[128];
    ump_status rc = UMP_OK;
    int64_t count = -1;
    if (t[pos].type == FOAM_TOK_LABEL)
        count = t[pos++].v.label;
    if (pos >= nt || t[pos].type != FOAM_TOK_PUNCT || t[pos].v.punct != '(') {
        rc = UMP_FAIL(err, UMP_ERR_PARSE, "%s: expected '(' to open the patch list, found %s",
                      foam_tok_where(t, nt, pos, f->path, w, sizeof w),
                      pos < nt ? foam_tok_str(&t[pos], s, sizeof s) : "end of file");
        goto done;
    }
    pos++;
    size_t first = pos;
    while (pos + 1 < nt && (t[pos].type == FOAM_TOK_WORD || t[pos].type == FOAM_TOK_STRING) &&
           t[pos + 1].type == FOAM_TOK_DICT)
        pos += 2;
    if (pos >= nt || t[pos].type != FOAM_TOK_PUNCT || t[pos].v.punct != ')') {
        rc = UMP_FAIL(err, UMP_ERR_PARSE, "%s: expected a patch 'name { ... }' or ')', found %s",
                      foam_tok_where(t, nt, pos, f->path, w, sizeof w),
                      pos < nt ? foam_tok_str(&t[pos], s, sizeof s) : "end of file");
        goto done;
    }
    size_t np = (pos - first) / 2;
    if (count >= 0 && (size_t)count != np) {
        rc = UMP_FAIL(err, UMP_ERR_PARSE, "%s: the list declares %lld patches but holds %zu",
                      f->path, (long long)count, np);
        goto done;
    }
    if ((rc = expect_end(f, pos + 1, err)) != UMP_OK)
        goto done;
    m->patch = ump_alloc_array(np, sizeof *m->patch);
    if (!m->patch) {
        rc = UMP_FAIL(err, UMP_ERR_NOMEM, "%s: out of memory", f->path);
        goto done;
    }
    m->npatches = (int)np;
    for (size_t i = 0; i < np && rc == UMP_OK; i++)
        rc = read_patch(t[first + 2 * i + 1].v.dict, t[first + 2 * i].v.str, &m->patch[i], f->path, err);
    for (int i = 0; i < m->npatches && rc == UMP_OK; i++) {
        pmesh_patch *p = &m->patch[i];
        for (int j = 0; j < i; j++)
            if (strcmp(m->patch[j].name, p->name) == 0)
                rc = UMP_FAIL(err, UMP_ERR_INPUT, "%s: patch name '%s' appears twice", f->path, p->name);
        if (rc == UMP_OK && p->kind == PMESH_CYCLIC) {
            p->nbr = pmesh_patch_index(m, p->neighbour_patch);
            if (p->nbr < 0 || p->nbr == i)
                rc = UMP_FAIL(err, UMP_ERR_INPUT, "%s: cyclic patch '%s' names neighbourPatch '%s', "
                              "which is not another patch", f->path, p->name, p->neighbour_patch);
        }
    }
done:
    foam_file_free(&f);
    return rc;
}

/* Newell area vector of face f (|A| = area, right-hand rule). */
static void face_area(const pmesh *m, ump_idx f, double A[3])
{
    A[0] = A[1] = A[2] = 0.0;
    ump_idx b = m->face_off[f], e = m->face_off[f + 1];
    for (ump_idx i = b; i < e; i++) {
        const double *p = m->points + 3 * (size_t)m->face_pts[i];
        const double *q = m->points + 3 * (size_t)m->face_pts[i + 1 < e ? i + 1 : b];
        A[0] += 0.5 * (p[1] - q[1]) * (p[2] + q[2]);
        A[1] += 0.5 * (p[2] - q[2]) * (p[0] + q[0]);
        A[2] += 0.5 * (p[0] - q[0]) * (p[1] + q[1]);
    }
}

/* Per-face point labels (range, repeats: OpenFOAM's checkFaceVertices). */
static ump_status check_face_vertices(const pmesh *m, ump_err *err)
{
    const char *d = m->dir;
    for (ump_idx f = 0; f < m->nfaces; f++) {
        ump_idx b = m->face_off[f], n = m->face_off[f + 1] - b;
        if (n < 3)
            return UMP_FAIL(err, UMP_ERR_INPUT, "%s/faces: face %ld has %ld points (at least 3 needed)",
                            d, (long)f, (long)n);
        for (ump_idx i = b; i < b + n; i++) {
            if (m->face_pts[i] < 0 || m->face_pts[i] >= m->npoints)
                return UMP_FAIL(err, UMP_ERR_INPUT,
                                "%s/faces: face %ld uses point %ld, but points has %ld entries "
                                "(checkMesh: Faces with invalid vertex labels)",
                                d, (long)f, (long)m->face_pts[i], (long)m->npoints);
            /* faces are short (3-8 points, a few dozen for polyhedra): quadratic is fine
             * up to 64 points; longer faces are checked against a sorted copy below */
            for (ump_idx j = b; n <= 64 && j < i; j++)
                if (m->face_pts[j] == m->face_pts[i])
                    return UMP_FAIL(err, UMP_ERR_INPUT,
                                    "%s/faces: face %ld uses point %ld twice (checkMesh: Faces with "
                                    "invalid vertex labels)", d, (long)f, (long)m->face_pts[i]);
        }
    }
    return UMP_OK;
}

static int cmp_idx(const void *a, const void *b)
{
    ump_idx x = *(const ump_idx *)a, y = *(const ump_idx *)b;
    return (x > y) - (x < y);
}

/* Sorted copy of the point labels of every face (same CSR offsets). */
static ump_idx *sorted_faces(const pmesh *m)
{
    size_t n = (size_t)m->face_off[m->nfaces];
    ump_idx *s = ump_alloc_array(n ? n : 1, sizeof *s);
    if (!s)
        return NULL;
    if (n)
        memcpy(s, m->face_pts, n * sizeof *s);
    for (ump_idx f = 0; f < m->nfaces; f++) {
        ump_idx b = m->face_off[f], k = m->face_off[f + 1] - b;
        if (k <= 16) {
            for (ump_idx i = b + 1; i < b + k; i++) {
                ump_idx v = s[i], j = i;
                for (; j > b && s[j - 1] > v; j--)
                    s[j] = s[j - 1];
                s[j] = v;
            }
        } else {
            qsort(s + b, (size_t)k, sizeof *s, cmp_idx);
        }
    }
    return s;
}

static int same_face(const pmesh *m, const ump_idx *s, ump_idx f, ump_idx g)
{
    ump_idx nf = m->face_off[f + 1] - m->face_off[f];
    if (m->face_off[g + 1] - m->face_off[g] != nf)
        return 0;
    return memcmp(s + m->face_off[f], s + m->face_off[g], (size_t)nf * sizeof *s) == 0;
}

/* Long faces' repeated points, then duplicate faces (the same point set:
 * OpenFOAM's checkFaceFaces), by a hash of the sorted labels. */
static ump_status check_duplicate_faces(const pmesh *m, ump_err *err)
{
    const char *d = m->dir;
    ump_idx *s = sorted_faces(m);
    size_t cap = 16;
    while (cap < 2 * (size_t)m->nfaces)
        cap *= 2;
    ump_idx *tab = s ? ump_alloc_array(cap, sizeof *tab) : NULL;
    if (!tab) {
        free(s);
        return UMP_FAIL(err, UMP_ERR_NOMEM, "%s: out of memory checking the faces", d);
    }
    ump_status rc = UMP_OK;
    for (ump_idx f = 0; f < m->nfaces && rc == UMP_OK; f++) {
        ump_idx b = m->face_off[f], e = m->face_off[f + 1];
        uint64_t h = 1469598103934665603ull;
        for (ump_idx i = b; i < e; i++) {
            if (i > b && s[i] == s[i - 1]) {
                rc = UMP_FAIL(err, UMP_ERR_INPUT, "%s/faces: face %ld uses point %ld twice (checkMesh: "
                              "Faces with invalid vertex labels)", d, (long)f, (long)s[i]);
                break;
            }
            h = (h ^ (uint64_t)(uint32_t)s[i]) * 1099511628211ull;
        }
        if (rc != UMP_OK)
            break;
        size_t k = (size_t)(h ^ (h >> 29)) & (cap - 1);
        for (; tab[k]; k = (k + 1) & (cap - 1)) {
            ump_idx g = tab[k] - 1;
            if (!same_face(m, s, f, g))
                continue;
            int bf = f >= m->ninternal, bg = g >= m->ninternal;
            rc = UMP_FAIL(err, UMP_ERR_INPUT,
                          "%s/faces: faces %ld and %ld have the same %ld points: duplicate faces "
                          "(owners %ld and %ld%s; checkMesh -allTopology: duplicate faces)",
                          d, (long)g, (long)f, (long)(e - b), (long)m->owner[g], (long)m->owner[f],
                          bf && bg && m->owner[f] != m->owner[g]
                              ? ": two boundary faces in one place, a baffle, which is not supported"
                              : "");
            break;
        }
        if (rc == UMP_OK)
            tab[k] = f + 1;
    }
    free(tab);
    free(s);
    return rc;
}

/* Cell -> faces (CSR) into *off [ncells+1], *cf. */
static ump_status cell_faces(const pmesh *m, ump_idx **off, ump_idx **cf, ump_err *err)
{
    *off = ump_alloc_array((size_t)m->ncells + 1, sizeof **off);
    *cf = ump_alloc_array((size_t)m->nfaces + (size_t)m->ninternal + 1, sizeof **cf);
    ump_idx *fill = ump_alloc_array((size_t)m->ncells, sizeof *fill);
    if (!*off || !*cf || !fill) {
        free(fill);
        return UMP_FAIL(err, UMP_ERR_NOMEM, "%s: out of memory", m->dir);
    }
    ump_idx *o = *off;
    for (ump_idx f = 0; f < m->nfaces; f++) {
        o[m->owner[f] + 1]++;
        if (f < m->ninternal)
            o[m->neighbour[f] + 1]++;
    }
    for (ump_idx c = 0; c < m->ncells; c++)
        o[c + 1] += o[c];
    for (ump_idx f = 0; f < m->nfaces; f++) {
        (*cf)[o[m->owner[f]] + fill[m->owner[f]]++] = f;
        if (f < m->ninternal)
            (*cf)[o[m->neighbour[f]] + fill[m->neighbour[f]]++] = f;
    }
    free(fill);
    return UMP_OK;
}

/* Every cell closed: each of its edges used by exactly two of its faces
 * (checkMesh -allTopology: checkCellsZipUp), and the sum of its outward face
 * area vectors zero relative to their total (checkClosedCells, threshold
 * 1e-6: a face the wrong way round passes the first test, not this one). */
static ump_status check_closed_cells(const pmesh *m, const ump_idx *off, const ump_idx *cf, ump_err *err)
{
    const char *d = m->dir;
    size_t cap = 64;
    ump_idx (*edge)[3] = ump_alloc_array(cap, sizeof *edge);
    if (!edge)
        return UMP_FAIL(err, UMP_ERR_NOMEM, "%s: out of memory", d);
    ump_status rc = UMP_OK;
    for (ump_idx c = 0; c < m->ncells && rc == UMP_OK; c++) {
        if (off[c + 1] - off[c] < 4) {
            rc = UMP_FAIL(err, UMP_ERR_INPUT, "%s/owner: cell %ld has only %ld faces (checkMesh: Cells "
                          "with fewer than 4 faces)", d, (long)c, (long)(off[c + 1] - off[c]));
            break;
        }
        size_t ne = 0;
        double S[3] = {0, 0, 0}, mag = 0;
        for (ump_idx k = off[c]; k < off[c + 1] && rc == UMP_OK; k++) {
            ump_idx f = cf[k], b = m->face_off[f], e = m->face_off[f + 1];
            double A[3], sg = m->owner[f] == c ? 1.0 : -1.0;
            face_area(m, f, A);
            for (int q = 0; q < 3; q++)
                S[q] += sg * A[q];
            mag += sqrt(A[0] * A[0] + A[1] * A[1] + A[2] * A[2]);
            for (ump_idx i = b; i < e; i++) {
                ump_idx p = m->face_pts[i], q = m->face_pts[i + 1 < e ? i + 1 : b];
                ump_idx lo = UMP_MIN(p, q), hi = UMP_MAX(p, q);
                size_t j = 0;
                while (j < ne && !(edge[j][0] == lo && edge[j][1] == hi))
                    j++;
                if (j == ne) {
                    if (ne == cap) {
                        ump_idx (*ng)[3] = ump_realloc_array(edge, cap * 2, sizeof *edge);
                        if (!ng) {
                            rc = UMP_FAIL(err, UMP_ERR_NOMEM, "%s: out of memory", d);
                            break;
                        }
                        edge = ng;
                        cap *= 2;
                    }
                    edge[ne][0] = lo;
                    edge[ne][1] = hi;
                    edge[ne][2] = 0;
                    ne++;
                }
                edge[j][2]++;
            }
        }
        for (size_t j = 0; j < ne && rc == UMP_OK; j++)
            if (edge[j][2] != 2)
                rc = UMP_FAIL(err, UMP_ERR_INPUT,
                              "%s/owner: cell %ld is open: its edge (%ld %ld) is used by %ld of its faces, "
                              "not 2 (checkMesh -allTopology: Open cells found, not zipped up)",
                              d, (long)c, (long)edge[j][0], (long)edge[j][1], (long)edge[j][2]);
        if (rc != UMP_OK)
            break;
        double open = fmax(fabs(S[0]), fmax(fabs(S[1]), fabs(S[2]))) / (mag > 0 ? mag : 1.0);
        if (!(open <= 1e-6))
            rc = UMP_FAIL(err, UMP_ERR_INPUT,
                          "%s/faces: cell %ld is open: the sum of its outward face area vectors is %.3g "
                          "of their total area (checkMesh: Open cells found, openness threshold 1e-6; a "
                          "face the wrong way round, or owner/neighbour swapped?)", d, (long)c, open);
    }
    free(edge);
    return rc;
}

ump_status pmesh_check(const pmesh *m, ump_err *err)
{
    const char *d = m->dir;
    UMP_CALL(check_face_vertices(m, err));
    if (m->ncells <= 0)
        return UMP_FAIL(err, UMP_ERR_INPUT, "%s/owner: the mesh has no cells", d);
    for (ump_idx f = 0; f < m->nfaces; f++)
        if (m->owner[f] < 0 || m->owner[f] >= m->ncells)
            return UMP_FAIL(err, UMP_ERR_INPUT, "%s/owner: face %ld has owner %ld (the mesh has %ld cells)",
                            d, (long)f, (long)m->owner[f], (long)m->ncells);
    for (ump_idx f = 0; f < m->ninternal; f++) {
        if (m->neighbour[f] < 0 || m->neighbour[f] >= m->ncells)
            return UMP_FAIL(err, UMP_ERR_INPUT, "%s/neighbour: face %ld has neighbour %ld (the mesh has "
                            "%ld cells)", d, (long)f, (long)m->neighbour[f], (long)m->ncells);
        if (m->neighbour[f] <= m->owner[f])
            return UMP_FAIL(err, UMP_ERR_INPUT,
                            "%s/neighbour: internal face %ld has neighbour %ld not greater than its owner %ld",
                            d, (long)f, (long)m->neighbour[f], (long)m->owner[f]);
    }
    int64_t next = m->ninternal;
    for (int i = 0; i < m->npatches; i++) {
        const pmesh_patch *p = &m->patch[i];
        if (p->start != next)
            return UMP_FAIL(err, UMP_ERR_INPUT,
                            "%s/boundary: patch '%s' starts at face %ld, expected %lld (patches must follow "
                            "the internal faces and each other)", d, p->name, (long)p->start, (long long)next);
        if ((int64_t)p->n > (int64_t)m->nfaces - next)
            return UMP_FAIL(err, UMP_ERR_INPUT,
                            "%s/boundary: patch '%s' has startFace %ld and nFaces %ld, beyond the %ld faces "
                            "of the mesh", d, p->name, (long)p->start, (long)p->n, (long)m->nfaces);
        next += p->n;
    }
    if (next != m->nfaces)
        return UMP_FAIL(err, UMP_ERR_INPUT,
                        "%s/boundary: patches end at face %lld but the mesh has %ld faces", d, (long long)next,
                        (long)m->nfaces);
    /* the two topology checks are independent: concurrently on two threads;
     * a duplicate face is reported first, as when serial */
    ump_status rd = UMP_OK, rcl = UMP_OK;
    ump_err ed, ecl;
#pragma omp parallel sections num_threads(2) if (omp_get_max_threads() > 1)
    {
#pragma omp section
        rd = check_duplicate_faces(m, &ed);
#pragma omp section
        {
            ump_idx *off = NULL, *cf = NULL;
            rcl = cell_faces(m, &off, &cf, &ecl);
            if (rcl == UMP_OK)
                rcl = check_closed_cells(m, off, cf, &ecl);
            free(off);
            free(cf);
        }
    }
    if (rd != UMP_OK || rcl != UMP_OK) {
        if (err)
            *err = rd != UMP_OK ? ed : ecl;
        return rd != UMP_OK ? rd : rcl;
    }
    return UMP_OK;
}

ump_status pmesh_read(const char *dir, pmesh **out, ump_err *err)
{
    *out = NULL;
    pmesh *m = ump_alloc_array(1, sizeof *m);
    if (!m || !(m->dir = ump_strdup(dir))) {
        free(m);
        return UMP_FAIL(err, UMP_ERR_NOMEM, "%s: out of memory", dir);
    }
    ump_status rc;
    size_t nown = 0, nnei = 0;
    long note_cells = -1, unused = -1;
    /* The four list files are independent: read them concurrently (faces,
     * the largest, first), then report the first failure in the order
     * points, faces, owner, neighbour -- the message a serial read gives. */
    ump_status r[4] = {UMP_OK, UMP_OK, UMP_OK, UMP_OK};
    ump_err e[4];
#pragma omp parallel sections num_threads(2) if (omp_get_max_threads() > 1)
    {
#pragma omp section
        r[1] = read_faces(m, &e[1]);
#pragma omp section
        {
            r[0] = read_points(m, &e[0]);
            r[2] = read_labels(dir, "owner", &m->owner, &nown, &note_cells, &e[2]);
            r[3] = read_labels(dir, "neighbour", &m->neighbour, &nnei, &unused, &e[3]);
        }
    }
    for (int k = 0; k < 4; k++)
        if (r[k] != UMP_OK) {
            if (err)
                *err = e[k];
            rc = r[k];
            goto fail;
        }
    if ((rc = read_boundary(m, err)) != UMP_OK)
        goto fail;
    if (nown != (size_t)m->nfaces) {
        rc = UMP_FAIL(err, UMP_ERR_INPUT, "%s/owner: %zu entries, but faces has %ld faces",
                      dir, nown, (long)m->nfaces);
        goto fail;
    }
    if (nnei > nown) {
        rc = UMP_FAIL(err, UMP_ERR_INPUT, "%s/neighbour: %zu entries, more than the %zu faces",
                      dir, nnei, nown);
        goto fail;
    }
    m->ninternal = (ump_idx)nnei;
    ump_idx maxc = -1, fmaxc = -1;
    for (ump_idx f = 0; f < m->nfaces; f++)
        if (m->owner[f] > maxc) {
            maxc = m->owner[f];
            fmaxc = f;
        }
    int from_nbr = 0;
    for (ump_idx f = 0; f < m->ninternal; f++)
        if (m->neighbour[f] > maxc) {
            maxc = m->neighbour[f];
            fmaxc = f;
            from_nbr = 1;
        }
    /* a closed cell has at least 4 faces and a face bounds at most 2 cells:
     * more than nFaces/2 cells means a label out of range (refused before
     * anything is allocated per cell) */
    if ((int64_t)maxc + 1 > (int64_t)m->nfaces / 2) {
        rc = UMP_FAIL(err, UMP_ERR_INPUT, "%s/%s: face %ld has %s %ld: out of range (%ld faces close at "
                      "most %ld cells)", dir, from_nbr ? "neighbour" : "owner", (long)fmaxc,
                      from_nbr ? "neighbour" : "owner", (long)maxc, (long)m->nfaces, (long)(m->nfaces / 2));
        goto fail;
    }
    m->ncells = maxc + 1;
    if (note_cells >= 0 && m->ncells > note_cells) {
        /* the header says how many cells there are: name the first offender */
        for (ump_idx f = 0; f < m->nfaces; f++)
            if (m->owner[f] >= note_cells) {
                rc = UMP_FAIL(err, UMP_ERR_INPUT, "%s/owner: face %ld has owner %ld, but the mesh has "
                              "%ld cells (header note)", dir, (long)f, (long)m->owner[f], note_cells);
                goto fail;
            }
        for (ump_idx f = 0; f < m->ninternal; f++)
            if (m->neighbour[f] >= note_cells) {
                rc = UMP_FAIL(err, UMP_ERR_INPUT, "%s/neighbour: face %ld has neighbour %ld, but the "
                              "mesh has %ld cells (owner header note)", dir, (long)f,
                              (long)m->neighbour[f], note_cells);
                goto fail;
            }
    }
    if ((rc = pmesh_check(m, err)) != UMP_OK)
        goto fail;
    *out = m;
    return UMP_OK;
fail:
    pmesh_free(&m);
    return rc;
}
