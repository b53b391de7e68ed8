/* SPDX-License-Identifier: GPL-3.0-or-later
 * test_ppe.c -- the pressure Poisson equation (Eqs. 20, 22-26):
 *   (a) manufactured solutions with Dirichlet (and mixed) boundaries, observed
 *       order on three refinements of quad, distorted-quad, triangle and
 *       hybrid meshes, and on periodic meshes; the orthogonal quad matrix is
 *       the standard 5-point one;
 *   (b) all-Neumann (walls) with a reference cell: random fluxes, per-cell
 *       continuity of phi - dt grad p . A after the solve;
 *   (c) the same on periodic (cyclic) squares;
 *   (d) one factorization, many solves: results equal fresh solves, and no
 *       allocation inside ppe_solve;
 *   (e) refusals;
 *   (f) ppe_face_quadratic_flux: the face operator's flux of a quadratic.
 */
#include "testmesh.h"
#include "umppm/ppe.h"

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

/* Boundary condition sets for the manufactured solutions. */
typedef enum { BC_DIRICHLET, BC_MIXED, BC_PERIODIC } bc_kind;

/* A smooth non-polynomial pressure and its gradient. BC_MIXED: dp/dy = 0 on
 * y = 0, 1, which the walls impose (their gradient flux is zero: u . n is
 * the prescribed u* . n); BC_PERIODIC: periodic. */
static double pex(double x, double y, bc_kind bc, double *gx, double *gy)
{
    if (bc == BC_PERIODIC) {
        double w = 2 * UMP_PI;
        *gx = w * cos(w * x) * cos(w * y);
        *gy = -w * sin(w * x) * sin(w * y);
        return sin(w * x) * cos(w * y);
    }
    if (bc == BC_MIXED) {
        *gx = 1.3 * cos(1.3 * x + 0.4) * cos(UMP_PI * y) + 0.5;
        *gy = -UMP_PI * sin(1.3 * x + 0.4) * sin(UMP_PI * y);
        return sin(1.3 * x + 0.4) * cos(UMP_PI * y) + 0.5 * x;
    }
    *gx = 1.3 * cos(1.3 * x + 0.4) * cos(2.1 * y) + 0.5 * y;
    *gy = -2.1 * sin(1.3 * x + 0.4) * sin(2.1 * y) + 0.5 * x;
    return sin(1.3 * x + 0.4) * cos(2.1 * y) + 0.5 * x * y;
}

static ppe *make_ppe(const mesh2d *m, const lsq_grad *g, const unsigned char *dir, lsolve_kind kind,
                     ump_idx ref, double refv)
{
    ppe_opts o = {kind, ref, refv, 1};
    ppe *P = NULL;
    ump_err err;
    if (ppe_create(m, g, dir, &o, &P, &err) != UMP_OK)
        fail_msg("%s", err.msg);
    return P;
}

static lsq_grad *make_lsq(const mesh2d *m)
{
    lsq_grad *g = NULL;
    ump_err err;
    if (lsq_build(m, &g, &err) != UMP_OK)
        fail_msg("%s", err.msg);
    return g;
}

/* Solve with the exact face fluxes dt grad p_exact . n |f|; errors of p at
 * the centroids (max and area-weighted rms; periodic: up to the mean). */
static void manufactured(tm_kind kind, int n, double amp, bc_kind bc, double *emax, double *erms,
                         const char **solver)
{
    pmesh *pm = NULL;
    mesh2d *m = tm_mesh(kind, n, amp, bc == BC_PERIODIC, &pm);
    lsq_grad *g = make_lsq(m);
    size_t nf = (size_t)m->nfaces, nc = (size_t)m->ncells;
    unsigned char *dir = calloc(nf, 1);
    double *flux = malloc(sizeof(double) * nf), *pf = malloc(sizeof(double) * nf),
           *p = malloc(sizeof(double) * nc), dt = 0.01;
    for (ump_idx f = m->ninternal; f < m->nfaces; f++) {
        int patch = m->face_patch[f]; /* 0 bottom, 1 right, 2 top, 3 left */
        dir[f] = bc == BC_DIRICHLET || (bc == BC_MIXED && (patch == 1 || patch == 3));
    }
    for (size_t f = 0; f < nf; f++) {
        double gx, gy;
        pf[f] = pex(m->fx[f], m->fy[f], bc, &gx, &gy);
        flux[f] = dt * (gx * m->nx[f] + gy * m->ny[f]) * m->len[f];
    }
    double gx, gy;
    ppe *P = make_ppe(m, g, dir, LSOLVE_AUTO, 0, pex(m->cx[0], m->cy[0], bc, &gx, &gy));
    *solver = lsolve_name(P->fac);
    ump_err err;
    if (ppe_solve(P, flux, dt, pf, p, &err) != UMP_OK)
        fail_msg("%s", err.msg);
    double shift = 0, a = 0;
    if (bc == BC_PERIODIC) {
        for (size_t c = 0; c < nc; c++) {
            shift += (p[c] - pex(m->cx[c], m->cy[c], bc, &gx, &gy)) * m->area[c];
            a += m->area[c];
        }
        shift /= a;
    }
    double s2 = 0;
    a = 0;
    *emax = 0;
    for (size_t c = 0; c < nc; c++) {
        double e = fabs(p[c] - shift - pex(m->cx[c], m->cy[c], bc, &gx, &gy));
        *emax = fmax(*emax, e);
        s2 += e * e * m->area[c];
        a += m->area[c];
    }
    *erms = sqrt(s2 / a);
    ppe_free(&P);
    lsq_free(&g);
    mesh_free(&m);
    pmesh_free(&pm);
    free(dir);
    free(flux);
    free(pf);
    free(p);
}

static void test_manufactured(void **state)
{
    (void)state;
    struct {
        tm_kind kind;
        double amp;
        bc_kind bc;
        double min_order;
    } cases[] = {
        {TM_QUAD, 0.0, BC_DIRICHLET, 1.9},
        {TM_QUAD, 0.05, BC_DIRICHLET, 1.5},
        {TM_TRI, 0.0, BC_DIRICHLET, 1.5},
        {TM_TRI, 0.05, BC_DIRICHLET, 1.5},
        {TM_HYBRID, 0.0, BC_DIRICHLET, 1.5},
        {TM_HYBRID, 0.05, BC_DIRICHLET, 1.5},
        {TM_QUAD, 0.0, BC_MIXED, 1.9},
        {TM_TRI, 0.05, BC_MIXED, 1.5},
        {TM_HYBRID, 0.05, BC_MIXED, 1.5},
        {TM_QUAD, 0.0, BC_PERIODIC, 1.9},
        {TM_TRI, 0.05, BC_PERIODIC, 1.5},
        {TM_HYBRID, 0.05, BC_PERIODIC, 1.5},
    };
    const char *bcname[] = {"Dirichlet", "mixed", "periodic"};
    int ns[] = {10, 20, 40};
    for (size_t q = 0; q < sizeof cases / sizeof cases[0]; q++) {
        double emax[3], erms[3];
        const char *solver = "";
        for (int r = 0; r < 3; r++)
            manufactured(cases[q].kind, ns[r], cases[q].amp, cases[q].bc, &emax[r], &erms[r], &solver);
        double om1 = log2(emax[0] / emax[1]), om2 = log2(emax[1] / emax[2]);
        double or1 = log2(erms[0] / erms[1]), or2 = log2(erms[1] / erms[2]);
        printf("    PPE %-19s %-9s (%s): max err %.2e %.2e %.2e (order %.2f, %.2f); rms %.2e %.2e %.2e "
               "(order %.2f, %.2f)\n",
               tm_name(cases[q].kind, cases[q].amp), bcname[cases[q].bc], solver, emax[0], emax[1],
               emax[2], om1, om2, erms[0], erms[1], erms[2], or1, or2);
        if (!(or2 >= cases[q].min_order && om2 >= cases[q].min_order - 0.3))
            fail_msg("%s, %s: observed order %.2f (rms), %.2f (max) below %.2f",
                     tm_name(cases[q].kind, cases[q].amp), bcname[cases[q].bc], or2, om2,
                     cases[q].min_order);
    }
}

/* Orthogonal quads: the standard 5-point matrix, exactly symmetric, CHOLMOD */
static void test_five_point(void **state)
{
    (void)state;
    int n = 6;
    pmesh *pm = NULL;
    mesh2d *m = tm_mesh(TM_QUAD, n, 0.0, 0, &pm);
    lsq_grad *g = make_lsq(m);
    unsigned char *dir = calloc((size_t)m->nfaces, 1);
    for (ump_idx f = m->ninternal; f < m->nfaces; f++)
        dir[f] = 1;
    ppe *P = make_ppe(m, g, dir, LSOLVE_AUTO, 0, 0);
    assert_string_equal(lsolve_name(P->fac), "CHOLMOD");
    assert_true(lsolve_mat_is_symmetric(P->A, 0.0));
    const lsolve_mat *A = P->A;
    for (ump_idx j = 0; j < A->n; j++) {
        int i0 = j % n, j0 = j / n, nnz = 0;
        int nb = (i0 > 0) + (i0 < n - 1) + (j0 > 0) + (j0 < n - 1);
        for (ump_idx p = A->Ap[j]; p < A->Ap[j + 1]; p++) {
            ump_idx i = A->Ai[p];
            if (i == j) {
                /* -1 per interior face, -2 per Dirichlet face (half-cell distance) */
                TU_CLOSE(A->Ax[p], -(nb + 2.0 * (4 - nb)), 1e-13);
            } else {
                int di = abs(i % n - i0), dj = abs(i / n - j0);
                assert_true(di + dj == 1);
                TU_CLOSE(A->Ax[p], 1.0, 1e-13);
            }
            nnz++;
        }
        assert_int_equal(nnz, 1 + nb);
    }
    ppe_free(&P);
    assert_null(P);
    ppe_free(&P);
    lsq_free(&g);
    mesh_free(&m);
    pmesh_free(&pm);
    free(dir);
}

/* Per-cell continuity of phi - dt gflux after a solve with random fluxes:
 * returns the largest relative residual over the cells other than skip,
 * and the residual of cell skip in *rskip. */
static double continuity(const ppe *P, const double *flux, double dt, const double *p, const double *pf,
                         ump_idx skip, double *rskip)
{
    const mesh2d *m = P->m;
    size_t nf = (size_t)m->nfaces, nc = (size_t)m->ncells;
    double *gf = malloc(sizeof(double) * nf), *r = calloc(nc, sizeof(double)),
           *sc = calloc(nc, sizeof(double));
    ppe_face_gradient_flux(P, p, pf, gf);
    for (ump_idx f = 0; f < m->nfaces; f++) {
        double u = flux[f] - dt * gf[f];       /* corrected flux */
        double s = fabs(flux[f]) + fabs(dt * gf[f]);
        r[m->owner[f]] += u;
        sc[m->owner[f]] += s;
        if (f < m->ninternal) {
            r[m->neigh[f]] -= u;
            sc[m->neigh[f]] += s;
        }
    }
    double worst = 0;
    for (size_t c = 0; c < nc; c++)
        if ((ump_idx)c != skip)
            worst = fmax(worst, fabs(r[c]) / sc[c]);
    *rskip = skip >= 0 ? r[skip] : 0;
    free(gf);
    free(r);
    free(sc);
    return worst;
}

static void random_flux(rng *r, size_t nf, double *flux)
{
    for (size_t f = 0; f < nf; f++)
        flux[f] = rnd(r) - 0.5;
}

/* (b) walls only, (c) periodic: reference cell, random fluxes */
static void neumann_case(tm_kind kind, double amp, int periodic, lsolve_kind solver, int n)
{
    pmesh *pm = NULL;
    mesh2d *m = tm_mesh(kind, n, amp, periodic, &pm);
    lsq_grad *g = make_lsq(m);
    size_t nf = (size_t)m->nfaces, nc = (size_t)m->ncells;
    ump_idx ref = (ump_idx)(nc / 3);
    ppe *P = make_ppe(m, g, NULL, solver, ref, 0.25);
    assert_false(P->has_dirichlet);
    double *flux = malloc(sizeof(double) * nf), *p = malloc(sizeof(double) * nc), dt = 0.002;
    rng r = {42 + (uint64_t)kind};
    random_flux(&r, nf, flux);
    ump_err err;
    if (ppe_solve(P, flux, dt, NULL, p, &err) != UMP_OK)
        fail_msg("%s", err.msg);
    TU_CLOSE(p[ref], 0.25, 1e-13);
    double rref, worst = continuity(P, flux, dt, p, NULL, ref, &rref);
    /* the reference cell takes the net boundary outflow (zero when periodic) */
    double net = 0;
    for (ump_idx f = m->ninternal; f < m->nfaces; f++)
        net += flux[f];
    printf("    continuity, %s%s (%d cells, %s): max relative residual %.2e, reference cell %.3e "
           "(net outflow %.3e)\n",
           tm_name(kind, amp), periodic ? ", periodic" : ", walls", (int)nc, lsolve_name(P->fac), worst,
           rref, net);
    assert_true(worst < 1e-12);
    TU_CLOSE(rref, net, 1e-11);
    if (periodic)
        assert_int_equal(m->nfaces, m->ninternal);
    ppe_free(&P);
    lsq_free(&g);
    mesh_free(&m);
    pmesh_free(&pm);
    free(flux);
    free(p);
}

static void test_neumann_continuity(void **state)
{
    (void)state;
    neumann_case(TM_QUAD, 0.0, 0, LSOLVE_AUTO, 24);
    neumann_case(TM_QUAD, 0.05, 0, LSOLVE_AUTO, 24);
    neumann_case(TM_TRI, 0.05, 0, LSOLVE_KLU, 24);
    neumann_case(TM_HYBRID, 0.05, 0, LSOLVE_UMFPACK, 24);
}

static void test_periodic_continuity(void **state)
{
    (void)state;
    neumann_case(TM_QUAD, 0.0, 1, LSOLVE_AUTO, 24);
    neumann_case(TM_TRI, 0.05, 1, LSOLVE_KLU, 24);
    neumann_case(TM_HYBRID, 0.05, 1, LSOLVE_UMFPACK, 24);
}

/* Dirichlet flags [nfaces] (free after use): the left and right sides of
 * a tm_mesh square fixed, top and bottom walls */
static unsigned char *fixed_left_right(const mesh2d *m)
{
    unsigned char *dir = calloc((size_t)m->nfaces, 1);
    for (ump_idx f = m->ninternal; f < m->nfaces; f++)
        dir[f] = m->face_patch[f] == 1 || m->face_patch[f] == 3;
    return dir;
}

/* Mixed: fixed pressure left/right, walls top/bottom: every cell balances */
static void test_mixed_continuity(void **state)
{
    (void)state;
    pmesh *pm = NULL;
    mesh2d *m = tm_mesh(TM_HYBRID, 20, 0.05, 0, &pm);
    lsq_grad *g = make_lsq(m);
    size_t nf = (size_t)m->nfaces, nc = (size_t)m->ncells;
    unsigned char *dir = fixed_left_right(m);
    double *flux = malloc(sizeof(double) * nf), *pf = malloc(sizeof(double) * nf),
           *p = malloc(sizeof(double) * nc);
    rng r = {7};
    random_flux(&r, nf, flux);
    for (size_t f = 0; f < nf; f++)
        pf[f] = dir[f] ? rnd(&r) : NAN; /* only Dirichlet faces are read */
    ppe *P = make_ppe(m, g, dir, LSOLVE_AUTO, 0, 0);
    assert_true(P->has_dirichlet);
    ump_err err;
    assert_int_equal(ppe_solve(P, flux, 0.01, pf, p, &err), UMP_OK);
    double rs, worst = continuity(P, flux, 0.01, p, pf, -1, &rs);
    printf("    continuity, distorted hybrid, fixed p left/right (%d cells, %s): max relative residual "
           "%.2e\n", (int)nc, lsolve_name(P->fac), worst);
    assert_true(worst < 1e-12);
    ppe_free(&P);
    lsq_free(&g);
    mesh_free(&m);
    pmesh_free(&pm);
    free(dir);
    free(flux);
    free(pf);
    free(p);
}

/* (f) ppe_face_quadratic_flux(f, grad Q(x_f), H) is the flux that
 * ppe_face_gradient_flux gives for the cell field Q (and Q's face values on
 * Dirichlet faces) of a global quadratic Q, on every face of a distorted
 * hybrid mesh with fixed pressure left and right: the stored monomial
 * fluxes reproduce Eq. 25's expanded rows */
static void test_quadratic_flux(void **state)
{
    (void)state;
    pmesh *pm = NULL;
    mesh2d *m = tm_mesh(TM_HYBRID, 16, 0.05, 0, &pm);
    lsq_grad *g = make_lsq(m);
    size_t nf = (size_t)m->nfaces, nc = (size_t)m->ncells;
    unsigned char *dir = fixed_left_right(m);
    double *q = malloc(sizeof(double) * nc), *pf = malloc(sizeof(double) * nf),
           *gf = malloc(sizeof(double) * nf);
    const double a0[2] = {0.8, -1.7}, H[3] = {3.1, 0.9, -2.2};
#define Q(x, y) (0.4 + a0[0] * (x) + a0[1] * (y) + 0.5 * (H[0] * (x) * (x) + 2 * H[1] * (x) * (y) + H[2] * (y) * (y)))
    for (size_t c = 0; c < nc; c++)
        q[c] = Q(m->cx[c], m->cy[c]);
    for (size_t f = 0; f < nf; f++)
        pf[f] = Q(m->fx[f], m->fy[f]);
#undef Q
    ppe *P = make_ppe(m, g, dir, LSOLVE_AUTO, 0, 0);
    /* and without the stored fluxes (ppe_opts quadratic 0): the same */
    ppe_opts o0 = {LSOLVE_AUTO, 0, 0, 0};
    ppe *P0 = NULL;
    ump_err err;
    if (ppe_create(m, g, dir, &o0, &P0, &err) != UMP_OK)
        fail_msg("%s", err.msg);
    assert_non_null(P->qcoef);
    assert_null(P0->qcoef);
    ppe_face_gradient_flux(P, q, pf, gf);
    double e = 0, scale = 0;
    int ndir = 0;
    for (ump_idx f = 0; f < m->nfaces; f++) {
        double x = m->fx[f], y = m->fy[f];
        double a[2] = {a0[0] + H[0] * x + H[1] * y, a0[1] + H[1] * x + H[2] * y};
        double s = ppe_face_quadratic_flux(P, f, a, H), s0 = ppe_face_quadratic_flux(P0, f, a, H);
        e = fmax(e, fmax(fabs(s - gf[f]), fabs(s0 - gf[f])));
        scale = fmax(scale, fabs(gf[f]));
        ndir += f >= m->ninternal && dir[f];
    }
    printf("    quadratic face fluxes, %s (%d faces, %d Dirichlet): max difference %.2e of %.2e\n",
           tm_name(TM_HYBRID, 0.05), (int)nf, ndir, e, scale);
    assert_true(ndir > 0);
    assert_true(e < 1e-12 * scale);
    ppe_free(&P);
    ppe_free(&P0);
    lsq_free(&g);
    mesh_free(&m);
    pmesh_free(&pm);
    free(dir);
    free(q);
    free(pf);
    free(gf);
}

/* (d) factorize once, solve many times */
static void test_reuse(void **state)
{
    (void)state;
    pmesh *pm = NULL;
    mesh2d *m = tm_mesh(TM_TRI, 16, 0.05, 0, &pm);
    lsq_grad *g = make_lsq(m);
    size_t nf = (size_t)m->nfaces, nc = (size_t)m->ncells;
    unsigned char *dir = calloc(nf, 1);
    for (ump_idx f = m->ninternal; f < m->nfaces; f++)
        dir[f] = m->face_patch[f] == 1;       /* outlet on the right */
    lsolve_kind kinds[] = {LSOLVE_AUTO, LSOLVE_KLU};
    for (int k = 0; k < 2; k++) {
        ppe *P = make_ppe(m, g, dir, kinds[k], 0, 0);
        const lsolve_mat *A0 = P->A;
        const lsolve *F0 = P->fac;
        double *flux = malloc(sizeof(double) * nf), *pf = malloc(sizeof(double) * nf),
               *p = malloc(sizeof(double) * nc), *q = malloc(sizeof(double) * nc);
        rng r = {99};
        ump_err err;
        /* warm-up solve (CHOLMOD's solve2 allocates its blocks on first use) */
        random_flux(&r, nf, flux);
        random_flux(&r, nf, pf);
        assert_int_equal(ppe_solve(P, flux, 0.1, pf, p, &err), UMP_OK);
        for (int s = 0; s < 6; s++) {
            random_flux(&r, nf, flux);
            random_flux(&r, nf, pf);
            double dt = 0.001 * (s + 1);
            size_t before = ump_alloc_requested();
            assert_int_equal(ppe_solve(P, flux, dt, pf, p, &err), UMP_OK);
            assert_int_equal(ump_alloc_requested(), before); /* nothing allocated */
            assert_ptr_equal(P->A, A0);
            assert_ptr_equal(P->fac, F0);
            ppe *Q = make_ppe(m, g, dir, kinds[k], 0, 0); /* fresh assembly + factorization */
            assert_int_equal(ppe_solve(Q, flux, dt, pf, q, &err), UMP_OK);
            double e = 0, sc = 0;
            for (size_t c = 0; c < nc; c++) {
                e = fmax(e, fabs(p[c] - q[c]));
                sc = fmax(sc, fabs(q[c]));
            }
            assert_true(e <= 1e-13 * sc);
            ppe_free(&Q);
        }
        ppe_free(&P);
        free(flux);
        free(pf);
        free(p);
        free(q);
    }
    lsq_free(&g);
    mesh_free(&m);
    pmesh_free(&pm);
    free(dir);
}

/* the assembled PPE matrix (nonsymmetric on a distorted mesh, with the
 * reference row) also solves with BiCGSTAB + ILU(0): same pressure */
static void test_iterative_agrees(void **state)
{
    (void)state;
    pmesh *pm = NULL;
    mesh2d *m = tm_mesh(TM_HYBRID, 20, 0.05, 0, &pm);
    lsq_grad *g = make_lsq(m);
    size_t nf = (size_t)m->nfaces, nc = (size_t)m->ncells;
    ppe *P = make_ppe(m, g, NULL, LSOLVE_UMFPACK, 5, 1.0);
    assert_false(lsolve_mat_is_symmetric(P->A, 1e-8));
    double *flux = malloc(sizeof(double) * nf), *p = malloc(sizeof(double) * nc),
           *x = calloc(nc, sizeof(double));
    rng r = {2024};
    random_flux(&r, nf, flux);
    ump_err err;
    assert_int_equal(ppe_solve(P, flux, 0.05, NULL, p, &err), UMP_OK);
    lsolve_krylov *k = NULL;
    assert_int_equal(lsolve_krylov_create(m->ncells, &k, &err), UMP_OK);
    lsolve_stats st;
    assert_int_equal(lsolve_bicgstab(k, P->A, LSOLVE_PC_ILU0, P->rhs, x, 1e-13, 500, &st, &err), UMP_OK);
    printf("    BiCGSTAB/ILU(0) on the PPE matrix (%d cells): %d iterations, residual %.1e\n",
           (int)nc, st.iterations, st.res);
    assert_int_equal(st.converged, 1);
    double e = 0, sc = 0;
    for (size_t c = 0; c < nc; c++) {
        e = fmax(e, fabs(x[c] - p[c]));
        sc = fmax(sc, fabs(p[c]));
    }
    assert_true(e <= 1e-9 * sc);
    lsolve_krylov_free(&k);
    ppe_free(&P);
    lsq_free(&g);
    mesh_free(&m);
    pmesh_free(&pm);
    free(flux);
    free(p);
    free(x);
}

/* (e) refusals */
static void test_refusals(void **state)
{
    (void)state;
    pmesh *pm = NULL;
    mesh2d *m = tm_mesh(TM_QUAD, 4, 0.0, 0, &pm);
    lsq_grad *g = make_lsq(m);
    unsigned char *dir = calloc((size_t)m->nfaces, 1);
    ppe *P = NULL;
    ump_err err;
    ppe_opts o = {LSOLVE_AUTO, 16, 0, 0};
    assert_int_equal(ppe_create(m, g, NULL, &o, &P, &err), UMP_ERR_INPUT);
    assert_non_null(strstr(err.msg, "pRefCell 16"));
    assert_null(P);
    o.ref_cell = -1;
    assert_int_equal(ppe_create(m, g, NULL, &o, &P, &err), UMP_ERR_INPUT);
    dir[0] = 1;                                 /* an internal face */
    assert_int_equal(ppe_create(m, g, dir, NULL, &P, &err), UMP_ERR_INPUT);
    assert_non_null(strstr(err.msg, "face 0 is internal"));
    dir[0] = 0;
    dir[m->nfaces - 1] = 1;
    assert_int_equal(ppe_create(m, g, dir, NULL, &P, &err), UMP_OK);
    double flux[64] = {0}, p[16];
    assert_int_equal(ppe_solve(P, flux, 0.0, flux, p, &err), UMP_ERR_INPUT);
    assert_int_equal(ppe_solve(P, flux, 0.1, NULL, p, &err), UMP_ERR_INPUT);
    assert_int_equal(ppe_solve(P, flux, 0.1, flux, p, &err), UMP_OK);
    for (int c = 0; c < 16; c++)
        TU_CLOSE(p[c], 0, 0);
    ppe_free(&P);
    /* a gradient of another mesh */
    pmesh *pm2 = NULL;
    mesh2d *m2 = tm_mesh(TM_QUAD, 3, 0.0, 0, &pm2);
    assert_int_equal(ppe_create(m2, g, NULL, NULL, &P, &err), UMP_ERR_INPUT);
    mesh_free(&m2);
    pmesh_free(&pm2);
    lsq_free(&g);
    mesh_free(&m);
    pmesh_free(&pm);
    free(dir);
}

/* every allocation failure in lsq_build and ppe_create is reported, not a
 * crash or a leak (the sanitizer build checks the leaks) */
static void test_out_of_memory(void **state)
{
    (void)state;
    pmesh *pm = NULL;
    mesh2d *m = tm_mesh(TM_HYBRID, 6, 0.05, 0, &pm);
    int nfail = 0;
    for (long k = 0;; k++) {
        ump_err err;
        lsq_grad *g = NULL;
        ppe *P = NULL;
        ump_alloc_fail_after(k);
        ump_status rc = lsq_build(m, &g, &err);
        if (rc == UMP_OK)
            rc = ppe_create(m, g, NULL, NULL, &P, &err);
        ump_alloc_fail_after(-1);
        ppe_free(&P);
        lsq_free(&g);
        if (rc == UMP_OK)
            break;
        assert_int_equal(rc, UMP_ERR_NOMEM);
        assert_true(strlen(err.msg) > 0);
        nfail++;
    }
    assert_true(nfail >= 10);
    mesh_free(&m);
    pmesh_free(&pm);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_five_point),
        cmocka_unit_test(test_manufactured),
        cmocka_unit_test(test_neumann_continuity),
        cmocka_unit_test(test_periodic_continuity),
        cmocka_unit_test(test_mixed_continuity),
        cmocka_unit_test(test_reuse),
        cmocka_unit_test(test_iterative_agrees),
        cmocka_unit_test(test_refusals),
        cmocka_unit_test(test_out_of_memory),
        cmocka_unit_test(test_quadratic_flux),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
