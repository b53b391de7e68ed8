/* SPDX-License-Identifier: GPL-3.0-or-later
 * test_coarse.c -- the particle solves' coarse level (coarse.c) and the
 * factor it refactorizes every step (lsolve_factor_serial):
 *   - lsolve_factor_serial solves as lsolve_factor does (CHOLMOD with its
 *     own order and solves, KLU), and after a refactor with new values;
 *   - a refactor and the solves allocate nothing: every allocation, ours
 *     (ump_alloc_fail_after(0) makes one fail) and SuiteSparse's (counted
 *     through SuiteSparse_config), is zero;
 *   - coarse_add is P Ac^-1 P^T r, Ac = P^T A P on the squares of side H,
 *     checked against a dense Gaussian elimination of the same Ac;
 *   - particles that move within the squares already reached keep the
 *     pattern (no rebuild, no allocation in coarse_build and coarse_add);
 *     reaching new squares rebuilds it once.
 */
#include "testutil_lsolve.h"
#include "umppm/coarse.h"

#include <SuiteSparse_config.h>

/* SuiteSparse's allocations, counted */
static long ss_allocs;
static void *count_malloc(size_t n)
{
    ss_allocs++;
    return malloc(n);
}
static void *count_calloc(size_t n, size_t s)
{
    ss_allocs++;
    return calloc(n, s);
}
static void *count_realloc(void *p, size_t n)
{
    ss_allocs++;
    return realloc(p, n);
}
static void count_on(void)
{
    SuiteSparse_config.malloc_func = count_malloc;
    SuiteSparse_config.calloc_func = count_calloc;
    SuiteSparse_config.realloc_func = count_realloc;
}

static void test_serial_factor(void **state)
{
    (void)state;
    int m = 15, n = m * m;
    struct {
        lsolve_kind kind;
        double s, conv;
    } cases[] = {{LSOLVE_CHOLMOD, -1, 0}, {LSOLVE_CHOLMOD, 1, 0}, {LSOLVE_KLU, 1, 0.5}};
    double *b = malloc(sizeof *b * (size_t)n), *x = malloc(sizeof *x * (size_t)n),
           *y = malloc(sizeof *y * (size_t)n), *z = malloc(sizeof *z * (size_t)n);
    for (int i = 0; i < n; i++)
        b[i] = sin(0.37 * i) + 0.1 * i / n;
    for (int c = 0; c < 3; c++) {
        lsolve_mat *A = tu_grid_laplacian(m, cases[c].s, cases[c].conv);
        lsolve_mat *A2 = tu_grid_laplacian(m, cases[c].s, cases[c].conv);
        for (ump_idx j = 0; j < n; j++) /* other values, the same pattern, still diagonally dominant */
            for (ump_idx p = A2->Ap[j]; p < A2->Ap[j + 1]; p++)
                A2->Ax[p] *= A2->Ai[p] == j ? 1.25 : 1 + 0.2 * sin(0.1 * p);
        /* symmetric values for CHOLMOD: A2 = (A2 + A2^T) / 2 entrywise */
        if (cases[c].kind == LSOLVE_CHOLMOD)
            for (ump_idx j = 0; j < n; j++)
                for (ump_idx p = A2->Ap[j]; p < A2->Ap[j + 1]; p++) {
                    ump_idx i = A2->Ai[p];
                    if (i < j)
                        for (ump_idx q = A2->Ap[i]; q < A2->Ap[i + 1]; q++)
                            if (A2->Ai[q] == j)
                                A2->Ax[q] = A2->Ax[p];
                }
        lsolve *ref = NULL, *ser = NULL, *ref2 = NULL;
        ump_err err;
        assert_int_equal(lsolve_factor(A, cases[c].kind, &ref, &err), UMP_OK);
        assert_int_equal(lsolve_factor(A2, cases[c].kind, &ref2, &err), UMP_OK);
        ss_allocs = 0;
        assert_int_equal(lsolve_factor_serial(A, cases[c].kind, &ser, &err), UMP_OK);
        assert_true(ss_allocs > 0); /* the counting reaches SuiteSparse */
        assert_string_equal(lsolve_name(ser), lsolve_name(ref));
        assert_int_equal(lsolve_solve(ref, b, x, &err), UMP_OK);
        assert_int_equal(lsolve_solve(ser, b, y, &err), UMP_OK);
        for (int i = 0; i < n; i++)
            TU_CLOSE(y[i], x[i], 1e-12 * (1 + fabs(x[i])));
        /* a refactor and its solves: no allocation at all */
        ss_allocs = 0;
        ump_alloc_fail_after(0);
        ump_status rc = lsolve_refactor(ser, A2, &err);
        ump_status rs = rc == UMP_OK ? lsolve_solve(ser, b, y, &err) : rc;
        ump_alloc_fail_after(-1);
        assert_int_equal(rc, UMP_OK);
        assert_int_equal(rs, UMP_OK);
        assert_int_equal(ss_allocs, 0);
        assert_int_equal(lsolve_solve(ref2, b, z, &err), UMP_OK);
        for (int i = 0; i < n; i++)
            TU_CLOSE(y[i], z[i], 1e-12 * (1 + fabs(z[i])));
        lsolve_free(&ref);
        lsolve_free(&ref2);
        lsolve_free(&ser);
        lsolve_mat_free(&A);
        lsolve_mat_free(&A2);
    }
    free(b);
    free(x);
    free(y);
    free(z);
}

/* particles on a jittered lattice of spacing 1 in [0, nx) x [0, ny), the
 * symmetric kernel matrix of neighbours within radius re: rows rp/ci/av
 * (a_ij = -w(r), a_ii = 1 + sum w: SPD) */
typedef struct cloud {
    size_t n;
    double *x, *y;
    size_t *map;
    ump_idx *rp, *ci;
    double *av;
} cloud;

static void cloud_make(cloud *c, int nx, int ny, double jitter, double shift, double re)
{
    c->n = (size_t)nx * (size_t)ny;
    c->x = malloc(sizeof *c->x * c->n);
    c->y = malloc(sizeof *c->y * c->n);
    c->map = malloc(sizeof *c->map * c->n);
    for (int j = 0; j < ny; j++)
        for (int i = 0; i < nx; i++) {
            size_t k = (size_t)j * (size_t)nx + (size_t)i;
            c->x[k] = i + 0.5 + jitter * sin(1.7 * (double)k) + shift;
            c->y[k] = j + 0.5 + jitter * cos(2.3 * (double)k);
            c->map[k] = k;
        }
    c->rp = malloc(sizeof *c->rp * (c->n + 1));
    size_t cap = c->n * 32;
    c->ci = malloc(sizeof *c->ci * cap);
    c->av = malloc(sizeof *c->av * cap);
    size_t q = 0;
    for (size_t k = 0; k < c->n; k++) {
        c->rp[k] = (ump_idx)q;
        size_t d = q++;
        c->ci[d] = (ump_idx)k;
        c->av[d] = 1;
        for (size_t l = 0; l < c->n; l++) {
            double r = hypot(c->x[l] - c->x[k], c->y[l] - c->y[k]);
            if (l == k || r >= re)
                continue;
            assert_true(q < cap);
            c->ci[q] = (ump_idx)l;
            c->av[q] = -(re / r - 1);
            c->av[d] += re / r - 1;
            q++;
        }
    }
    c->rp[c->n] = (ump_idx)q;
}

static void cloud_free(cloud *c)
{
    free(c->x);
    free(c->y);
    free(c->map);
    free(c->rp);
    free(c->ci);
    free(c->av);
}

/* z = P Ac^-1 P^T r by dense Gaussian elimination, the squares of side H
 * numbered here by their own rule (the first unknown's) */
static void dense_coarse(const cloud *c, double H, const double *r, double *z)
{
    size_t n = c->n;
    long *bx = malloc(sizeof *bx * n), *by = malloc(sizeof *by * n);
    int *agg = malloc(sizeof *agg * n), na = 0;
    for (size_t k = 0; k < n; k++) {
        bx[k] = (long)floor(c->x[k] / H);
        by[k] = (long)floor(c->y[k] / H);
        agg[k] = -1;
        for (size_t l = 0; l < k && agg[k] < 0; l++)
            if (bx[l] == bx[k] && by[l] == by[k])
                agg[k] = agg[l];
        if (agg[k] < 0)
            agg[k] = na++;
    }
    double *M = calloc((size_t)na * (size_t)(na + 1), sizeof *M); /* [Ac | P^T r] */
    for (size_t k = 0; k < n; k++) {
        M[(size_t)agg[k] * (size_t)(na + 1) + (size_t)na] += r[k];
        for (ump_idx q = c->rp[k]; q < c->rp[k + 1]; q++)
            M[(size_t)agg[k] * (size_t)(na + 1) + (size_t)agg[c->ci[q]]] += c->av[q];
    }
    for (int p = 0; p < na; p++) /* SPD: no pivoting */
        for (int i = p + 1; i < na; i++) {
            double f = M[(size_t)i * (size_t)(na + 1) + (size_t)p] / M[(size_t)p * (size_t)(na + 1) + (size_t)p];
            for (int j = p; j <= na; j++)
                M[(size_t)i * (size_t)(na + 1) + (size_t)j] -= f * M[(size_t)p * (size_t)(na + 1) + (size_t)j];
        }
    double *zc = malloc(sizeof *zc * (size_t)na);
    for (int i = na - 1; i >= 0; i--) {
        double s = M[(size_t)i * (size_t)(na + 1) + (size_t)na];
        for (int j = i + 1; j < na; j++)
            s -= M[(size_t)i * (size_t)(na + 1) + (size_t)j] * zc[j];
        zc[i] = s / M[(size_t)i * (size_t)(na + 1) + (size_t)i];
    }
    for (size_t k = 0; k < n; k++)
        z[k] = zc[agg[k]];
    free(bx);
    free(by);
    free(agg);
    free(M);
    free(zc);
}

static void coarse_sequence(lsolve_kind lk)
{
    const double H = 3, re = 2.1;
    cloud c, c2, c3;
    cloud_make(&c, 20, 14, 0.2, 0, re);
    cloud_make(&c2, 20, 14, 0.25, 0.4, re); /* moved within the squares reached */
    cloud_make(&c3, 20, 14, 0.2, 7.5, re);  /* beyond them and their ring */
    size_t n = c.n;
    double *r = malloc(sizeof *r * n), *z = malloc(sizeof *z * n), *zd = malloc(sizeof *zd * n);
    for (size_t k = 0; k < n; k++)
        r[k] = cos(0.21 * (double)k) + 0.3;
    coarse *cl = NULL;
    ump_err err;
    int ok = 0;
    assert_int_equal(coarse_create(&cl, &err), UMP_OK);
    const cloud *seq[] = {&c, &c2, &c3, &c};
    const size_t rebuilds[] = {1, 1, 2, 2};
    for (int s = 0; s < 4; s++) {
        const cloud *q = seq[s];
        /* the builds with the pattern in place: nothing allocated */
        ss_allocs = 0;
        ump_alloc_fail_after(s == 1 || s == 3 ? 0 : -1);
        ump_status rc = coarse_build(cl, n, q->x, q->y, q->map, H, q->rp, q->ci, q->av, lk, &ok, &err);
        memset(z, 0, sizeof *z * n);
        coarse_add(cl, r, z);
        ump_alloc_fail_after(-1);
        assert_int_equal(rc, UMP_OK);
        assert_true(ok);
        if (s == 1 || s == 3)
            assert_int_equal(ss_allocs, 0);
        else
            assert_true(ss_allocs > 0); /* a new pattern: analysed and factorized anew */
        assert_int_equal(coarse_rebuilds(cl), rebuilds[s]);
        dense_coarse(q, H, r, zd);
        for (size_t k = 0; k < n; k++)
            TU_CLOSE(z[k], zd[k], 1e-11 * (1 + fabs(zd[k])));
    }
    coarse_free(&cl);
    assert_null(cl);
    cloud_free(&c);
    cloud_free(&c2);
    cloud_free(&c3);
    free(r);
    free(z);
    free(zd);
}

static void test_coarse_cholmod(void **state)
{
    (void)state;
    coarse_sequence(LSOLVE_CHOLMOD);
}

static void test_coarse_klu(void **state)
{
    (void)state;
    coarse_sequence(LSOLVE_KLU);
}

int main(void)
{
    count_on();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_serial_factor),
        cmocka_unit_test(test_coarse_cholmod),
        cmocka_unit_test(test_coarse_klu),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
