/* SPDX-License-Identifier: GPL-3.0-or-later
 * spd_small_body.h -- internal: the body of spd_factor_invert, included
 * twice by spd_small.h (SPD_NAME, SPD_SPEC, SPD_LOOP set there): once
 * plain, for any n, and once with its loops unrolled, for callers that pass
 * n as a constant (the 6x6 MLS and 5x5 CPM matrices: the unrolled version
 * runs in about a tenth of the instructions). No include guard, on purpose.
 */
SPD_SPEC double SPD_NAME(spd_small *f, int n, double a[SPD_MAX][SPD_MAX])
{
    double l[SPD_MAX][SPD_MAX], li[SPD_MAX][SPD_MAX], d[SPD_MAX];
    f->n = n;
    f->rcond = 0;
    int ok = 1;
    SPD_LOOP
    for (int i = 0; i < n; i++) {
        ok &= a[i][i] > 0 && a[i][i] < INFINITY;
        f->s[i] = 1 / sqrt(a[i][i]);
    }
    if (!ok)
        return 0;
    /* A_hat = S A S (symmetric, unit diagonal): upper triangle into l[j][i],
     * i.e. the lower triangle, and its 1-norm. */
    double colsum[SPD_MAX];
    SPD_LOOP
    for (int j = 0; j < n; j++)
        colsum[j] = 1;
    SPD_LOOP
    for (int i = 0; i < n; i++)
        SPD_LOOP
        for (int j = i + 1; j < n; j++) {
            double v = a[i][j] * f->s[i] * f->s[j];
            l[j][i] = v;
            colsum[i] += fabs(v);
            colsum[j] += fabs(v);
        }
    double anorm = 0;
    SPD_LOOP
    for (int j = 0; j < n; j++) {
        if (!(colsum[j] < INFINITY)) /* inf or NaN */
            return 0;
        anorm = colsum[j] > anorm ? colsum[j] : anorm;
    }
    /* Cholesky A_hat = L L^T (lower triangle of l); d = 1 / L_jj. */
    SPD_LOOP
    for (int j = 0; j < n; j++) {
        double p = 1;
        SPD_LOOP
        for (int k = 0; k < j; k++)
            p -= l[j][k] * l[j][k];
        if (!(p > 0))
            return 0;
        p = sqrt(p);
        l[j][j] = p;
        d[j] = 1 / p;
        SPD_LOOP
        for (int i = j + 1; i < n; i++) {
            double v = l[i][j];
            SPD_LOOP
            for (int k = 0; k < j; k++)
                v -= l[i][k] * l[j][k];
            l[i][j] = v * d[j];
        }
    }
    /* L^-1 (lower triangular), column by column. */
    SPD_LOOP
    for (int j = 0; j < n; j++) {
        li[j][j] = d[j];
        SPD_LOOP
        for (int i = j + 1; i < n; i++) {
            double v = 0;
            SPD_LOOP
            for (int k = j; k < i; k++)
                v -= l[i][k] * li[k][j];
            li[i][j] = v * d[i];
        }
    }
    /* A_hat^-1 = L^-T L^-1: (i, j) = sum_{k >= max(i, j)} li[k][i] li[k][j]. */
    SPD_LOOP
    for (int j = 0; j < n; j++)
        colsum[j] = 0;
    SPD_LOOP
    for (int i = 0; i < n; i++)
        SPD_LOOP
        for (int j = i; j < n; j++) {
            double v = 0;
            SPD_LOOP
            for (int k = j; k < n; k++)
                v += li[k][i] * li[k][j];
            f->inv[i][j] = f->inv[j][i] = v;
            colsum[i] += fabs(v);
            if (j != i)
                colsum[j] += fabs(v);
        }
    double inorm = 0;
    SPD_LOOP
    for (int j = 0; j < n; j++)
        inorm = colsum[j] > inorm ? colsum[j] : inorm;
    double rc = 1 / (anorm * inorm);
    f->rcond = rc < INFINITY ? rc : 0;
    return f->rcond;
}

