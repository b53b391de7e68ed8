/* SPDX-License-Identifier: GPL-3.0-or-later
 * spd_small.h -- internal: dense symmetric positive definite solves of size
 * n <= SPD_MAX (the 6x6 MLS normal matrix, the CPM moment matrices: 2x2,
 * 5x5, 9x9 in 1-, 2-, 3-D; the d x d IPS gradient matrices).
 *
 * These run once per particle or face per time step, so they use fixed-size
 * stack arrays and never allocate. The matrix is first equilibrated
 * symmetrically, A_hat = S A S with S = diag(1/sqrt(A_ii)): Cholesky's
 * rounding behaviour does not depend on such scaling (van der Sluis), but a
 * condition number does, and the one of A_hat is the meaningful one (it is
 * within a factor n of the best diagonal scaling). The reciprocal 1-norm
 * condition number of A_hat is computed exactly from its inverse, formed as
 * L^-T L^-1 from the triangular factor (n^3/2 multiply-adds in all: about
 * 110 for the 6x6 MLS matrix) -- cheaper than being wrong about it, and the
 * callers need columns of that inverse anyway.
 */
#ifndef UMPPM_SPD_SMALL_H
#define UMPPM_SPD_SMALL_H

#include <math.h>

#define SPD_MAX 9

typedef struct spd_small {
    int n;                       /* order, 1..SPD_MAX */
    double s[SPD_MAX];           /* equilibration S = diag(s) */
    double inv[SPD_MAX][SPD_MAX];/* (S A S)^{-1}, full symmetric */
    double rcond;                /* 1 / (|S A S|_1 |(S A S)^{-1}|_1), 0 if not SPD */
} spd_small;

/* Factor the symmetric matrix a (only the upper triangle a[i][j], j >= i, is
 * read) and form the inverse of its equilibration. Returns f->rcond, which is
 * 0 when a is not numerically positive definite (a zero or negative pivot,
 * or a non-finite entry); f->inv is then unspecified.
 *
 * Cost for n = 6 (the MLS normal matrix): the Cholesky factor (n^3/6
 * multiply-adds), the inverse of the triangular factor (n^3/6) and
 * inv = L^-T L^-1 on the upper triangle (n^3/6): about 110 multiply-adds and
 * n square roots and divisions, no per-column solves; the exact 1-norm
 * condition number then comes for free. Callers pass n as a constant, so
 * the loops are unrolled where this header is inlined.
 * spd_factor_invert_fixed is the same with its loops unrolled by the
 * compiler; use it only with a constant n (the 6x6 MLS and 5x5 CPM
 * matrices), where it costs about a tenth of the instructions. */
#define SPD_NAME spd_factor_invert
#define SPD_SPEC static inline
#define SPD_LOOP
#include "spd_small_body.h"
#undef SPD_NAME
#undef SPD_SPEC
#undef SPD_LOOP
#define SPD_NAME spd_factor_invert_fixed
#define SPD_SPEC static inline __attribute__((always_inline))
#define SPD_LOOP _Pragma("GCC unroll 9")
#include "spd_small_body.h"
#undef SPD_NAME
#undef SPD_SPEC
#undef SPD_LOOP

/* Column c of A^{-1} (unscaled): x_i = s_i (A_hat^{-1})_{ic} s_c. */
static inline void spd_inv_column(const spd_small *f, int c, double *x)
{
    for (int i = 0; i < f->n; i++)
        x[i] = f->s[i] * f->inv[i][c] * f->s[c];
}

#endif
