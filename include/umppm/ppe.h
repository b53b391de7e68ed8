/* SPDX-License-Identifier: GPL-3.0-or-later
 * ppe.h -- the pressure Poisson equation on the fixed pressure mesh
 * (module prefix ppe_), Eqs. (20), (22)-(26) of Ng, Sheu & Hwang (2016)
 * [NSH16]; docs/METHOD.md section 3.3.
 *
 * Kinematic pressure p (as icoFoam): sum_f grad p_f . A_f = (1/dt) sum_f u*_f . A_f.
 * Interior (and cyclic) face f between A (owner) and B (neighbour, at x_B - sep):
 *   grad p_f . A_f = [p_B - p_A + grad p_B . BB' - grad p_A . AA'] / |A'B'| * |A_f|
 * with A', B' the feet of the perpendiculars from A, B onto the line through
 * x_f along n_f, and grad p_A, grad p_B the LS gradients of lsq.h expanded in
 * their stencils (so the matrix reaches second neighbours, Fig. 4).
 * Boundary faces:
 *   - velocity prescribed (walls, inlets, noSlip, fixedValue U, symmetry):
 *     Neumann, no gradient term (the flux comes from the prescribed u_f);
 *   - pressure prescribed (p fixedValue, e.g. outlets): Dirichlet,
 *     grad p_f . A_f = (p_f - p_A') / |A'f| * |A_f|, A' the foot from A;
 *     p_f goes to the right-hand side.
 * With no Dirichlet face the problem is singular up to a constant: the row
 * of the reference cell (fvSolution pRefCell) is replaced by p = pRefValue,
 * as OpenFOAM's setReference does in effect (and its column moved to the
 * right-hand side, so a symmetric matrix stays symmetric). Every other cell
 * then balances exactly; the reference cell absorbs the net imbalance of the
 * fluxes (the net boundary outflow).
 * Faces whose centroid offsets AA', BB' are round-off (below 1e-10 of the
 * centroid-face distance) are treated as orthogonal: an orthogonal quad mesh
 * gives exactly the symmetric 5-point matrix (CHOLMOD under LSOLVE_AUTO).
 * The matrix depends only on the mesh and the set of Dirichlet faces: it is
 * assembled and factorized ONCE (ppe_create); each time step is one solve.
 */
#ifndef UMPPM_PPE_H
#define UMPPM_PPE_H

#include "umppm/lsolve.h"
#include "umppm/lsq.h"
#include "umppm/mesh2d.h"

typedef struct ppe_opts {
    lsolve_kind solver;   /* default LSOLVE_AUTO */
    ump_idx ref_cell;     /* used only if no face is Dirichlet */
    double ref_value;
    int quadratic;        /* 1: store the monomials' fluxes for
                             ppe_face_quadratic_flux (balanced buoyancy);
                             0: it computes them at each call */
} ppe_opts;

typedef struct ppe {
    const mesh2d *m;          /* borrowed */
    const lsq_grad *g;        /* borrowed */
    unsigned char *dirichlet; /* [nfaces] 1 for pressure-prescribed boundary faces */
    int has_dirichlet;
    ump_idx ref_cell;
    double ref_value;
    lsolve_mat *A;            /* assembled matrix (rows: cells) */
    lsolve *fac;              /* its factorization */
    double *bd_coef;          /* [nfaces] coefficient of p_f on Dirichlet faces */
    double *rhs;              /* [ncells] workspace */
    /* Face operator (Eq. 25 expanded through the LS weights), CSR over faces:
     * grad p_f . A_f = sum_k fop_val[k] p[fop_col[k]] (+ bd_coef[f] p_f on
     * Dirichlet faces); empty rows on Neumann faces. The matrix is assembled
     * from these rows (+ for the owner's row, - for the neighbour's), so
     * ppe_face_gradient_flux is exactly the matrix discretisation. */
    ump_idx *fop_off;         /* [nfaces+1] */
    ump_idx *fop_col;         /* [fop_off[nfaces]] cells */
    double *fop_val;          /* [fop_off[nfaces]] */
    /* [5 nfaces] ppe_face_quadratic_flux of x, y, x^2/2, xy, y^2/2 about
     * x_f: the face's flux of any quadratic is their combination; NULL
     * unless ppe_opts quadratic */
    double *qcoef;
    /* Reference cell (no Dirichlet face): its row becomes ref_diag p = ref_diag
     * pRefValue and its column is moved to the right-hand side, which keeps a
     * symmetric matrix symmetric (CHOLMOD on orthogonal meshes). */
    ump_idx nref;             /* entries of the reference column moved */
    ump_idx *ref_row;         /* [nref] rows i != ref_cell */
    double *ref_a;            /* [nref] original A(i, ref_cell) */
    double ref_diag;          /* A(ref_cell, ref_cell) */
    /* OpenFOAM's normalised residuals of the last ppe_solve's system (its
     * log line): before the solve, at the incoming p (the previous step's),
     * and after it */
    double res0, res;
    double *ax, *rowsum;      /* [ncells] workspace, row sums of A (NULL until used) */
    int symmetric;            /* A equals its transpose: products by lsolve_mat_mult_sym */
} ppe;

/* dirichlet [m->nfaces] (may be NULL: none) marks faces with prescribed p
 * (boundary faces only). o may be NULL: LSOLVE_AUTO, ref_cell 0, ref_value 0.
 * g must be the LS gradient of m; both are borrowed and must outlive *out. */
ump_status ppe_create(const mesh2d *m, const lsq_grad *g, const unsigned char *dirichlet,
                      const ppe_opts *o, ppe **out, ump_err *err);
void ppe_free(ppe **P);
/* Solve for p [ncells] given face fluxes phi_f = u*_f . n_f |f| [nfaces]
 * (per unit thickness), dt, and the prescribed face pressures pf [nfaces]
 * (read on Dirichlet faces only; may be NULL when there are none). */
ump_status ppe_solve(ppe *P, const double *flux, double dt, const double *pf, double *p, ump_err *err);
/* Face pressure-gradient flux grad p_f . A_f (per unit thickness) [nfaces]
 * from p, with the same discretisation as the matrix (Eq. 25): the
 * correction u_f = u*_f - dt grad p_f makes sum_f u_f . A_f = 0 per cell. */
void ppe_face_gradient_flux(const ppe *P, const double *p, const double *pf, double *gflux);

/* Eq. 25 of interior face f applied to the quadratic
 *   q(x) = a . (x - x_f) + 1/2 (x - x_f)^T H (x - x_f),  H = {Hxx, Hxy, Hyy},
 * evaluated at the centroids of the face's row (with cyclic shifts): the
 * flux grad q_f . A_f that ppe_face_gradient_flux would give for the cell
 * field q, so fluxes made of it are solved exactly by a global quadratic
 * with that gradient and Hessian (the balanced buoyancy, docs/METHOD.md
 * section 8). Dirichlet faces: their rule applied to q with q(x_f) = 0;
 * 0 on the other boundary faces. Five products where ppe_create stored the
 * monomials' fluxes (ppe_opts quadratic), else Eq. 25 expanded at each call
 * (the same numbers up to rounding). */
double ppe_face_quadratic_flux(const ppe *P, ump_idx f, const double a[2], const double H[3]);
#endif
