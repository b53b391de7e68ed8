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
 * condition number of A_hat is computed exactly from the full inverse, which
 * for n <= 9 costs under a thousand flops -- cheaper than being wrong about it.
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
 * or a non-finite entry); f->inv is then unspecified. */
static inline double spd_factor_invert(spd_small *f, int n, double a[SPD_MAX][SPD_MAX])
{
    double l[SPD_MAX][SPD_MAX];
    f->n = n;
    f->rcond = 0;
    for (int i = 0; i < n; i++) {
        if (!(a[i][i] > 0) || !isfinite(a[i][i]))
            return 0;
        f->s[i] = 1 / sqrt(a[i][i]);
    }
    /* A_hat = S A S (symmetric, unit diagonal); its 1-norm. */
    double anorm = 0;
    for (int i = 0; i < n; i++) {
        l[i][i] = 1;
        for (int j = i + 1; j < n; j++)
            l[i][j] = l[j][i] = a[i][j] * f->s[i] * f->s[j];
    }
    for (int j = 0; j < n; j++) {
        double c = 0;
        for (int i = 0; i < n; i++)
            c += fabs(l[i][j]);
        if (!isfinite(c))
            return 0;
        anorm = c > anorm ? c : anorm;
    }
    /* Cholesky A_hat = L L^T in place (lower triangle of l). */
    for (int j = 0; j < n; j++) {
        double d = l[j][j];
        for (int k = 0; k < j; k++)
            d -= l[j][k] * l[j][k];
        if (!(d > 0))
            return 0;
        d = sqrt(d);
        l[j][j] = d;
        for (int i = j + 1; i < n; i++) {
            double v = l[i][j];
            for (int k = 0; k < j; k++)
                v -= l[i][k] * l[j][k];
            l[i][j] = v / d;
        }
    }
    /* A_hat^{-1} = L^{-T} L^{-1}: solve for each unit vector. */
    double inorm = 0;
    for (int c = 0; c < n; c++) {
        double y[SPD_MAX];
        for (int i = 0; i < n; i++) { /* L y = e_c */
            double v = (i == c) ? 1.0 : 0.0;
            for (int k = 0; k < i; k++)
                v -= l[i][k] * y[k];
            y[i] = v / l[i][i];
        }
        for (int i = n - 1; i >= 0; i--) { /* L^T x = y */
            double v = y[i];
            for (int k = i + 1; k < n; k++)
                v -= l[k][i] * f->inv[k][c];
            f->inv[i][c] = v / l[i][i];
        }
        double col = 0;
        for (int i = 0; i < n; i++)
            col += fabs(f->inv[i][c]);
        inorm = col > inorm ? col : inorm;
    }
    double rc = 1 / (anorm * inorm);
    f->rcond = isfinite(rc) ? rc : 0;
    return f->rcond;
}

/* Column c of A^{-1} (unscaled): x_i = s_i (A_hat^{-1})_{ic} s_c. */
static inline void spd_inv_column(const spd_small *f, int c, double *x)
{
    for (int i = 0; i < f->n; i++)
        x[i] = f->s[i] * f->inv[i][c] * f->s[c];
}

#endif
