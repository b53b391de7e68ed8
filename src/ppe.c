/* SPDX-License-Identifier: GPL-3.0-or-later
 * ppe.c -- the pressure Poisson equation of UMPPM on the fixed pressure mesh,
 * Eqs. (18)-(26) of Ng, Sheu & Hwang (2016) [NSH16], Section 3.2.2.1, Fig. 2
 * (docs/METHOD.md section 3.3).
 *
 * For every cell P (Eq. 20, kinematic pressure, per unit thickness):
 *   sum_f s_f grad p_f . A_f = (1/dt) sum_f s_f phi_f,
 * s_f = +1 when P owns f, -1 when P is its neighbour (A_f and phi_f point
 * owner -> neighbour), so both sides are outward sums over P's faces.
 *
 * Interior face f, owner A, neighbour B seen from A at x_B - sep (Eq. 25):
 *   grad p_f . A_f = |f| / |A'B'| [p_B - p_A + grad p_B . BB' - grad p_A . AA'],
 * A', B' the feet of the perpendiculars from A, B onto the line through x_f
 * along n_f, so AA' = t - (t . n) n with t = x_f - x_A (likewise BB'), and
 * |A'B'| = ((x_B - sep) - x_A) . n_f. The LS gradient (Eq. 26, lsq.h) is
 * grad p_P = sum_k g_k (p_j(k) - p_P), which makes every face a linear row in
 * N1(A) u N1(B) u {A, B} (second neighbours of A in the matrix, Fig. 4):
 *   p_B: +c (1 - sum_k g_k.BB'),  p_j (j in N1(B)): +c g_k.BB',
 *   p_A: -c (1 - sum_k g_k.AA'),  p_j (j in N1(A)): -c g_k.AA',  c = |f|/|A'B'|.
 * Dirichlet boundary face (p_f prescribed, A' the foot from A):
 *   grad p_f . A_f = |f| / |A'f| (p_f - p_A - grad p_A . AA'),  |A'f| = (x_f - x_A) . n_f.
 * Neumann boundary face (velocity prescribed): no gradient term.
 *
 * On faces whose perpendicular offsets are round-off (|AA'| below 1e-10 of
 * |x_f - x_A|), the offset is taken as exactly zero: an orthogonal mesh then
 * gives the standard compact (5-point on quads) matrix, exactly symmetric,
 * and AUTO picks CHOLMOD for it.
 *
 * The face rows are stored (the "face operator"); the matrix is their signed
 * sum, and ppe_face_gradient_flux applies the same rows, so the corrected
 * fluxes phi_f - dt grad p_f . A_f balance in every cell (but the reference
 * cell) to the accuracy of the direct solve.
 */
#include "umppm/ppe.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define ALLOC(p, n) ((p) = ump_alloc_array((size_t)(n), sizeof *(p)))

/* Perpendicular offsets below this fraction of the centroid-face distance are
 * round-off of an orthogonal face. */
#define PPE_ORTHO_TOL 1e-10
/* |A'B'| (or |A'f|) must exceed this fraction of |AB| (or |Af|). */
#define PPE_DIST_MIN 1e-8

void ppe_free(ppe **pP)
{
    if (!pP || !*pP)
        return;
    ppe *P = *pP;
    lsolve_free(&P->fac);
    lsolve_mat_free(&P->A);
    free(P->dirichlet);
    free(P->bd_coef);
    free(P->rhs);
    free(P->ax);
    free(P->rowsum);
    free(P->fop_off);
    free(P->fop_col);
    free(P->fop_val);
    free(P->qcoef);
    free(P->ref_row);
    free(P->ref_a);
    free(P);
    *pP = NULL;
}

/* Sparse row under construction, duplicates merged through pos[] (-1 = absent). */
typedef struct rowbuf {
    ump_idx n;
    ump_idx *col;
    double *val;
    ump_idx *pos; /* [ncells] */
} rowbuf;

static void row_add(rowbuf *r, ump_idx c, double v)
{
    if (r->pos[c] >= 0) {
        r->val[r->pos[c]] += v;
    } else {
        r->pos[c] = r->n;
        r->col[r->n] = c;
        r->val[r->n] = v;
        r->n++;
    }
}

/* Perpendicular offset from centroid (x, y) to its foot on the face line,
 * (x_f - x) - ((x_f - x) . n) n, zeroed at round-off level; returns
 * (x_f - x) . n, the normal distance. */
static double foot_offset(const mesh2d *m, ump_idx f, double x, double y, double *ox, double *oy)
{
    double tx = m->fx[f] - x, ty = m->fy[f] - y;
    double dn = tx * m->nx[f] + ty * m->ny[f];
    *ox = tx - dn * m->nx[f];
    *oy = ty - dn * m->ny[f];
    if (hypot(*ox, *oy) <= PPE_ORTHO_TOL * hypot(tx, ty))
        *ox = *oy = 0.0;
    return dn;
}

/* -c * grad p_P . o expanded through the LS weights of P (Eqs. 23, 24, 26). */
static void add_gradient_term(rowbuf *r, const lsq_grad *g, ump_idx P, double ox, double oy, double c)
{
    if (ox == 0.0 && oy == 0.0)
        return;
    const mesh2d *m = g->m;
    for (ump_idx k = m->n1_off[P]; k < m->n1_off[P + 1]; k++) {
        double a = c * (g->wx[k] * ox + g->wy[k] * oy);
        row_add(r, m->n1[k], a);  /* + c g_k.o p_j */
        row_add(r, P, -a);        /* - c g_k.o p_P */
    }
}

static const char *mesh_name(const mesh2d *m)
{
    return m->pm && m->pm->dir ? m->pm->dir : "mesh";
}

/* Face rows of Eq. 25 (interior) and of the Dirichlet boundary rule. */
static ump_status build_face_operator(ppe *P, ump_err *err)
{
    const mesh2d *m = P->m;
    const lsq_grad *g = P->g;
    ump_idx nf = m->nfaces, ni = m->ninternal;
    size_t bound = 0, maxrow = 0;
    for (ump_idx f = 0; f < nf; f++) {
        size_t len = 0;
        ump_idx A = m->owner[f];
        if (f < ni)
            len = 2 + (size_t)(m->n1_off[A + 1] - m->n1_off[A]) +
                  (size_t)(m->n1_off[m->neigh[f] + 1] - m->n1_off[m->neigh[f]]);
        else if (P->dirichlet[f])
            len = 1 + (size_t)(m->n1_off[A + 1] - m->n1_off[A]);
        bound += len;
        maxrow = len > maxrow ? len : maxrow;
    }
    UMP_CHECK(bound <= (size_t)UMP_IDX_MAX, err, UMP_ERR_NOMEM,
              "%s: pressure equation too large (%zu face coefficients)", mesh_name(m), bound);
    ALLOC(P->fop_off, (size_t)nf + 1);
    ALLOC(P->fop_col, bound);
    ALLOC(P->fop_val, bound);
    rowbuf r = {0, NULL, NULL, NULL};
    ALLOC(r.col, maxrow);
    ALLOC(r.val, maxrow);
    ALLOC(r.pos, m->ncells);
    ump_status rc = UMP_OK;
    if (!P->fop_off || !P->fop_col || !P->fop_val || !r.col || !r.val || !r.pos) {
        rc = UMP_FAIL(err, UMP_ERR_NOMEM, "%s: out of memory for the pressure equation", mesh_name(m));
        goto done;
    }
    for (ump_idx c = 0; c < m->ncells; c++)
        r.pos[c] = -1;
    ump_idx nz = 0;
    for (ump_idx f = 0; f < nf; f++) {
        ump_idx A = m->owner[f];
        r.n = 0;
        if (f < ni) {
            ump_idx B = m->neigh[f];
            double bx = m->cx[B] - (m->sepx ? m->sepx[f] : 0.0); /* B seen from A */
            double by = m->cy[B] - (m->sepy ? m->sepy[f] : 0.0);
            double aox, aoy, box, boy;
            double dA = foot_offset(m, f, m->cx[A], m->cy[A], &aox, &aoy); /* (x_f - x_A).n */
            double dB = foot_offset(m, f, bx, by, &box, &boy);             /* (x_f - x_B).n */
            double dAB = dA - dB;            /* |A'B'| = (x_B' - x_A').n_f, Eq. 22 */
            if (!(dAB > PPE_DIST_MIN * hypot(bx - m->cx[A], by - m->cy[A]))) {
                rc = UMP_FAIL(err, UMP_ERR_INPUT,
                              "%s: face %d: centroids of cells %d and %d are not on opposite sides "
                              "of the face (|A'B'| = %g): Eq. 22 undefined",
                              mesh_name(m), (int)f, (int)A, (int)B, dAB);
                goto done;
            }
            double c = m->len[f] / dAB;
            /* PPE face flux with projected centroids, Eq. 25:
             * c [p_B - p_A + grad p_B . BB' - grad p_A . AA'] */
            row_add(&r, B, c);
            row_add(&r, A, -c);
            add_gradient_term(&r, g, B, box, boy, c);
            add_gradient_term(&r, g, A, aox, aoy, -c);
        } else if (P->dirichlet[f]) {
            double aox, aoy;
            double dA = foot_offset(m, f, m->cx[A], m->cy[A], &aox, &aoy); /* |A'f| */
            if (!(dA > PPE_DIST_MIN * hypot(m->fx[f] - m->cx[A], m->fy[f] - m->cy[A]))) {
                rc = UMP_FAIL(err, UMP_ERR_INPUT,
                              "%s: boundary face %d: centroid of cell %d is not inside the face "
                              "(|A'f| = %g)", mesh_name(m), (int)f, (int)A, dA);
                goto done;
            }
            double c = m->len[f] / dA;
            /* Dirichlet face: c (p_f - p_A'), p_A' = p_A + grad p_A . AA' (Eq. 23) */
            P->bd_coef[f] = c;
            row_add(&r, A, -c);
            add_gradient_term(&r, g, A, aox, aoy, -c);
        }
        P->fop_off[f] = nz;
        for (ump_idx k = 0; k < r.n; k++) {
            P->fop_col[nz] = r.col[k];
            P->fop_val[nz] = r.val[k];
            nz++;
            r.pos[r.col[k]] = -1;
        }
    }
    P->fop_off[nf] = nz;
done:
    free(r.col);
    free(r.val);
    free(r.pos);
    return rc;
}

/* Matrix = signed sum of the face rows: + in the owner's row, - in the neighbour's. */
static ump_status assemble(ppe *P, ump_err *err)
{
    const mesh2d *m = P->m;
    lsolve_trip t;
    ump_idx nz = P->fop_off[m->nfaces];
    UMP_CALL(lsolve_trip_init(&t, m->ncells, 2 * (size_t)nz + (size_t)m->ncells, err));
    ump_status rc = UMP_OK;
    /* keep every diagonal in the pattern (ILU and the reference row want it) */
    for (ump_idx c = 0; c < m->ncells && rc == UMP_OK; c++)
        rc = lsolve_trip_add(&t, c, c, 0.0, err);
    for (ump_idx f = 0; f < m->nfaces && rc == UMP_OK; f++) {
        ump_idx o = m->owner[f];
        for (ump_idx k = P->fop_off[f]; k < P->fop_off[f + 1] && rc == UMP_OK; k++) {
            rc = lsolve_trip_add(&t, o, P->fop_col[k], P->fop_val[k], err);
            if (rc == UMP_OK && f < m->ninternal)
                rc = lsolve_trip_add(&t, m->neigh[f], P->fop_col[k], -P->fop_val[k], err);
        }
    }
    if (rc == UMP_OK)
        rc = lsolve_trip_to_mat(&t, &P->A, err);
    lsolve_trip_free(&t);
    return rc;
}

/* Replace the reference row by ref_diag p_ref = ref_diag pRefValue and move
 * the reference column to the right-hand side (see ppe.h). */
static ump_status fix_reference(ppe *P, ump_err *err)
{
    lsolve_mat *A = P->A;
    ump_idx r = P->ref_cell;
    ump_idx n = A->n;
    P->ref_diag = 0.0;
    for (ump_idx j = 0; j < n; j++)
        for (ump_idx p = A->Ap[j]; p < A->Ap[j + 1]; p++)
            if (A->Ai[p] == r) {
                if (j == r)
                    P->ref_diag = A->Ax[p];
                else
                    A->Ax[p] = 0.0;  /* reference row: only the diagonal stays */
            }
    UMP_CHECK(P->ref_diag != 0.0, err, UMP_ERR_SINGULAR,
              "%s: reference cell %d (pRefCell) has no pressure coupling", mesh_name(P->m), (int)r);
    ump_idx cnt = 0;
    for (ump_idx p = A->Ap[r]; p < A->Ap[r + 1]; p++)
        cnt += A->Ai[p] != r;
    ALLOC(P->ref_row, cnt);
    ALLOC(P->ref_a, cnt);
    UMP_CHECK(P->ref_row && P->ref_a, err, UMP_ERR_NOMEM, "%s: out of memory", mesh_name(P->m));
    P->nref = 0;
    for (ump_idx p = A->Ap[r]; p < A->Ap[r + 1]; p++)
        if (A->Ai[p] != r) {
            P->ref_row[P->nref] = A->Ai[p];
            P->ref_a[P->nref] = A->Ax[p];
            P->nref++;
            A->Ax[p] = 0.0;          /* reference column: to the right-hand side */
        }
    return UMP_OK;
}

/* q(x) = a . x + 1/2 x^T H x, x relative to x_f (ppe_face_quadratic_flux) */
static inline double quad_at(const double a[2], const double H[3], double x, double y)
{
    return a[0] * x + a[1] * y + 0.5 * (H[0] * x * x + 2 * H[1] * x * y + H[2] * y * y);
}

/* grad q_P . o with the LS gradient (Eq. 26) at P = x_f + (px, py):
 * sum_k g_k . o (q(x_j) - q(x_P)); 0 for a zero offset o */
static double quadratic_ls_dot(const lsq_grad *g, ump_idx P, double px, double py, const double a[2],
                               const double H[3], double ox, double oy)
{
    if (ox == 0.0 && oy == 0.0)
        return 0.0;
    const mesh2d *m = g->m;
    double qP = quad_at(a, H, px, py), s = 0.0;
    for (ump_idx k = m->n1_off[P]; k < m->n1_off[P + 1]; k++) {
        ump_idx j = m->n1[k];
        double x = px + m->cx[j] + (m->n1_sx ? m->n1_sx[k] : 0.0) - m->cx[P];
        double y = py + m->cy[j] + (m->n1_sy ? m->n1_sy[k] : 0.0) - m->cy[P];
        s += (g->wx[k] * ox + g->wy[k] * oy) * (quad_at(a, H, x, y) - qP);
    }
    return s;
}

static double face_quadratic_flux(const ppe *P, ump_idx f, const double a[2], const double H[3])
{
    const mesh2d *m = P->m;
    if (f >= m->ninternal && !P->dirichlet[f])
        return 0.0;
    ump_idx A = m->owner[f];
    double aox, aoy;
    double dA = foot_offset(m, f, m->cx[A], m->cy[A], &aox, &aoy);
    double ax = m->cx[A] - m->fx[f], ay = m->cy[A] - m->fy[f]; /* x_A - x_f */
    /* - q_A - grad q_A . AA' (q_f = 0 at the face) */
    double s = -quad_at(a, H, ax, ay) - quadratic_ls_dot(P->g, A, ax, ay, a, H, aox, aoy);
    if (f >= m->ninternal) /* Dirichlet: c (q_f - q_A - grad q_A . AA') */
        return P->bd_coef[f] * s;
    /* Eq. 25: c [q_B - q_A + grad q_B . BB' - grad q_A . AA'], B seen from
     * A as build_face_operator */
    ump_idx B = m->neigh[f];
    double bx = m->cx[B] - (m->sepx ? m->sepx[f] : 0.0), by = m->cy[B] - (m->sepy ? m->sepy[f] : 0.0);
    double box, boy;
    double dB = foot_offset(m, f, bx, by, &box, &boy);
    double qx = bx - m->fx[f], qy = by - m->fy[f]; /* x_B - x_f */
    s += quad_at(a, H, qx, qy) + quadratic_ls_dot(P->g, B, qx, qy, a, H, box, boy);
    return m->len[f] / (dA - dB) * s;
}

/* The flux of q is linear in (a, H): store it for the five monomials x, y,
 * x^2/2, xy, y^2/2 about x_f once (mesh-only), so the step's flux is a dot
 * product (ppe_face_quadratic_flux) */
static ump_status build_quadratic_coefficients(ppe *P, ump_err *err)
{
    const mesh2d *m = P->m;
    ALLOC(P->qcoef, 5 * (size_t)m->nfaces);
    UMP_CHECK(P->qcoef, err, UMP_ERR_NOMEM, "%s: out of memory for the quadratic face fluxes",
              mesh_name(m));
    static const double mono[5][5] = {{1, 0, 0, 0, 0}, {0, 1, 0, 0, 0}, {0, 0, 1, 0, 0},
                                      {0, 0, 0, 1, 0}, {0, 0, 0, 0, 1}};
    for (ump_idx f = 0; f < m->nfaces; f++)
        for (int i = 0; i < 5; i++)
            P->qcoef[5 * (size_t)f + i] = face_quadratic_flux(P, f, mono[i], mono[i] + 2);
    return UMP_OK;
}

double ppe_face_quadratic_flux(const ppe *P, ump_idx f, const double a[2], const double H[3])
{
    if (!P->qcoef)
        return face_quadratic_flux(P, f, a, H);
    const double *c = P->qcoef + 5 * (size_t)f;
    return c[0] * a[0] + c[1] * a[1] + c[2] * H[0] + c[3] * H[1] + c[4] * H[2];
}

ump_status ppe_create(const mesh2d *m, const lsq_grad *g, const unsigned char *dirichlet,
                      const ppe_opts *o, ppe **out, ump_err *err)
{
    *out = NULL;
    ppe_opts def = {LSOLVE_AUTO, 0, 0.0, 0};
    if (!o)
        o = &def;
    UMP_CHECK(g && g->m == m, err, UMP_ERR_INPUT, "%s: PPE needs the LS gradient of the same mesh",
              mesh_name(m));
    UMP_CHECK(m->ncells > 0, err, UMP_ERR_INPUT, "%s: mesh has no cells", mesh_name(m));
    ppe *P = ump_alloc_array(1, sizeof *P);
    UMP_CHECK(P, err, UMP_ERR_NOMEM, "%s: out of memory", mesh_name(m));
    P->m = m;
    P->g = g;
    ALLOC(P->dirichlet, m->nfaces);
    ALLOC(P->bd_coef, m->nfaces);
    ALLOC(P->rhs, m->ncells);
    ump_status rc = UMP_OK;
    if (!P->dirichlet || !P->bd_coef || !P->rhs) {
        rc = UMP_FAIL(err, UMP_ERR_NOMEM, "%s: out of memory for the pressure equation", mesh_name(m));
        goto fail;
    }
    for (ump_idx f = 0; f < m->nfaces && dirichlet; f++) {
        if (!dirichlet[f])
            continue;
        if (f < m->ninternal) {
            rc = UMP_FAIL(err, UMP_ERR_INPUT, "%s: face %d is internal and cannot carry a fixed pressure",
                          mesh_name(m), (int)f);
            goto fail;
        }
        P->dirichlet[f] = 1;
        P->has_dirichlet = 1;
    }
    P->ref_cell = o->ref_cell;
    P->ref_value = o->ref_value;
    if (!P->has_dirichlet && (o->ref_cell < 0 || o->ref_cell >= m->ncells)) {
        rc = UMP_FAIL(err, UMP_ERR_INPUT, "%s: pRefCell %d is not a cell (0..%d)", mesh_name(m),
                      (int)o->ref_cell, (int)m->ncells - 1);
        goto fail;
    }
    if (!P->has_dirichlet && !isfinite(o->ref_value)) {
        rc = UMP_FAIL(err, UMP_ERR_INPUT, "%s: pRefValue is not finite", mesh_name(m));
        goto fail;
    }
    if ((rc = build_face_operator(P, err)) != UMP_OK || (rc = assemble(P, err)) != UMP_OK ||
        (o->quadratic && (rc = build_quadratic_coefficients(P, err)) != UMP_OK))
        goto fail;
    if (!P->has_dirichlet && (rc = fix_reference(P, err)) != UMP_OK)
        goto fail;
    P->symmetric = lsolve_mat_is_symmetric(P->A, 0.0);
    rc = lsolve_factor(P->A, o->solver, &P->fac, err);
    if (rc != UMP_OK) {
        char msg[sizeof err->msg];
        memcpy(msg, err->msg, sizeof msg);
        msg[sizeof msg - 1] = '\0';
        rc = UMP_FAIL(err, rc, "%s: pressure equation (%d cells%s): %s", mesh_name(m), (int)m->ncells,
                      P->has_dirichlet ? "" : ", reference cell", msg);
        goto fail;
    }
    *out = P;
    return UMP_OK;
fail:
    ppe_free(&P);
    return rc;
}

/* OpenFOAM's normalised residual of A x = b (lduMatrix::solver::normFactor):
 * sum|b - A x| / (sum(|A x - A xbar| + |b - A xbar|) + 1e-20), xbar the
 * mean of x, A xbar = xbar times the row sums; 1 for x = 0 and b != 0 as in
 * OpenFOAM's first solve. Two passes over A a step (the log line). */
static ump_status residual(ppe *P, const double *b, const double *x, double *out, ump_err *err)
{
    ump_idx n = P->m->ncells;
    if (!P->ax) {
        ALLOC(P->ax, n);
        ALLOC(P->rowsum, n);
        UMP_CHECK(P->ax && P->rowsum, err, UMP_ERR_NOMEM, "%s: out of memory for the PPE residual",
                  mesh_name(P->m));
        for (ump_idx i = 0; i < n; i++)
            P->rowsum[i] = 0;
        const lsolve_mat *A = P->A;
        for (ump_idx j = 0; j < n; j++)
            for (ump_idx k = A->Ap[j]; k < A->Ap[j + 1]; k++)
                P->rowsum[A->Ai[k]] += A->Ax[k];
    }
    if (P->symmetric)
        lsolve_mat_mult_sym(P->A, x, P->ax);
    else
        lsolve_mat_mult(P->A, x, P->ax);
    double xbar = 0;
    for (ump_idx i = 0; i < n; i++)
        xbar += x[i];
    xbar /= n;
    double num = 0, den = 0;
    for (ump_idx i = 0; i < n; i++) {
        double ar = xbar * P->rowsum[i];
        num += fabs(b[i] - P->ax[i]);
        den += fabs(P->ax[i] - ar) + fabs(b[i] - ar);
    }
    *out = num / (den + 1e-20);
    return UMP_OK;
}

ump_status ppe_solve(ppe *P, const double *flux, double dt, const double *pf, double *p, ump_err *err)
{
    const mesh2d *m = P->m;
    UMP_CHECK(dt > 0 && isfinite(dt), err, UMP_ERR_INPUT, "PPE: time step %g is not positive", dt);
    UMP_CHECK(pf || !P->has_dirichlet, err, UMP_ERR_INPUT,
              "PPE: fixed-pressure faces need face pressures");
    double *b = P->rhs;
    for (ump_idx c = 0; c < m->ncells; c++)
        b[c] = 0.0;
    double rdt = 1.0 / dt;
    /* Eq. 20 right-hand side: (1/dt) sum_f s_f phi_f, outward from each cell */
    for (ump_idx f = 0; f < m->ninternal; f++) {
        double q = rdt * flux[f];
        b[m->owner[f]] += q;
        b[m->neigh[f]] -= q;
    }
    for (ump_idx f = m->ninternal; f < m->nfaces; f++) {
        ump_idx o = m->owner[f];
        b[o] += rdt * flux[f];
        if (P->dirichlet[f])
            b[o] -= P->bd_coef[f] * pf[f]; /* known c p_f of the Dirichlet face row */
    }
    if (!P->has_dirichlet) {
        b[P->ref_cell] = P->ref_diag * P->ref_value;
        for (ump_idx k = 0; k < P->nref; k++)
            b[P->ref_row[k]] -= P->ref_a[k] * P->ref_value;
    }
    UMP_CALL(residual(P, b, p, &P->res0, err));
    UMP_CALL(lsolve_solve(P->fac, b, p, err));
    return residual(P, b, p, &P->res, err);
}

void ppe_face_gradient_flux(const ppe *P, const double *p, const double *pf, double *gflux)
{
    const mesh2d *m = P->m;
#pragma omp parallel for schedule(static) if (m->nfaces > 4096)
    for (ump_idx f = 0; f < m->nfaces; f++) {
        double s = 0.0;
        for (ump_idx k = P->fop_off[f]; k < P->fop_off[f + 1]; k++)
            s += P->fop_val[k] * p[P->fop_col[k]]; /* Eq. 25 row of face f */
        if (f >= m->ninternal && P->dirichlet[f])
            s += P->bd_coef[f] * pf[f];
        gflux[f] = s;
    }
}
