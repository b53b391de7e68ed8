/* SPDX-License-Identifier: GPL-3.0-or-later
 * lsolve_csr.c -- compressed-column matrices rebuilt from rows without
 * per-step allocation (the particle predictor's matrix changes its pattern
 * every step as particles move).
 *
 * A row-wise (CSR) matrix is the column-wise (CSC) storage of its
 * transpose; transposing by a counting pass over the rows in increasing
 * order leaves each column's row indices sorted, as SuiteSparse and the
 * ILU(0) preconditioner want.
 */
#include "umppm/lsolve.h"

#include <stdlib.h>
#include <string.h>

ump_status lsolve_mat_from_csr(lsolve_mat *A, size_t *cap, ump_idx n, const ump_idx *rowptr,
                               const ump_idx *col, const double *val, ump_err *err)
{
    size_t nnz = (size_t)rowptr[n];
    if (*cap < nnz || !A->Ai) {
        /* entries grow geometrically: particle counts fluctuate step to step */
        size_t nc = nnz > 2 * *cap ? nnz : 2 * *cap;
        ump_idx *Ai = ump_realloc_array(A->Ai, nc ? nc : 1, sizeof *Ai);
        if (!Ai)
            return UMP_FAIL(err, UMP_ERR_NOMEM, "predictor matrix: out of memory (%zu entries)", nnz);
        A->Ai = Ai;
        double *Ax = ump_realloc_array(A->Ax, nc ? nc : 1, sizeof *Ax);
        if (!Ax)
            return UMP_FAIL(err, UMP_ERR_NOMEM, "predictor matrix: out of memory (%zu entries)", nnz);
        A->Ax = Ax;
        *cap = nc;
    }
    if (A->n < n || !A->Ap) {
        /* realloc to the same size is cheap; a smaller n keeps the block */
        ump_idx *Ap = ump_realloc_array(A->Ap, (size_t)n + 1, sizeof *Ap);
        if (!Ap)
            return UMP_FAIL(err, UMP_ERR_NOMEM, "predictor matrix: out of memory (%ld rows)", (long)n);
        A->Ap = Ap;
    }
    A->n = n;
    memset(A->Ap, 0, ((size_t)n + 1) * sizeof *A->Ap);
    for (size_t k = 0; k < nnz; k++)
        A->Ap[col[k] + 1]++;
    for (ump_idx j = 0; j < n; j++)
        A->Ap[j + 1] += A->Ap[j];
    /* scatter rows in order: Ap[j] is used as the fill pointer, then shifted back */
    for (ump_idx i = 0; i < n; i++)
        for (ump_idx k = rowptr[i]; k < rowptr[i + 1]; k++) {
            ump_idx q = A->Ap[col[k]]++;
            A->Ai[q] = i;
            A->Ax[q] = val[k];
        }
    for (ump_idx j = n; j > 0; j--)
        A->Ap[j] = A->Ap[j - 1];
    A->Ap[0] = 0;
    return UMP_OK;
}
