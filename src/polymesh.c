/* SPDX-License-Identifier: GPL-3.0-or-later
 * polymesh.c -- reads an OpenFOAM constant/polyMesh directory.
 *
 * Files (each plain or .gz, ascii or binary, through foam.h): points
 * (vectorField), faces (faceList or faceCompactList), owner and neighbour
 * (labelList), boundary (polyBoundaryMesh: a list of "name { dict }").
 * The number of cells is 1 + the largest owner/neighbour label, as OpenFOAM
 * computes it. pmesh_check() then verifies the topology so that later
 * stages can index without bounds checks.
 */
#include "umppm/polymesh.h"
#include "umppm/foam.h"

#include <math.h>
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
    if (nf < 0 || sf < 0 || nf > UMP_IDX_MAX || sf > UMP_IDX_MAX)
        return UMP_FAIL(err, UMP_ERR_INPUT, "%s:%d: patch '%s' has nFaces %lld startFace %lld",
                        path, d->line, name, (long long)nf, (long long)sf);
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

ump_status pmesh_check(const pmesh *m, ump_err *err)
{
    const char *d = m->dir;
    for (ump_idx f = 0; f < m->nfaces; f++) {
        ump_idx n = m->face_off[f + 1] - m->face_off[f];
        if (n < 3)
            return UMP_FAIL(err, UMP_ERR_INPUT, "%s/faces: face %ld has %ld points (at least 3 needed)",
                            d, (long)f, (long)n);
        for (ump_idx i = m->face_off[f]; i < m->face_off[f + 1]; i++)
            if (m->face_pts[i] < 0 || m->face_pts[i] >= m->npoints)
                return UMP_FAIL(err, UMP_ERR_INPUT,
                                "%s/faces: face %ld uses point %ld, but points has %ld entries",
                                d, (long)f, (long)m->face_pts[i], (long)m->npoints);
    }
    if (m->ncells <= 0)
        return UMP_FAIL(err, UMP_ERR_INPUT, "%s/owner: the mesh has no cells", d);
    for (ump_idx f = 0; f < m->nfaces; f++)
        if (m->owner[f] < 0)
            return UMP_FAIL(err, UMP_ERR_INPUT, "%s/owner: face %ld has owner %ld", d, (long)f,
                            (long)m->owner[f]);
    for (ump_idx f = 0; f < m->ninternal; f++) {
        if (m->neighbour[f] < 0)
            return UMP_FAIL(err, UMP_ERR_INPUT, "%s/neighbour: face %ld has neighbour %ld", d,
                            (long)f, (long)m->neighbour[f]);
        if (m->neighbour[f] <= m->owner[f])
            return UMP_FAIL(err, UMP_ERR_INPUT,
                            "%s/neighbour: internal face %ld has neighbour %ld not greater than its owner %ld",
                            d, (long)f, (long)m->neighbour[f], (long)m->owner[f]);
    }
    ump_idx next = m->ninternal;
    for (int i = 0; i < m->npatches; i++) {
        const pmesh_patch *p = &m->patch[i];
        if (p->start != next)
            return UMP_FAIL(err, UMP_ERR_INPUT,
                            "%s/boundary: patch '%s' starts at face %ld, expected %ld (patches must follow "
                            "the internal faces and each other)", d, p->name, (long)p->start, (long)next);
        next += p->n;
    }
    if (next != m->nfaces)
        return UMP_FAIL(err, UMP_ERR_INPUT,
                        "%s/boundary: patches end at face %ld but the mesh has %ld faces", d, (long)next,
                        (long)m->nfaces);
    /* every cell must have at least 4 faces to be closed in 3-D */
    ump_idx *nfc = ump_alloc_array((size_t)m->ncells, sizeof *nfc);
    if (!nfc)
        return UMP_FAIL(err, UMP_ERR_NOMEM, "%s: out of memory", d);
    for (ump_idx f = 0; f < m->nfaces; f++) {
        nfc[m->owner[f]]++;
        if (f < m->ninternal)
            nfc[m->neighbour[f]]++;
    }
    for (ump_idx c = 0; c < m->ncells; c++)
        if (nfc[c] < 4) {
            ump_idx k = nfc[c];
            free(nfc);
            return UMP_FAIL(err, UMP_ERR_INPUT, "%s/owner: cell %ld has only %ld faces", d, (long)c, (long)k);
        }
    free(nfc);
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
    if ((rc = read_points(m, err)) != UMP_OK || (rc = read_faces(m, err)) != UMP_OK ||
        (rc = read_labels(dir, "owner", &m->owner, &nown, &note_cells, err)) != UMP_OK ||
        (rc = read_labels(dir, "neighbour", &m->neighbour, &nnei, &unused, err)) != UMP_OK ||
        (rc = read_boundary(m, err)) != UMP_OK)
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
    ump_idx maxc = -1;
    for (ump_idx f = 0; f < m->nfaces; f++)
        maxc = UMP_MAX(maxc, m->owner[f]);
    for (ump_idx f = 0; f < m->ninternal; f++)
        maxc = UMP_MAX(maxc, m->neighbour[f]);
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
