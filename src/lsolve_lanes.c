/* SPDX-License-Identifier: GPL-3.0-or-later
 * lsolve_lanes.c -- the two triangular solves with a Cholesky factor L
 * (L L^T = P A P^T), in two lanes that run concurrently.
 *
 * The pressure equation is factorized once and solved every step; its
 * triangular solves were the largest serial part of a threaded step (8 % of
 * the 2-thread step on the 160^2 cavity). They are split by the elimination
 * tree of L (parent(j) = the first off-diagonal row of column j): column j
 * depends only on its descendants in the forward solve and only on its
 * ancestors in the backward solve, so disjoint subtrees are independent.
 * Two sets of disjoint subtrees ("lanes"), balanced by their entries of L,
 * and the rest ("top": the ancestors of the lanes' subtrees, the last
 * separators of the ordering):
 *
 *   forward  L y = b:    each lane solves its columns in increasing order;
 *                        an update of a top row goes to the lane's own
 *                        accumulator; then every top row takes
 *                        b - acc_0 - acc_1 and the top columns are solved
 *                        in increasing order;
 *   backward L^T x = y:  the top columns in decreasing order, then each
 *                        lane its columns in decreasing order, reading x
 *                        of its own subtrees and of the top only.
 *
 * No two lanes write the same entry and every sum runs in one fixed order,
 * whatever the thread count: the result is the same bits on 1 and 2 threads.
 * The split is made once per factorization, O(nnz(L)).
 */
#include "umppm/lsolve.h"

#include <stdlib.h>
#include <string.h>

#ifdef _OPENMP
#include <omp.h>
#endif

struct lsolve_lanes {
    ump_idx n;
    const int *Lp, *Li;        /* borrowed: column pointers [n+1], rows (diagonal first) */
    const double *Lx;          /* borrowed: values */
    ump_idx *col[2];           /* the columns of each lane, increasing */
    ump_idx ncol[2];
    ump_idx *top;              /* [ntop] the top columns, increasing */
    ump_idx ntop;
    ump_idx *tpos;             /* [n] position of a column in top, or -1 */
    int *split;                /* [n] lane columns: first entry in a top row (rows ascend, and
                                  a column's ancestors in its own subtree precede the top ones) */
    double *acc;               /* [2 ntop] the lanes' updates of the top rows */
    size_t work[3];            /* entries of L in lane 0, lane 1, top */
};

void lsolve_lanes_free(lsolve_lanes **pz)
{
    if (!pz || !*pz)
        return;
    lsolve_lanes *z = *pz;
    free(z->col[0]);
    free(z->col[1]);
    free(z->top);
    free(z->tpos);
    free(z->split);
    free(z->acc);
    free(z);
    *pz = NULL;
}

void lsolve_lanes_work(const lsolve_lanes *z, size_t work[3])
{
    memcpy(work, z->work, sizeof z->work);
}

/* Largest-first assignment of the candidate subtrees to the two lanes;
 * returns the larger load. */
static size_t assign(const ump_idx *F, ump_idx nf, const size_t *W, signed char *lane_of_root,
                     ump_idx *order)
{
    for (ump_idx a = 0; a < nf; a++) { /* order: F by W descending (insertion: nf is small) */
        if (nf > 4096) { /* a forest of many small trees: in index order, O(nf) */
            order[a] = a;
            continue;
        }
        ump_idx k = a;
        while (k > 0 && W[F[order[k - 1]]] < W[F[a]]) {
            order[k] = order[k - 1];
            k--;
        }
        order[k] = a;
    }
    size_t load[2] = {0, 0};
    for (ump_idx a = 0; a < nf; a++) {
        int l = load[1] < load[0];
        lane_of_root[order[a]] = (signed char)l;
        load[l] += W[F[order[a]]];
    }
    return load[0] > load[1] ? load[0] : load[1];
}

ump_status lsolve_lanes_build(ump_idx n, const int *Lp, const int *Li, const double *Lx, lsolve_lanes **out,
                              ump_err *err)
{
    *out = NULL;
    ump_idx *parent = ump_alloc_array((size_t)n, sizeof *parent);
    ump_idx *coff = ump_alloc_array((size_t)n + 1, sizeof *coff);
    ump_idx *child = ump_alloc_array((size_t)n + 1, sizeof *child);
    size_t *W = ump_alloc_array((size_t)n, sizeof *W);
    ump_idx *F = ump_alloc_array((size_t)n + 1, sizeof *F);
    ump_idx *order = ump_alloc_array((size_t)n + 1, sizeof *order);
    signed char *lroot = ump_alloc_array((size_t)n + 1, 1), *lane = ump_alloc_array((size_t)n, 1);
    lsolve_lanes *z = ump_alloc_array(1, sizeof *z);
    ump_status rc = UMP_OK;
    if (!parent || !coff || !child || !W || !F || !order || !lroot || !lane || !z) {
        rc = UMP_FAIL(err, UMP_ERR_NOMEM, "lsolve: out of memory splitting a factor of order %d", (int)n);
        goto done;
    }
    /* elimination tree, subtree entries, children lists */
    for (ump_idx j = 0; j < n; j++) {
        if (Lp[j + 1] <= Lp[j] || Li[Lp[j]] != j) {
            rc = UMP_FAIL(err, UMP_ERR_INPUT, "lsolve: factor column %d does not start with its diagonal",
                          (int)j);
            goto done;
        }
        for (int q = Lp[j] + 1; q < Lp[j + 1]; q++)
            if (Li[q] <= Li[q - 1] || Li[q] >= n) {
                rc = UMP_FAIL(err, UMP_ERR_INPUT, "lsolve: factor column %d: rows not ascending below the "
                              "diagonal (row %d)", (int)j, Li[q]);
                goto done;
            }
        parent[j] = Lp[j + 1] - Lp[j] > 1 ? Li[Lp[j] + 1] : -1;
        W[j] = (size_t)(Lp[j + 1] - Lp[j]);
    }
    for (ump_idx j = 0; j < n; j++) /* children before parents: parent(j) > j */
        if (parent[j] >= 0)
            W[parent[j]] += W[j];
    for (ump_idx j = 0; j < n; j++) /* children lists (the roots are nobody's child) */
        if (parent[j] >= 0)
            coff[parent[j] + 1]++;
    for (ump_idx j = 0; j < n; j++)
        coff[j + 1] += coff[j];
    for (ump_idx j = 0; j < n; j++)
        if (parent[j] >= 0)
            child[coff[parent[j]]++] = j;
    for (ump_idx j = n; j > 0; j--)
        coff[j] = coff[j - 1];
    coff[0] = 0;
    /* candidates F: the roots; while the lanes are unbalanced, replace the
     * largest candidate by its children (its root joins the top) */
    ump_idx nf = 0;
    size_t total = 0;
    for (ump_idx j = 0; j < n; j++)
        if (parent[j] < 0) {
            F[nf++] = j;
            total += W[j];
        }
    for (int iter = 0; iter < 100000 && nf < 4096; iter++) { /* bounds: the insertion order is O(nf^2) */
        size_t in_f = 0;
        for (ump_idx a = 0; a < nf; a++)
            in_f += W[F[a]];
        size_t big = assign(F, nf, W, lroot, order);
        /* balanced to 2 % of the lanes' sum: done */
        if (nf >= 2 && big <= in_f / 2 + in_f / 50)
            break;
        ump_idx r = F[order[0]]; /* the largest */
        ump_idx nch = coff[r + 1] - coff[r];
        if (nch == 0 || in_f - W[r] + (W[r] - (size_t)(Lp[r + 1] - Lp[r])) < total / 2)
            break; /* a leaf, or the top would hold most of L: keep what we have */
        F[order[0]] = F[--nf];
        for (ump_idx a = coff[r]; a < coff[r + 1]; a++)
            F[nf++] = child[a];
    }
    assign(F, nf, W, lroot, order);
    /* lanes: a candidate's subtree is its lane; everything else is top */
    memset(lane, -1, (size_t)n);
    for (ump_idx a = 0; a < nf; a++)
        lane[F[a]] = (signed char)(2 + lroot[a]); /* 2, 3: a root, resolved below */
    for (ump_idx j = n - 1; j >= 0; j--) {
        if (lane[j] >= 2)
            lane[j] = (signed char)(lane[j] - 2);
        else if (parent[j] >= 0 && lane[parent[j]] >= 0 && lane[parent[j]] < 2)
            lane[j] = lane[parent[j]];
        else
            lane[j] = -1;
    }
    z->n = n;
    z->Lp = Lp;
    z->Li = Li;
    z->Lx = Lx;
    for (ump_idx j = 0; j < n; j++) {
        int l = lane[j] < 0 ? 2 : lane[j];
        z->work[l] += (size_t)(Lp[j + 1] - Lp[j]);
        if (l < 2)
            z->ncol[l]++;
        else
            z->ntop++;
    }
    if (!(z->col[0] = ump_alloc_array((size_t)z->ncol[0] + 1, sizeof(ump_idx))) ||
        !(z->col[1] = ump_alloc_array((size_t)z->ncol[1] + 1, sizeof(ump_idx))) ||
        !(z->top = ump_alloc_array((size_t)z->ntop + 1, sizeof(ump_idx))) ||
        !(z->tpos = ump_alloc_array((size_t)n, sizeof(ump_idx))) ||
        !(z->split = ump_alloc_array((size_t)n, sizeof(int))) ||
        !(z->acc = ump_alloc_array(2 * (size_t)z->ntop + 1, sizeof(double)))) {
        rc = UMP_FAIL(err, UMP_ERR_NOMEM, "lsolve: out of memory splitting a factor of order %d", (int)n);
        goto done;
    }
    ump_idx k0 = 0, k1 = 0, kt = 0;
    for (ump_idx j = 0; j < n; j++) {
        z->tpos[j] = -1;
        if (lane[j] == 0)
            z->col[0][k0++] = j;
        else if (lane[j] == 1)
            z->col[1][k1++] = j;
        else {
            z->tpos[j] = kt;
            z->top[kt++] = j;
        }
    }
    for (ump_idx j = 0; j < n; j++) {
        int q = Lp[j] + 1;
        while (q < Lp[j + 1] && z->tpos[Li[q]] < 0)
            q++;
        z->split[j] = q;
        for (; q < Lp[j + 1]; q++)
            if (z->tpos[Li[q]] < 0) { /* cannot happen for an elimination tree: keep CHOLMOD's solve */
                rc = UMP_FAIL(err, UMP_ERR_INPUT, "lsolve: factor column %d: a lane row after a top row",
                              (int)j);
                goto done;
            }
    }
    *out = z;
    z = NULL;
done:
    lsolve_lanes_free(&z);
    free(parent);
    free(coff);
    free(child);
    free(W);
    free(F);
    free(order);
    free(lroot);
    free(lane);
    return rc;
}

/* Forward solve of lane l's columns: its own rows in y, top rows into acc. */
static void lane_forward(const lsolve_lanes *z, int l, double *restrict y)
{
    const int *restrict Lp = z->Lp, *restrict Li = z->Li;
    const double *restrict Lx = z->Lx;
    const ump_idx *restrict tpos = z->tpos, *restrict col = z->col[l];
    const int *restrict split = z->split;
    double *restrict acc = z->acc + (size_t)l * (size_t)z->ntop;
    memset(acc, 0, sizeof *acc * (size_t)z->ntop);
    for (ump_idx a = 0; a < z->ncol[l]; a++) {
        ump_idx j = col[a];
        double yj = y[j] / Lx[Lp[j]];
        y[j] = yj;
        int q = Lp[j] + 1, qs = split[j];
        for (; q < qs; q++)
            y[Li[q]] -= Lx[q] * yj;
        for (; q < Lp[j + 1]; q++)
            acc[tpos[Li[q]]] += Lx[q] * yj;
    }
}

/* Backward solve of the columns col[0..nc) in decreasing order. */
static void backward(const lsolve_lanes *z, const ump_idx *col, ump_idx nc, double *restrict y)
{
    const int *restrict Lp = z->Lp, *restrict Li = z->Li;
    const double *restrict Lx = z->Lx;
    for (ump_idx a = nc - 1; a >= 0; a--) {
        ump_idx j = col[a];
        double s = y[j];
        for (int q = Lp[j] + 1; q < Lp[j + 1]; q++)
            s -= Lx[q] * y[Li[q]];
        y[j] = s / Lx[Lp[j]];
    }
}

void lsolve_lanes_solve(const lsolve_lanes *z, double *y)
{
    const int *Lp = z->Lp, *Li = z->Li;
    const double *Lx = z->Lx;
    int two = 1;
#ifdef _OPENMP
    two = omp_get_max_threads() > 1;
#endif
    /* forward, lanes */
#pragma omp parallel for schedule(static, 1) num_threads(2) if (two)
    for (int l = 0; l < 2; l++)
        lane_forward(z, l, y);
    /* forward, top: b - acc_0 - acc_1, then the top columns */
    const double *acc0 = z->acc, *acc1 = z->acc + z->ntop;
    for (ump_idx t = 0; t < z->ntop; t++) {
        ump_idx i = z->top[t];
        y[i] = y[i] - acc0[t] - acc1[t];
    }
    for (ump_idx t = 0; t < z->ntop; t++) {
        ump_idx j = z->top[t];
        double yj = y[j] / Lx[Lp[j]];
        y[j] = yj;
        for (int q = Lp[j] + 1; q < Lp[j + 1]; q++)
            y[Li[q]] -= Lx[q] * yj; /* rows above a top column are top */
    }
    /* backward: top, then the lanes */
    backward(z, z->top, z->ntop, y);
#pragma omp parallel for schedule(static, 1) num_threads(2) if (two)
    for (int l = 0; l < 2; l++)
        backward(z, z->col[l], z->ncol[l], y);
}
