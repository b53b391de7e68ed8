/* SPDX-License-Identifier: GPL-3.0-or-later
 * function1.h -- OpenFOAM v1912's Function1: a value of time, scalar or
 * vector (module prefix f1_). Used by the boundary conditions
 * uniformFixedValue (uniformValue) and flowRateInletVelocity
 * (volumetricFlowRate); docs/METHOD.md section 5 and the README's
 * boundary-condition table.
 *
 * Reading (f1_read) follows v1912's Function1::New, checked against the
 * installed v1912 binaries:
 *   key 1.5;  key (1 0 0);             bare value: constant
 *   key constant 1.5;  key uniform 1.5;  constant (v1912's "uniform" is
 *                                       the same type)
 *   key table ((t0 v0) (t1 v1) ...);   also N((...)...), as OpenFOAM
 *                                       writes it; v a number or (x y z)
 *   key sine;  key square;             coefficients from the sub-dictionary
 *                                       <key>Coeffs when present, else from
 *                                       the dictionary holding key itself
 *   key { type sine; ... }             the dictionary form (sine, square;
 *                                       v1912 cannot read constant or table
 *                                       this way: refused with the form to use)
 * Coefficients (v1912 Sine.C/Square.C): t0 (default 0), amplitude and
 * frequency (scalar Function1s), scale and level (Function1s of the
 * value's type), square's markSpace (default 1). Table: outOfBounds clamp
 * (default) or repeat, interpolationScheme linear (the default, the only
 * one). Anything else -- other Function1 types (polynomial, csvFile, ...),
 * outOfBounds error/warn, other interpolation schemes, the OpenFOAM
 * Foundation's key `start` (which v1912 ignores: its key is t0) -- is
 * refused by name, "<file>:<line>: <what>: ...".
 *
 * Values (f1_value), t the time:
 *   constant  v
 *   table     linear interpolation between the rows around t; outside the
 *             rows clamp: the first/last value; repeat: t mapped into
 *             [t_first, t_last] by fmod(t - t_first, span) + t_first
 *   sine      amplitude(t) sin(2 pi frequency(t) (t - t0)) scale(t) + level(t)
 *   square    amplitude(t) s scale(t) + level(t), s = +1 when the fraction
 *             of frequency(t) (t - t0) (C modf: negative before t0) is below
 *             markSpace/(1 + markSpace), else -1
 * A Function1 is built once (reading) and evaluated without allocating.
 */
#ifndef UMPPM_FUNCTION1_H
#define UMPPM_FUNCTION1_H

#include "umppm/foam.h"
#include "umppm/ump.h"

typedef enum f1_kind { F1_CONSTANT, F1_TABLE, F1_SINE, F1_SQUARE } f1_kind;

typedef enum f1_bounds { F1_CLAMP, F1_REPEAT } f1_bounds;

typedef struct f1 {
    f1_kind kind;
    int ncomp;                /* 1 (scalar) or 3 (vector) */
    double value[3];          /* constant: the value (ncomp used) */
    size_t n;                 /* table: rows (>= 1) */
    double *t;                /* table: [n] strictly increasing times */
    double *v;                /* table: [n*ncomp] values */
    f1_bounds bounds;         /* table: outOfBounds */
    double t0;                /* sine, square: time origin */
    double mark_space;        /* square: mark/space ratio (default 1) */
    struct f1 *amplitude;     /* sine, square: scalar Function1 */
    struct f1 *frequency;     /* sine, square: scalar Function1 [1/s] */
    struct f1 *scale;         /* sine, square: ncomp Function1 */
    struct f1 *level;         /* sine, square: ncomp Function1 */
} f1;

/* Flags of f1_read. */
#define F1_PATCH 1u /* a PatchFunction1 entry (uniformFixedValue's uniformValue):
                       "nonuniform" is then named as refused (per-face values) */

/* Read the Function1 entry `key` of dictionary d with ncomp (1 or 3)
 * components. what names it in messages (e.g. "patch 'lid': uniformValue").
 * *out is owned by the caller (f1_free). */
ump_status f1_read(const foam_dict *d, const char *key, int ncomp, unsigned flags, const char *what,
                   f1 **out, ump_err *err);
/* Value at time t into out[ncomp]. */
void f1_value(const f1 *f, double t, double *out);
/* An upper bound of |value| (the Euclidean norm of a vector) over all
 * times: the largest constant or table row, |amplitude| |scale| + |level|
 * for the waves (bounds of their own Function1s). */
double f1_max_abs(const f1 *f);
/* Deep copy (NULL src gives *out = NULL). */
ump_status f1_copy(const f1 *src, f1 **out, ump_err *err);
/* Release f and everything it owns; *f = NULL. Accepts NULL. */
void f1_free(f1 **f);
/* OpenFOAM's type word ("constant", "table", "sine", "square"). */
const char *f1_kind_name(f1_kind k);

#endif
