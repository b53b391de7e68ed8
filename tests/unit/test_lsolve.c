/* SPDX-License-Identifier: GPL-3.0-or-later
 * test_lsolve.c -- sparse assembly, the three direct solvers against each
 * other and against known solutions, refactorization, singular matrices,
 * BiCGSTAB with each preconditioner, and a differential test (random sparse
 * matrices, direct vs iterative).
 */
#include "testutil_lsolve.h"

#include <omp.h>

/* xorshift64*: reproducible pseudo-random numbers in [0, 1) */
typedef struct rng {
    uint64_t s;
} rng;
static double rnd(rng *r)
{
    r->s ^= r->s >> 12;
    r->s ^= r->s << 25;
    r->s ^= r->s >> 27;
    return (double)((r->s * 2685821657736338717ULL) >> 11) * (1.0 / 9007199254740992.0);
}

static lsolve_mat *from_trip(lsolve_trip *t)
{
    lsolve_mat *A = NULL;
    ump_err err;
    if (lsolve_trip_to_mat(t, &A, &err) != UMP_OK)
        fail_msg("%s", err.msg);
    return A;
}

static lsolve_mat *from_dense(int n, const double *d)
{
    lsolve_trip t;
    ump_err err;
    assert_int_equal(lsolve_trip_init(&t, n, 0, &err), UMP_OK);
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++)
            if (d[i * n + j] != 0.0)
                assert_int_equal(lsolve_trip_add(&t, i, j, d[i * n + j], &err), UMP_OK);
    lsolve_mat *A = from_trip(&t);
    lsolve_trip_free(&t);
    return A;
}

static double norm1(int n, const double *x)
{
    double s = 0;
    for (int i = 0; i < n; i++)
        s += fabs(x[i]);
    return s;
}

static double relres(const lsolve_mat *A, const double *x, const double *b)
{
    int n = A->n;
    double *y = malloc(sizeof(double) * (size_t)n), rr = 0, bb = 0;
    lsolve_mat_mult(A, x, y);
    for (int i = 0; i < n; i++) {
        rr += (b[i] - y[i]) * (b[i] - y[i]);
        bb += b[i] * b[i];
    }
    free(y);
    return sqrt(rr / bb);
}

static void solve_with(const lsolve_mat *A, lsolve_kind kind, const double *b, double *x)
{
    lsolve *s = NULL;
    ump_err err;
    if (lsolve_factor(A, kind, &s, &err) != UMP_OK)
        fail_msg("%s", err.msg);
    if (lsolve_solve(s, b, x, &err) != UMP_OK)
        fail_msg("%s", err.msg);
    lsolve_free(&s);
    assert_null(s);
}

static void test_triplets(void **state)
{
    (void)state;
    lsolve_trip t;
    ump_err err;
    assert_int_equal(lsolve_trip_init(&t, 3, 1, &err), UMP_OK);
    /* out of order, duplicates, an explicit zero, and growth past the hint */
    double tr[][3] = {{2, 2, 1}, {0, 0, 4}, {1, 0, -1}, {0, 0, 1}, {2, 0, 3}, {0, 2, 0},
                      {1, 1, 5}, {2, 2, 1}, {1, 0, -1}, {0, 1, 7}, {2, 2, 1}, {1, 1, 0},
                      {2, 1, 2}, {0, 0, 0}, {1, 2, 6}, {2, 0, -3}, {2, 1, 1}, {0, 1, 1}};
    for (size_t k = 0; k < sizeof tr / sizeof tr[0]; k++)
        assert_int_equal(lsolve_trip_add(&t, (ump_idx)tr[k][0], (ump_idx)tr[k][1], tr[k][2], &err),
                         UMP_OK);
    assert_int_equal(lsolve_trip_add(&t, 3, 0, 1.0, &err), UMP_ERR_INPUT);
    assert_non_null(strstr(err.msg, "(3, 0)"));
    assert_int_equal(lsolve_trip_add(&t, 0, -1, 1.0, &err), UMP_ERR_INPUT);
    lsolve_mat *A = from_trip(&t);
    /* dense: [5 8 0; -2 5 6; 0 3 3], with (0,2) and (2,0) explicit zeros */
    ump_idx Ap[] = {0, 3, 6, 9};
    ump_idx Ai[] = {0, 1, 2, 0, 1, 2, 0, 1, 2};
    double Ax[] = {5, -2, 0, 8, 5, 3, 0, 6, 3};
    assert_memory_equal(A->Ap, Ap, sizeof Ap);
    assert_memory_equal(A->Ai, Ai, sizeof Ai);
    for (int p = 0; p < 9; p++)
        TU_CLOSE(A->Ax[p], Ax[p], 0);
    double x[] = {1, 2, 3}, y[3];
    lsolve_mat_mult(A, x, y);
    TU_CLOSE(y[0], 21, 0);
    TU_CLOSE(y[1], 26, 0);
    TU_CLOSE(y[2], 15, 0);
    assert_false(lsolve_mat_is_symmetric(A, 1e-12));
    lsolve_mat_free(&A);
    assert_null(A);
    lsolve_mat_free(&A); /* NULL is a no-op */
    /* clear keeps storage; a symmetric matrix */
    lsolve_trip_clear(&t);
    assert_int_equal(t.nz, 0);
    assert_int_equal(lsolve_trip_add(&t, 0, 1, 2.0, &err), UMP_OK);
    assert_int_equal(lsolve_trip_add(&t, 1, 0, 2.0 + 1e-15, &err), UMP_OK);
    assert_int_equal(lsolve_trip_add(&t, 2, 2, 1.0, &err), UMP_OK);
    A = from_trip(&t);
    assert_true(lsolve_mat_is_symmetric(A, 1e-12));
    assert_false(lsolve_mat_is_symmetric(A, 0.0));
    lsolve_mat_free(&A);
    lsolve_trip_free(&t);
    /* empty matrix */
    assert_int_equal(lsolve_trip_init(&t, 0, 0, &err), UMP_OK);
    A = from_trip(&t);
    assert_int_equal(A->n, 0);
    assert_int_equal(A->Ap[0], 0);
    lsolve *s = NULL;
    assert_int_equal(lsolve_factor(A, LSOLVE_UMFPACK, &s, &err), UMP_ERR_INPUT);
    lsolve_mat_free(&A);
    lsolve_trip_free(&t);
}

/* 4 x 4 systems with hand-checkable solutions */
static void test_small_known(void **state)
{
    (void)state;
    /* nonsymmetric, needs pivoting (zero (0,0)) */
    double d[] = {0, 2, 0, 1,
                  3, 1, 0, 0,
                  0, 1, 4, 1,
                  1, 0, 2, 5};
    double xe[] = {1, -2, 3, -4};
    double b[4], x[4];
    for (int i = 0; i < 4; i++) {
        b[i] = 0;
        for (int j = 0; j < 4; j++)
            b[i] += d[i * 4 + j] * xe[j];
    }
    lsolve_mat *A = from_dense(4, d);
    lsolve_kind kinds[] = {LSOLVE_UMFPACK, LSOLVE_KLU, LSOLVE_AUTO};
    for (int k = 0; k < 3; k++) {
        memset(x, 0, sizeof x);
        solve_with(A, kinds[k], b, x);
        for (int i = 0; i < 4; i++)
            TU_CLOSE(x[i], xe[i], 1e-14);
    }
    /* CHOLMOD refuses a nonsymmetric matrix */
    lsolve *s = NULL;
    ump_err err;
    assert_int_equal(lsolve_factor(A, LSOLVE_CHOLMOD, &s, &err), UMP_ERR_INPUT);
    assert_non_null(strstr(err.msg, "CHOLMOD"));
    assert_non_null(strstr(err.msg, "not symmetric"));
    assert_null(s);
    lsolve_mat_free(&A);

    /* SPD, then its negative: every solver, AUTO -> CHOLMOD */
    double sp[] = {4, 1, 0, 1,
                   1, 5, 2, 0,
                   0, 2, 6, 1,
                   1, 0, 1, 3};
    for (int sign = 1; sign >= -1; sign -= 2) {
        double ds[16];
        for (int i = 0; i < 16; i++)
            ds[i] = sign * sp[i];
        for (int i = 0; i < 4; i++) {
            b[i] = 0;
            for (int j = 0; j < 4; j++)
                b[i] += ds[i * 4 + j] * xe[j];
        }
        A = from_dense(4, ds);
        assert_true(lsolve_mat_is_symmetric(A, 0.0));
        lsolve_kind all[] = {LSOLVE_UMFPACK, LSOLVE_KLU, LSOLVE_CHOLMOD};
        for (int k = 0; k < 3; k++) {
            solve_with(A, all[k], b, x);
            for (int i = 0; i < 4; i++)
                TU_CLOSE(x[i], xe[i], 1e-14);
        }
        assert_int_equal(lsolve_factor(A, LSOLVE_AUTO, &s, &err), UMP_OK);
        assert_string_equal(lsolve_name(s), "CHOLMOD");
        assert_true(lsolve_factor_nnz(s) >= 4);
        assert_int_equal(lsolve_solve(s, b, x, &err), UMP_OK);
        for (int i = 0; i < 4; i++)
            TU_CLOSE(x[i], xe[i], 1e-14);
        lsolve_free(&s);
        lsolve_mat_free(&A);
    }
    /* symmetric indefinite with a positive diagonal: AUTO falls back to UMFPACK */
    double ind[] = {1, 2, 0, 0,
                    2, 1, 0, 0,
                    0, 0, 1, 0,
                    0, 0, 0, 1};
    A = from_dense(4, ind);
    assert_int_equal(lsolve_factor(A, LSOLVE_AUTO, &s, &err), UMP_OK);
    assert_string_equal(lsolve_name(s), "UMFPACK");
    lsolve_free(&s);
    assert_int_equal(lsolve_factor(A, LSOLVE_CHOLMOD, &s, &err), UMP_ERR_SINGULAR);
    assert_non_null(strstr(err.msg, "CHOLMOD"));
    assert_non_null(strstr(err.msg, "not positive definite"));
    lsolve_mat_free(&A);
}

/* the three direct solvers agree on a 2-D Laplacian (and its negative) */
static void test_direct_agree(void **state)
{
    (void)state;
    int m = 30, n = m * m;
    double *b = malloc(sizeof(double) * n), *x[3];
    rng r = {12345};
    for (int i = 0; i < n; i++)
        b[i] = rnd(&r) - 0.5;
    for (double s = 1; s >= -1; s -= 2) {
        lsolve_mat *A = tu_grid_laplacian(m, s, 0.0);
        lsolve_kind all[] = {LSOLVE_UMFPACK, LSOLVE_KLU, LSOLVE_CHOLMOD};
        for (int k = 0; k < 3; k++) {
            x[k] = malloc(sizeof(double) * n);
            solve_with(A, all[k], b, x[k]);
            assert_true(relres(A, x[k], b) < 1e-14);
        }
        for (int i = 0; i < n; i++) {
            TU_CLOSE(x[1][i], x[0][i], 1e-12);
            TU_CLOSE(x[2][i], x[0][i], 1e-12);
        }
        for (int k = 0; k < 3; k++)
            free(x[k]);
        lsolve_mat_free(&A);
    }
    free(b);
}

/* CHOLMOD's solves in two lanes (lsolve_lanes.c): the 5-point Laplacian's
 * elimination tree splits into two balanced lanes with a small serial top;
 * the solution equals UMFPACK's, and 1 and 2 threads give the same bits.
 * A chain (tridiagonal: no two independent subtrees) and a forest (two
 * decoupled blocks) are solved correctly too. */
static void test_cholmod_lanes(void **state)
{
    (void)state;
    int m = 60, n = m * m;
    double *b = malloc(sizeof(double) * n), *x0 = malloc(sizeof(double) * n),
           *x1 = malloc(sizeof(double) * n), *x2 = malloc(sizeof(double) * n);
    rng r = {777};
    for (int i = 0; i < n; i++)
        b[i] = rnd(&r) - 0.5;
    lsolve_mat *A = tu_grid_laplacian(m, -1, 0.0);
    lsolve *s = NULL;
    ump_err err;
    assert_int_equal(lsolve_factor(A, LSOLVE_CHOLMOD, &s, &err), UMP_OK);
    size_t w[3];
    assert_true(lsolve_lane_work(s, w));
    size_t tot = w[0] + w[1] + w[2];
    assert_int_equal(tot, lsolve_factor_nnz(s));
    double big = (double)(w[0] > w[1] ? w[0] : w[1]), lanes = (double)(w[0] + w[1]);
    assert_true(big <= 0.53 * lanes);          /* balanced to 3 % */
    assert_true((double)w[2] <= 0.15 * (double)tot); /* the serial top is small */
    int nt = omp_get_max_threads();
    omp_set_num_threads(1);
    assert_int_equal(lsolve_solve(s, b, x1, &err), UMP_OK);
    omp_set_num_threads(2);
    assert_int_equal(lsolve_solve(s, b, x2, &err), UMP_OK);
    omp_set_num_threads(nt);
    assert_memory_equal(x1, x2, sizeof(double) * (size_t)n);
    solve_with(A, LSOLVE_UMFPACK, b, x0);
    for (int i = 0; i < n; i++)
        TU_CLOSE(x1[i], x0[i], 1e-12);
    assert_true(relres(A, x1, b) < 1e-14);
    lsolve_free(&s);
    lsolve_mat_free(&A);
    /* a diagonal matrix (n roots, no tree): split in index order, exact */
    {
        int nd = 20000;
        lsolve_trip t;
        assert_int_equal(lsolve_trip_init(&t, nd, (size_t)nd, &err), UMP_OK);
        for (int i = 0; i < nd; i++)
            assert_int_equal(lsolve_trip_add(&t, i, i, 2.0 + (i % 7), &err), UMP_OK);
        lsolve_mat *D = from_trip(&t);
        lsolve_trip_free(&t);
        double *bd = malloc(sizeof(double) * nd), *xd = malloc(sizeof(double) * nd);
        for (int i = 0; i < nd; i++)
            bd[i] = 1.0 + i;
        assert_int_equal(lsolve_factor(D, LSOLVE_CHOLMOD, &s, &err), UMP_OK);
        assert_true(lsolve_lane_work(s, w));
        assert_true(w[0] + w[1] == (size_t)nd && w[2] == 0);
        assert_int_equal(lsolve_solve(s, bd, xd, &err), UMP_OK);
        for (int i = 0; i < nd; i++)
            TU_CLOSE(xd[i], bd[i] / (2.0 + (i % 7)), 1e-15);
        lsolve_free(&s);
        lsolve_mat_free(&D);
        free(bd);
        free(xd);
    }
    /* chain and forest */
    int k = 200;
    double *d = calloc((size_t)k * k, sizeof(double));
    for (int forest = 0; forest < 2; forest++) {
        memset(d, 0, sizeof(double) * (size_t)k * k);
        for (int i = 0; i < k; i++) {
            d[i * k + i] = 2.5;
            if (i + 1 < k && !(forest && i + 1 == k / 2)) {
                d[i * k + i + 1] = -1;
                d[(i + 1) * k + i] = -1;
            }
        }
        lsolve_mat *C = from_dense(k, d);
        assert_int_equal(lsolve_factor(C, LSOLVE_CHOLMOD, &s, &err), UMP_OK);
        assert_int_equal(lsolve_solve(s, b, x1, &err), UMP_OK);
        solve_with(C, LSOLVE_UMFPACK, b, x0);
        for (int i = 0; i < k; i++)
            TU_CLOSE(x1[i], x0[i], 1e-12);
        lsolve_free(&s);
        lsolve_mat_free(&C);
    }
    free(d);
    free(b);
    free(x0);
    free(x1);
    free(x2);
}

/* new values on the same pattern; a different pattern is refused */
/* The symmetric product (rows in parallel) gives lsolve_mat_mult's bits on
 * 1 and 2 threads: a 90x90 Laplacian (n = 8100 > the parallel threshold)
 * with random symmetric values and random x. */
static void test_mult_sym(void **state)
{
    (void)state;
    int m = 90, n = m * m;
    lsolve_mat *A = tu_grid_laplacian(m, -1, 0.0);
    rng r = {4242};
    for (ump_idx j = 0; j < A->n; j++)
        for (ump_idx p = A->Ap[j]; p < A->Ap[j + 1]; p++) {
            ump_idx i = A->Ai[p];
            if (i > j)
                continue;
            double v = rnd(&r) - 0.5; /* the same value at (i, j) and (j, i) */
            A->Ax[p] = v;
            for (ump_idx q = A->Ap[i]; q < A->Ap[i + 1]; q++)
                if (A->Ai[q] == j)
                    A->Ax[q] = v;
        }
    assert_true(lsolve_mat_is_symmetric(A, 0.0));
    double *x = malloc(sizeof(double) * n), *y0 = malloc(sizeof(double) * n),
           *y1 = malloc(sizeof(double) * n), *y2 = malloc(sizeof(double) * n);
    for (int i = 0; i < n; i++)
        x[i] = rnd(&r) * 100.0 - 50.0;
    lsolve_mat_mult(A, x, y0);
    int nt = omp_get_max_threads();
    omp_set_num_threads(1);
    lsolve_mat_mult_sym(A, x, y1);
    omp_set_num_threads(2);
    lsolve_mat_mult_sym(A, x, y2);
    omp_set_num_threads(nt);
    assert_memory_equal(y0, y1, sizeof(double) * (size_t)n);
    assert_memory_equal(y0, y2, sizeof(double) * (size_t)n);
    free(x);
    free(y0);
    free(y1);
    free(y2);
    lsolve_mat_free(&A);
}

static void test_refactor(void **state)
{
    (void)state;
    int m = 12, n = m * m;
    lsolve_mat *A = tu_grid_laplacian(m, -1, 0.0);
    lsolve_mat *A2 = tu_grid_laplacian(m, -1, 0.0);
    for (ump_idx p = 0; p < A2->Ap[n]; p++)
        A2->Ax[p] *= 2.5;            /* still negative definite */
    lsolve_mat *B = tu_grid_laplacian(m + 1, -1, 0.0);
    double *b = malloc(sizeof(double) * n), *x = malloc(sizeof(double) * n),
           *y = malloc(sizeof(double) * n);
    for (int i = 0; i < n; i++)
        b[i] = sin(0.3 * i);
    lsolve_kind all[] = {LSOLVE_UMFPACK, LSOLVE_KLU, LSOLVE_CHOLMOD};
    for (int k = 0; k < 3; k++) {
        lsolve *s = NULL;
        ump_err err;
        assert_int_equal(lsolve_factor(A, all[k], &s, &err), UMP_OK);
        assert_int_equal(lsolve_solve(s, b, x, &err), UMP_OK);
        assert_true(relres(A, x, b) < 1e-14);
        assert_int_equal(lsolve_refactor(s, A2, &err), UMP_OK);
        assert_int_equal(lsolve_solve(s, b, y, &err), UMP_OK);
        assert_true(relres(A2, y, b) < 1e-14);
        for (int i = 0; i < n; i++)
            TU_CLOSE(y[i], x[i] / 2.5, 1e-13);
        assert_int_equal(lsolve_refactor(s, B, &err), UMP_ERR_INPUT);
        assert_non_null(strstr(err.msg, "pattern"));
        assert_non_null(strstr(err.msg, lsolve_name(s)));
        /* back to the first values */
        assert_int_equal(lsolve_refactor(s, A, &err), UMP_OK);
        assert_int_equal(lsolve_solve(s, b, y, &err), UMP_OK);
        for (int i = 0; i < n; i++)
            TU_CLOSE(y[i], x[i], 1e-13);
        lsolve_free(&s);
    }
    free(b);
    free(x);
    free(y);
    lsolve_mat_free(&A);
    lsolve_mat_free(&A2);
    lsolve_mat_free(&B);
}

/* Neumann 5-point Laplacian: singular up to a constant (in exact arithmetic) */
static lsolve_mat *neumann_laplacian(int m)
{
    lsolve_trip t;
    ump_err err;
    assert_int_equal(lsolve_trip_init(&t, m * m, 0, &err), UMP_OK);
    for (int j = 0; j < m; j++)
        for (int i = 0; i < m; i++) {
            int r = j * m + i, nb[4], k = 0;
            if (i > 0) nb[k++] = r - 1;
            if (i < m - 1) nb[k++] = r + 1;
            if (j > 0) nb[k++] = r - m;
            if (j < m - 1) nb[k++] = r + m;
            for (int q = 0; q < k; q++)
                assert_int_equal(lsolve_trip_add(&t, r, nb[q], -1.0, &err), UMP_OK);
            assert_int_equal(lsolve_trip_add(&t, r, r, k, &err), UMP_OK);
        }
    lsolve_mat *A = from_trip(&t);
    lsolve_trip_free(&t);
    return A;
}

static void test_singular(void **state)
{
    (void)state;
    ump_err err;
    lsolve *s = NULL;
    /* exactly singular: column 2 is zero */
    double d[] = {2, 1, 0, 0,
                  1, 3, 0, 1,
                  0, 1, 0, 1,
                  0, 0, 0, 4};
    lsolve_mat *A = from_dense(4, d);
    assert_int_equal(lsolve_factor(A, LSOLVE_UMFPACK, &s, &err), UMP_ERR_SINGULAR);
    assert_non_null(strstr(err.msg, "UMFPACK"));
    assert_non_null(strstr(err.msg, "column 2"));
    assert_null(s);
    assert_int_equal(lsolve_factor(A, LSOLVE_KLU, &s, &err), UMP_ERR_SINGULAR);
    assert_non_null(strstr(err.msg, "KLU"));
    assert_non_null(strstr(err.msg, "column 2"));
    assert_null(s);
    lsolve_mat_free(&A);
    /* exactly singular, full pattern: two equal rows and columns */
    double e[] = {2, 1, 1, 2,
                  1, 2, 1, 1,
                  1, 1, 2, 1,
                  2, 1, 1, 2};
    A = from_dense(4, e);
    lsolve_kind all[] = {LSOLVE_UMFPACK, LSOLVE_KLU, LSOLVE_CHOLMOD, LSOLVE_AUTO};
    const char *names[] = {"UMFPACK", "KLU", "CHOLMOD", "CHOLMOD"};
    for (int k = 0; k < 4; k++) {
        assert_int_equal(lsolve_factor(A, all[k], &s, &err), UMP_ERR_SINGULAR);
        assert_null(s);
        assert_non_null(strstr(err.msg, names[k]));
        assert_non_null(strstr(err.msg, "singular"));
        if (k < 2) /* UMFPACK and KLU report the zero pivot's column */
            assert_non_null(strstr(err.msg, "column 3"));
    }
    lsolve_mat_free(&A);
    /* singular in exact arithmetic only (pure Neumann): a round-off pivot,
     * caught by the condition estimate (CHOLMOD: not positive definite) */
    A = neumann_laplacian(20);
    for (int k = 0; k < 4; k++) {
        ump_status rc = lsolve_factor(A, all[k], &s, &err);
        assert_int_equal(rc, UMP_ERR_SINGULAR);
        assert_null(s);
        /* AUTO: CHOLMOD says not definite, the UMFPACK fallback says singular */
        assert_non_null(strstr(err.msg, k == 3 ? "UMFPACK" : names[k]));
        assert_non_null(strstr(err.msg, k != 2 ? "numerically singular" : "not positive definite"));
        assert_non_null(strstr(err.msg, "column"));
    }
    /* pinning one cell (row and column) makes it regular and well conditioned */
    for (ump_idx j = 0; j < A->n; j++)
        for (ump_idx p = A->Ap[j]; p < A->Ap[j + 1]; p++)
            if ((A->Ai[p] == 0) != (j == 0))
                A->Ax[p] = 0.0;
    for (int k = 0; k < 4; k++) {
        assert_int_equal(lsolve_factor(A, all[k], &s, &err), UMP_OK);
        assert_true(lsolve_condest(s) > 100 && lsolve_condest(s) < 1e5);
        lsolve_free(&s);
    }
    lsolve_mat_free(&A);
    /* NaN refused */
    double nan_d[] = {1, 0, 0, NAN};
    A = from_dense(2, nan_d);
    assert_int_equal(lsolve_factor(A, LSOLVE_KLU, &s, &err), UMP_ERR_INPUT);
    assert_non_null(strstr(err.msg, "NaN"));
    lsolve_mat_free(&A);
}

/* the condition estimate against the exact ||A||_1 ||A^-1||_1 */
static void test_condest(void **state)
{
    (void)state;
    int n = 40;
    rng r = {777};
    double *d = calloc((size_t)n * n, sizeof(double));
    for (int i = 0; i < n; i++) {
        for (int q = 0; q < 4; q++)
            d[i * n + (int)(rnd(&r) * n)] = rnd(&r) - 0.5;
        d[i * n + i] = 0.3 + rnd(&r);  /* not dominant: condition well above 1 */
    }
    lsolve_mat *A = from_dense(n, d);
    double anorm = 0, ainv = 0, *e = calloc((size_t)n, sizeof(double)), *x = malloc(sizeof(double) * n);
    for (int j = 0; j < n; j++) {
        double c = 0;
        for (int i = 0; i < n; i++)
            c += fabs(d[i * n + j]);
        anorm = fmax(anorm, c);
    }
    lsolve_kind all[] = {LSOLVE_UMFPACK, LSOLVE_KLU};
    for (int k = 0; k < 2; k++) {
        lsolve *s = NULL;
        ump_err err;
        if (lsolve_factor(A, all[k], &s, &err) != UMP_OK)
            fail_msg("%s", err.msg);
        ainv = 0;
        for (int j = 0; j < n; j++) {   /* exact: max column sum of A^-1 */
            e[j] = 1;
            assert_int_equal(lsolve_solve(s, e, x, &err), UMP_OK);
            e[j] = 0;
            ainv = fmax(ainv, norm1(n, x));
        }
        double exact = anorm * ainv, est = lsolve_condest(s);
        printf("    %s: cond_1 exact %.6g, estimate %.6g\n", lsolve_name(s), exact, est);
        assert_true(est <= exact * (1 + 1e-10) && est >= exact / 3);
        lsolve_free(&s);
    }
    lsolve_mat_free(&A);
    free(d);
    free(e);
    free(x);
}

static void bicgstab_case(const lsolve_mat *A, const char *what, int maxit_expect[3])
{
    int n = A->n;
    double *b = malloc(sizeof(double) * n), *xd = malloc(sizeof(double) * n),
           *x = malloc(sizeof(double) * n);
    for (int i = 0; i < n; i++)
        b[i] = cos(0.1 * i) + 0.5;
    solve_with(A, LSOLVE_UMFPACK, b, xd);
    lsolve_krylov *k = NULL;
    ump_err err;
    assert_int_equal(lsolve_krylov_create(n, &k, &err), UMP_OK);
    lsolve_pc pcs[] = {LSOLVE_PC_NONE, LSOLVE_PC_JACOBI, LSOLVE_PC_ILU0};
    const char *names[] = {"none", "Jacobi", "ILU(0)"};
    int its[3];
    for (int q = 0; q < 3; q++) {
        lsolve_stats st;
        memset(x, 0, sizeof(double) * n);
        assert_int_equal(lsolve_bicgstab(k, A, pcs[q], b, x, 1e-12, 2000, &st, &err), UMP_OK);
        assert_int_equal(st.converged, 1);
        TU_CLOSE(st.res0, 1.0, 1e-14);        /* from x = 0 */
        assert_true(st.res <= 1e-12);
        assert_true(relres(A, x, b) <= 1e-12); /* the reported residual is the true one */
        double emax = 0, xmax = 0;
        for (int i = 0; i < n; i++) {
            emax = fmax(emax, fabs(x[i] - xd[i]));
            xmax = fmax(xmax, fabs(xd[i]));
        }
        assert_true(emax <= 1e-9 * xmax);
        its[q] = st.iterations;
        assert_true(its[q] <= maxit_expect[q]);
        printf("    BiCGSTAB %-8s on %s (n = %d): %3d iterations, residual %.2e\n", names[q], what, n,
               st.iterations, st.res);
        /* warm start from the solution: no iteration */
        assert_int_equal(lsolve_bicgstab(k, A, pcs[q], b, x, 1e-10, 2000, &st, &err), UMP_OK);
        assert_int_equal(st.iterations, 0);
        assert_int_equal(st.converged, 1);
        assert_true(st.res0 <= 1e-10);
    }
    assert_true(its[2] < its[1]);
    /* too few iterations: reported, not an error */
    lsolve_stats st;
    memset(x, 0, sizeof(double) * n);
    assert_int_equal(lsolve_bicgstab(k, A, LSOLVE_PC_JACOBI, b, x, 1e-14, 2, &st, &err), UMP_OK);
    assert_int_equal(st.converged, 0);
    assert_int_equal(st.iterations, 2);
    assert_true(isfinite(st.res) && st.res > 1e-14); /* BiCGSTAB is not monotone */
    lsolve_krylov_free(&k);
    assert_null(k);
    free(b);
    free(xd);
    free(x);
}

static void test_bicgstab(void **state)
{
    (void)state;
    /* nonsymmetric, diagonally dominant (upwind convection-diffusion), rows
     * scaled by 1..100 so that Jacobi has something to do */
    lsolve_mat *A = tu_grid_laplacian(40, 1, 2.0);
    for (ump_idx p = 0; p < A->Ap[A->n]; p++)
        A->Ax[p] *= pow(10.0, (A->Ai[p] % 5) / 2.0);
    int lim1[] = {1000, 300, 100};
    bicgstab_case(A, "convection-diffusion", lim1);
    lsolve_mat_free(&A);
    /* negative definite 2-D Laplacian */
    A = tu_grid_laplacian(40, -1, 0.0);
    int lim2[] = {400, 400, 150};
    bicgstab_case(A, "Laplacian", lim2);
    lsolve_mat_free(&A);
}

/* ILU(0) of a tridiagonal matrix is its exact LU: one iteration */
static void test_ilu0_exact(void **state)
{
    (void)state;
    int n = 200;
    lsolve_trip t;
    ump_err err;
    assert_int_equal(lsolve_trip_init(&t, n, 0, &err), UMP_OK);
    for (int i = 0; i < n; i++) {
        assert_int_equal(lsolve_trip_add(&t, i, i, 2.0 + 0.01 * i, &err), UMP_OK);
        if (i > 0)
            assert_int_equal(lsolve_trip_add(&t, i, i - 1, -1.0, &err), UMP_OK);
        if (i < n - 1)
            assert_int_equal(lsolve_trip_add(&t, i, i + 1, -0.7, &err), UMP_OK);
    }
    lsolve_mat *A = from_trip(&t);
    lsolve_trip_free(&t);
    double *b = malloc(sizeof(double) * n), *x = calloc((size_t)n, sizeof(double));
    for (int i = 0; i < n; i++)
        b[i] = 1.0 + (i % 7);
    lsolve_krylov *k = NULL;
    assert_int_equal(lsolve_krylov_create(n, &k, &err), UMP_OK);
    lsolve_stats st;
    assert_int_equal(lsolve_bicgstab(k, A, LSOLVE_PC_ILU0, b, x, 1e-13, 10, &st, &err), UMP_OK);
    assert_int_equal(st.converged, 1);
    assert_int_equal(st.iterations, 1);
    /* zero right-hand side: x = 0 exactly */
    memset(b, 0, sizeof(double) * n);
    x[3] = 5;
    assert_int_equal(lsolve_bicgstab(k, A, LSOLVE_PC_ILU0, b, x, 1e-13, 10, &st, &err), UMP_OK);
    assert_int_equal(st.converged, 1);
    TU_CLOSE(x[3], 0, 0);
    /* a second right-hand side reuses the ILU(0) factors: same solution as a fresh solve */
    {
        double *b2 = calloc((size_t)n, sizeof *b2), *x2 = calloc((size_t)n, sizeof *x2), *x3 = calloc((size_t)n, sizeof *x3);
        for (int i = 0; i < n; i++)
            b2[i] = cos(0.3 * (double)i);
        lsolve_krylov *k3 = NULL;
        assert_int_equal(lsolve_krylov_create(n, &k3, &err), UMP_OK);
        assert_int_equal(lsolve_bicgstab_again(k3, A, LSOLVE_PC_ILU0, b2, x2, 1e-13, 10, &st, &err),
                         UMP_ERR_INPUT); /* nothing built yet */
        assert_int_equal(lsolve_bicgstab(k3, A, LSOLVE_PC_ILU0, b, x, 1e-13, 10, &st, &err), UMP_OK);
        assert_int_equal(lsolve_bicgstab_again(k3, A, LSOLVE_PC_ILU0, b2, x2, 1e-13, 10, &st, &err), UMP_OK);
        assert_int_equal(st.converged, 1);
        assert_int_equal(lsolve_bicgstab(k3, A, LSOLVE_PC_ILU0, b2, x3, 1e-13, 10, &st, &err), UMP_OK);
        for (int i = 0; i < n; i++)
            TU_CLOSE(x2[i], x3[i], 1e-11);
        lsolve_krylov_free(&k3);
        free(b2);
        free(x2);
        free(x3);
    }
    /* a larger workspace serves a smaller matrix (the particle count varies);
     * a smaller one is refused */
    lsolve_krylov *k2 = NULL;
    assert_int_equal(lsolve_krylov_create(n + 7, &k2, &err), UMP_OK);
    assert_int_equal(lsolve_bicgstab(k2, A, LSOLVE_PC_ILU0, b, x, 1e-13, 10, &st, &err), UMP_OK);
    assert_int_equal(st.converged, 1);
    lsolve_krylov_free(&k2);
    assert_int_equal(lsolve_krylov_create(n - 1, &k2, &err), UMP_OK);
    assert_int_equal(lsolve_bicgstab(k2, A, LSOLVE_PC_NONE, b, x, 1e-13, 10, &st, &err), UMP_ERR_INPUT);
    lsolve_krylov_free(&k2);
    lsolve_mat_free(&A);
    /* zero diagonal: Jacobi and ILU(0) refuse */
    double d[] = {0, 1, 1, 0};
    A = from_dense(2, d);
    b[0] = b[1] = 1;
    lsolve_krylov *k3 = NULL;
    assert_int_equal(lsolve_krylov_create(2, &k3, &err), UMP_OK);
    assert_int_equal(lsolve_bicgstab(k3, A, LSOLVE_PC_JACOBI, b, x, 1e-13, 10, &st, &err),
                     UMP_ERR_SINGULAR);
    assert_non_null(strstr(err.msg, "row 0"));
    assert_int_equal(lsolve_bicgstab(k3, A, LSOLVE_PC_ILU0, b, x, 1e-13, 10, &st, &err),
                     UMP_ERR_SINGULAR);
    lsolve_krylov_free(&k3);
    lsolve_mat_free(&A);
    lsolve_krylov_free(&k);
    free(b);
    free(x);
}

/* Differential test: random sparse diagonally dominant nonsymmetric
 * matrices of growing size, UMFPACK vs KLU vs BiCGSTAB(ILU0, Jacobi), and a
 * changing pattern through one Krylov workspace. */
static void test_random_differential(void **state)
{
    (void)state;
    rng r = {0x9e3779b97f4a7c15ULL};
    int nmax = 600;
    lsolve_krylov *k = NULL;
    ump_err err;
    assert_int_equal(lsolve_krylov_create(nmax, &k, &err), UMP_OK);
    double *b = malloc(sizeof(double) * nmax), *xu = malloc(sizeof(double) * nmax),
           *xk = malloc(sizeof(double) * nmax), *xi = malloc(sizeof(double) * nmax),
           *rowsum = malloc(sizeof(double) * nmax);
    int ncase = 0;
    for (int trial = 0; trial < 30; trial++) {
        int n = trial % 3 == 0 ? nmax : 5 + (int)(rnd(&r) * (nmax - 5));
        int per = 1 + (int)(rnd(&r) * 8);
        lsolve_trip t;
        assert_int_equal(lsolve_trip_init(&t, n, 0, &err), UMP_OK);
        for (int i = 0; i < n; i++)
            rowsum[i] = 0;
        for (int i = 0; i < n; i++)
            for (int q = 0; q < per; q++) {
                int j = (int)(rnd(&r) * n);
                if (j == i)
                    continue;
                double v = rnd(&r) - 0.5;
                assert_int_equal(lsolve_trip_add(&t, i, j, v, &err), UMP_OK);
                rowsum[i] += fabs(v);
            }
        for (int i = 0; i < n; i++)
            assert_int_equal(lsolve_trip_add(&t, i, i, (rnd(&r) < 0.5 ? -1 : 1) * (1.2 * rowsum[i] + 0.1),
                                             &err), UMP_OK);
        lsolve_mat *A = from_trip(&t);
        lsolve_trip_free(&t);
        for (int i = 0; i < n; i++)
            b[i] = rnd(&r) - 0.5;
        solve_with(A, LSOLVE_UMFPACK, b, xu);
        solve_with(A, LSOLVE_KLU, b, xk);
        /* BiCGSTAB needs a workspace of the matrix order */
        lsolve_krylov *kn = k;
        if (n != nmax)
            assert_int_equal(lsolve_krylov_create(n, &kn, &err), UMP_OK);
        lsolve_pc pcs[] = {LSOLVE_PC_ILU0, LSOLVE_PC_JACOBI};
        for (int q = 0; q < 2; q++) {
            lsolve_stats st;
            memset(xi, 0, sizeof(double) * n);
            assert_int_equal(lsolve_bicgstab(kn, A, pcs[q], b, xi, 1e-13, 1000, &st, &err), UMP_OK);
            assert_int_equal(st.converged, 1);
            double e = 0, s = 0;
            for (int i = 0; i < n; i++) {
                e = fmax(e, fabs(xi[i] - xu[i]));
                s = fmax(s, fabs(xu[i]));
            }
            if (e > 1e-10 * s)
                fail_msg("trial %d (n = %d, %d per row): BiCGSTAB differs from UMFPACK by %g", trial,
                         n, per, e / s);
        }
        for (int i = 0; i < n; i++)
            TU_CLOSE(xk[i], xu[i], 1e-11);
        if (kn != k)
            lsolve_krylov_free(&kn);
        lsolve_mat_free(&A);
        ncase++;
    }
    assert_int_equal(ncase, 30);
    lsolve_krylov_free(&k);
    free(b);
    free(xu);
    free(xk);
    free(xi);
    free(rowsum);
}

/* lsolve_rows: BiCGSTAB on rows, several right-hand sides in lockstep.
 * Random diagonally dominant matrices (the CSR of A is the CSC of A^T, so
 * columns come sorted), n up to 9000 so that ILU(0) spans three blocks of
 * LSOLVE_ILU_BLOCK rows. Asserts: every preconditioner converges to the
 * UMFPACK solution (1e-8 relative, the bound of the residual test); three systems in lockstep give exactly
 * (memcmp) the solutions and iteration counts of three separate solves;
 * a row with unsorted columns is refused. */
static void test_rows_lockstep(void **state)
{
    (void)state;
    rng r = {0x2545f4914f6cdd1dULL};
    ump_err err;
    lsolve_rows *k = NULL;
    assert_int_equal(lsolve_rows_create(&k, &err), UMP_OK);
    int sizes[] = {7, 300, 2500, 9000};
    for (int t = 0; t < 4; t++) {
        int n = sizes[t], per = 6;
        lsolve_trip ta, tt;
        assert_int_equal(lsolve_trip_init(&ta, n, 0, &err), UMP_OK);
        assert_int_equal(lsolve_trip_init(&tt, n, 0, &err), UMP_OK);
        double *rowsum = calloc((size_t)n, sizeof(double));
        for (int i = 0; i < n; i++)
            for (int q = 0; q < per; q++) {
                int j = (i + 1 + (int)(rnd(&r) * 40)) % n; /* near neighbours, as particles sorted by cell */
                if (j == i)
                    continue;
                double v = rnd(&r) - 0.5;
                assert_int_equal(lsolve_trip_add(&ta, i, j, v, &err), UMP_OK);
                assert_int_equal(lsolve_trip_add(&tt, j, i, v, &err), UMP_OK);
                rowsum[i] += fabs(v);
            }
        for (int i = 0; i < n; i++) {
            double d = 1.1 * rowsum[i] + 0.1;
            assert_int_equal(lsolve_trip_add(&ta, i, i, d, &err), UMP_OK);
            assert_int_equal(lsolve_trip_add(&tt, i, i, d, &err), UMP_OK);
        }
        lsolve_mat *A = from_trip(&ta), *AT = from_trip(&tt);
        lsolve_trip_free(&ta);
        lsolve_trip_free(&tt);
        lsolve_csr R = {AT->n, AT->Ap, AT->Ai, AT->Ax}; /* rows of A */
        double *b[3], *x[3], *xs[3], *xu[3];
        for (int q = 0; q < 3; q++) {
            b[q] = malloc(sizeof(double) * n);
            x[q] = malloc(sizeof(double) * n);
            xs[q] = malloc(sizeof(double) * n);
            xu[q] = malloc(sizeof(double) * n);
            for (int i = 0; i < n; i++)
                b[q][i] = q == 2 ? 0.0 : rnd(&r) - 0.5; /* the third: b = 0 */
            solve_with(A, LSOLVE_UMFPACK, b[q], xu[q]);
        }
        lsolve_pc pcs[] = {LSOLVE_PC_NONE, LSOLVE_PC_JACOBI, LSOLVE_PC_ILU0};
        for (int c = 0; c < 3; c++) {
            assert_int_equal(lsolve_rows_setup(k, &R, pcs[c], &err), UMP_OK);
            lsolve_stats st[3], st1;
            for (int q = 0; q < 3; q++)
                for (int i = 0; i < n; i++)
                    x[q][i] = xs[q][i] = 0.01 * i; /* a warm start */
            assert_int_equal(lsolve_rows_bicgstab(k, &R, 3, (const double *const *)b, x, 1e-13, 1000, st, &err),
                             UMP_OK);
            for (int q = 0; q < 3; q++) {
                assert_int_equal(lsolve_rows_bicgstab(k, &R, 1, (const double *const *)&b[q], &xs[q], 1e-13,
                                                      1000, &st1, &err), UMP_OK);
                assert_int_equal(st[q].converged, 1);
                assert_int_equal(st[q].iterations, st1.iterations);
                assert_memory_equal(x[q], xs[q], sizeof(double) * (size_t)n);
                double e = 0, sc = 0;
                for (int i = 0; i < n; i++) {
                    e = fmax(e, fabs(x[q][i] - xu[q][i]));
                    sc = fmax(sc, fabs(xu[q][i]));
                }
                /* relative residual 1e-13 times kappa_inf <= ~70 (row dominance
                 * margin 0.1 rowsum + 0.1) times the 2-norm/inf-norm factor sqrt(n) */
                if (e > 1e-8 * sc && sc > 0)
                    fail_msg("n = %d, preconditioner %d, rhs %d: differs from UMFPACK by %g", n, c, q, e / sc);
                if (q == 2)
                    for (int i = 0; i < n; i++)
                        assert_true(x[q][i] == 0.0); /* b = 0: the exact solution */
            }
        }
        if (n >= 2 && AT->Ap[1] - AT->Ap[0] >= 2) { /* unsorted columns refused */
            ump_idx tmp = AT->Ai[AT->Ap[0]];
            AT->Ai[AT->Ap[0]] = AT->Ai[AT->Ap[0] + 1];
            AT->Ai[AT->Ap[0] + 1] = tmp;
            assert_int_equal(lsolve_rows_setup(k, &R, LSOLVE_PC_JACOBI, &err), UMP_ERR_INPUT);
        }
        for (int q = 0; q < 3; q++) {
            free(b[q]);
            free(x[q]);
            free(xs[q]);
            free(xu[q]);
        }
        free(rowsum);
        lsolve_mat_free(&A);
        lsolve_mat_free(&AT);
    }
    lsolve_rows_free(&k);
}

/* lsolve_mat_from_csr with a size that goes up and down every call (the
 * predictor of adaptive UMPPM): the storage stays bounded by twice the
 * largest matrix and every rebuild is the right matrix. Regression: the
 * capacity used to double whenever n grew, overflowing after ~40 rises. */
static void test_from_csr_fluctuating(void **state)
{
    (void)state;
    ump_err err;
    lsolve_mat *A = ump_alloc_array(1, sizeof *A);
    assert_non_null(A);
    size_t cap = 0;
    enum { NMAX = 41 };
    ump_idx rp[NMAX + 1], ci[3 * NMAX];
    double cv[3 * NMAX], x[NMAX], y[NMAX];
    for (int it = 0; it < 400; it++) {
        ump_idx n = (ump_idx)(it % 2 ? 40 + it % 2 : 30 + it % 7);
        size_t nz = 0;
        rp[0] = 0;
        for (ump_idx i = 0; i < n; i++) { /* tridiagonal, off-diagonals listed first */
            if (i + 1 < n) { ci[nz] = i + 1; cv[nz++] = -1.0 - i; }
            if (i > 0) { ci[nz] = i - 1; cv[nz++] = -2.0; }
            ci[nz] = i;
            cv[nz++] = 4.0 + it;
            rp[i + 1] = (ump_idx)nz;
        }
        assert_int_equal(lsolve_mat_from_csr(A, &cap, n, rp, ci, cv, &err), UMP_OK);
        assert_true(cap <= 2 * 3 * NMAX);
        for (ump_idx i = 0; i < n; i++)
            x[i] = 1.0 + i;
        lsolve_mat_mult(A, x, y);
        for (ump_idx i = 0; i < n; i++) {
            double e = (4.0 + it) * x[i];
            if (i + 1 < n) e += (-1.0 - i) * x[i + 1];
            if (i > 0) e += -2.0 * x[i - 1];
            TU_CLOSE(y[i], e, 1e-12);
        }
    }
    lsolve_mat_free(&A);
}

/* allocation failures in assembly, factorization and the Krylov workspace
 * are reported as UMP_ERR_NOMEM (SuiteSparse's own allocations excepted) */
static void test_out_of_memory(void **state)
{
    (void)state;
    int nfail = 0;
    for (long k = 0;; k++) {
        ump_err err;
        lsolve_trip t = {0, 0, 0, NULL, NULL, NULL};
        lsolve_mat *A = NULL;
        lsolve *s = NULL;
        lsolve_krylov *kr = NULL;
        ump_alloc_fail_after(k);
        ump_status rc = lsolve_trip_init(&t, 50, 4, &err);
        for (int i = 0; i < 50 && rc == UMP_OK; i++) {
            rc = lsolve_trip_add(&t, i, i, 3.0, &err);
            if (rc == UMP_OK && i > 0)
                rc = lsolve_trip_add(&t, i, i - 1, -1.0, &err);
            if (rc == UMP_OK && i > 0)
                rc = lsolve_trip_add(&t, i - 1, i, -1.0, &err);
        }
        if (rc == UMP_OK)
            rc = lsolve_trip_to_mat(&t, &A, &err);
        for (int kind = 1; kind <= 3 && rc == UMP_OK; kind++) {
            rc = lsolve_factor(A, (lsolve_kind)kind, &s, &err);
            lsolve_free(&s);
        }
        if (rc == UMP_OK)
            rc = lsolve_krylov_create(50, &kr, &err);
        if (rc == UMP_OK) {
            double b[50], x[50] = {0};
            lsolve_stats st;
            for (int i = 0; i < 50; i++)
                b[i] = 1;
            rc = lsolve_bicgstab(kr, A, LSOLVE_PC_ILU0, b, x, 1e-10, 100, &st, &err);
        }
        ump_alloc_fail_after(-1);
        lsolve_krylov_free(&kr);
        lsolve_mat_free(&A);
        lsolve_trip_free(&t);
        if (rc == UMP_OK)
            break;
        if (rc != UMP_ERR_NOMEM)
            fail_msg("allocation %ld failing: %s", k, err.msg);
        nfail++;
    }
    assert_true(nfail >= 10);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_triplets),
        cmocka_unit_test(test_small_known),
        cmocka_unit_test(test_direct_agree),
        cmocka_unit_test(test_cholmod_lanes),
        cmocka_unit_test(test_refactor),
        cmocka_unit_test(test_singular),
        cmocka_unit_test(test_condest),
        cmocka_unit_test(test_bicgstab),
        cmocka_unit_test(test_ilu0_exact),
        cmocka_unit_test(test_random_differential),
        cmocka_unit_test(test_rows_lockstep),
        cmocka_unit_test(test_from_csr_fluctuating),
        cmocka_unit_test(test_out_of_memory),
        cmocka_unit_test(test_mult_sym),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
