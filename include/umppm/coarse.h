/* SPDX-License-Identifier: GPL-3.0-or-later
 * coarse.h -- the coarse level of a two-level preconditioner for the
 * particle pressure equations (module prefix coarse_), shared by the MPS
 * (symmetric, CG) and FPM (non-symmetric, BiCGSTAB) pressure solves.
 *
 * A one-level preconditioner (Jacobi, ILU(0)) leaves the iterations growing
 * like the square root of the number of unknowns: the smooth error is
 * reduced only by the Krylov method. The coarse level adds
 *     z += P Ac^-1 P^T r,   Ac = P^T A P (the Galerkin product),
 * P the piecewise-constant prolongation from aggregates: the unknowns in
 * squares of side H (a few particle spacings, about nine particles), so the
 * condition number is bounded by the aggregate size instead of the domain
 * size. The squares are those of a fixed lattice and every sum runs in
 * the order of A's rows, so everything is deterministic. Ac (about N/9
 * unknowns) is refactorized with SuiteSparse at every build, in a pattern
 * that changes only when the liquid reaches squares it has not reached
 * before (coarse.c): the other builds allocate nothing.
 *
 * The caller adds the coarse correction to its own one-level
 * preconditioner (additive two-level); coarse_build reports with *ok = 0
 * when the coarse level is not worth it (under 64 unknowns, a liquid
 * scattered over four times as many bins as unknowns) or when the coarse
 * matrix does not factorize (then only the speed changes).
 */
#ifndef UMPPM_COARSE_H
#define UMPPM_COARSE_H

#include <stddef.h>

#include "umppm/lsolve.h"
#include "umppm/ump.h"

typedef struct coarse coarse;

ump_status coarse_create(coarse **out, ump_err *err);
void coarse_free(coarse **c);

/* Aggregates of the nu unknowns, unknown k at (px[map[k]], py[map[k]]),
 * squares of side H; Ac = P^T A P of the row-compressed A (order nu: rows
 * rp/ci/av, columns < nu), factorized as kind (LSOLVE_CHOLMOD for a
 * symmetric definite A, LSOLVE_KLU or LSOLVE_UMFPACK otherwise). *ok: the
 * coarse level can be applied. Errors: out of memory only. */
ump_status coarse_build(coarse *c, size_t nu, const double *px, const double *py, const size_t *map, double H,
                        const ump_idx *rp, const ump_idx *ci, const double *av, lsolve_kind kind, int *ok,
                        ump_err *err);

/* How many builds made the pattern of Ac anew (and allocated): the first,
 * those where the liquid reached squares it had not reached before, and
 * those whose couplings reached further than any before (reach). */
size_t coarse_rebuilds(const coarse *c);

/* z += P Ac^-1 P^T r over the nu unknowns of the last build with *ok = 1
 * (a failing solve adds nothing). */
void coarse_add(coarse *c, const double *r, double *z);

#endif
