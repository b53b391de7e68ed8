/* SPDX-License-Identifier: GPL-3.0-or-later
 * mps.c -- the fully implicit MPS step (see mps.h and docs/METHOD.md
 * section 9).
 *
 * Layout: the part_set holds solid particles [0, ns) then fluid particles
 * [ns, n). Per-particle arrays of this module (pressure, number density,
 * flags) have the same indexing. Each stage rebuilds what it needs:
 *
 *   viscous step   grid + neighbour rows at r^n for fluid particles;
 *                  (I - dt nu L) u* = u^n + dt g, CG per component
 *   move           r* = r^n + dt u*
 *   collisions     (optional) rows at r*, approaching close pairs
 *                  exchange momentum, rows rebuilt if any did
 *   pressure       rows at r* for fluid and wall particles: n*, free
 *                  surface, PPE, CG
 *   correction     u^{n+1} = u* - dt/rho grad p, r^{n+1} = r* + dt u'
 *
 * A row is the list of neighbours of one particle within the largest
 * radius, in increasing particle index (so every sum is the same for any
 * number of threads), with the offset and the distance of each.
 */
#include "umppm/mps.h"
#include "umppm/coarse.h"
#include "umppm/pnbr.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/time.h>
#include <time.h>

#define DIM 2 /* d of Eqs. 4, 6: the plane */
#define MPS_SKIN 0.6 /* Verlet skin of the neighbour rows, in l0 */
#define MPS_AGG 3.0  /* side of the PPE's coarse aggregates, in l0 */

struct mps {
    mps_params P;
    part_set *s;
    size_t ns;                 /* solid particles */
    unsigned char *kind;       /* [cap] MPS_FLUID / MPS_WALL / MPS_DUMMY / MPS_HIDDEN */
    unsigned char *kind0;      /* [ns] the solids' own kinds (mps_hide) */
    double n0_n, n0_lap, lambda;
    size_t cap;                /* capacity of the per-particle arrays */
    double *p, *nd, *gx, *gy, *div, *tmp;
    unsigned char *surf;
    long *unk;                 /* PPE unknown of a particle, -1 if none */
    size_t *unk_part;          /* particle of an unknown */
    pnbr nb;                   /* neighbour rows (pnbr.h) */
    /* matrix of the current solve (rows of unknowns) */
    ump_idx *rp, *ci;
    double *av, *b, *x;
    size_t mcap_rows, mcap_nz;
    lsolve_rows *kry;
    /* two-level preconditioner of the PPE (see pressure(); coarse.h) */
    coarse *cl;                /* the coarse level */
    double *dinv;              /* [cap] Jacobi */
    ump_idx trip_rows;         /* order of the fine system of coarse_apply */
    int coarse_ok;             /* the coarse factor of this step is usable */
};

static double cpu_seconds(void) { return (double)clock() / CLOCKS_PER_SEC; }

static double wall_seconds(void)
{
    struct timeval tv;
    gettimeofday(&tv, NULL);
    return (double)tv.tv_sec + 1e-6 * (double)tv.tv_usec;
}

void mps_lattice_sums(double re, double *sum_w, double *sum_r2w)
{
    long k = (long)ceil(re) + 1;
    double sw = 0, sr = 0;
    for (long a = -k; a <= k; a++)
        for (long c = -k; c <= k; c++) {
            if (!a && !c)
                continue;
            double r = sqrt((double)(a * a + c * c)), w = mps_weight(r, re);
            sw += w;
            sr += r * r * w;
        }
    *sum_w = sw;
    *sum_r2w = sr;
}

/* ---- storage ------------------------------------------------------------- */

#define GROW_TO(ptr, n)                                              \
    do {                                                             \
        void *q_ = ump_realloc_array((ptr), (n), sizeof *(ptr));     \
        if (!q_)                                                     \
            return UMP_FAIL(err, UMP_ERR_NOMEM, "MPS: out of memory for %zu particles", (size_t)(n)); \
        (ptr) = q_;                                                  \
    } while (0)

/* Per-particle arrays for the part_set's current size (grown x1.5). */
static ump_status reserve(mps *m, ump_err *err)
{
    size_t n = m->s->n;
    if (n <= m->cap && m->p)
        return UMP_OK;
    size_t nc = n + n / 2 + 16, old = m->cap;
    GROW_TO(m->kind, nc);
    GROW_TO(m->p, nc);
    GROW_TO(m->nd, nc);
    GROW_TO(m->gx, nc);
    GROW_TO(m->gy, nc);
    GROW_TO(m->div, nc);
    GROW_TO(m->tmp, nc);
    GROW_TO(m->dinv, nc);
    GROW_TO(m->surf, nc);
    GROW_TO(m->unk, nc);
    GROW_TO(m->unk_part, nc);
    for (size_t i = old; i < nc; i++) {
        m->kind[i] = MPS_FLUID;
        m->p[i] = m->nd[i] = 0;
        m->surf[i] = 0;
    }
    m->cap = nc;
    return UMP_OK;
}

ump_status mps_create(const mps_params *prm, part_set *s, size_t nsolid, const unsigned char *kinds, mps **out,
                      ump_err *err)
{
    *out = NULL;
    UMP_CHECK(prm->l0 > 0 && isfinite(prm->l0), err, UMP_ERR_INPUT, "MPS: particle spacing %g", prm->l0);
    UMP_CHECK(prm->re_n > 1 && prm->re_lap >= prm->re_n, err, UMP_ERR_INPUT,
              "MPS: radii %g (number density) and %g (Laplacian) x l0: need 1 < first <= second", prm->re_n,
              prm->re_lap);
    UMP_CHECK(prm->beta > 0 && prm->beta < 1, err, UMP_ERR_INPUT, "MPS: beta %g not in (0, 1)", prm->beta);
    UMP_CHECK(prm->rho > 0 && prm->nu >= 0, err, UMP_ERR_INPUT, "MPS: rho %g, nu %g", prm->rho, prm->nu);
    UMP_CHECK(nsolid <= s->n, err, UMP_ERR_INPUT, "MPS: %zu solid particles of %zu", nsolid, s->n);
    mps *m = ump_alloc_array(1, sizeof *m);
    UMP_CHECK(m, err, UMP_ERR_NOMEM, "MPS: out of memory");
    m->P = *prm;
    m->s = s;
    m->ns = nsolid;
    ump_status rc;
    if ((rc = reserve(m, err)) != UMP_OK || (rc = lsolve_rows_create(&m->kry, err)) != UMP_OK ||
        (rc = coarse_create(&m->cl, err)) != UMP_OK) {
        mps_free(&m);
        return rc;
    }
    m->kind0 = ump_alloc_array(nsolid + 1, sizeof *m->kind0);
    if (!m->kind0) {
        mps_free(&m);
        return UMP_FAIL(err, UMP_ERR_NOMEM, "MPS: out of memory");
    }
    for (size_t i = 0; i < nsolid; i++)
        m->kind[i] = m->kind0[i] = kinds[i];
    double sw, sr;
    mps_lattice_sums(prm->re_n, &sw, &sr);
    m->n0_n = sw; /* Eq. 5 on the initial lattice, in units where l0 = 1 */

    mps_lattice_sums(prm->re_lap, &sw, &sr);
    m->n0_lap = sw;
    /* Eq. 7 on the lattice: lambda = sum r^2 w / sum w, in m^2 */
    m->lambda = prm->lambda > 0 ? prm->lambda : sr / sw * prm->l0 * prm->l0;
    *out = m;
    return UMP_OK;
}

void mps_free(mps **pm)
{
    if (!pm || !*pm)
        return;
    mps *m = *pm;
    free(m->kind);
    free(m->kind0);
    free(m->p);
    free(m->nd);
    free(m->gx);
    free(m->gy);
    free(m->div);
    free(m->tmp);
    free(m->dinv);
    coarse_free(&m->cl);
    free(m->surf);
    free(m->unk);
    free(m->unk_part);
    pnbr_free(&m->nb);
    free(m->rp);
    free(m->ci);
    free(m->av);
    free(m->b);
    free(m->x);
    lsolve_rows_free(&m->kry);
    free(m);
    *pm = NULL;
}

size_t mps_nsolid(const mps *m) { return m->ns; }

void mps_hide(mps *m, const unsigned char *hidden)
{
    for (size_t i = 0; i < m->ns; i++)
        m->kind[i] = hidden[i] ? MPS_HIDDEN : m->kind0[i];
}
void mps_set_gravity(mps *m, const double g[2])
{
    m->P.g[0] = g[0];
    m->P.g[1] = g[1];
}
const double *mps_pressure(const mps *m) { return m->p; }
const double *mps_density(const mps *m) { return m->nd; }
const unsigned char *mps_surface(const mps *m) { return m->surf; }

void mps_constants(const mps *m, double *n0_n, double *n0_lap, double *lambda)
{
    *n0_n = m->n0_n;
    *n0_lap = m->n0_lap;
    *lambda = m->lambda;
}

void mps_compact(mps *m, const unsigned char *keep, size_t n_before)
{
    size_t k = 0;
    for (size_t i = 0; i < n_before; i++) {
        if (!keep[i])
            continue;
        m->kind[k] = m->kind[i];
        m->p[k] = m->p[i];
        m->nd[k] = m->nd[i];
        m->surf[k] = m->surf[i];
        k++;
    }
}

/* ---- neighbours (pnbr.h) ----------------------------------------------------- */

/* Rows of fluid and wall particles within the largest radius plus a skin
 * (a Verlet list, pnbr.h): at r^n a new search (force), at r* and after
 * collisions an update that searches again only when some particle has
 * moved by more than half the skin since the build. */
static ump_status rows_update(mps *m, int force, ump_err *err)
{
    static const int need[4] = {1, 1, 0, -1};
    return pnbr_update(&m->nb, m->s, m->kind, need, m->P.re_lap * m->P.l0, MPS_SKIN * m->P.l0, force, "MPS",
                       err);
}
static ump_status neighbours(mps *m, ump_err *err) { return rows_update(m, 1, err); }
static ump_status refresh(mps *m, ump_err *err) { return rows_update(m, 0, err); }

/* ---- matrices ---------------------------------------------------------------- */

static ump_status matrix_reserve(mps *m, size_t nrows, size_t nz, ump_err *err)
{
    if (nrows + 1 > m->mcap_rows) {
        size_t nc = nrows + 1 + nrows / 2 + 16;
        GROW_TO(m->rp, nc);
        GROW_TO(m->b, nc);
        GROW_TO(m->x, nc);
        m->mcap_rows = nc;
    }
    if (nz > m->mcap_nz) {
        size_t nc = nz + nz / 2 + 64;
        GROW_TO(m->ci, nc);
        GROW_TO(m->av, nc);
        m->mcap_nz = nc;
    }
    return UMP_OK;
}

/* Row i of a Laplacian-type matrix  diag = d0 + c sum_{j in sum} w_ij,
 * off(j) = -c w_ij for j with unk[j] >= 0: columns in increasing unknown
 * order (unknowns are numbered in particle order, rows sorted by particle:
 * the same order), the diagonal in its place. Returns the entries written. */
static size_t laplace_row(const mps *m, size_t i, double d0, double c, double re, const unsigned char *in_sum,
                          ump_idx *col, double *val)
{
    const pnbr *R = &m->nb;
    size_t k = 0;
    double diag = d0;
    long me = m->unk[i];
    int placed = 0;
    for (size_t q = R->off[i]; q < R->off[i + 1]; q++) {
        size_t j = R->j[q];
        double w = mps_weight(R->r[q], re);
        if (w == 0 || !in_sum[m->kind[j]])
            continue;
        diag += c * w;
        if (m->unk[j] < 0)
            continue; /* known value: zero (wall velocity, free-surface pressure) */
        if (!placed && m->unk[j] > me) {
            col[k] = (ump_idx)me;
            val[k++] = 0; /* the diagonal, filled below */
            placed = 1;
        }
        col[k] = (ump_idx)m->unk[j];
        val[k++] = -c * w;
    }
    if (!placed) {
        col[k] = (ump_idx)me;
        val[k++] = 0;
    }
    for (size_t q = 0; q < k; q++)
        if (col[q] == (ump_idx)me)
            val[q] = diag;
    return k;
}

/* Assemble the rows of the unknowns (unk_part[0..nu-1]) into rp/ci/av. */
static ump_status assemble(mps *m, size_t nu, double d0, double c, double re, const unsigned char in_sum[4],
                           ump_err *err)
{
    const pnbr *R = &m->nb;
    size_t nz = 0;
    for (size_t k = 0; k < nu; k++) {
        size_t i = m->unk_part[k];
        nz += R->off[i + 1] - R->off[i] + 1;
    }
    UMP_CHECK(nz < (size_t)UMP_IDX_MAX && nu < (size_t)UMP_IDX_MAX, err, UMP_ERR_INPUT,
              "MPS: %zu matrix entries exceed the index type", nz);
    UMP_CALL(matrix_reserve(m, nu, nz, err));
    /* row starts: upper bounds first (row length + 1), then compacted */
    m->rp[0] = 0;
    for (size_t k = 0; k < nu; k++) {
        size_t i = m->unk_part[k];
        m->rp[k + 1] = m->rp[k] + (ump_idx)(R->off[i + 1] - R->off[i] + 1);
    }
#pragma omp parallel for schedule(static)
    for (size_t k = 0; k < nu; k++) {
        size_t i = m->unk_part[k];
        size_t len = laplace_row(m, i, d0, c, re, in_sum, m->ci + m->rp[k], m->av + m->rp[k]);
        m->tmp[k] = (double)len;
    }
    /* compact the rows in place (serial, O(nz)) */
    ump_idx w = 0;
    for (size_t k = 0; k < nu; k++) {
        ump_idx start = m->rp[k], len = (ump_idx)m->tmp[k];
        if (start != w) {
            memmove(m->ci + w, m->ci + start, sizeof *m->ci * (size_t)len);
            memmove(m->av + w, m->av + start, sizeof *m->av * (size_t)len);
        }
        m->rp[k] = w;
        w += len;
    }
    m->rp[nu] = w;
    return UMP_OK;
}

/* ---- the stages -------------------------------------------------------------- */


/* Implicit viscosity and gravity, Eqs. 11-14:
 *   u*_i - dt nu 2d/(lambda n0) sum_j (u*_j - u*_i) w_ij = u^n_i + dt g
 * over fluid neighbours (unknown) and solid ones (u = 0: no-slip). The
 * matrix is symmetric positive definite: CG per component (Jacobi). */
static ump_status viscous(mps *m, double dt, mps_stats *st, ump_err *err)
{
    part_set *s = m->s;
    size_t n = s->n, ns = m->ns, nf = n - ns;
    const mps_params *P = &m->P;
    if (P->nu == 0 || nf == 0) {
        for (size_t i = ns; i < n; i++) {
            s->u[i] += dt * P->g[0];
            s->v[i] += dt * P->g[1];
        }
        return UMP_OK;
    }
    for (size_t i = 0; i < n; i++)
        m->unk[i] = i < ns ? -1 : (long)(i - ns);
    for (size_t k = 0; k < nf; k++)
        m->unk_part[k] = ns + k;
    double c = dt * P->nu * 2.0 * DIM / (m->lambda * m->n0_lap); /* Eq. 6 with weights in lattice units */
    static const unsigned char in_sum[4] = {1, 1, 1, 0};
    UMP_CALL(assemble(m, nf, 1.0, c, P->re_lap * P->l0, in_sum, err));
    lsolve_csr A = {(ump_idx)nf, m->rp, m->ci, m->av};
    UMP_CALL(lsolve_rows_setup(m->kry, &A, LSOLVE_PC_JACOBI, err));
    int solid_moves = 0; /* the sum over solid neighbours only for moving walls */
    for (size_t i = 0; i < ns && !solid_moves; i++)
        solid_moves = s->u[i] != 0 || s->v[i] != 0;
    for (int d = 0; d < 2; d++) {
        double *vel = d ? s->v : s->u;
        const pnbr *R = &m->nb;
        const double re = P->re_lap * P->l0;
#pragma omp parallel for schedule(static)
        for (size_t k = 0; k < nf; k++) {
            size_t i = ns + k;
            m->b[k] = vel[i] + dt * P->g[d]; /* Eq. 14 right-hand side */
            /* the known velocities of the solid particles (no-slip on a
             * moving wall; zero on a fixed one) */
            for (size_t q = R->off[i]; solid_moves && q < R->off[i + 1]; q++)
                if (R->j[q] < ns)
                    m->b[k] += c * mps_weight(R->r[q], re) * vel[R->j[q]];
            m->x[k] = m->b[k];
        }
        UMP_CALL(lsolve_rows_cg(m->kry, &A, m->b, m->x, P->u_tol, P->maxit, &st->visc[d], err));
        if (st->visc[d].converged != 1)
            return UMP_FAIL(err, UMP_ERR_SINGULAR, "MPS viscous step: CG for %s did not converge (%d iterations, "
                            "residual %g)", d ? "Uy" : "Ux", st->visc[d].iterations, st->visc[d].res);
        for (size_t k = 0; k < nf; k++)
            vel[ns + k] = m->x[k];
    }
    return UMP_OK;
}

/* Collision model: fluid pairs closer than alpha l0 that approach exchange
 * the approaching part of their relative velocity with restitution e (equal
 * masses); against a solid particle the fluid particle alone reflects. Each
 * particle's change is computed from the velocities before the model, so
 * the result does not depend on the order (Jacobi-like). Returns pairs. */
static size_t collide(mps *m, double dt)
{
    part_set *s = m->s;
    size_t n = s->n, ns = m->ns, hits = 0;
    const double dc = m->P.collision * m->P.l0, e = m->P.restitution;
    const pnbr *R = &m->nb;
#pragma omp parallel for schedule(static) reduction(+ : hits)
    for (size_t i = ns; i < n; i++) {
        double du = 0, dv = 0;
        for (size_t q = R->off[i]; q < R->off[i + 1]; q++) {
            double r = R->r[q];
            if (r >= dc || r <= 0)
                continue;
            size_t j = R->j[q];
            double ex = R->dx[q] / r, ey = R->dy[q] / r;
            double uj = s->u[j], vj = s->v[j]; /* a solid's: its wall's (0, or a moving wall's) */
            double vn = (s->u[i] - uj) * ex + (s->v[i] - vj) * ey; /* > 0: approaching */
            if (vn <= 0)
                continue;
            double f = j < ns ? (1 + e) * vn : 0.5 * (1 + e) * vn;
            du -= f * ex;
            dv -= f * ey;
            hits++;
        }
        m->gx[i] = du;
        m->gy[i] = dv;
    }
    for (size_t i = ns; i < n; i++) {
        s->u[i] += m->gx[i];
        s->v[i] += m->gy[i];
        s->x[i] += dt * m->gx[i];
        s->y[i] += dt * m->gy[i];
    }
    return hits;
}

/* Number density (Eq. 5) at the current positions for particles with rows,
 * free surface flags, and the divergence of u (for the mixed source). */
static void density(mps *m)
{
    const part_set *s = m->s;
    size_t n = s->n;
    const pnbr *R = &m->nb;
    const double beta = m->P.beta, n0 = m->n0_n;
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; i++) {
        double nd = 0, dv = 0;
        double ui = s->u[i], vi = s->v[i]; /* solids: their wall's velocity (0 unless it moves) */
        for (size_t q = R->off[i]; q < R->off[i + 1]; q++) {
            double w = mps_weight(R->r[q] / m->P.l0, m->P.re_n);
            if (w == 0)
                continue;
            nd += w;
            size_t j = R->j[q];
            double uj = s->u[j], vj = s->v[j];
            double r2 = R->r[q] * R->r[q];
            dv += ((uj - ui) * R->dx[q] + (vj - vi) * R->dy[q]) / r2 * w; /* divergence model, after Eq. 4 */
        }
        m->nd[i] = nd / n0;
        m->div[i] = DIM / n0 * dv;
        /* free surface: n* < beta n0 (dummy particles never take part) */
        m->surf[i] = m->kind[i] == MPS_DUMMY ? 0 : m->nd[i] < beta;
    }
}

/* ---- two-level preconditioner of the PPE ----------------------------------
 * Jacobi-preconditioned CG needs iterations growing as the square root of
 * the number of particles (measured: 206 at 10^4, 392 at 4 x 10^4), so the
 * cost per particle-step would grow with N. The additive two-level
 * preconditioner M^-1 = D^-1 + P (P^T A P)^-1 P^T, P the piecewise-constant
 * prolongation from aggregates (the unknowns in squares of side 3 l0, about
 * nine particles each; coarse.h), bounds the condition number by the
 * aggregate size instead of the domain size: the iterations stop growing
 * with N. The coarse matrix is refactorized by CHOLMOD every step in a
 * pattern that changes only when the liquid reaches new squares (coarse.c).
 * Symmetric positive definite, so CG keeps
 * its guarantees; if the coarse factorization fails, the step falls back to
 * Jacobi alone (only the speed changes). */

/* z = D^-1 r + P Ac^-1 P^T r */
static void coarse_apply(void *ctx, const double *r, double *z)
{
    mps *m = ctx;
    size_t nu = (size_t)m->trip_rows;
#pragma omp parallel for schedule(static)
    for (size_t k = 0; k < nu; k++)
        z[k] = m->dinv[k] * r[k];
    coarse_add(m->cl, r, z);
}

/* Pressure Poisson equation, Eqs. 16-18, for fluid and wall particles that
 * are not on the free surface:
 *   2d/(lambda n0) sum_j (p_i - p_j) w_ij = (rho/dt^2)(n*_i - n0)/n0
 * (the sign flipped to make the matrix positive definite), p_j = 0 on the
 * free surface, dummy particles outside the sums. Mixed source:
 *   ... = -(rho/dt) div u*_i + gamma (rho/dt^2)(n*_i - n0)/n0. */
static ump_status pressure(mps *m, double dt, mps_stats *st, ump_err *err)
{
    const part_set *s = m->s;
    size_t n = s->n;
    const mps_params *P = &m->P;
    size_t nu = 0, nsurf = 0;
    for (size_t i = 0; i < n; i++) {
        int take = m->kind[i] != MPS_DUMMY && !m->surf[i] && m->nb.off[i + 1] > m->nb.off[i];
        if (m->kind[i] == MPS_FLUID && m->surf[i])
            nsurf++;
        if (take) {
            m->unk_part[nu] = i;
            m->unk[i] = (long)nu++;
        } else
            m->unk[i] = -1;
    }
    st->nsurface = nsurf;
    st->nunknowns = nu;
    double a = 2.0 * DIM / (m->lambda * m->n0_lap);
    static const unsigned char in_sum[4] = {1, 1, 0, 0}; /* fluid and wall, not dummy */
    UMP_CALL(assemble(m, nu, 0.0, a, P->re_lap * P->l0, in_sum, err));
    double k_dens = P->rho / (dt * dt), k_div = P->rho / dt;
    for (size_t k = 0; k < nu; k++) {
        size_t i = m->unk_part[k];
        double dev = m->nd[i] - 1.0; /* (n*_i - n0)/n0 */
        m->b[k] = P->source == MPS_SOURCE_DENSITY ? k_dens * dev /* Eq. 18 */
                                                  : -k_div * m->div[i] + P->gamma * k_dens * dev;
        m->x[k] = m->p[i]; /* warm start: the last pressure */
    }
    lsolve_csr A = {(ump_idx)nu, m->rp, m->ci, m->av};
    UMP_CALL(lsolve_rows_setup(m->kry, &A, LSOLVE_PC_JACOBI, err));
    for (size_t k = 0; k < nu; k++)
        for (ump_idx q = m->rp[k]; q < m->rp[k + 1]; q++)
            if (m->ci[q] == (ump_idx)k)
                m->dinv[k] = 1.0 / m->av[q];
    UMP_CALL(coarse_build(m->cl, nu, s->x, s->y, m->unk_part, MPS_AGG * P->l0, m->rp, m->ci, m->av, LSOLVE_CHOLMOD,
                          &m->coarse_ok, err));
    m->trip_rows = (ump_idx)nu;
    UMP_CALL(lsolve_rows_cg_pc(m->kry, &A, m->b, m->x, P->p_tol, P->maxit, m->coarse_ok ? coarse_apply : NULL, m,
                               &st->pres, err));
    if (st->pres.converged != 1)
        return UMP_FAIL(err, UMP_ERR_SINGULAR, "MPS pressure equation: CG did not converge (%d iterations, "
                        "residual %g): a region of fluid without free-surface particles makes it singular",
                        st->pres.iterations, st->pres.res);
    for (size_t i = 0; i < n; i++)
        m->p[i] = 0;
    for (size_t k = 0; k < nu; k++)
        m->p[m->unk_part[k]] = m->x[k];
    return UMP_OK;
}

/* Pressure gradient of p at the fluid particles (Eq. 4, with the local
 * minimum p^_i in place of p_i) into gx, gy. */
static void gradient(const mps *m, const double *p, double *gxo, double *gyo)
{
    const part_set *s = m->s;
    size_t n = s->n, ns = m->ns;
    const pnbr *R = &m->nb;
    const double re = m->P.re_n, l0 = m->P.l0, k = DIM / m->n0_n;
#pragma omp parallel for schedule(static)
    for (size_t i = ns; i < n; i++) {
        double pmin = p[i];
        for (size_t q = R->off[i]; q < R->off[i + 1]; q++) {
            size_t j = R->j[q];
            if (m->kind[j] != MPS_DUMMY && R->r[q] < re * l0)
                pmin = fmin(pmin, p[j]);
        }
        double gx = 0, gy = 0;
        for (size_t q = R->off[i]; q < R->off[i + 1]; q++) {
            size_t j = R->j[q];
            double w = mps_weight(R->r[q] / l0, re);
            if (w == 0 || m->kind[j] == MPS_DUMMY)
                continue;
            double f = (p[j] - pmin) / (R->r[q] * R->r[q]) * w;
            gx += f * R->dx[q];
            gy += f * R->dy[q];
        }
        gxo[i] = k * gx; /* Eq. 4 */
        gyo[i] = k * gy;
    }
}

/* The correction of Eq. 20 for fluid particles. */
static void correct(mps *m, double dt, mps_stats *st)
{
    part_set *s = m->s;
    size_t n = s->n, ns = m->ns;
    const double rho = m->P.rho;
    gradient(m, m->p, m->gx, m->gy);
    double pmin = HUGE_VAL, pmax = -HUGE_VAL, nmin = HUGE_VAL, nmax = -HUGE_VAL;
    for (size_t i = ns; i < n; i++) {
        double du = -dt / rho * m->gx[i], dv = -dt / rho * m->gy[i]; /* Eq. 20 */
        s->u[i] += du;
        s->v[i] += dv;
        s->x[i] += dt * du;
        s->y[i] += dt * dv;
        pmin = fmin(pmin, m->p[i]);
        pmax = fmax(pmax, m->p[i]);
        nmin = fmin(nmin, m->nd[i]);
        nmax = fmax(nmax, m->nd[i]);
    }
    st->p_min = n > ns ? pmin : 0;
    st->p_max = n > ns ? pmax : 0;
    st->n_min = n > ns ? nmin : 0;
    st->n_max = n > ns ? nmax : 0;
}

ump_status mps_step(mps *m, double dt, mps_stats *st, ump_err *err)
{
    memset(st, 0, sizeof *st);
    UMP_CHECK(dt > 0 && isfinite(dt), err, UMP_ERR_INPUT, "MPS: time step %g", dt);
    UMP_CALL(reserve(m, err));
    part_set *s = m->s;
    size_t n = s->n, ns = m->ns;
    st->nfluid = n - ns;
    double c0 = cpu_seconds(), w0 = wall_seconds(), c1, w1;
    /* 0. rows at r^n */
    UMP_CALL(neighbours(m, err));
    c1 = cpu_seconds(), w1 = wall_seconds();
    st->cpu[0] += c1 - c0, st->wall[0] += w1 - w0;
    c0 = c1, w0 = w1;
    /* 1. viscosity and gravity, implicit (Eqs. 11-14) */
    UMP_CALL(viscous(m, dt, st, err));
    c1 = cpu_seconds(), w1 = wall_seconds();
    st->cpu[1] += c1 - c0, st->wall[1] += w1 - w0;
    /* 2. temporary positions (Eq. 10) */
    for (size_t i = ns; i < n; i++) {
        s->x[i] += dt * s->u[i];
        s->y[i] += dt * s->v[i];
    }
    /* 3. rows at r*; collisions */
    UMP_CALL(refresh(m, err));
    if (m->P.collision > 0 && (st->collisions = collide(m, dt)) > 0)
        UMP_CALL(refresh(m, err));
    density(m);
    c0 = cpu_seconds(), w0 = wall_seconds();
    st->cpu[0] += c0 - c1, st->wall[0] += w0 - w1;
    /* 4. pressure (Eqs. 16-18) */
    UMP_CALL(pressure(m, dt, st, err));
    c1 = cpu_seconds(), w1 = wall_seconds();
    st->cpu[2] += c1 - c0, st->wall[2] += w1 - w0;
    /* 5. correction (Eq. 20) */
    correct(m, dt, st);
    st->cpu[3] += cpu_seconds() - c1, st->wall[3] += wall_seconds() - w1;
    return UMP_OK;
}
