/* SPDX-License-Identifier: GPL-3.0-or-later
 * field.c -- cell-centred fields with OpenFOAM boundary conditions, in
 * memory: creation, deep copy, release, and the boundary-type words.
 */
#include "umppm/field.h"

#include <stdlib.h>
#include <string.h>

/* Indexed by fld_bc_type: the words OpenFOAM v1912 uses in field files. */
static const char *const bc_names[FLD_BC_NTYPES] = {
    [FLD_BC_CALCULATED] = "calculated",
    [FLD_BC_FIXEDVALUE] = "fixedValue",
    [FLD_BC_NOSLIP] = "noSlip",
    [FLD_BC_MOVINGWALLVELOCITY] = "movingWallVelocity",
    [FLD_BC_ZEROGRADIENT] = "zeroGradient",
    [FLD_BC_EMPTY] = "empty",
    [FLD_BC_CYCLIC] = "cyclic",
    [FLD_BC_SYMMETRYPLANE] = "symmetryPlane",
    [FLD_BC_SYMMETRY] = "symmetry",
    [FLD_BC_FIXEDFLUXPRESSURE] = "fixedFluxPressure",
    [FLD_BC_INLETOUTLET] = "inletOutlet",
    [FLD_BC_SLIP] = "slip",
    [FLD_BC_UNIFORMFIXEDVALUE] = "uniformFixedValue",
    [FLD_BC_FLOWRATEINLETVELOCITY] = "flowRateInletVelocity",
    [FLD_BC_OUTLETINLET] = "outletInlet",
    [FLD_BC_TOTALPRESSURE] = "totalPressure",
    [FLD_BC_PRESSUREINLETOUTLETVELOCITY] = "pressureInletOutletVelocity",
};

const char *fld_bc_name(fld_bc_type t)
{
    if ((int)t < 0 || t >= FLD_BC_NTYPES)
        return "unknown";
    return bc_names[t];
}

int fld_bc_parse(const char *word)
{
    if (!word)
        return -1;
    for (int t = 0; t < FLD_BC_NTYPES; t++)
        if (strcmp(word, bc_names[t]) == 0)
            return t;
    return -1;
}

int fld_bc_is_fixed(fld_bc_type t)
{
    return t == FLD_BC_FIXEDVALUE || t == FLD_BC_NOSLIP || t == FLD_BC_MOVINGWALLVELOCITY ||
           t == FLD_BC_UNIFORMFIXEDVALUE || t == FLD_BC_FLOWRATEINLETVELOCITY || t == FLD_BC_TOTALPRESSURE;
}

int fld_bc_eval(const fld_patch *p, int ncomp, double t, const double *nrm, double area, double *out)
{
    size_t nc = (size_t)ncomp;
    double v[3] = {0, 0, 0};
    if (!p->fn)
        return 0;
    if (p->type == FLD_BC_UNIFORMFIXEDVALUE) {
        /* uniformFixedValueFvPatchField::updateCoeffs: uniformValue at the
         * time of the step */
        f1_value(p->fn, t, v);
        for (ump_idx i = 0; i < p->n; i++)
            memcpy(out + (size_t)i * nc, v, nc * sizeof *out);
        return 1;
    }
    if (p->type == FLD_BC_FLOWRATEINLETVELOCITY && ncomp == 3) {
        /* flowRateInletVelocityFvPatchVectorField::updateValues, volumetric:
         * avgU = -Q/gSum(magSf), U = n avgU (n outward: into the domain for
         * Q > 0) */
        double q;
        f1_value(p->fn, t, &q);
        double avg = -q / area;
        for (ump_idx i = 0; i < p->n; i++)
            for (int k = 0; k < 3; k++)
                out[3 * (size_t)i + (size_t)k] = avg * nrm[3 * (size_t)i + (size_t)k];
        return 1;
    }
    return 0;
}

static void free_patch(fld_patch *p)
{
    free(p->value);
    free(p->aux);
    f1_free(&p->fn);
    for (int i = 0; i < p->nextra; i++) {
        free(p->extra[i].key);
        free(p->extra[i].text);
    }
    free(p->extra);
    memset(p, 0, sizeof *p);
}

void fld_free(fld_field **f)
{
    if (!f || !*f)
        return;
    fld_field *g = *f;
    free(g->name);
    free(g->internal);
    if (g->patch)
        for (int i = 0; i < g->npatches; i++)
            free_patch(&g->patch[i]);
    free(g->patch);
    free(g);
    *f = NULL;
}

ump_status fld_create(const char *name, int ncomp, ump_idx ncells, int npatches,
                      const ump_idx *patch_sizes, fld_field **out, ump_err *err)
{
    UMP_CHECK(out, err, UMP_ERR_INPUT, "fld_create: no output pointer");
    *out = NULL;
    UMP_CHECK(name && *name, err, UMP_ERR_INPUT, "fld_create: field without a name");
    UMP_CHECK(ncomp == 1 || ncomp == 3, err, UMP_ERR_INPUT,
              "field %s: %d components (expected 1 or 3)", name, ncomp);
    UMP_CHECK(ncells >= 0, err, UMP_ERR_INPUT, "field %s: negative cell count %ld",
              name, (long)ncells);
    UMP_CHECK(npatches >= 0 && (npatches == 0 || patch_sizes), err, UMP_ERR_INPUT,
              "field %s: %d patches without sizes", name, npatches);
    for (int i = 0; i < npatches; i++)
        UMP_CHECK(patch_sizes[i] >= 0, err, UMP_ERR_INPUT,
                  "field %s: patch %d has negative size %ld", name, i,
                  (long)patch_sizes[i]);

    fld_field *f = ump_alloc_array(1, sizeof *f);
    if (!f)
        return UMP_FAIL(err, UMP_ERR_NOMEM, "field %s: out of memory", name);
    f->ncomp = ncomp;
    f->ncells = ncells;
    f->npatches = npatches;
    f->name = ump_strdup(name);
    f->internal = ump_alloc_array((size_t)ncells, (size_t)ncomp * sizeof(double));
    f->patch = ump_alloc_array((size_t)npatches, sizeof *f->patch);
    if (!f->name || !f->internal || !f->patch) {
        fld_free(&f);
        return UMP_FAIL(err, UMP_ERR_NOMEM, "field %s: out of memory", name);
    }
    for (int i = 0; i < npatches; i++) {
        fld_patch *p = &f->patch[i];
        p->type = FLD_BC_CALCULATED;
        p->n = patch_sizes[i];
        /* calculated patches carry values, so allocate even when n == 0
         * to keep "value never NULL" simple for callers */
        p->value = ump_alloc_array((size_t)p->n, (size_t)ncomp * sizeof(double));
        if (!p->value) {
            fld_free(&f);
            return UMP_FAIL(err, UMP_ERR_NOMEM, "field %s: out of memory", name);
        }
    }
    *out = f;
    return UMP_OK;
}

/* Copy of n doubles, or NULL when src is NULL (aux is optional). *ok = 0 on
 * allocation failure. */
static double *dup_doubles(const double *src, size_t n, int *ok)
{
    if (!src)
        return NULL;
    double *d = ump_alloc_array(n, sizeof(double));
    if (!d) {
        *ok = 0;
        return NULL;
    }
    if (n)
        memcpy(d, src, n * sizeof(double));
    return d;
}

ump_status fld_copy(const fld_field *src, fld_field **out, ump_err *err)
{
    UMP_CHECK(out, err, UMP_ERR_INPUT, "fld_copy: no output pointer");
    *out = NULL;
    UMP_CHECK(src, err, UMP_ERR_INPUT, "fld_copy: no source field");

    fld_field *f = ump_alloc_array(1, sizeof *f);
    if (!f)
        return UMP_FAIL(err, UMP_ERR_NOMEM, "field %s: out of memory", src->name);
    int ok = 1;
    f->ncomp = src->ncomp;
    memcpy(f->dims, src->dims, sizeof f->dims);
    f->ncells = src->ncells;
    f->name = src->name ? ump_strdup(src->name) : NULL;
    if (src->name && !f->name)
        ok = 0;
    f->internal = dup_doubles(src->internal, (size_t)src->ncells * (size_t)src->ncomp, &ok);
    f->patch = ump_alloc_array((size_t)src->npatches, sizeof *f->patch);
    if (!f->patch)
        ok = 0;
    else
        f->npatches = src->npatches;
    for (int i = 0; ok && i < src->npatches; i++) {
        const fld_patch *s = &src->patch[i];
        fld_patch *d = &f->patch[i];
        size_t nv = (size_t)s->n * (size_t)src->ncomp;
        d->type = s->type;
        d->n = s->n;
        d->value_given = s->value_given;
        d->value = dup_doubles(s->value, nv, &ok);
        d->aux = dup_doubles(s->aux, nv, &ok);
        if (ok && s->fn) {
            ump_err e;
            if (f1_copy(s->fn, &d->fn, &e) != UMP_OK)
                ok = 0;
        }
        if (s->nextra > 0) {
            d->extra = ump_alloc_array((size_t)s->nextra, sizeof *d->extra);
            if (!d->extra) {
                ok = 0;
                break;
            }
            d->nextra = s->nextra;
            for (int k = 0; k < s->nextra; k++) {
                d->extra[k].key = ump_strdup(s->extra[k].key ? s->extra[k].key : "");
                d->extra[k].text = ump_strdup(s->extra[k].text ? s->extra[k].text : "");
                if (!d->extra[k].key || !d->extra[k].text)
                    ok = 0;
            }
        }
    }
    if (!ok) {
        fld_free(&f);
        return UMP_FAIL(err, UMP_ERR_NOMEM, "field %s: out of memory", src->name);
    }
    *out = f;
    return UMP_OK;
}

const char *fld_bc_aux_key(fld_bc_type t)
{
    switch (t) {
    case FLD_BC_INLETOUTLET: return "inletValue";
    case FLD_BC_FIXEDFLUXPRESSURE: return "gradient";
    case FLD_BC_OUTLETINLET: return "outletValue";
    case FLD_BC_TOTALPRESSURE: return "p0";
    case FLD_BC_PRESSUREINLETOUTLETVELOCITY: return "tangentialVelocity";
    default: return NULL;
    }
}
