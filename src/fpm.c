/* SPDX-License-Identifier: GPL-3.0-or-later
 * fpm.c -- the finite particle method step (see fpm.h and docs/METHOD.md
 * section 11).
 *
 *   move          fluid x += dt u^n                              Eq. 21
 *   rows          neighbours within h0 (pnbr.h) at x^{n+1}
 *   MLS           per fluid particle and wall point: number density,
 *                 free surface / dry wall, the coefficients of d/dx,
 *                 d/dy and the Laplacian over its row (mls_full)
 *   predictor     u~ = u^n + dt (nu lap u^n + g)                 Eq. 21
 *   pressure      lap p = rho/dt div u~ (fluid inside)           Eq. 24
 *                 dp/dn = rho n.(g - a_w) + mu n.lap u (wet wall) Eq. 25
 *                 p = 0 (free surface, dry wall); BiCGSTAB, ILU(0)
 *   correction    u^{n+1} = u~ - dt/rho grad p                   Eq. 22
 *
 * A row's coefficients are stored aligned with its pnbr row (ghost
 * neighbours and those beyond h0 get 0), the particle's own coefficient
 * apart (the MLS fit includes the particle itself, at offset 0). Every
 * sum runs over a row in increasing particle index: the result does not
 * depend on the number of threads.
 */
#include "umppm/fpm.h"
#include "umppm/coarse.h"
#include "umppm/mps.h"
#include "umppm/pnbr.h"
#include "umppm/vor.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/time.h>
#include <time.h>

#define FPM_SKIN 0.5 /* Verlet skin of the rows, in l0 */
#define FPM_MAXROW 512
#define FPM_AGG 3.0 /* side of the pressure solve's coarse aggregates, in l0 (coarse.h) */

struct fpm {
    fpm_params P;
    part_set *s;
    size_t nw, ns;
    double n0;               /* number density of the full lattice, radius re_s */
    double *wnx, *wny;       /* [nw] outward normals */
    double *wacc;            /* [2 nw] wall accelerations */
    size_t cap;
    unsigned char *kind;     /* [cap] */
    double *p, *nd, *ut, *vt;
    double *sx, *sy, *sl;    /* the particle's own coefficient in its fit */
    double *src;             /* right-hand side of the pressure rows */
    unsigned char *surf;     /* fluid: free surface; wall: dry (p = 0) */
    unsigned char *quad;     /* the fit used the quadratic basis */
    long *unk;               /* PPE unknown of a particle, -1 if none */
    size_t *unk_part;
    pnbr nb;
    double *cx, *cy, *cl;    /* [rcap] per row entry */
    double *cp, *sp;         /* the pressure Laplacian (fpm_laplacian_row): [rcap], [cap] */
    size_t rcap;
    /* the pressure system, rows of unknowns */
    ump_idx *rp, *ci;
    double *av, *b, *x;
    size_t mrows, mnz;
    lsolve_mat A;
    size_t acap;
    lsolve_krylov *kry;
    size_t kry_n;
    coarse *coa;                /* the coarse level of the pressure solve */
    /* particle management */
    unsigned char *keep;        /* [kcap] */
    size_t kcap;
    unsigned char *mask;        /* [mcap] */
    size_t mcap;
    double *hx, *hy;            /* [mcap] the coordinates handed to qhull */
    size_t *hmap;               /* [mcap] their particles */
    vor_work *vw;               /* the hole search's arrays, kept between steps */
    double *dsx, *dsy, *dsu, *dsv; /* [mcap] particle shifts and their velocity changes */
    double dt_last;             /* the last step's dt (particle shifting) */
    int rows_stale;             /* particles hidden or shown: search again */
};

static double cpu_seconds(void) { return (double)clock() / CLOCKS_PER_SEC; }
static double wall_seconds(void)
{
    struct timeval tv;
    gettimeofday(&tv, NULL);
    return (double)tv.tv_sec + 1e-6 * (double)tv.tv_usec;
}

#define GROW_TO(ptr, n)                                                                                 \
    do {                                                                                                \
        void *q_ = ump_realloc_array((ptr), (n), sizeof *(ptr));                                        \
        if (!q_)                                                                                        \
            return UMP_FAIL(err, UMP_ERR_NOMEM, "FPM: out of memory for %zu particles", (size_t)(n));   \
        (ptr) = q_;                                                                                     \
    } while (0)

/* Kernel of the free-surface number density: the spline of Eq. 5 on the
 * radius rs. Smooth, unlike MPS's r_e/r - 1, whose pole makes the density
 * of a jittered lattice swing by 7 % (measured: +-0.1 l0 jitter gave
 * n/n0 = 0.93 inside the liquid, a false free surface). */
static inline double surf_weight(double r, double rs)
{
    double w, w1, wq, w2;
    mls_wfun_eval(MLS_WFUN_SPLINE, r / rs, &w, &w1, &wq, &w2);
    return w;
}

static ump_status reserve(fpm *f, ump_err *err)
{
    size_t n = f->s->n;
    if (n <= f->cap && f->p)
        return UMP_OK;
    size_t nc = n + n / 2 + 16, old = f->cap;
    GROW_TO(f->kind, nc);
    GROW_TO(f->p, nc);
    GROW_TO(f->nd, nc);
    GROW_TO(f->ut, nc);
    GROW_TO(f->vt, nc);
    GROW_TO(f->sx, nc);
    GROW_TO(f->sy, nc);
    GROW_TO(f->sl, nc);
    GROW_TO(f->sp, nc);
    GROW_TO(f->src, nc);
    GROW_TO(f->surf, nc);
    GROW_TO(f->quad, nc);
    GROW_TO(f->unk, nc);
    GROW_TO(f->unk_part, nc);
    for (size_t i = old; i < nc; i++) {
        f->kind[i] = FPM_FLUID;
        f->p[i] = f->nd[i] = 0;
        f->surf[i] = 0;
        f->quad[i] = 0;
    }
    f->cap = nc;
    return UMP_OK;
}

ump_status fpm_create(const fpm_params *prm, part_set *s, size_t nwall, size_t nsolid, const double *nx,
                      const double *ny, fpm **out, ump_err *err)
{
    *out = NULL;
    UMP_CHECK(prm->l0 > 0 && prm->h >= 2 * prm->l0 && prm->rho > 0 && prm->nu >= 0 && prm->re_s > 1 &&
                  prm->beta > 0 && prm->beta < 1 && prm->stab >= 0 && prm->p_tol > 0 && prm->maxit > 0 &&
                  nwall <= nsolid && nsolid <= s->n,
              err, UMP_ERR_INPUT, "FPM: parameters out of range (l0 %g, h0 %g, rho %g, nu %g, r_s %g, beta %g)",
              prm->l0, prm->h, prm->rho, prm->nu, prm->re_s, prm->beta);
    UMP_CHECK(prm->weight == MLS_WFUN_EXP || prm->weight == MLS_WFUN_SPLINE, err, UMP_ERR_INPUT,
              "FPM: unknown weight function %d", (int)prm->weight);
    fpm *f = calloc(1, sizeof *f);
    UMP_CHECK(f, err, UMP_ERR_NOMEM, "FPM: out of memory");
    f->P = *prm;
    f->s = s;
    f->nw = nwall;
    f->ns = nsolid;
    /* n0: the density of the full square lattice (origin excluded) */
    f->n0 = 0;
    int kmax = (int)ceil(prm->re_s) + 1;
    for (int a = -kmax; a <= kmax; a++)
        for (int b = -kmax; b <= kmax; b++)
            if (a || b)
                f->n0 += surf_weight(prm->l0 * hypot(a, b), prm->re_s * prm->l0);
    ump_status rc = reserve(f, err);
    if (rc == UMP_OK)
        rc = vor_work_create(&f->vw, err);
    if (rc == UMP_OK) {
        f->wnx = ump_alloc_array(nwall + 1, sizeof *f->wnx);
        f->wny = ump_alloc_array(nwall + 1, sizeof *f->wny);
        f->wacc = ump_alloc_array(2 * nwall + 2, sizeof *f->wacc);
        if (!f->wnx || !f->wny || !f->wacc)
            rc = UMP_FAIL(err, UMP_ERR_NOMEM, "FPM: out of memory");
    }
    if (rc != UMP_OK) {
        fpm_free(&f);
        return rc;
    }
    for (size_t i = 0; i < nwall; i++) {
        f->wnx[i] = nx[i];
        f->wny[i] = ny[i];
        f->wacc[2 * i] = f->wacc[2 * i + 1] = 0;
    }
    for (size_t i = 0; i < s->n; i++)
        f->kind[i] = i < nwall ? FPM_WALL : i < nsolid ? FPM_GHOST : FPM_FLUID;
    *out = f;
    return UMP_OK;
}

void fpm_free(fpm **pf)
{
    fpm *f = *pf;
    if (!f)
        return;
    free(f->wnx);
    free(f->wny);
    free(f->wacc);
    free(f->kind);
    free(f->p);
    free(f->nd);
    free(f->ut);
    free(f->vt);
    free(f->sx);
    free(f->sy);
    free(f->sl);
    free(f->src);
    free(f->surf);
    free(f->quad);
    free(f->unk);
    free(f->unk_part);
    pnbr_free(&f->nb);
    free(f->cx);
    free(f->cy);
    free(f->cl);
    free(f->cp);
    free(f->sp);
    free(f->rp);
    free(f->ci);
    free(f->av);
    free(f->b);
    free(f->x);
    free(f->A.Ap);
    free(f->A.Ai);
    free(f->A.Ax);
    lsolve_krylov_free(&f->kry);
    coarse_free(&f->coa);
    free(f->keep);
    free(f->mask);
    free(f->hx);
    free(f->hy);
    free(f->hmap);
    vor_work_free(&f->vw);
    free(f->dsx);
    free(f->dsy);
    free(f->dsu);
    free(f->dsv);
    free(f);
    *pf = NULL;
}

double *fpm_wall_accel(fpm *f) { return f->wacc; }
double *fpm_wall_normal(fpm *f, int comp) { return comp ? f->wny : f->wnx; }
size_t fpm_nsolid(const fpm *f) { return f->ns; }
void fpm_set_gravity(fpm *f, const double g[2])
{
    f->P.g[0] = g[0];
    f->P.g[1] = g[1];
}
void fpm_hide(fpm *f, const unsigned char *hidden)
{
    for (size_t i = 0; i < f->ns; i++) {
        unsigned char k = hidden[i] ? FPM_HIDDEN : i < f->nw ? FPM_WALL : FPM_GHOST;
        f->rows_stale |= k != f->kind[i];
        f->kind[i] = k;
    }
}

size_t fpm_nwall(const fpm *f) { return f->nw; }
const double *fpm_pressure(const fpm *f) { return f->p; }
const double *fpm_density(const fpm *f) { return f->nd; }
const unsigned char *fpm_surface(const fpm *f) { return f->surf; }
double fpm_n0(const fpm *f) { return f->n0; }

void fpm_compact(fpm *f, const unsigned char *keep, size_t n_before)
{
    size_t k = 0;
    for (size_t i = 0; i < n_before; i++) {
        if (!keep[i])
            continue;
        f->kind[k] = f->kind[i];
        f->p[k] = f->p[i];
        f->nd[k] = f->nd[i];
        f->surf[k] = f->surf[i];
        k++;
    }
}

double fpm_max_dt(const fpm *f, double co, double cg, double u_wave)
{
    const part_set *s = f->s;
    double umax = 0;
    for (size_t i = f->ns; i < s->n; i++)
        umax = fmax(umax, hypot(s->u[i], s->v[i]));
    for (size_t i = 0; i < f->nw; i++) /* a moving wall sets the pace too */
        umax = fmax(umax, hypot(s->u[i], s->v[i]));
    /* Eq. 26 on max(|U|max, u_wave): the free surface is explicit, and its
     * gravity waves (celerity sqrt(g H)) must be resolved even at rest --
     * with Eqs. 26-27 alone the tank at rest (depth 0.3 m, l0 5 mm, dt of
     * Eq. 27 0.0095 s: 3 particle spacings per step at sqrt(g H)) diverged
     * from its corners within 0.2 s (measured) */
    umax = fmax(umax, u_wave);
    double h = f->P.h, g = hypot(f->P.g[0], f->P.g[1]), dt = HUGE_VAL;
    if (umax > 0)
        dt = co * h / umax; /* Eq. 26 */
    if (g > 0)
        dt = fmin(dt, cg * sqrt(h / g)); /* Eq. 27 */
    if (f->P.nu > 0)
        dt = fmin(dt, 0.1 * f->P.l0 * f->P.l0 / f->P.nu); /* explicit viscosity (the paper is silent) */
    return dt;
}

/* ---- the pressure Laplacian ------------------------------------------------------ */

/* See fpm.h. The bracket, expanded over the row: sum_j c_j p_j - (sum_j
 * c_j) p_i - m . grad p_i - (mxx H_xx + 2 mxy H_xy + myy H_yy) / 2 with
 * the c-weighted moments m = sum_j c_j d_j, mab = sum_j c_j d_ja d_jb,
 * and each derivative the row of its MLS coefficients. */
void fpm_laplacian_row(const double *dx, const double *dy, int k, double h, mls_wfun wf, const double *cx,
                       const double *cy, const double *cxx, const double *cxy, const double *cyy, double eps,
                       double *lap)
{
    double sw = 0;
    if (eps != 0)
        for (int t = 0; t < k; t++) { /* lap holds the weights until the MLS Laplacian goes in */
            double w1, wq, w2, r2 = dx[t] * dx[t] + dy[t] * dy[t];
            mls_wfun_eval(wf, sqrt(r2) / h, &lap[t], &w1, &wq, &w2);
            sw += lap[t] * r2;
        }
    int stab = eps != 0 && sw > 0;
    double csum = 0, mx = 0, my = 0, mxx = 0, mxy = 0, myy = 0;
    for (int t = 0; t < k; t++) {
        double w = stab ? lap[t] : 0, r2 = dx[t] * dx[t] + dy[t] * dy[t];
        lap[t] = (cxx ? cxx[t] : 0) + (cyy ? cyy[t] : 0); /* Eq. 18: the MLS Laplacian */
        if (!stab)
            continue;
        /* the positive weights c_j; the particle itself (d = 0) gets none */
        double c = r2 > 0 ? 4 * w / sw : 0;
        lap[t] += eps * c;
        csum += c;
        mx += c * dx[t], my += c * dy[t];
        mxx += c * dx[t] * dx[t], mxy += c * dx[t] * dy[t], myy += c * dy[t] * dy[t];
    }
    if (!stab)
        return;
    for (int t = 0; t < k; t++) {
        double r = (t == 0 ? csum : 0) + mx * cx[t] + my * cy[t];
        if (cxx && cxy && cyy)
            r += 0.5 * mxx * cxx[t] + mxy * cxy[t] + 0.5 * myy * cyy[t];
        lap[t] -= eps * r;
    }
}

/* ---- MLS rows ------------------------------------------------------------------ */


/* Number density, free surface and the MLS coefficients of every fluid
 * particle and wall point (Eqs. 1-18 via mls_full). The free surface: a
 * number density below beta n0, or the weighted centroid of the
 * neighbours off by more than shift l0 -- the second finds the particles
 * at the toe of a front running along a wall, whose density the ghosts
 * keep near n0 (measured: without it the dam-break toe was solved as
 * inside liquid with nothing ahead of it, and diverged). Two passes: the
 * number densities decide which wall points are wet; the fits then take
 * the particle itself, its fluid neighbours and its wet wall neighbours.
 * A dry wall point (above the liquid) is no sample: it is not the gas at
 * p = 0 but a wall, and taking it as p = 0 put a pressure gradient into
 * the corner where the free surface meets a wall (measured: the tank at
 * rest diverged from those corners) -- next to it a fit is one-sided, as
 * at the free surface. */
static ump_status mls_rows(fpm *f, fpm_stats *st, ump_err *err)
{
    const part_set *s = f->s;
    size_t n = s->n;
    const pnbr *R = &f->nb;
    size_t nz = R->off[n];
    if (nz > f->rcap) {
        size_t nc = nz + nz / 2 + 64;
        GROW_TO(f->cx, nc);
        GROW_TO(f->cy, nc);
        GROW_TO(f->cl, nc);
        GROW_TO(f->cp, nc);
        f->rcap = nc;
    }
    const double rs = f->P.re_s * f->P.l0, h = f->P.h, thr = f->P.beta, shift = f->P.shift * f->P.l0;
    const mls_wfun wf = f->P.weight;
    size_t nlin = 0;
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; i++) {
        if (f->kind[i] >= FPM_GHOST) {
            if (f->kind[i] == FPM_HIDDEN)
                f->surf[i] = 1; /* dry: p = 0 */
            continue;
        }
        /* number density of fluid and ghost particles (the MPS kernel), and
         * the offset of their weighted centroid */
        double nd = 0, mx = 0, my = 0;
        for (size_t q = R->off[i]; q < R->off[i + 1]; q++)
            if (f->kind[R->j[q]] != FPM_WALL) {
                double w = surf_weight(R->r[q], rs);
                nd += w;
                mx += w * R->dx[q];
                my += w * R->dy[q];
            }
        f->nd[i] = nd / f->n0;
        f->surf[i] = f->nd[i] < thr || (nd > 0 && hypot(mx, my) > shift * nd);
    }
#pragma omp parallel reduction(+ : nlin)
    {
        double dx[FPM_MAXROW + 1], dy[FPM_MAXROW + 1], c1[FPM_MAXROW + 1], c2[FPM_MAXROW + 1],
            c3[FPM_MAXROW + 1], c4[FPM_MAXROW + 1], c5[FPM_MAXROW + 1], cl[FPM_MAXROW + 1];
        int pos[FPM_MAXROW + 1];
        double *c[MLS_NOUT] = {NULL, c1, c2, c3, c4, c5};
#pragma omp for schedule(dynamic, 64)
        for (size_t i = 0; i < n; i++) {
            if (f->kind[i] >= FPM_GHOST)
                continue;
            for (size_t q = R->off[i]; q < R->off[i + 1]; q++)
                f->cx[q] = f->cy[q] = f->cl[q] = f->cp[q] = 0;
            f->sx[i] = f->sy[i] = f->sl[i] = f->sp[i] = 0;
            f->quad[i] = 0;
            if (f->kind[i] == FPM_WALL && f->surf[i])
                continue; /* dry: p = 0, no row */
            int k = 0;
            dx[k] = dy[k] = 0; /* the particle itself */
            pos[k++] = -1;
            for (size_t q = R->off[i]; q < R->off[i + 1]; q++) {
                size_t j = R->j[q];
                int take = f->kind[j] == FPM_FLUID || (f->kind[j] == FPM_WALL && !f->surf[j]);
                if (take && R->r[q] < h) {
                    dx[k] = R->dx[q];
                    dy[k] = R->dy[q];
                    pos[k++] = (int)(q - R->off[i]);
                }
            }
            mls_basis b = mls_full(dx, dy, k, h, wf, c, NULL);
            f->quad[i] = b == MLS_QUADRATIC; /* if not, surf[i] is set after the loop */
            nlin += b != MLS_QUADRATIC;
            f->sx[i] = c1[0];
            f->sy[i] = c2[0];
            f->sl[i] = c3[0] + c5[0];
            for (int t = 1; t < k; t++) {
                size_t q = R->off[i] + (size_t)pos[t];
                f->cx[q] = c1[t];
                f->cy[q] = c2[t];
                f->cl[q] = c3[t] + c5[t];
            }
            if (f->kind[i] == FPM_FLUID && f->quad[i]) { /* the pressure row's Laplacian */
                fpm_laplacian_row(dx, dy, k, h, wf, c1, c2, c3, c4, c5, f->P.stab, cl);
                f->sp[i] = cl[0];
                for (int t = 1; t < k; t++)
                    f->cp[R->off[i] + (size_t)pos[t]] = cl[t];
            }
        }
    }
    /* too few neighbours for the quadratic fit: a free-surface particle (a
     * wet wall point: dry). Set after the loop, which reads its neighbours'
     * surf: within it the rows would depend on the order of the particles
     * and on the threads' schedule. */
    for (size_t i = 0; i < n; i++)
        if (f->kind[i] < FPM_GHOST && !f->quad[i])
            f->surf[i] = 1;
    st->nlinear = nlin;
    return UMP_OK;
}

/* sum over the row of i of coef * v, plus the particle's own term */
static inline double row_sum(const fpm *f, size_t i, const double *coef, double self, const double *v)
{
    const pnbr *R = &f->nb;
    double t = self * v[i];
    for (size_t q = R->off[i]; q < R->off[i + 1]; q++)
        t += coef[q] * v[R->j[q]];
    return t;
}

/* ---- the pressure equation -------------------------------------------------- */

static ump_status matrix_reserve(fpm *f, size_t nrows, size_t nz, ump_err *err)
{
    if (nrows + 1 > f->mrows) {
        size_t nc = nrows + 1 + nrows / 2;
        GROW_TO(f->rp, nc);
        GROW_TO(f->b, nc);
        GROW_TO(f->x, nc);
        f->mrows = nc;
    }
    if (nz > f->mnz) {
        size_t nc = nz + nz / 2 + 64;
        GROW_TO(f->ci, nc);
        GROW_TO(f->av, nc);
        f->mnz = nc;
    }
    return UMP_OK;
}

/* The pressure system at the current classification: lap p = src_i on
 * the fluid particles inside (Eq. 24's form), dp/dn = flux_i on the wet
 * wall points (Eq. 25's form; i < nwall), p = pd_i (NULL: 0) on the
 * free-surface particles and dry wall points; BiCGSTAB with ILU(0) and
 * the coarse level of aggregates (coarse.h) from the last pressure. src and flux are indexed by particle [n]. */
static void coarse_add_fn(void *ctx, const double *r, double *z) { coarse_add(ctx, r, z); }

static ump_status solve_ppe(fpm *f, const double *src, const double *flux, const double *pd, fpm_stats *st,
                            ump_err *err)
{
    size_t n = f->s->n;
    const pnbr *R = &f->nb;
    const double l0 = f->P.l0;
    /* unknowns: fluid particles inside the liquid, wet wall points */
    size_t nu = 0, nneu = 0;
    for (size_t i = 0; i < n; i++) {
        f->unk[i] = -1;
        if (f->kind[i] >= FPM_GHOST || f->surf[i])
            continue;
        f->unk[i] = (long)nu;
        f->unk_part[nu++] = i;
        nneu += f->kind[i] == FPM_WALL;
    }
    st->nunknowns = nu;
    st->nneumann = nneu;
    for (size_t i = 0; i < n; i++)
        if (f->unk[i] < 0)
            f->p[i] = f->kind[i] < FPM_GHOST && pd ? pd[i] : 0;
    if (nu == 0)
        return UMP_OK;
    /* row lengths: the unknown neighbours with a coefficient, and itself */
    UMP_CALL(matrix_reserve(f, nu, 0, err));
    f->rp[0] = 0;
    for (size_t r = 0; r < nu; r++) {
        size_t i = f->unk_part[r], k = 1;
        for (size_t q = R->off[i]; q < R->off[i + 1]; q++)
            k += f->unk[R->j[q]] >= 0 && (f->cx[q] != 0 || f->cy[q] != 0 || f->cp[q] != 0);
        f->rp[r + 1] = f->rp[r] + (ump_idx)k;
    }
    UMP_CALL(matrix_reserve(f, nu, (size_t)f->rp[nu], err));
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t r = 0; r < nu; r++) {
        size_t i = f->unk_part[r];
        ump_idx k = f->rp[r];
        int wall = f->kind[i] == FPM_WALL;
        /* a Laplacian row, or a normal-derivative row scaled by -1/l0: one
         * sign on the diagonal for ILU(0), and entries of the Laplacian
         * rows' size, 1/l0^2. Scaled by -l0 instead, the wall rows' b
         * (rho g.n l0) was so small against the Laplacian rows' A p that the
         * relative residual 1e-8 could not be reached (measured, 10^4
         * particles at rest: 5000 iterations, stuck at 5.5e-8) */
        double nx = wall ? f->wnx[i] : 0, ny = wall ? f->wny[i] : 0, sc = wall ? -1.0 / l0 : 1;
        double b = wall ? flux[i] : src[i];
        f->ci[k] = (ump_idx)r;
        f->av[k++] = wall ? sc * (nx * f->sx[i] + ny * f->sy[i]) : f->sp[i];
        for (size_t q = R->off[i]; q < R->off[i + 1]; q++) {
            size_t j = R->j[q];
            if (f->cx[q] == 0 && f->cy[q] == 0 && f->cp[q] == 0)
                continue;
            double a = wall ? sc * (nx * f->cx[q] + ny * f->cy[q]) : f->cp[q];
            long u = f->unk[j];
            if (u >= 0) {
                f->ci[k] = (ump_idx)u;
                f->av[k++] = a;
            } else if (f->kind[j] != FPM_GHOST) {
                b -= (wall ? a / sc : a) * f->p[j]; /* a known (Dirichlet) value */
            }
        }
        f->b[r] = sc * b;
    }
    for (size_t r = 0; r < nu; r++)
        f->x[r] = f->p[f->unk_part[r]]; /* warm start: the last pressure */
    UMP_CALL(lsolve_mat_from_csr(&f->A, &f->acap, (ump_idx)nu, f->rp, f->ci, f->av, err));
    if (!f->kry || f->kry_n < nu) {
        lsolve_krylov_free(&f->kry);
        size_t kn = nu + nu / 2 + 16;
        UMP_CALL(lsolve_krylov_create((ump_idx)kn, &f->kry, err));
        f->kry_n = kn;
    }
    /* two-level: ILU(0) plus the coarse level of aggregates of side 3 l0
     * (coarse.h), as MPS's; the coarse matrix is not symmetric: KLU */
    int cok = 0;
    if (!f->coa)
        UMP_CALL(coarse_create(&f->coa, err));
    UMP_CALL(coarse_build(f->coa, nu, f->s->x, f->s->y, f->unk_part, FPM_AGG * l0, f->rp, f->ci, f->av, LSOLVE_KLU,
                          &cok, err));
    ump_status rc = cok ? lsolve_bicgstab_pc(f->kry, &f->A, LSOLVE_PC_ILU0, coarse_add_fn, f->coa, f->b, f->x,
                                             f->P.p_tol, f->P.maxit, &st->pres, err)
                        : lsolve_bicgstab(f->kry, &f->A, LSOLVE_PC_ILU0, f->b, f->x, f->P.p_tol, f->P.maxit,
                                          &st->pres, err);
    if (rc != UMP_OK)
        return rc; /* lsolve names it */
    if (st->pres.converged < 0)
        return UMP_FAIL(err, UMP_ERR_SINGULAR, "FPM: BiCGSTAB broke down on the pressure equation (%zu unknowns, "
                        "residual %g after %d iterations)", nu, st->pres.res, st->pres.iterations);
    for (size_t r = 0; r < nu; r++)
        f->p[f->unk_part[r]] = f->x[r];
    return UMP_OK;
}

/* The step's pressure: Eq. 24's source rho/dt div u~ (plus the optional
 * density term) and Eq. 25's wall flux, p = 0 on the free surface. */
static ump_status pressure(fpm *f, double dt, fpm_stats *st, ump_err *err)
{
    part_set *s = f->s;
    size_t n = s->n;
    const double rho = f->P.rho, mu = f->P.rho * f->P.nu, rs = f->P.re_s * f->P.l0;
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; i++) {
        f->src[i] = 0;
        if (f->kind[i] >= FPM_GHOST || f->surf[i])
            continue;
        if (f->kind[i] == FPM_FLUID) {
            /* Eq. 24: lap p = rho/dt div u~; + the density deviation (a
             * departure, docs/METHOD.md 11, off by default) */
            double div = row_sum(f, i, f->cx, f->sx[i], f->ut) + row_sum(f, i, f->cy, f->sy[i], f->vt);
            f->src[i] = rho / dt * div;
            /* the density term; where the kernel of the number density
             * reaches the free surface, n < n0 by geometry, not by a cavity
             * (at rest the rows below the surface would move): there only
             * compression (n > n0) counts */
            if (f->P.gamma > 0) {
                int near = 0;
                const pnbr *R = &f->nb;
                for (size_t q = R->off[i]; q < R->off[i + 1] && !near; q++)
                    near = f->kind[R->j[q]] == FPM_FLUID && f->surf[R->j[q]] && R->r[q] < rs;
                double dev = f->nd[i] - 1;
                if (near && dev < 0)
                    dev = 0;
                f->src[i] -= f->P.gamma * rho / (dt * dt) * dev;
            }
        } else {
            /* Eq. 25: dp/dn = rho n.(g - a_w) + mu n.lap u */
            double nx = f->wnx[i], ny = f->wny[i];
            double lu = row_sum(f, i, f->cl, f->sl[i], s->u), lv = row_sum(f, i, f->cl, f->sl[i], s->v);
            f->src[i] = rho * (nx * (f->P.g[0] - f->wacc[2 * i]) + ny * (f->P.g[1] - f->wacc[2 * i + 1])) +
                        mu * (nx * lu + ny * lv);
        }
    }
    return solve_ppe(f, f->src, f->src, NULL, st, err);
}

ump_status fpm_poisson(fpm *f, const double *src, const double *flux, const double *pd, fpm_stats *st,
                       ump_err *err)
{
    memset(st, 0, sizeof *st);
    UMP_CALL(reserve(f, err));
    static const int need[4] = {1, 1, 0, -1};
    UMP_CALL(pnbr_update(&f->nb, f->s, f->kind, need, f->P.h, FPM_SKIN * f->P.l0, 1, "FPM", err));
    UMP_CALL(mls_rows(f, st, err));
    return solve_ppe(f, src, flux, pd, st, err);
}

/* ---- the step ------------------------------------------------------------------ */

ump_status fpm_step(fpm *f, double dt, fpm_stats *st, ump_err *err)
{
    memset(st, 0, sizeof *st);
    UMP_CHECK(dt > 0 && isfinite(dt), err, UMP_ERR_INPUT, "FPM: time step %g", dt);
    f->dt_last = dt;
    UMP_CALL(reserve(f, err));
    part_set *s = f->s;
    size_t n = s->n, ns = f->ns;
    st->nfluid = n - ns;
    double c0 = cpu_seconds(), w0 = wall_seconds(), c1, w1;
    /* 1. move (Eq. 21): positions change only here */
    for (size_t i = ns; i < n; i++) {
        s->x[i] += dt * s->u[i];
        s->y[i] += dt * s->v[i];
    }
    /* 2. rows and MLS coefficients at x^{n+1} */
    static const int need[4] = {1, 1, 0, -1};
    UMP_CALL(pnbr_update(&f->nb, s, f->kind, need, f->P.h, FPM_SKIN * f->P.l0, f->rows_stale, "FPM", err));
    f->rows_stale = 0;
    UMP_CALL(mls_rows(f, st, err));
    c1 = cpu_seconds(), w1 = wall_seconds();
    st->cpu[0] += c1 - c0, st->wall[0] += w1 - w0;
    /* 3. predictor (Eq. 21): u~ = u^n + dt (nu lap u^n + g). A wall point
     * gets u~ = u_w + dt (g - a_w): u^{n+1} = u~ - dt/rho grad p there too,
     * so this is the u~ whose normal part agrees with the Neumann condition
     * of Eq. 25 (its inviscid part); with u~ = u_w instead, the divergence
     * next to a wall sees a jump of g dt over l0/2, and the hydrostatic
     * pressure came out 2.1 times rho g h (measured, the tank at rest) */
    const double nu = f->P.nu;
    const double nus = f->P.surf_damp * f->P.l0 * sqrt(hypot(f->P.g[0], f->P.g[1]) * f->P.l0);
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; i++) {
        if (f->kind[i] == FPM_WALL) {
            f->ut[i] = s->u[i] + dt * (f->P.g[0] - f->wacc[2 * i]);
            f->vt[i] = s->v[i] + dt * (f->P.g[1] - f->wacc[2 * i + 1]);
            continue;
        }
        if (f->kind[i] != FPM_FLUID) {
            f->ut[i] = f->vt[i] = 0;
            continue;
        }
        double lu = 0, lv = 0;
        if (nu > 0 && f->quad[i]) {
            lu = row_sum(f, i, f->cl, f->sl[i], s->u);
            lv = row_sum(f, i, f->cl, f->sl[i], s->v);
        }
        f->ut[i] = s->u[i] + dt * (nu * lu + f->P.g[0]);
        f->vt[i] = s->v[i] + dt * (nu * lv + f->P.g[1]);
        if (nus > 0 && f->surf[i]) {
            /* free-surface damping (a departure, docs/METHOD.md 11):
             * nu_s 4/sum_j w_j r_j^2 sum_j w_j (u_j - u_i) over the fluid
             * neighbours within h0. The MLS operators do not damp the
             * surface row's motion relative to the rows below (measured: nu
             * 1e-5, or a damping of the quadratic fit's residual, left its
             * growing orbits nearly as they were; presumably a one-sided
             * quadratic fit over three rows follows the surface row) */
            const pnbr *R = &f->nb;
            double sw = 0, sw0 = 0, ru = 0, rv = 0;
            for (size_t q = R->off[i]; q < R->off[i + 1]; q++) {
                size_t j = R->j[q];
                if (f->kind[j] != FPM_FLUID || R->r[q] >= f->P.h)
                    continue;
                double w, wd1, wq, w2;
                mls_wfun_eval(f->P.weight, R->r[q] / f->P.h, &w, &wd1, &wq, &w2);
                sw += w * R->r[q] * R->r[q];
                sw0 += w;
                ru += w * (s->u[j] - s->u[i]);
                rv += w * (s->v[j] - s->v[i]);
            }
            if (sw > 0) {
                double a = dt * nus * 4 / sw;
                if (a * sw0 > 0.5)
                    a = 0.5 / sw0; /* explicit: at most half way to the neighbours' mean per step */
                f->ut[i] += a * ru;
                f->vt[i] += a * rv;
            }
        }
    }
    c0 = cpu_seconds(), w0 = wall_seconds();
    st->cpu[1] += c0 - c1, st->wall[1] += w0 - w1;
    /* 4. pressure (Eqs. 24-25) */
    UMP_CALL(pressure(f, dt, st, err));
    c1 = cpu_seconds(), w1 = wall_seconds();
    st->cpu[2] += c1 - c0, st->wall[2] += w1 - w0;
    /* 5. correction (Eq. 22) */
    const double k = dt / f->P.rho;
    double pmin = HUGE_VAL, pmax = -HUGE_VAL, nmin = HUGE_VAL, nmax = -HUGE_VAL;
    size_t nsurf = 0;
#pragma omp parallel for schedule(static) reduction(min : pmin, nmin) reduction(max : pmax, nmax) \
    reduction(+ : nsurf)
    for (size_t i = ns; i < n; i++) {
        double gx = row_sum(f, i, f->cx, f->sx[i], f->p), gy = row_sum(f, i, f->cy, f->sy[i], f->p);
        s->u[i] = f->ut[i] - k * gx;
        s->v[i] = f->vt[i] - k * gy;
        pmin = fmin(pmin, f->p[i]);
        pmax = fmax(pmax, f->p[i]);
        nmin = fmin(nmin, f->nd[i]);
        nmax = fmax(nmax, f->nd[i]);
        nsurf += f->surf[i];
    }
    st->nsurface = nsurf;
    st->p_min = n > ns ? pmin : 0;
    st->p_max = n > ns ? pmax : 0;
    st->n_min = n > ns ? nmin : 0;
    st->n_max = n > ns ? nmax : 0;
    st->cpu[3] += cpu_seconds() - c1, st->wall[3] += wall_seconds() - w1;
    return UMP_OK;
}

/* ---- particle management (Section 4.1) ----------------------------------------- */

/* MLS value (c0 of Eq. 1) at (x, y) of v over particle c0's row and c0
 * itself (fluid and wet wall points within h). */
static double interp_at(const fpm *f, size_t c0, double x, double y, const double *v)
{
    const part_set *s = f->s;
    const pnbr *R = &f->nb;
    double dx[FPM_MAXROW + 1], dy[FPM_MAXROW + 1], c[FPM_MAXROW + 1], val[FPM_MAXROW + 1];
    double *cc[MLS_NOUT] = {c, NULL, NULL, NULL, NULL, NULL};
    int k = 0;
    dx[k] = s->x[c0] - x;
    dy[k] = s->y[c0] - y;
    val[k++] = v[c0];
    for (size_t q = R->off[c0]; q < R->off[c0 + 1] && k <= FPM_MAXROW; q++) {
        size_t j = R->j[q];
        if (!(f->kind[j] == FPM_FLUID || (f->kind[j] == FPM_WALL && !f->surf[j])))
            continue;
        dx[k] = s->x[j] - x;
        dy[k] = s->y[j] - y;
        val[k++] = v[j];
    }
    mls_full(dx, dy, k, f->P.h, f->P.weight, cc, NULL);
    double t = 0;
    for (int q = 0; q < k; q++)
        t += c[q] * val[q];
    return t;
}

/* Particle i's displacement (sx, sy), at most cap long, plus dt times a
 * velocity change (cu, cv) (a collision's): kept in dsx..dsv with the
 * velocity at the new place, u + cu + (sx, sy).grad u (MLS gradient), for
 * apply_shifts; returns the capped |(sx, sy)|. */
static double stage_shift(fpm *f, size_t i, double sx, double sy, double cap, double cu, double cv, double dt)
{
    const double *u = f->s->u, *v = f->s->v;
    double len = hypot(sx, sy);
    if (len > cap) {
        sx *= cap / len;
        sy *= cap / len;
        len = cap;
    }
    f->dsx[i] = sx + dt * cu;
    f->dsy[i] = sy + dt * cv;
    f->dsu[i] = cu + sx * row_sum(f, i, f->cx, f->sx[i], u) + sy * row_sum(f, i, f->cy, f->sy[i], u);
    f->dsv[i] = cv + sx * row_sum(f, i, f->cx, f->sx[i], v) + sy * row_sum(f, i, f->cy, f->sy[i], v);
    return len;
}

/* Apply what stage_shift kept, to the fluid particles [ns, n) (all
 * computed first: Jacobi, no order or thread dependence). */
static void apply_shifts(fpm *f, size_t ns, size_t n)
{
    part_set *s = f->s;
    for (size_t i = ns; i < n; i++) {
        s->x[i] += f->dsx[i];
        s->y[i] += f->dsy[i];
        s->u[i] += f->dsu[i];
        s->v[i] += f->dsv[i];
    }
}

ump_status fpm_manage(fpm *f, const fpm_manage_params *mg, const unsigned char **keep, fpm_manage_stats *ms,
                      ump_err *err)
{
    memset(ms, 0, sizeof *ms);
    part_set *s = f->s;
    size_t n = s->n, ns = f->ns, nw = f->nw;
    const pnbr *R = &f->nb;
    const double l0 = f->P.l0;
    if (n + 1 > f->kcap) {
        size_t nc = 2 * n + 16;
        GROW_TO(f->keep, nc);
        f->kcap = nc;
    }
    if (n + 1 > f->mcap) {
        size_t nc = 2 * n + 16;
        GROW_TO(f->mask, nc);
        GROW_TO(f->hx, nc);
        GROW_TO(f->hy, nc);
        GROW_TO(f->hmap, nc);
        GROW_TO(f->dsx, nc);
        GROW_TO(f->dsy, nc);
        GROW_TO(f->dsu, nc);
        GROW_TO(f->dsv, nc);
        f->mcap = nc;
    }
    memset(f->keep, 1, n);
    *keep = f->keep;
    /* the rows are those of the step (positions at x^{n+1}); the caller
     * may have put some particles back (stopped at a wall): offsets are
     * taken from the positions, not from the rows */
    if (mg->shift > 0 && f->dt_last > 0) {
        /* particle shifting (a departure, fpm.h): dr = -D grad C (Lind et
         * al. 2012), D = A (r_s/2) |u| dt (Skillen et al. 2013: A h |u| dt,
         * r_s = 2h); computed for all, then applied (Jacobi: the result
         * does not depend on the order or the threads) */
        const double rs = f->P.re_s * l0, cap = 0.1 * l0, A = mg->shift, dt = f->dt_last;
        double big = 0;
#pragma omp parallel for schedule(static) reduction(max : big)
        for (size_t i = ns; i < n; i++) {
            double gx = 0, gy = 0;
            int near = f->surf[i];
            for (size_t q = R->off[i]; q < R->off[i + 1]; q++) {
                size_t j = R->j[q];
                if (f->kind[j] == FPM_WALL)
                    continue; /* on the wall face: the ghosts complete the lattice */
                double dx = s->x[j] - s->x[i], dy = s->y[j] - s->y[i], r = sqrt(dx * dx + dy * dy);
                if (r >= rs || r <= 0)
                    continue;
                near |= f->kind[j] == FPM_FLUID && f->surf[j];
                double w, w1, wq, w2;
                mls_wfun_eval(MLS_WFUN_SPLINE, r / rs, &w, &w1, &wq, &w2);
                gx -= wq / (rs * rs) * dx; /* grad_i w(|x_i - x_j| / rs) = w'(q)/q (x_i - x_j) / rs^2 */
                gy -= wq / (rs * rs) * dy;
            }
            gx /= f->n0;
            gy /= f->n0;
            double D = A * 0.5 * rs * hypot(s->u[i], s->v[i]) * dt;
            double sx = -D * gx, sy = -D * gy, g2 = gx * gx + gy * gy;
            if (near && g2 > 0) {
                /* the free surface: along it only (Lind et al. 2012) */
                double t = (sx * gx + sy * gy) / g2;
                sx -= t * gx;
                sy -= t * gy;
            }
            big = fmax(big, stage_shift(f, i, sx, sy, cap, 0, 0, 0));
        }
        apply_shifts(f, ns, n);
        ms->max_shift = big / l0;
    }
    if (mg->d_rep > 0 && f->dt_last > 0) {
        /* close-pair repulsion (a departure, fpm.h). Merging alone loses
         * the liquid in violent sloshing: rows of a squashed lattice come
         * 0.4 l0 apart while n stays near n0, which neither the density
         * source nor Fickian shifting (Lind et al. 2012) sees. (a) The
         * collision model of MPS (mps.c's, Lee et al., Comput. Methods
         * Appl. Mech. Engrg. 200 (2011) 1113-1125; restitution 0.2) stops
         * the approach; (b) a
         * spring-like shift dr_i = c sum_j (d - r_ij) e_ij -- a fixed
         * fraction of the overlap per step, not tied to |u| as the shift
         * of Xu, Stansby & Laurence (J. Comput. Phys. 228 (2009) 6703-6725),
         * C U dt sum_j (rbar/r_ij)^2 e_ij, is --
         * separates what has come close. Measured in the swaying tank:
         * either alone lost the liquid or diverged, both together kept it.
         * Computed for all, then applied (Jacobi: no order or thread
         * dependence); at rest on a lattice nothing is closer than l0. */
        const double d = mg->d_rep * l0, c = mg->c_rep, cap = 0.2 * l0, e = 0.2, dt = f->dt_last;
        double big = 0;
#pragma omp parallel for schedule(static) reduction(max : big)
        for (size_t i = ns; i < n; i++) {
            double sx = 0, sy = 0, du = 0, dv = 0;
            for (size_t q = R->off[i]; q < R->off[i + 1]; q++) {
                size_t j = R->j[q];
                if (f->kind[j] != FPM_FLUID && f->kind[j] != FPM_GHOST)
                    continue; /* wall points sit on the faces, 0.5 l0 off the lattice: wallDistance keeps to them */
                double dx = s->x[i] - s->x[j], dy = s->y[i] - s->y[j], r = sqrt(dx * dx + dy * dy);
                if (r >= d || r <= 0)
                    continue;
                double ex = dx / r, ey = dy / r; /* from j to i */
                sx += c * (d - r) * ex;
                sy += c * (d - r) * ey;
                if (f->kind[j] == FPM_FLUID) {
                    double vn = (s->u[j] - s->u[i]) * ex + (s->v[j] - s->v[i]) * ey; /* > 0: approaching */
                    if (vn > 0) {
                        du += 0.5 * (1 + e) * vn * ex;
                        dv += 0.5 * (1 + e) * vn * ey;
                    }
                }
            }
            if (f->surf[i])
                sx = sy = 0; /* measured: shifting the surface particles, even along the surface, lost the liquid */
            big = fmax(big, stage_shift(f, i, sx, sy, cap, du, dv, dt));
        }
        apply_shifts(f, ns, n);
        ms->max_shift = fmax(ms->max_shift, big / l0);
    }
    if (mg->d_wall > 0) {
        const double dw = mg->d_wall * l0;
        size_t nsh = 0;
#pragma omp parallel for schedule(static) reduction(+ : nsh)
        for (size_t i = ns; i < n; i++) {
            double best = HUGE_VAL;
            size_t wb = 0;
            for (size_t q = R->off[i]; q < R->off[i + 1]; q++) {
                size_t w = R->j[q];
                if (w >= nw)
                    continue;
                double rx = s->x[i] - s->x[w], ry = s->y[i] - s->y[w];
                double dn = -(rx * f->wnx[w] + ry * f->wny[w]);        /* into the liquid */
                double dt = fabs(rx * f->wny[w] - ry * f->wnx[w]);     /* along the wall */
                if (dt <= 0.5 * l0 * 1.0001 && dn < best) {
                    best = dn;
                    wb = w;
                }
            }
            if (best < dw) {
                double nx = f->wnx[wb], ny = f->wny[wb], mv = dw - best;
                s->x[i] -= mv * nx;
                s->y[i] -= mv * ny;
                double un = (s->u[i] - s->u[wb]) * nx + (s->v[i] - s->v[wb]) * ny;
                if (un > 0) {
                    s->u[i] -= un * nx;
                    s->v[i] -= un * ny;
                }
                nsh++;
            }
        }
        ms->shifted = nsh;
    }
    if (mg->d_min > 0) {
        /* pairs in increasing index, each particle at most once per call:
         * serial and in a fixed order, so the result is deterministic */
        const double d2 = mg->d_min * l0 * mg->d_min * l0;
        for (size_t i = ns; i < n; i++) {
            if (!f->keep[i])
                continue;
            for (size_t q = R->off[i]; q < R->off[i + 1]; q++) {
                size_t j = R->j[q];
                if (j <= i || j < ns || !f->keep[j])
                    continue;
                double dx = s->x[j] - s->x[i], dy = s->y[j] - s->y[i];
                if (dx * dx + dy * dy >= d2)
                    continue;
                s->x[i] += 0.5 * dx;
                s->y[i] += 0.5 * dy;
                s->u[i] = 0.5 * (s->u[i] + s->u[j]);
                s->v[i] = 0.5 * (s->v[i] + s->v[j]);
                f->p[i] = 0.5 * (f->p[i] + f->p[j]);
                f->keep[j] = 0;
                ms->merged++;
                break;
            }
        }
    }
    if (mg->r_hole > 0 && mg->insert) {
        /* the liquid's points: inside fluid particles and wet wall points */
        size_t m = 0;
        for (size_t i = 0; i < n; i++) {
            int in = f->keep[i] && ((f->kind[i] == FPM_FLUID && !f->surf[i] && f->quad[i]) ||
                                    (f->kind[i] == FPM_WALL && !f->surf[i]));
            if (f->kind[i] >= FPM_GHOST)
                continue;
            f->hx[m] = s->x[i];
            f->hy[m] = s->y[i];
            f->hmap[m] = i;
            f->mask[m] = (unsigned char)in;
            m++;
        }
        const vor_hole *H = NULL;
        size_t nh = 0;
        /* the largest holes whose centre lies inside their triangle
         * (barycentric >= -0.05): not across a wall (vor.h); H is the
         * workspace's, valid until its next search */
        UMP_CALL(vor_work_holes_inside(f->vw, f->hx, f->hy, m, f->mask, mg->r_hole * l0, 0.05, &H, &nh, err));
        for (size_t k = 0; k < m; k++)
            f->mask[k] = 0; /* now: vertex used by an insertion of this call */
        ump_status rc = UMP_OK;
        for (size_t h = 0; h < nh && rc == UMP_OK; h++) {
            const vor_hole *o = &H[h];
            if (f->mask[o->v[0]] || f->mask[o->v[1]] || f->mask[o->v[2]])
                continue;
            /* interpolate from a fluid vertex's row */
            size_t c0 = f->hmap[o->v[0]];
            for (int t = 0; t < 3; t++)
                if (f->kind[f->hmap[o->v[t]]] == FPM_FLUID) {
                    c0 = f->hmap[o->v[t]];
                    break;
                }
            if (f->kind[c0] != FPM_FLUID)
                continue; /* three wall points: not a hole in the liquid */
            double u = interp_at(f, c0, o->x, o->y, s->u), v = interp_at(f, c0, o->x, o->y, s->v);
            double pr = interp_at(f, c0, o->x, o->y, f->p);
            size_t idx;
            rc = part_add(s, o->x, o->y, u, v, 0, s->cell[c0], &idx, err);
            if (rc != UMP_OK)
                break;
            rc = reserve(f, err);
            if (rc != UMP_OK)
                break;
            if (idx + 1 > f->kcap) {
                size_t nc = 2 * idx + 16;
                void *q1 = ump_realloc_array(f->keep, nc, 1);
                if (!q1) {
                    rc = UMP_FAIL(err, UMP_ERR_NOMEM, "FPM: out of memory");
                    break;
                }
                f->keep = q1;
                f->kcap = nc;
                *keep = f->keep;
            }
            f->keep[idx] = 1;
            f->kind[idx] = FPM_FLUID;
            f->p[idx] = pr;
            f->nd[idx] = 1;
            f->surf[idx] = 0;
            f->quad[idx] = 0;
            f->mask[o->v[0]] = f->mask[o->v[1]] = f->mask[o->v[2]] = 1;
            ms->inserted++;
        }
        UMP_CALL(rc);
    }
    return UMP_OK;
}
