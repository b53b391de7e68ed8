/* SPDX-License-Identifier: GPL-3.0-or-later
 * lsolve.h -- sparse linear algebra (module prefix lsolve_): the only code
 * that calls SuiteSparse (UMFPACK, KLU, CHOLMOD).
 *
 * Matrices are assembled as triplets (duplicates summed) and stored in
 * compressed-column form, as SuiteSparse wants them. A direct solver object
 * is analysed and factorized once (lsolve_factor) and then solves any number
 * of right-hand sides (the PPE of UMPPM: Step 4 of the paper, factor once);
 * lsolve_refactor reuses the symbolic analysis for new values on the same
 * pattern. The iterative solver (BiCGSTAB, van der Vorst 1992, with ILU(0)
 * or Jacobi preconditioning) serves matrices whose pattern changes every
 * step (the implicit particle predictor) and returns its convergence as data.
 */
#ifndef UMPPM_LSOLVE_H
#define UMPPM_LSOLVE_H

#include <stddef.h>
#include "umppm/ump.h"

/* Compressed-column matrix (n x n), column j in Ai/Ax[Ap[j] .. Ap[j+1]-1],
 * row indices sorted, no duplicates. */
typedef struct lsolve_mat {
    ump_idx n;
    ump_idx *Ap;   /* [n+1] */
    ump_idx *Ai;   /* [nnz] */
    double *Ax;    /* [nnz] */
} lsolve_mat;

/* Triplet accumulator: lsolve_trip_add appends (i, j, x); duplicates are
 * summed by lsolve_trip_to_mat. Grows as needed (amortised O(1)). */
typedef struct lsolve_trip {
    ump_idx n;
    size_t nz, cap;
    ump_idx *Ti, *Tj;
    double *Tx;
} lsolve_trip;

ump_status lsolve_trip_init(lsolve_trip *t, ump_idx n, size_t cap_hint, ump_err *err);
ump_status lsolve_trip_add(lsolve_trip *t, ump_idx i, ump_idx j, double x, ump_err *err);
void lsolve_trip_clear(lsolve_trip *t);           /* nz = 0, keeps storage */
void lsolve_trip_free(lsolve_trip *t);
/* Build the CSC matrix (caller frees with lsolve_mat_free). */
ump_status lsolve_trip_to_mat(const lsolve_trip *t, lsolve_mat **A, ump_err *err);
void lsolve_mat_free(lsolve_mat **A);
/* Fill A (storage reused; it grows only when needed, *cap holding the
 * capacity in entries -- start with a zeroed lsolve_mat and *cap = 0) with
 * the n x n matrix given by rows: rowptr [n+1], col/val [rowptr[n]]. Column
 * indices within a row may be in any order; no duplicates. For matrices
 * rebuilt every step (the particle predictor) without per-step allocation. */
ump_status lsolve_mat_from_csr(lsolve_mat *A, size_t *cap, ump_idx n, const ump_idx *rowptr,
                               const ump_idx *col, const double *val, ump_err *err);
/* y = A x */
void lsolve_mat_mult(const lsolve_mat *A, const double *x, double *y);
/* y = A x for A equal to its transpose (pattern and values): y_i is
 * column i dotted with x, rows in parallel (OpenMP) -- the same products
 * summed in the same order as lsolve_mat_mult, so the same bits. */
void lsolve_mat_mult_sym(const lsolve_mat *A, const double *x, double *y);
/* 1 if A equals its transpose to within tol * max|A_ij| */
int lsolve_mat_is_symmetric(const lsolve_mat *A, double tol);

typedef enum lsolve_kind {
    LSOLVE_AUTO,     /* CHOLMOD if exactly symmetric with a one-signed diagonal
                        (UMFPACK if CHOLMOD then finds it indefinite), else UMFPACK */
    LSOLVE_UMFPACK,
    LSOLVE_KLU,
    LSOLVE_CHOLMOD   /* symmetric (to 1e-12 relative; the upper triangle is
                        used) positive or negative (sign handled) definite */
} lsolve_kind;

typedef struct lsolve lsolve; /* opaque factorization */

/* Analyse and factorize A. A singular matrix fails with UMP_ERR_SINGULAR
 * naming the failing column/row when SuiteSparse reports it; so does a
 * numerically singular one (estimated 1-norm condition number > 1e11, e.g. a
 * pure-Neumann Laplacian that factorizes with a round-off pivot). */
ump_status lsolve_factor(const lsolve_mat *A, lsolve_kind kind, lsolve **out, ump_err *err);
/* The same for a small matrix refactorized every step with one pattern
 * (the particle solves' coarse level): with CHOLMOD the matrix is kept in
 * its fill-reducing order and solved by this module's serial loops, so
 * that with CHOLMOD and KLU lsolve_refactor and lsolve_solve allocate
 * nothing after the first call (UMFPACK's refactor still does). */
ump_status lsolve_factor_serial(const lsolve_mat *A, lsolve_kind kind, lsolve **out, ump_err *err);
/* New numerical values, same pattern as the factorized matrix. On failure
 * the object stays allocated but lsolve_solve refuses until a refactor
 * succeeds. */
ump_status lsolve_refactor(lsolve *s, const lsolve_mat *A, ump_err *err);
/* Solve A x = b (x and b may not alias). */
ump_status lsolve_solve(lsolve *s, const double *b, double *x, ump_err *err);
/* Which solver was used ("UMFPACK", "KLU", "CHOLMOD") and factor nnz. */
const char *lsolve_name(const lsolve *s);
size_t lsolve_factor_nnz(const lsolve *s);
/* CHOLMOD: the entries of L in the two lanes and the serial top of its
 * solves (lsolve_lanes.c); returns 0 (work untouched) for the other
 * solvers or when the factor was not split. */
int lsolve_lane_work(const lsolve *s, size_t work[3]);
/* Estimated 1-norm condition number of the factorized matrix (Hager/Higham). */
double lsolve_condest(const lsolve *s);
void lsolve_free(lsolve **s);

/* ---- iterative ---------------------------------------------------------- */
typedef enum { LSOLVE_PC_NONE, LSOLVE_PC_JACOBI, LSOLVE_PC_ILU0 } lsolve_pc;

typedef struct lsolve_stats {
    int iterations;
    double res0, res;       /* ||b - A x|| / ||b|| before and after */
    int converged;          /* 1 converged, 0 max iterations, -1 breakdown */
} lsolve_stats;

/* Workspace for BiCGSTAB on n unknowns (allocated once, reused each step). */
typedef struct lsolve_krylov lsolve_krylov;
/* n: the largest order it will serve (a smaller matrix may be solved with it). */
ump_status lsolve_krylov_create(ump_idx n, lsolve_krylov **out, ump_err *err);
void lsolve_krylov_free(lsolve_krylov **k);
/* Solve A x = b from the initial guess in x (warm start) to relative
 * residual tol or maxit iterations. A may have a new pattern each call (the
 * ILU(0) value array grows to the largest nnz seen; nothing else is
 * allocated). Preconditioning is on the right, so st->res is the true
 * ||b - A x|| / ||b||, recomputed at the end. Non-convergence and breakdown
 * are reported in st (UMP_OK); errors are bad sizes, a zero diagonal
 * (Jacobi) or a zero ILU(0) pivot (UMP_ERR_SINGULAR), out of memory. */
ump_status lsolve_bicgstab(lsolve_krylov *k, const lsolve_mat *A, lsolve_pc pc, const double *b,
                           double *x, double tol, int maxit, lsolve_stats *st, ump_err *err);

/* Preconditioner callback: z from r over the order of the solve (see the
 * functions taking one for whether it replaces or adds to z). */
typedef void (*lsolve_pc_fn)(void *ctx, const double *r, double *z);

/* As lsolve_bicgstab with a two-level preconditioner: M^-1 r = (the one
 * of pc) r, then add(ctx, r, z) adds its correction to that z (e.g. a
 * coarse level, coarse.h). */
ump_status lsolve_bicgstab_pc(lsolve_krylov *k, const lsolve_mat *A, lsolve_pc pc, lsolve_pc_fn add, void *ctx,
                              const double *b, double *x, double tol, int maxit, lsolve_stats *st, ump_err *err);

/* As lsolve_bicgstab for the same matrix values as the previous call (a
 * second right-hand side, e.g. v after u): the preconditioner built then is
 * reused instead of being recomputed. */
ump_status lsolve_bicgstab_again(lsolve_krylov *k, const lsolve_mat *A, lsolve_pc pc, const double *b,
                                 double *x, double tol, int maxit, lsolve_stats *st, ump_err *err);

/* ---- row-compressed, several right-hand sides, threaded ------------------ */
/* Row-compressed matrix (n x n): row i in ci/v[rp[i] .. rp[i+1]-1], columns
 * strictly increasing within a row, the diagonal present. Borrowed arrays. */
typedef struct lsolve_csr {
    ump_idx n;
    const ump_idx *rp, *ci;
    const double *v;
} lsolve_csr;

#define LSOLVE_MAX_RHS 3       /* systems solved in lockstep (u, v, T) */
#define LSOLVE_DOT_BLOCK 2048  /* rows per partial sum of a reduction */
#define LSOLVE_ILU_BLOCK 4096  /* rows per diagonal block of the ILU(0) */

/* Triangular solves with a Cholesky factor in two concurrent lanes
 * (lsolve_lanes.c): L is simplicial, compressed columns with the diagonal
 * first (Lp [n+1], Li, Lx borrowed: they must outlive the object). The
 * split follows the elimination tree; results are the same bits for any
 * thread count. */
typedef struct lsolve_lanes lsolve_lanes;
ump_status lsolve_lanes_build(ump_idx n, const int *Lp, const int *Li, const double *Lx, lsolve_lanes **out,
                              ump_err *err);
/* y [n]: in b, out L^-T L^-1 b */
void lsolve_lanes_solve(const lsolve_lanes *z, double *y);
/* entries of L in lane 0, lane 1 and the serial top */
void lsolve_lanes_work(const lsolve_lanes *z, size_t work[3]);
void lsolve_lanes_free(lsolve_lanes **z);

/* BiCGSTAB workspace for row matrices (lsolve_rows.c); grows with the
 * largest system served. Deterministic for any OpenMP thread count. */
typedef struct lsolve_rows lsolve_rows;
ump_status lsolve_rows_create(lsolve_rows **out, ump_err *err);
void lsolve_rows_free(lsolve_rows **k);
/* Build the preconditioner of A (ILU(0) of its diagonal blocks of
 * LSOLVE_ILU_BLOCK rows, Jacobi, or none). UMP_ERR_INPUT if a row lacks its
 * diagonal or its columns are not strictly increasing; UMP_ERR_SINGULAR on a
 * zero pivot. */
ump_status lsolve_rows_setup(lsolve_rows *k, const lsolve_csr *A, lsolve_pc pc, ump_err *err);
/* Solve A x[r] = b[r], r < nrhs <= LSOLVE_MAX_RHS, each from its warm start
 * x[r], to relative residual tol or maxit iterations, with the
 * preconditioner of the last lsolve_rows_setup (same A). The systems iterate
 * in lockstep, sharing every sweep over A; each gets exactly the iterates of
 * a separate solve. st[r] as lsolve_bicgstab's. */
ump_status lsolve_rows_bicgstab(lsolve_rows *k, const lsolve_csr *A, int nrhs, const double *const *b,
                                double *const *x, double tol, int maxit, lsolve_stats *st, ump_err *err);

/* Preconditioned conjugate gradients (Hestenes & Stiefel 1952) on a
 * symmetric positive definite A, from the warm start x, to relative
 * residual tol or maxit iterations, with the preconditioner of the last
 * lsolve_rows_setup (Jacobi or none: ILU0 is refused, it is not
 * symmetric). The same deterministic reductions as BiCGSTAB (any thread
 * count, the same bits). st as lsolve_bicgstab's; converged -1 when (p, Ap)
 * is not positive (A not definite) or not finite. */
ump_status lsolve_rows_cg(lsolve_rows *k, const lsolve_csr *A, const double *b, double *x, double tol, int maxit,
                          lsolve_stats *st, ump_err *err);
/* lsolve_rows_cg with the preconditioner fn(ctx, r, z): z = M^-1 r, M
 * symmetric positive definite, given by the caller (r, z of the order of A;
 * r must not be changed). NULL: the one of lsolve_rows_setup, which must
 * still have been called for A's order. */
ump_status lsolve_rows_cg_pc(lsolve_rows *k, const lsolve_csr *A, const double *b, double *x, double tol, int maxit,
                             lsolve_pc_fn fn, void *ctx, lsolve_stats *st, ump_err *err);

#endif
