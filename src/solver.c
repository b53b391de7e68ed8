/* SPDX-License-Identifier: GPL-3.0-or-later
 * solver.c -- one UMPPM time step (Steps 5-12, Section 3.3 of seed 000).
 *
 * Data flow of a step (particles P, mesh M):
 *   P: u^n, r^n --(Eq. 14 implicit predictor, CPM Laplacian)--> u*
 *   P: r* = r^n + dt u*                                  (Eq. 9)
 *   M: u*_f, u*_P by MLS from P at r*                    (Eqs. 28-35, 32)
 *   M: PPE sum_f grad p_f . A_f = (1/dt) sum_f u*_f . A_f (Eqs. 20, 25)
 *   P: u^{n+1} = u* - dt grad p (MLS over centroid p)    (Eqs. 10, 33-34)
 *   P: r^{n+1} = r^n + dt u^{n+1}                        (Eq. 7)
 *   M: u_P = u*_P - dt grad p_P (LS gradient)            (Eqs. 36, 26)
 *   P: delete/add particles (UMPPM or UMPPM*)            (Section 3.2.2.2)
 *
 * Choices where the paper is silent (also in the README):
 *   - Boundary particles carry the prescribed velocity on fixedValue/noSlip/
 *     movingWallVelocity faces; on zeroGradient (outlet) faces the velocity of
 *     the owner cell (Eq. 36 of the previous step); on inletOutlet faces the
 *     inletValue where the last flux entered, else the owner cell velocity;
 *     on symmetry planes the owner cell velocity without its normal part.
 *   - MLS at a face whose velocity is not prescribed leaves out that face's
 *     own boundary particle (its value is derived from the interior).
 *   - The pressure gradient at a particle (Eq. 10) is the MLS derivative of
 *     the centroid pressures of the particle's cell and its N2 stencil,
 *     evaluated at the intermediate position r* where the particle was
 *     binned for Step 8.
 *   - A particle whose CPM moment matrix is singular (too few independent
 *     neighbours) gets the MPS Laplacian for that step (counted in stats).
 *   - Particles that cross a boundary face at r* or r^{n+1} are removed at
 *     the end of the step; the empty-cell refill then repopulates.
 *   - Buoyant: the energy equation (Eq. 37) uses the predictor's Laplacian
 *     rows (same particles at r^n, same coefficients a_j) scaled by
 *     dt kappa instead of dt nu. Temperature boundary particles carry the
 *     fixedValue; on zeroGradient (adiabatic) and symmetry faces they carry
 *     T_P + grad T_P . d_t of the owner cell, d_t the tangential part of
 *     x_f - x_P (the value a zero normal gradient gives, second order on
 *     smooth fields), so the implicit Laplacian sees no spurious flux there;
 *     inletOutlet: the inletValue where the last flux entered. T_P (Step 10)
 *     is the MLS value at the centroid of the particle temperatures after
 *     the move, before management, so refilled particles get T = T_P.
 */
#include "umppm/solver.h"
#include "umppm/lsq.h"
#include "umppm/mls.h"
#include "umppm/ppe.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

enum { BU_FIXED = 0, BU_OUTLET, BU_INLETOUTLET, BU_SYMMETRY };
enum { BT_FIXED = 0, BT_ZEROGRADIENT, BT_INLETOUTLET };

struct sol {
    const mesh2d *m;
    sol_settings set;
    part_set *P;
    part_bins bins;
    part_boundary bp;
    lsq_grad *g;
    ppe *pe;
    lsolve_krylov *kry;
    ump_idx kry_n;
    /* boundary conditions per boundary face b = f - ninternal */
    unsigned char *u_kind;
    double *ub, *vb;           /* prescribed velocity or inletValue */
    unsigned char *p_dir;      /* [nfaces] */
    double *pf;                /* [nfaces] prescribed face pressure (pi) */
    int need_ref;              /* no fixed-pressure face: pRefCell fixes the level */
    /* buoyant: temperature boundary conditions per boundary face, the
     * prescribed p_rgh of fixed-pressure faces, gh at cells and faces */
    unsigned char *t_kind;
    double *tb, *prgh_f, *ghc, *ghf;
    double *Tc, *gtx, *gty;    /* mesh temperature T_P and its LS gradient */
    /* mesh fields */
    double *p, *uc, *vc, *usc, *vsc, *flux, *gflux, *gx, *gy, *div;
    /* per particle workspace */
    size_t wcap;
    double *x0, *y0, *us, *vs, *rhs_u, *rhs_v, *Ts, *rhs_T;
    ump_idx *cell0;
    unsigned char *keep;
    /* predictor matrix rows */
    ump_idx *rp, *ci;
    double *lv, *cv;           /* Laplacian rows (sum a_j on the diagonal, -a_j
                                  off it) and the scaled system I + dt nu L */
    size_t rowcap;
    lsolve_mat *A;
    size_t Acap;
    /* neighbour scratch */
    part_nbr *nb;
    size_t nbcap;
    double *h, *k, *a, *c0, *cx, *cy, *vals;
};

void sol_default_settings(sol_settings *s)
{
    memset(s, 0, sizeof *s);
    s->nu = 0;
    s->variant = PART_UMPPM_STAR;
    s->alpha = 0.09;
    s->lap.model = LAP_CPM;
    s->lap.re_factor = 0; /* the model's default */
    s->ppe_solver = LSOLVE_AUTO;
    s->pred_pc = LSOLVE_PC_ILU0;
    s->pred_tol = 1e-12;
    s->pred_maxit = 500;
    s->p_ref_cell = 0;
    s->p_ref_value = 0;
}

#define FREE(p) do { free(p); (p) = NULL; } while (0)

void sol_free(sol **pS)
{
    if (!pS || !*pS)
        return;
    sol *S = *pS;
    part_free(&S->P);
    part_bins_free(&S->bins);
    part_boundary_free(&S->bp);
    lsq_free(&S->g);
    ppe_free(&S->pe);
    lsolve_krylov_free(&S->kry);
    lsolve_mat_free(&S->A);
    void *arr[] = {S->u_kind, S->ub, S->vb, S->p_dir, S->pf, S->p, S->uc, S->vc, S->usc, S->vsc,
                   S->flux, S->gflux, S->gx, S->gy, S->div, S->x0, S->y0, S->us, S->vs, S->rhs_u,
                   S->rhs_v, S->Ts, S->rhs_T, S->cell0, S->keep, S->rp, S->ci, S->lv, S->cv, S->nb,
                   S->h, S->k, S->a, S->c0, S->cx, S->cy, S->vals, S->t_kind, S->tb, S->prgh_f,
                   S->ghc, S->ghf, S->Tc, S->gtx, S->gty};
    for (size_t i = 0; i < sizeof arr / sizeof arr[0]; i++)
        free(arr[i]);
    free(S);
    *pS = NULL;
}

/* Grow the per-particle workspace to at least n particles. */
static ump_status grow_particle_work(sol *S, size_t n, ump_err *err)
{
    if (n <= S->wcap)
        return UMP_OK;
    size_t c = n > 2 * S->wcap ? n : 2 * S->wcap;
    void **arr[] = {(void **)&S->x0,    (void **)&S->y0,    (void **)&S->us, (void **)&S->vs,
                    (void **)&S->rhs_u, (void **)&S->rhs_v, (void **)&S->Ts, (void **)&S->rhs_T};
    for (size_t i = 0; i < sizeof arr / sizeof arr[0]; i++) {
        void *q = ump_realloc_array(*arr[i], c, sizeof(double));
        if (!q)
            return UMP_FAIL(err, UMP_ERR_NOMEM, "particles: out of memory (%zu)", c);
        *arr[i] = q;
    }
    ump_idx *cl = ump_realloc_array(S->cell0, c, sizeof *cl);
    unsigned char *kp = ump_realloc_array(S->keep, c, 1);
    ump_idx *rp = ump_realloc_array(S->rp, c + 1, sizeof *rp);
    if (!cl) return UMP_FAIL(err, UMP_ERR_NOMEM, "particles: out of memory (%zu)", c);
    S->cell0 = cl;
    if (!kp) return UMP_FAIL(err, UMP_ERR_NOMEM, "particles: out of memory (%zu)", c);
    S->keep = kp;
    if (!rp) return UMP_FAIL(err, UMP_ERR_NOMEM, "particles: out of memory (%zu)", c);
    S->rp = rp;
    S->wcap = c;
    return UMP_OK;
}

/* Scratch arrays for neighbour lists and MLS/Laplacian coefficients. */
static ump_status ensure_scratch(sol *S, size_t nc, ump_err *err)
{
    if (nc <= S->nbcap)
        return UMP_OK;
    part_nbr *nb = ump_realloc_array(S->nb, nc, sizeof *nb);
    if (!nb)
        return UMP_FAIL(err, UMP_ERR_NOMEM, "neighbour list: out of memory (%zu)", nc);
    S->nb = nb;
    double **arr[] = {&S->h, &S->k, &S->a, &S->c0, &S->cx, &S->cy, &S->vals};
    for (size_t i = 0; i < sizeof arr / sizeof arr[0]; i++) {
        double *q = ump_realloc_array(*arr[i], nc, sizeof(double));
        if (!q)
            return UMP_FAIL(err, UMP_ERR_NOMEM, "neighbour list: out of memory (%zu)", nc);
        *arr[i] = q;
    }
    S->nbcap = nc;
    return UMP_OK;
}

/* Neighbour list of a point into S->nb (grown as needed). */
static ump_status gather(sol *S, ump_idx c, double x, double y, size_t exclude, size_t *n, ump_err *err)
{
    for (;;) {
        size_t cnt = part_neighbours(S->m, S->P, &S->bins, &S->bp, c, x, y, exclude, S->nb, S->nbcap);
        if (cnt <= S->nbcap) {
            *n = cnt;
            return UMP_OK;
        }
        UMP_CALL(ensure_scratch(S, cnt + 64, err));
    }
}

/* The neighbours of fluid particle i (all but itself) and their offsets
 * into S->h, S->k: the set every particle Laplacian sees. */
static ump_status gather_offsets(sol *S, size_t i, size_t *n, ump_err *err)
{
    const part_set *P = S->P;
    UMP_CALL(gather(S, P->cell[i], P->x[i], P->y[i], i, n, err));
    for (size_t j = 0; j < *n; j++) {
        S->h[j] = S->nb[j].dx;
        S->k[j] = S->nb[j].dy;
    }
    return UMP_OK;
}

/* The temperature a zero normal gradient gives on boundary face f:
 * T_P + grad T_P . d_t, d_t = (x_f - x_P) minus its normal part. */
static double zero_gradient_T(const sol *S, ump_idx f)
{
    const mesh2d *m = S->m;
    ump_idx o = m->owner[f];
    double dx = m->fx[f] - m->cx[o], dy = m->fy[f] - m->cy[o];
    double dn = dx * m->nx[f] + dy * m->ny[f];
    dx -= dn * m->nx[f];
    dy -= dn * m->ny[f];
    return S->Tc[o] + S->gtx[o] * dx + S->gty[o] * dy;
}

/* Boundary particle values for this step (see the choices at the top). */
static void set_boundary_particles(sol *S)
{
    const mesh2d *m = S->m;
    for (ump_idx b = 0; b < S->bp.n; b++) {
        ump_idx f = S->bp.face[b], o = m->owner[f];
        double u = S->uc[o], v = S->vc[o];
        switch (S->u_kind[b]) {
        case BU_FIXED:
            u = S->ub[b];
            v = S->vb[b];
            break;
        case BU_INLETOUTLET:
            if (S->flux[f] < 0) {
                u = S->ub[b];
                v = S->vb[b];
            }
            break;
        case BU_SYMMETRY: {
            double un = u * m->nx[f] + v * m->ny[f];
            u -= un * m->nx[f];
            v -= un * m->ny[f];
            break;
        }
        default:
            break;
        }
        S->bp.u[b] = u;
        S->bp.v[b] = v;
    }
    if (!S->set.buoyant)
        return;
    lsq_gradient(S->g, S->Tc, S->gtx, S->gty);
    for (ump_idx b = 0; b < S->bp.n; b++) {
        ump_idx f = S->bp.face[b];
        double T = S->tb[b];
        if (S->t_kind[b] == BT_ZEROGRADIENT || (S->t_kind[b] == BT_INLETOUTLET && S->flux[f] >= 0))
            T = zero_gradient_T(S, f);
        S->bp.T[b] = T;
        /* fixed p_rgh: pi = p_rgh - beta (T_f - TRef) gh_f (the buoyant p_rgh
         * relation of solver.h) */
        if (S->p_dir[f])
            S->pf[f] = S->prgh_f[f] - S->set.beta * (T - S->set.t_ref) * S->ghf[f];
    }
}

static ump_status read_bcs(sol *S, const fld_field *U, const fld_field *pf, ump_err *err)
{
    const mesh2d *m = S->m;
    const pmesh *pm = m->pm;
    for (int p = 0; p < pm->npatches; p++) {
        const pmesh_patch *pp = &pm->patch[p];
        const fld_patch *bu = &U->patch[p], *bpp = &pf->patch[p];
        for (ump_idx i = 0; i < pp->n; i++) {
            ump_idx f = m->pmface_to_face[pp->start + i];
            if (f < m->ninternal)
                continue; /* empty (f < 0) or cyclic: not a boundary in 2-D */
            ump_idx b = f - m->ninternal;
            const double *val = bu->value + 3 * (size_t)i;
            switch (bu->type) {
            case FLD_BC_FIXEDVALUE:
            case FLD_BC_NOSLIP:
            case FLD_BC_MOVINGWALLVELOCITY:
                S->u_kind[b] = BU_FIXED;
                S->ub[b] = val[m->ax[0]];
                S->vb[b] = val[m->ax[1]];
                break;
            case FLD_BC_ZEROGRADIENT:
            case FLD_BC_CALCULATED:
                S->u_kind[b] = BU_OUTLET;
                break;
            case FLD_BC_INLETOUTLET:
                S->u_kind[b] = BU_INLETOUTLET;
                S->ub[b] = bu->aux[3 * (size_t)i + (size_t)m->ax[0]];
                S->vb[b] = bu->aux[3 * (size_t)i + (size_t)m->ax[1]];
                break;
            case FLD_BC_SYMMETRYPLANE:
            case FLD_BC_SYMMETRY:
                S->u_kind[b] = BU_SYMMETRY;
                break;
            default:
                return UMP_FAIL(err, UMP_ERR_UNSUPPORTED,
                                "U: boundary condition '%s' on patch '%s' is not supported for velocity",
                                fld_bc_name(bu->type), pp->name);
            }
            switch (bpp->type) {
            case FLD_BC_FIXEDVALUE:
                S->p_dir[f] = 1;
                S->pf[f] = bpp->value[i];
                if (S->prgh_f)
                    S->prgh_f[f] = bpp->value[i];
                break;
            case FLD_BC_ZEROGRADIENT:
            case FLD_BC_FIXEDFLUXPRESSURE:
            case FLD_BC_SYMMETRYPLANE:
            case FLD_BC_SYMMETRY:
            case FLD_BC_CALCULATED:
                break;
            default:
                return UMP_FAIL(err, UMP_ERR_UNSUPPORTED,
                                "p: boundary condition '%s' on patch '%s' is not supported for pressure",
                                fld_bc_name(bpp->type), pp->name);
            }
            if (S->p_dir[f] && S->u_kind[b] == BU_FIXED)
                return UMP_FAIL(err, UMP_ERR_INPUT,
                                "patch '%s': both U and p are fixed; fix one of them (inlet: fixedValue U "
                                "with zeroGradient p; outlet: zeroGradient/inletOutlet U with fixedValue p)",
                                pp->name);
        }
    }
    return UMP_OK;
}

/* Temperature boundary conditions (see the choices at the top). */
static ump_status read_t_bcs(sol *S, const fld_field *T, ump_err *err)
{
    const mesh2d *m = S->m;
    const pmesh *pm = m->pm;
    for (int p = 0; p < pm->npatches; p++) {
        const pmesh_patch *pp = &pm->patch[p];
        const fld_patch *bt = &T->patch[p];
        for (ump_idx i = 0; i < pp->n; i++) {
            ump_idx f = m->pmface_to_face[pp->start + i];
            if (f < m->ninternal)
                continue;
            ump_idx b = f - m->ninternal;
            switch (bt->type) {
            case FLD_BC_FIXEDVALUE:
                S->t_kind[b] = BT_FIXED;
                S->tb[b] = bt->value[i];
                break;
            case FLD_BC_ZEROGRADIENT:
            case FLD_BC_SYMMETRYPLANE:
            case FLD_BC_SYMMETRY:
                S->t_kind[b] = BT_ZEROGRADIENT;
                break;
            case FLD_BC_INLETOUTLET:
                S->t_kind[b] = BT_INLETOUTLET;
                S->tb[b] = bt->aux[i];
                break;
            default:
                return UMP_FAIL(err, UMP_ERR_UNSUPPORTED,
                                "T: boundary condition '%s' on patch '%s' is not supported for temperature "
                                "(fixedValue, zeroGradient, symmetry, symmetryPlane, inletOutlet)",
                                fld_bc_name(bt->type), pp->name);
            }
        }
    }
    return UMP_OK;
}

ump_status sol_create(const mesh2d *m, const sol_settings *s, const fld_field *U, const fld_field *pfld,
                      const fld_field *T, sol **out, ump_err *err)
{
    *out = NULL;
    sol *S = ump_alloc_array(1, sizeof *S);
    if (!S)
        return UMP_FAIL(err, UMP_ERR_NOMEM, "solver: out of memory");
    S->m = m;
    S->set = *s;
    ump_idx nc = m->ncells, nf = m->nfaces, nb = nf - m->ninternal;
    ump_status rc;
    double **cellarr[] = {&S->p, &S->uc, &S->vc, &S->usc, &S->vsc, &S->gx, &S->gy, &S->div};
    for (size_t i = 0; i < sizeof cellarr / sizeof cellarr[0]; i++)
        if (!(*cellarr[i] = ump_alloc_array((size_t)nc, sizeof(double))))
            goto nomem;
    if (!(S->flux = ump_alloc_array((size_t)nf, sizeof(double))) ||
        !(S->gflux = ump_alloc_array((size_t)nf, sizeof(double))) ||
        !(S->pf = ump_alloc_array((size_t)nf, sizeof(double))) ||
        !(S->p_dir = ump_alloc_array((size_t)nf, 1)) ||
        !(S->u_kind = ump_alloc_array((size_t)nb, 1)) ||
        !(S->ub = ump_alloc_array((size_t)nb, sizeof(double))) ||
        !(S->vb = ump_alloc_array((size_t)nb, sizeof(double))) ||
        !(S->A = ump_alloc_array(1, sizeof *S->A)))
        goto nomem;
    if (s->buoyant) {
        if (!T) {
            rc = UMP_FAIL(err, UMP_ERR_INPUT, "solver: a buoyant case needs the temperature field T");
            goto fail;
        }
        double **carr[] = {&S->Tc, &S->gtx, &S->gty, &S->ghc};
        for (size_t i = 0; i < sizeof carr / sizeof carr[0]; i++)
            if (!(*carr[i] = ump_alloc_array((size_t)nc, sizeof(double))))
                goto nomem;
        if (!(S->ghf = ump_alloc_array((size_t)nf, sizeof(double))) ||
            !(S->prgh_f = ump_alloc_array((size_t)nf, sizeof(double))) ||
            !(S->t_kind = ump_alloc_array((size_t)nb, 1)) ||
            !(S->tb = ump_alloc_array((size_t)nb, sizeof(double))))
            goto nomem;
        /* gh = g . x - ghRef with the 3-D cell and face centres (gh.H) */
        double X[3];
        for (ump_idx c = 0; c < nc; c++) {
            mesh_to3d(m, m->cx[c], m->cy[c], X);
            S->ghc[c] = s->g[0] * X[0] + s->g[1] * X[1] + s->g[2] * X[2] - s->gh_ref;
            S->Tc[c] = T->internal[c];
        }
        for (ump_idx f = 0; f < nf; f++) {
            mesh_to3d(m, m->fx[f], m->fy[f], X);
            S->ghf[f] = s->g[0] * X[0] + s->g[1] * X[1] + s->g[2] * X[2] - s->gh_ref;
        }
        if ((rc = read_t_bcs(S, T, err)) != UMP_OK)
            goto fail;
    }
    for (ump_idx c = 0; c < nc; c++) {
        S->uc[c] = U->internal[3 * (size_t)c + (size_t)m->ax[0]];
        S->vc[c] = U->internal[3 * (size_t)c + (size_t)m->ax[1]];
        S->p[c] = pfld->internal[c];
    }
    if ((rc = read_bcs(S, U, pfld, err)) != UMP_OK)
        goto fail;
    S->need_ref = 1;
    for (ump_idx f = 0; f < nf; f++)
        S->need_ref &= !S->p_dir[f];
    if (s->buoyant) /* the initial p_rgh as pi (solver.h) */
        for (ump_idx c = 0; c < nc; c++)
            S->p[c] -= s->beta * (S->Tc[c] - s->t_ref) * S->ghc[c];
    /* Step 1-4: mesh-only work, once */
    ppe_opts po = {s->ppe_solver, s->p_ref_cell, s->p_ref_value};
    if (s->p_ref_cell < 0 || s->p_ref_cell >= nc) {
        rc = UMP_FAIL(err, UMP_ERR_INPUT, "system/fvSolution: pRefCell %ld is not a cell (0..%ld)",
                      (long)s->p_ref_cell, (long)nc - 1);
        goto fail;
    }
    if ((rc = lsq_build(m, &S->g, err)) != UMP_OK ||
        (rc = ppe_create(m, S->g, S->p_dir, &po, &S->pe, err)) != UMP_OK ||
        (rc = part_boundary_create(&S->bp, m, err)) != UMP_OK ||
        (rc = part_create((size_t)nc * 2, &S->P, err)) != UMP_OK ||
        (rc = part_seed_centroids(S->P, m, S->uc, S->vc, S->Tc, err)) != UMP_OK ||
        (rc = part_bins_build(&S->bins, m, S->P, err)) != UMP_OK ||
        (rc = grow_particle_work(S, S->P->n, err)) != UMP_OK)
        goto fail;
    /* scratch large enough for any N2 stencil (pressure-gradient MLS) */
    ump_idx maxn2 = 0;
    for (ump_idx c = 0; c < nc; c++)
        maxn2 = UMP_MAX(maxn2, m->n2_off[c + 1] - m->n2_off[c]);
    if ((rc = ensure_scratch(S, (size_t)maxn2 + 64, err)) != UMP_OK)
        goto fail;
    /* face fluxes of the initial cell velocities (linear interpolation), as
     * icoFoam's createPhi: the first Courant number and inletOutlet need them */
    for (ump_idx f = 0; f < m->nfaces; f++) {
        ump_idx o = m->owner[f];
        double u = S->uc[o], v = S->vc[o];
        if (f < m->ninternal) {
            u = 0.5 * (u + S->uc[m->neigh[f]]);
            v = 0.5 * (v + S->vc[m->neigh[f]]);
        } else if (S->u_kind[f - m->ninternal] == BU_FIXED) {
            u = S->ub[f - m->ninternal];
            v = S->vb[f - m->ninternal];
        } else if (S->u_kind[f - m->ninternal] == BU_SYMMETRY) {
            u = v = 0;
        }
        S->flux[f] = (u * m->nx[f] + v * m->ny[f]) * m->len[f];
    }
    set_boundary_particles(S);
    *out = S;
    return UMP_OK;
nomem:
    rc = UMP_FAIL(err, UMP_ERR_NOMEM, "solver: out of memory");
fail:
    sol_free(&S);
    return rc;
}

ump_status sol_set_particles(sol *S, size_t n, const double *x, const double *y, const double *u,
                             const double *v, const double *T, const int64_t *id, const ump_idx *hint,
                             size_t *dropped, ump_err *err)
{
    part_set *P = S->P;
    P->n = 0;
    *dropped = 0;
    UMP_CALL(part_reserve(P, n, err));
    int64_t maxid = -1;
    for (size_t i = 0; i < n; i++) {
        double px = x[i], py = y[i];
        ump_idx cell, face;
        ump_idx start = hint && hint[i] >= 0 && hint[i] < S->m->ncells ? hint[i] : 0;
        if (part_locate(S->m, start, &px, &py, &cell, &face) != PART_INSIDE) {
            (*dropped)++;
            continue;
        }
        size_t idx;
        double Ti = T ? T[i] : S->Tc ? S->Tc[cell] : 0.0;
        UMP_CALL(part_add(P, px, py, u[i], v[i], Ti, cell, &idx, err));
        if (id) {
            P->id[idx] = id[i];
            if (id[i] > maxid)
                maxid = id[i];
        }
    }
    if (id && maxid + 1 > P->next_id)
        P->next_id = maxid + 1;
    UMP_CALL(part_bins_build(&S->bins, S->m, P, err));
    return grow_particle_work(S, P->n, err);
}

void sol_set_pressure(sol *S, const double *p)
{
    memcpy(S->p, p, (size_t)S->m->ncells * sizeof *S->p);
}

/* The system I + dts L of the stored Laplacian rows (diagonal first in
 * each row) into S->A. */
static ump_status scaled_system(sol *S, size_t n, double dts, ump_err *err)
{
    size_t nz = (size_t)S->rp[n];
    for (size_t k = 0; k < nz; k++)
        S->cv[k] = dts * S->lv[k];
    for (size_t i = 0; i < n; i++)
        S->cv[S->rp[i]] += 1.0;
    return lsolve_mat_from_csr(S->A, &S->Acap, (ump_idx)n, S->rp, S->ci, S->cv, err);
}

/* Step 6: implicit predictor (Eq. 14) with the particle Laplacian (Eq. 16),
 * the Boussinesq source (Eq. 4) and, buoyant, the energy equation (Eq. 37). */
static ump_status predictor(sol *S, double dt, sol_stats *st, ump_err *err)
{
    const mesh2d *m = S->m;
    part_set *P = S->P;
    size_t n = P->n, nz = 0;
    const sol_settings *set = &S->set;
    int buoyant = set->buoyant;
    double dnu = dt * set->nu, dkap = dt * set->kappa;
    double gx = buoyant ? set->g[m->ax[0]] : 0, gy = buoyant ? set->g[m->ax[1]] : 0;
    lap_params mps = {LAP_MPS, 3.1};
    S->rp[0] = 0;
    for (size_t i = 0; i < n; i++) {
        size_t cnt;
        ump_idx c = P->cell[i];
        UMP_CALL(gather_offsets(S, i, &cnt, err));
        double l0 = sqrt(m->area[c]);
        ump_err lerr;
        if (lap_coeffs(&set->lap, S->h, S->k, (int)cnt, l0, S->a, &lerr) != UMP_OK) {
            st->lap_fallbacks++;
            UMP_CALL(lap_coeffs(&mps, S->h, S->k, (int)cnt, l0, S->a, err));
        }
        /* grow the row storage: at most cnt + 1 entries in this row */
        if (nz + cnt + 1 > S->rowcap) {
            size_t ncap = 2 * (nz + cnt + 1) + 1024;
            ump_idx *ci = ump_realloc_array(S->ci, ncap, sizeof *ci);
            if (!ci)
                return UMP_FAIL(err, UMP_ERR_NOMEM, "predictor: out of memory");
            S->ci = ci;
            double *lv = ump_realloc_array(S->lv, ncap, sizeof *lv);
            if (!lv)
                return UMP_FAIL(err, UMP_ERR_NOMEM, "predictor: out of memory");
            S->lv = lv;
            double *cv = ump_realloc_array(S->cv, ncap, sizeof *cv);
            if (!cv)
                return UMP_FAIL(err, UMP_ERR_NOMEM, "predictor: out of memory");
            S->cv = cv;
            S->rowcap = ncap;
        }
        /* Laplacian row: L phi_i = sum_j a_j (phi_j - phi_i); boundary
         * particles are known values, moved to the right-hand side:
         * (1 + dt nu sum a_j) u*_i - dt nu sum_fluid a_j u*_j
         *     = u^n_i + dt nu sum_bnd a_j u_b + dt S_i        (Eq. 14)
         * and likewise T with dt kappa                         (Eq. 37) */
        double suma = 0, bu = 0, bv = 0, bT = 0;
        size_t dpos = nz++;
        for (size_t j = 0; j < cnt; j++) {
            double a = S->a[j];
            suma += a;
            if (S->nb[j].is_boundary) {
                size_t q = S->nb[j].index;
                bu += a * S->bp.u[q];
                bv += a * S->bp.v[q];
                bT += a * S->bp.T[q];
            } else {
                S->ci[nz] = (ump_idx)S->nb[j].index;
                S->lv[nz++] = -a;
            }
        }
        S->ci[dpos] = (ump_idx)i;
        S->lv[dpos] = suma;
        S->rp[i + 1] = (ump_idx)nz;
        /* Boussinesq source per unit mass, -beta (T^n - TRef) g (Eq. 4) */
        double b = buoyant ? -set->beta * (P->T[i] - set->t_ref) : 0;
        S->rhs_u[i] = P->u[i] + dnu * bu + dt * b * gx;
        S->rhs_v[i] = P->v[i] + dnu * bv + dt * b * gy;
        S->rhs_T[i] = P->T[i] + dkap * bT;
    }
    UMP_CALL(scaled_system(S, n, dnu, err));
    if (!S->kry || S->kry_n < (ump_idx)n) {
        lsolve_krylov_free(&S->kry);
        ump_idx kn = (ump_idx)(n + n / 2 + 16);
        UMP_CALL(lsolve_krylov_create(kn, &S->kry, err));
        S->kry_n = kn;
    }
    memcpy(S->us, P->u, n * sizeof *S->us); /* warm start from u^n */
    memcpy(S->vs, P->v, n * sizeof *S->vs);
    UMP_CALL(lsolve_bicgstab(S->kry, S->A, set->pred_pc, S->rhs_u, S->us, set->pred_tol, set->pred_maxit,
                             &st->pred[0], err));
    UMP_CALL(lsolve_bicgstab_again(S->kry, S->A, set->pred_pc, S->rhs_v, S->vs, set->pred_tol,
                                   set->pred_maxit, &st->pred[1], err));
    int ns = 2;
    if (buoyant) {
        /* Eq. 37: the same rows with dt kappa; T^n is the warm start */
        memcpy(S->Ts, P->T, n * sizeof *S->Ts);
        if (dkap == dnu) {
            UMP_CALL(lsolve_bicgstab_again(S->kry, S->A, set->pred_pc, S->rhs_T, S->Ts, set->pred_tol,
                                           set->pred_maxit, &st->pred[2], err));
        } else {
            UMP_CALL(scaled_system(S, n, dkap, err));
            UMP_CALL(lsolve_bicgstab(S->kry, S->A, set->pred_pc, S->rhs_T, S->Ts, set->pred_tol,
                                     set->pred_maxit, &st->pred[2], err));
        }
        ns = 3;
    }
    for (int k = 0; k < ns; k++)
        if (st->pred[k].converged < 0)
            return UMP_FAIL(err, UMP_ERR_SINGULAR, "predictor: BiCGSTAB broke down solving for %s "
                            "(residual %g)", k == 2 ? "T" : k ? "v" : "u", st->pred[k].res);
    if (buoyant)
        memcpy(P->T, S->Ts, n * sizeof *P->T);
    return UMP_OK;
}

/* MLS value (Eq. 32) at (x, y) in cell c of nv particle quantities:
 * fluid[k] [particles] and bnd[k] [boundary particles] give quantity k,
 * out[k] its value, and gx[k], gy[k] its derivatives (Eqs. 33-34) unless gx
 * is NULL; skip_face's own boundary particle is left out (-1: none). */
static ump_status mls_particles(sol *S, ump_idx c, double x, double y, double mdx, double mdy,
                                ump_idx skip_face, int nv, const double *const *fluid,
                                const double *const *bnd, double *out, double *gx, double *gy,
                                sol_stats *st, ump_err *err)
{
    size_t cnt;
    UMP_CALL(gather(S, c, x, y, SIZE_MAX, &cnt, err));
    int n = 0;
    for (size_t j = 0; j < cnt && n < MLS_MAX_SAMPLES; j++) {
        const part_nbr *q = &S->nb[j];
        if (q->is_boundary && S->bp.face[q->index] == skip_face)
            continue;
        S->h[n] = q->dx;
        S->k[n] = q->dy;
        S->nb[n] = *q;
        n++;
    }
    mls_info info;
    mls_basis b = mls_weights(S->h, S->k, n, mdx, mdy, S->c0, gx ? S->cx : NULL, gx ? S->cy : NULL, &info);
    if (b != MLS_QUADRATIC)
        st->mls_fallbacks++;
    for (int k = 0; k < nv; k++) {
        double sum = 0, sx = 0, sy = 0;
        for (int j = 0; j < n; j++) {
            const part_nbr *q = &S->nb[j];
            double v = q->is_boundary ? bnd[k][q->index] : fluid[k][q->index];
            sum += S->c0[j] * v;
            if (gx) {
                sx += S->cx[j] * v;
                sy += S->cy[j] * v;
            }
        }
        out[k] = sum;
        if (gx) {
            gx[k] = sx;
            gy[k] = sy;
        }
    }
    return UMP_OK;
}

/* MLS u* (Step 8) at (x, y) in cell c. */
static ump_status mls_velocity(sol *S, ump_idx c, double x, double y, double mdx, double mdy,
                               ump_idx skip_face, double *u, double *v, sol_stats *st, ump_err *err)
{
    const double *fluid[2] = {S->us, S->vs}, *bnd[2] = {S->bp.u, S->bp.v};
    double uv[2];
    UMP_CALL(mls_particles(S, c, x, y, mdx, mdy, skip_face, 2, fluid, bnd, uv, NULL, NULL, st, err));
    *u = uv[0];
    *v = uv[1];
    return UMP_OK;
}

/* MLS gradient of the centroid pressure at (x, y) in cell c (Eqs. 33-34). */
static void mls_pressure_gradient(sol *S, ump_idx c, double x, double y, double *gx, double *gy,
                                  sol_stats *st)
{
    const mesh2d *m = S->m;
    int n = 0;
    S->h[n] = m->cx[c] - x;
    S->k[n] = m->cy[c] - y;
    S->vals[n++] = S->p[c];
    for (ump_idx k = m->n2_off[c]; k < m->n2_off[c + 1] && n < (int)S->nbcap; k++) {
        ump_idx q = m->n2[k];
        S->h[n] = m->cx[q] + (m->n2_sx ? m->n2_sx[k] : 0) - x;
        S->k[n] = m->cy[q] + (m->n2_sy ? m->n2_sy[k] : 0) - y;
        S->vals[n++] = S->p[q];
    }
    mls_info info;
    mls_basis b = mls_weights(S->h, S->k, n, m->dx[c], m->dy[c], S->c0, S->cx, S->cy, &info);
    if (b != MLS_QUADRATIC)
        st->mls_fallbacks++;
    double sx = 0, sy = 0;
    for (int j = 0; j < n; j++) {
        sx += S->cx[j] * S->vals[j];
        sy += S->cy[j] * S->vals[j];
    }
    *gx = sx;
    *gy = sy;
}

ump_status sol_step(sol *S, double dt, sol_stats *st, ump_err *err)
{
    const mesh2d *m = S->m;
    part_set *P = S->P;
    memset(st, 0, sizeof *st);
    UMP_CALL(grow_particle_work(S, P->n, err));
    size_t n = P->n;
    set_boundary_particles(S);

    /* Step 6: u* */
    UMP_CALL(predictor(S, dt, st, err));

    /* Step 7: r* = r^n + dt u* (Eq. 9), re-locate and re-bin */
    for (size_t i = 0; i < n; i++) {
        S->x0[i] = P->x[i];
        S->y0[i] = P->y[i];
        S->cell0[i] = P->cell[i];
        S->keep[i] = 1;
        double x = P->x[i] + dt * S->us[i], y = P->y[i] + dt * S->vs[i];
        ump_idx cell, face;
        if (part_locate(m, P->cell[i], &x, &y, &cell, &face) == PART_INSIDE) {
            P->x[i] = x;
            P->y[i] = y;
            P->cell[i] = cell;
        } else {
            S->keep[i] = 0; /* left the domain: stays at r^n for this step's interpolation */
        }
    }
    UMP_CALL(part_bins_build(&S->bins, m, P, err));

    /* Step 8: MLS u* at faces (fluxes) and centroids */
    for (ump_idx f = 0; f < m->nfaces; f++) {
        double u, v;
        if (f >= m->ninternal) {
            ump_idx b = f - m->ninternal;
            if (S->u_kind[b] == BU_FIXED) {
                S->flux[f] = (S->ub[b] * m->nx[f] + S->vb[b] * m->ny[f]) * m->len[f];
                continue;
            }
            if (S->u_kind[b] == BU_SYMMETRY) {
                S->flux[f] = 0;
                continue;
            }
        }
        ump_idx o = m->owner[f];
        double mdx = m->dx[o], mdy = m->dy[o];
        if (f < m->ninternal) {
            mdx = 0.5 * (mdx + m->dx[m->neigh[f]]);
            mdy = 0.5 * (mdy + m->dy[m->neigh[f]]);
        }
        UMP_CALL(mls_velocity(S, o, m->fx[f], m->fy[f], mdx, mdy, f, &u, &v, st, err));
        S->flux[f] = (u * m->nx[f] + v * m->ny[f]) * m->len[f]; /* u*_f . A_f, Eq. 20 RHS */
    }
    for (ump_idx c = 0; c < m->ncells; c++)
        UMP_CALL(mls_velocity(S, c, m->cx[c], m->cy[c], m->dx[c], m->dy[c], -1, &S->usc[c], &S->vsc[c],
                              st, err));

    /* Step 9: PPE, one solve with the factorization made at start-up */
    UMP_CALL(ppe_solve(S->pe, S->flux, dt, S->pf, S->p, err));
    ppe_face_gradient_flux(S->pe, S->p, S->pf, S->gflux);
    for (ump_idx f = 0; f < m->nfaces; f++)
        S->flux[f] -= dt * S->gflux[f]; /* corrected face flux u^{n+1}_f . A_f */

    /* Step 10: velocity correction (Eq. 10) and final positions (Eq. 7) */
    for (size_t i = 0; i < n; i++) {
        double gx, gy;
        mls_pressure_gradient(S, P->cell[i], P->x[i], P->y[i], &gx, &gy, st);
        P->u[i] = S->us[i] - dt * gx;
        P->v[i] = S->vs[i] - dt * gy;
        double x = S->x0[i] + dt * P->u[i], y = S->y0[i] + dt * P->v[i];
        ump_idx cell, face;
        if (part_locate(m, S->cell0[i], &x, &y, &cell, &face) == PART_INSIDE) {
            P->x[i] = x;
            P->y[i] = y;
            P->cell[i] = cell;
        } else {
            S->keep[i] = 0;
        }
    }
    /* mesh velocity, Eq. 36, with the LS gradient of Eq. 26 */
    lsq_gradient(S->g, S->p, S->gx, S->gy);
    for (ump_idx c = 0; c < m->ncells; c++) {
        S->uc[c] = S->usc[c] - dt * S->gx[c];
        S->vc[c] = S->vsc[c] - dt * S->gy[c];
    }

    /* Step 11: removal, then management and refill */
    size_t before = P->n;
    part_compact(P, S->keep);
    st->left = before - P->n;
    UMP_CALL(part_bins_build(&S->bins, m, P, err));
    if (S->set.buoyant) {
        /* Step 10: mesh temperature T_P, MLS of the particle temperatures */
        const double *fluid[1] = {P->T}, *bnd[1] = {S->bp.T};
        for (ump_idx c = 0; c < m->ncells; c++)
            UMP_CALL(mls_particles(S, c, m->cx[c], m->cy[c], m->dx[c], m->dy[c], -1, 1, fluid, bnd,
                                   &S->Tc[c], NULL, NULL, st, err));
    }
    part_manage_stats ms;
    UMP_CALL(part_manage(P, &S->bins, m, S->set.variant, S->set.alpha, S->uc, S->vc, S->Tc, &ms, err));
    st->added = ms.added;
    st->deleted = ms.deleted_close + ms.deleted_extra;
    st->np = P->n;

    /* continuity after correction, as icoFoam's continuityErrs.H */
    memset(S->div, 0, (size_t)m->ncells * sizeof *S->div);
    for (ump_idx f = 0; f < m->nfaces; f++) {
        S->div[m->owner[f]] += S->flux[f];
        if (f < m->ninternal)
            S->div[m->neigh[f]] -= S->flux[f];
    }
    double atot = 0, sl = 0, sg = 0, mx = 0;
    for (ump_idx c = 0; c < m->ncells; c++) {
        atot += m->area[c];
        sl += fabs(S->div[c]);
        sg += S->div[c];
        mx = fmax(mx, fabs(S->div[c]) / m->area[c]);
    }
    st->cont_local = dt * sl / atot;
    st->cont_global = dt * sg / atot;
    st->cont_max = dt * mx;
    sol_courant(S, dt, &st->co_mean, &st->co_max);
    return UMP_OK;
}

void sol_courant(const sol *S, double dt, double *mean, double *max)
{
    const mesh2d *m = S->m;
    double mx = 0, s = 0, atot = 0;
    /* 0.5 dt sum_f |phi_f| / V per cell (OpenFOAM CourantNo.H) */
    for (ump_idx c = 0; c < m->ncells; c++) {
        double sum = 0;
        for (ump_idx k = m->cell_face_off[c]; k < m->cell_face_off[c + 1]; k++)
            sum += fabs(S->flux[m->cell_faces[k]]);
        double co = 0.5 * dt * sum / m->area[c];
        mx = fmax(mx, co);
        s += sum;
        atot += m->area[c];
    }
    *max = mx;
    *mean = 0.5 * dt * s / atot;
}

const double *sol_cell_u(const sol *S) { return S->uc; }
const double *sol_cell_v(const sol *S) { return S->vc; }
const double *sol_cell_p(const sol *S) { return S->p; }
/* Seed 001 Eqs. 13 and 22 per fluid particle, over the predictor's
 * neighbours (the same gather), r_e = re_factor * sqrt(cell area). */
ump_status sol_particle_quality(sol *S, double *uN, double *tau, size_t *nfail, ump_err *err)
{
    part_set *P = S->P;
    size_t bad = 0;
    /* the bins are current between steps: sol_set_particles and the
     * management of Step 11 (part_manage) rebuild them on exit */
    for (size_t i = 0; i < P->n; i++) {
        size_t cnt;
        ump_idx c = P->cell[i];
        UMP_CALL(gather_offsets(S, i, &cnt, err));
        const double *off[2] = {S->h, S->k};
        lap_quality q;
        ump_err lerr;
        if (lap_quality_d(S->set.lap.re_factor, 2, off, (int)cnt, sqrt(S->m->area[c]), S->a, &q,
                          &lerr) != UMP_OK) {
            memset(&q, 0, sizeof q);
            bad++;
        }
        uN[2 * i] = q.uN[0];
        uN[2 * i + 1] = q.uN[1];
        tau[3 * i] = q.tau[0];
        tau[3 * i + 1] = q.tau[1];
        tau[3 * i + 2] = q.tau[3];
    }
    if (nfail)
        *nfail = bad;
    return UMP_OK;
}

const part_set *sol_particles(const sol *S) { return S->P; }

void sol_face_values(const sol *S, ump_idx f, double *u, double *v, double *p)
{
    const mesh2d *m = S->m;
    ump_idx o = m->owner[f];
    *u = S->uc[o];
    *v = S->vc[o];
    *p = S->p[o];
    if (f < m->ninternal)
        return;
    ump_idx b = f - m->ninternal;
    if (S->u_kind[b] == BU_FIXED) {
        *u = S->ub[b];
        *v = S->vb[b];
    } else if (S->u_kind[b] == BU_SYMMETRY) {
        double un = *u * m->nx[f] + *v * m->ny[f];
        *u -= un * m->nx[f];
        *v -= un * m->ny[f];
    } else if (S->u_kind[b] == BU_INLETOUTLET && S->flux[f] < 0) {
        *u = S->ub[b];
        *v = S->vb[b];
    }
    if (S->p_dir[f])
        *p = S->pf[f];
}

const double *sol_cell_T(const sol *S) { return S->Tc; }

double sol_face_T(const sol *S, ump_idx f)
{
    if (!S->set.buoyant || f < S->m->ninternal)
        return S->Tc ? S->Tc[S->m->owner[f]] : 0.0;
    return S->bp.T[f - S->m->ninternal];
}

void sol_buoyant_pressure(const sol *S, ump_idx c, ump_idx f, double *p, double *p_rgh)
{
    const sol_settings *s = &S->set;
    double shift = 0;
    if (S->need_ref) { /* pEqn.H: p += pRefValue - p[pRefCell] */
        ump_idx r = s->p_ref_cell;
        shift = s->p_ref_value - (S->p[r] + S->ghc[r]);
    }
    double pi, gh, T;
    if (f >= 0) {
        double u, v;
        sol_face_values(S, f, &u, &v, &pi);
        gh = S->ghf[f];
        T = sol_face_T(S, f);
    } else {
        pi = S->p[c];
        gh = S->ghc[c];
        T = S->Tc[c];
    }
    double rhok = 1.0 - s->beta * (T - s->t_ref);
    *p = pi + gh + shift;
    *p_rgh = *p - rhok * gh;
}

ump_status sol_wall_dTdn(sol *S, ump_idx f, sol_grad_method how, double *dTdn, ump_err *err)
{
    const mesh2d *m = S->m;
    if (!S->set.buoyant || f < m->ninternal || f >= m->nfaces)
        return UMP_FAIL(err, UMP_ERR_INPUT, "wall heat flux: face %ld is not a boundary face of a buoyant case",
                        (long)f);
    ump_idx o = m->owner[f];
    double nx = m->nx[f], ny = m->ny[f];
    if (how == SOL_GRAD_SNGRAD) {
        double d = (m->fx[f] - m->cx[o]) * nx + (m->fy[f] - m->cy[o]) * ny;
        *dTdn = (sol_face_T(S, f) - S->Tc[o]) / d;
        return UMP_OK;
    }
    /* quadratic MLS derivative (Eqs. 33-34) at the face centre over the
     * fluid and boundary particles of the owner's N2 stencil */
    const double *fluid[1] = {S->P->T}, *bnd[1] = {S->bp.T};
    double T, gx, gy;
    sol_stats st = {0};
    UMP_CALL(mls_particles(S, o, m->fx[f], m->fy[f], m->dx[o], m->dy[o], -1, 1, fluid, bnd, &T, &gx, &gy,
                           &st, err));
    *dTdn = gx * nx + gy * ny;
    return UMP_OK;
}
