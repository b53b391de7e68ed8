/* SPDX-License-Identifier: GPL-3.0-or-later
 * laplacianAccuracy -- the accuracy experiments of Hwang, Ng & Sheu (2016)
 * [HNS16], Section 4, for the particle Laplacians of src/laplacian.c, on
 * irregular 1-, 2- and 3-D point clouds (Eqs. 35, 41, 45):
 *   x = (i - 1) dx + alpha (chi - 0.5) dx,  dx = 1/nC,  chi uniform in [0,1).
 *
 *   laplacianAccuracy operator  [options]
 *       Laplacian of phi = prod_d sin(2 pi x_d) (Eqs. 34, 43, 47) on a
 *       periodic cloud of nC^dim points in [0,1)^dim; for each model one
 *       line  OPERATOR model=.. dim=.. nC=.. alpha=.. points=.. nbrs=..
 *       L2=.. L2rel=.. Linf=.. ReN=.. tauxx=.. tauxxdev=.. tauxy=..
 *       L2: RMS of <lap phi> - lap phi (Eq. 38 as an RMS), L2rel: over the
 *       RMS of lap phi, ReN: artificial cell Reynolds number of PS, RMS of
 *       u_N,x dx (Eqs. 37b, 42a, 46a), tauxx: mean IPS effective normal
 *       diffusivity, tauxxdev: RMS of tau_xx - 1, tauxy: RMS of the shear
 *       diffusivity (Eqs. 22-23). The quality numbers do not depend on the
 *       model of the line ([HNS16] defines them for PS and IPS).
 *   laplacianAccuracy diffusion [options] [-CD 1] [-endTime 0.02] [-beta 1]
 *                               [-gamma 1] [-samples 10]
 *       The pure diffusion problems (Eqs. 39, 44, 48) on [0,1]^dim with
 *       (nC+1)^dim points, boundary points unjittered and set to the exact
 *       solution, explicit Euler (Eq. 39c) with dt = C_D min_i Omega_0 /
 *       (2 d Omega_2^(0)) (Eqs. 39d, 44c, 48c: the PS monotonicity limit,
 *       used for every model). Lines
 *       DIFFUSION model=.. dim=.. nC=.. alpha=.. CD=.. dt=.. t=.. err=.. max=..
 *       at the sample times, err the RMS over interior points of
 *       phi - phi_ex (Eq. 40).
 *   laplacianAccuracy threePoint [-phiStar 2]
 *       The 1-D three-point problem (Eqs. 31-33) for alpha = 0 ... 0.9:
 *       THREEPOINT alpha=.. exact=.. PS=.. IPS=.. realityPS=.. realityIPS=..
 *       eq33b=..  (our operators beside the reality factor of Eq. 33b).
 * Options: -dim 1|2|3 (2), -nC N (32), -alpha A (0.3), -seed S (1),
 *          -reFactor R (2: r_e = R dx; every model gets the neighbours
 *          closer than r_e), -models CPM,PS,IPS,MPS (all four).
 * Neighbours come from the lattice index window, never an all-pairs search.
 */
#include "umppm/laplacian.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const double PI = 3.14159265358979323846;

static void die(const char *msg)
{
    fprintf(stderr, "laplacianAccuracy: %s\n", msg);
    exit(1);
}

static void *xcalloc(size_t n, size_t s)
{
    void *p = calloc(n ? n : 1, s);
    if (!p)
        die("out of memory");
    return p;
}

/* ---- random numbers (splitmix64, reproducible per seed) ---------------- */
static uint64_t rng;
static double rnd(void)
{
    uint64_t z = (rng += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    z ^= z >> 31;
    return (double)(z >> 11) * (1.0 / 9007199254740992.0);
}

/* ---- the cloud --------------------------------------------------------- */
typedef struct cloud {
    int dim, periodic;
    int np;                 /* points per direction */
    size_t n;               /* np^dim */
    double dx, re;          /* spacing, cut-off radius r_e */
    double *x[3];
    unsigned char *bnd;     /* on the boundary (non-periodic clouds) */
} cloud;

static void cloud_make(cloud *c, int dim, int nc, double alpha, int periodic, double refac)
{
    c->dim = dim;
    c->periodic = periodic;
    c->np = periodic ? nc : nc + 1;
    c->dx = 1.0 / nc;
    c->re = refac * c->dx;
    c->n = 1;
    for (int d = 0; d < dim; d++)
        c->n *= (size_t)c->np;
    for (int d = 0; d < dim; d++)
        c->x[d] = xcalloc(c->n, sizeof(double));
    c->bnd = xcalloc(c->n, 1);
    for (size_t p = 0; p < c->n; p++) {
        size_t q = p;
        int idx[3];
        for (int d = 0; d < dim; d++) {
            idx[d] = (int)(q % (size_t)c->np);
            q /= (size_t)c->np;
            if (!periodic && (idx[d] == 0 || idx[d] == c->np - 1))
                c->bnd[p] = 1;
        }
        for (int d = 0; d < dim; d++) {
            double chi = rnd(); /* drawn for every point and axis: same cloud for all models */
            double jit = c->bnd[p] ? 0 : alpha * (chi - 0.5);
            c->x[d][p] = (idx[d] + jit) * c->dx; /* Eqs. 35, 41, 45 */
        }
    }
}

static void cloud_free(cloud *c)
{
    for (int d = 0; d < c->dim; d++)
        free(c->x[d]);
    free(c->bnd);
}

/* Neighbours of point p closer than r_e, from the index window +-w. */
typedef struct nbrs {
    int cap, n;
    size_t *idx;
    double *off[3];
} nbrs;

static void nbrs_gather(const cloud *c, size_t p, int w, nbrs *nb)
{
    int idx[3] = {0, 0, 0}, lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    size_t q = p;
    for (int d = 0; d < c->dim; d++) {
        idx[d] = (int)(q % (size_t)c->np);
        q /= (size_t)c->np;
        lo[d] = -w;
        hi[d] = w;
    }
    nb->n = 0;
    int o[3];
    for (o[2] = lo[2]; o[2] <= hi[2]; o[2]++)
        for (o[1] = lo[1]; o[1] <= hi[1]; o[1]++)
            for (o[0] = lo[0]; o[0] <= hi[0]; o[0]++) {
                size_t j = 0, stride = 1;
                double shift[3] = {0, 0, 0};
                int skip = 1, out = 0;
                for (int d = 0; d < c->dim; d++) {
                    int k = idx[d] + o[d];
                    if (o[d])
                        skip = 0;
                    if (c->periodic) {
                        if (k < 0) { k += c->np; shift[d] = -1; }
                        else if (k >= c->np) { k -= c->np; shift[d] = 1; }
                    } else if (k < 0 || k >= c->np) {
                        out = 1;
                    }
                    j += (size_t)k * stride;
                    stride *= (size_t)c->np;
                }
                if (skip || out)
                    continue;
                double r2 = 0, dd[3];
                for (int d = 0; d < c->dim; d++) {
                    dd[d] = c->x[d][j] + shift[d] - c->x[d][p];
                    r2 += dd[d] * dd[d];
                }
                if (r2 >= c->re * c->re)
                    continue;
                if (nb->n == nb->cap)
                    die("neighbour buffer too small");
                nb->idx[nb->n] = j;
                for (int d = 0; d < c->dim; d++)
                    nb->off[d][nb->n] = dd[d];
                nb->n++;
            }
}

static int window(const cloud *c, double alpha)
{
    return (int)ceil(c->re / c->dx + alpha);
}

static void nbrs_init(nbrs *nb, const cloud *c, int w)
{
    int side = 2 * w + 1;
    nb->cap = 1;
    for (int d = 0; d < c->dim; d++)
        nb->cap *= side;
    nb->idx = xcalloc((size_t)nb->cap, sizeof *nb->idx);
    for (int d = 0; d < 3; d++)
        nb->off[d] = xcalloc((size_t)nb->cap, sizeof(double));
}

static void nbrs_free(nbrs *nb)
{
    free(nb->idx);
    for (int d = 0; d < 3; d++)
        free(nb->off[d]);
}

/* The Laplacian rows of every point (boundary points of non-periodic clouds
 * get empty rows): lap_i = sum_k val[k] (phi[col[k]] - phi_i). */
typedef struct rows {
    size_t *ptr, *col;
    double *val;
} rows;

static void rows_build(const cloud *c, double alpha, const lap_params *lp, rows *R, double *nbr_mean)
{
    int w = window(c, alpha);
    nbrs nb;
    nbrs_init(&nb, c, w);
    size_t cap = c->n * 8, nz = 0, cnt = 0, tot = 0;
    R->ptr = xcalloc(c->n + 1, sizeof *R->ptr);
    R->col = xcalloc(cap, sizeof *R->col);
    R->val = xcalloc(cap, sizeof *R->val);
    double *a = xcalloc((size_t)nb.cap, sizeof *a);
    for (size_t p = 0; p < c->n; p++) {
        if (!c->bnd[p]) {
            nbrs_gather(c, p, w, &nb);
            ump_err err;
            const double *off[3] = {nb.off[0], nb.off[1], nb.off[2]};
            if (lap_coeffs_d(lp, c->dim, off, nb.n, c->dx, a, &err) != UMP_OK) {
                fprintf(stderr, "laplacianAccuracy: point %zu: %s\n", p, err.msg);
                exit(1);
            }
            if (nz + (size_t)nb.n > cap) {
                cap = 2 * (nz + (size_t)nb.n);
                R->col = realloc(R->col, cap * sizeof *R->col);
                R->val = realloc(R->val, cap * sizeof *R->val);
                if (!R->col || !R->val)
                    die("out of memory");
            }
            for (int j = 0; j < nb.n; j++) {
                R->col[nz] = nb.idx[j];
                R->val[nz++] = a[j];
            }
            cnt++;
            tot += (size_t)nb.n;
        }
        R->ptr[p + 1] = nz;
    }
    if (nbr_mean)
        *nbr_mean = cnt ? (double)tot / (double)cnt : 0;
    free(a);
    nbrs_free(&nb);
}

static void rows_free(rows *R)
{
    free(R->ptr);
    free(R->col);
    free(R->val);
}

static double rows_apply(const rows *R, const double *phi, size_t p)
{
    double s = 0;
    for (size_t k = R->ptr[p]; k < R->ptr[p + 1]; k++)
        s += R->val[k] * (phi[R->col[k]] - phi[p]);
    return s;
}

/* ---- options ------------------------------------------------------------ */
typedef struct opts {
    int dim, nc, seed, samples;
    double alpha, refac, cd, end, beta, gamma, phistar;
    lap_model models[4];
    int nmodels;
} opts;

static void parse_models(const char *s, opts *o)
{
    char buf[256];
    snprintf(buf, sizeof buf, "%s", s);
    o->nmodels = 0;
    for (char *t = strtok(buf, ","); t; t = strtok(NULL, ",")) {
        int m = lap_parse(t);
        if (m < 0 || o->nmodels == 4) {
            fprintf(stderr, "laplacianAccuracy: -models: '%s' is not one of CPM, MPS, IPS, PS\n", t);
            exit(1);
        }
        o->models[o->nmodels++] = (lap_model)m;
    }
}

static double num(const char *s, const char *name)
{
    char *end;
    double v = strtod(s, &end);
    if (end == s || *end || !isfinite(v)) {
        fprintf(stderr, "laplacianAccuracy: %s '%s' is not a number\n", name, s);
        exit(1);
    }
    return v;
}

static int inum(const char *s, const char *name)
{
    double v = num(s, name);
    if (v != floor(v) || fabs(v) > 1e9) {
        fprintf(stderr, "laplacianAccuracy: %s '%s' is not an integer\n", name, s);
        exit(1);
    }
    return (int)v;
}

/* ---- operator test ------------------------------------------------------ */
static double sinprod(const cloud *c, size_t p)
{
    double f = 1;
    for (int d = 0; d < c->dim; d++)
        f *= sin(2 * PI * c->x[d][p]);
    return f;
}

static void run_operator(const opts *o)
{
    cloud c;
    rng = (uint64_t)o->seed * 0x2545F4914F6CDD1DULL + 17;
    cloud_make(&c, o->dim, o->nc, o->alpha, 1, o->refac);
    if (c.np < 2 * window(&c, o->alpha) + 2)
        die("nC too small for the neighbour window of a periodic cloud");
    double *phi = xcalloc(c.n, sizeof *phi);
    for (size_t p = 0; p < c.n; p++)
        phi[p] = sinprod(&c, p);
    /* quality of the distribution ([HNS16] Eqs. 13, 22): PS and IPS */
    double sun = 0, stx = 0, stxd = 0, sts = 0;
    {
        int w = window(&c, o->alpha);
        nbrs nb;
        nbrs_init(&nb, &c, w);
        double *work = xcalloc((size_t)nb.cap, sizeof *work);
        for (size_t p = 0; p < c.n; p++) {
            nbrs_gather(&c, p, w, &nb);
            lap_quality q;
            ump_err err;
            const double *off[3] = {nb.off[0], nb.off[1], nb.off[2]};
            if (lap_quality_d(o->refac, c.dim, off, nb.n, c.dx, work, &q, &err) != UMP_OK) {
                fprintf(stderr, "laplacianAccuracy: point %zu: %s\n", p, err.msg);
                exit(1);
            }
            sun += q.uN[0] * q.uN[0];
            stx += q.tau[0];
            stxd += (q.tau[0] - 1) * (q.tau[0] - 1);
            sts += q.tau[1] * q.tau[1];
        }
        free(work);
        nbrs_free(&nb);
    }
    double N = (double)c.n;
    double ren = sqrt(sun / N) * c.dx, taum = stx / N, taud = sqrt(stxd / N), taus = sqrt(sts / N);
    for (int m = 0; m < o->nmodels; m++) {
        lap_params lp = {o->models[m], o->refac};
        rows R;
        double nbm;
        rows_build(&c, o->alpha, &lp, &R, &nbm);
        double se = 0, sx = 0, emax = 0;
        for (size_t p = 0; p < c.n; p++) {
            double ex = -c.dim * 4 * PI * PI * phi[p]; /* Eqs. 34b, 43b, 47b */
            double e = rows_apply(&R, phi, p) - ex;
            se += e * e;
            sx += ex * ex;
            emax = fmax(emax, fabs(e));
        }
        printf("OPERATOR model=%s dim=%d nC=%d alpha=%g seed=%d points=%zu nbrs=%.2f L2=%.6e "
               "L2rel=%.6e Linf=%.6e ReN=%.6e tauxx=%.6f tauxxdev=%.6e tauxy=%.6e\n",
               lap_name(lp.model), c.dim, o->nc, o->alpha, o->seed, c.n, nbm, sqrt(se / N),
               sqrt(se / sx), emax, ren, taum, taud, taus);
        rows_free(&R);
    }
    free(phi);
    cloud_free(&c);
}

/* ---- pure diffusion ----------------------------------------------------- */
/* Exact solutions, Eqs. 39b, 44b, 48b. */
static double diffusion_exact(const cloud *c, size_t p, double t, double beta, double gamma)
{
    double x = c->x[0][p], y = c->dim > 1 ? c->x[1][p] : 0, z = c->dim > 2 ? c->x[2][p] : 0;
    double k = 2 * PI * gamma, decay = beta * exp(-c->dim * k * k * t);
    switch (c->dim) {
    case 1:
        return decay * sin(k * x) + x;
    case 2:
        return decay * sin(k * x) * sin(k * y) + 4 * x * (x - 1) - 4 * y * (y - 1) +
               (x - 0.5) * (y - 0.5);
    default:
        return decay * sin(k * x) * sin(k * y) * sin(k * z) + 4 * x * (x - 1) - 4 * y * (y - 1) +
               (x - 0.5) * (y - 0.5) * (z - 0.5);
    }
}

static void run_diffusion(const opts *o)
{
    cloud c;
    rng = (uint64_t)o->seed * 0x2545F4914F6CDD1DULL + 17;
    cloud_make(&c, o->dim, o->nc, o->alpha, 0, o->refac);
    /* dt from PS, Eqs. 39d/44c/48c: Omega_0 / (2 d Omega_2^(0)) = 1 / sum_j a_j^PS */
    lap_params ps = {LAP_PS, o->refac};
    rows R;
    rows_build(&c, o->alpha, &ps, &R, NULL);
    double dtmin = INFINITY;
    for (size_t p = 0; p < c.n; p++) {
        double s = 0;
        for (size_t k = R.ptr[p]; k < R.ptr[p + 1]; k++)
            s += R.val[k];
        if (s > 0)
            dtmin = fmin(dtmin, 1 / s);
    }
    rows_free(&R);
    double dt = o->cd * dtmin;
    double *phi = xcalloc(c.n, sizeof *phi), *nxt = xcalloc(c.n, sizeof *nxt);
    for (int m = 0; m < o->nmodels; m++) {
        lap_params lp = {o->models[m], o->refac};
        rows_build(&c, o->alpha, &lp, &R, NULL);
        for (size_t p = 0; p < c.n; p++)
            phi[p] = diffusion_exact(&c, p, 0, o->beta, o->gamma);
        double t = 0;
        for (int s = 1; s <= o->samples; s++) {
            double target = o->end * s / o->samples;
            while (t < target - 1e-12 * o->end) {
                double h = fmin(dt, target - t);
                for (size_t p = 0; p < c.n; p++) /* Eq. 39c */
                    nxt[p] = c.bnd[p] ? diffusion_exact(&c, p, t + h, o->beta, o->gamma)
                                      : phi[p] + h * rows_apply(&R, phi, p);
                double *tmp = phi;
                phi = nxt;
                nxt = tmp;
                t += h;
            }
            double se = 0, emax = 0;
            size_t ni = 0;
            for (size_t p = 0; p < c.n; p++) {
                if (c.bnd[p])
                    continue;
                double e = phi[p] - diffusion_exact(&c, p, t, o->beta, o->gamma);
                se += e * e;
                emax = fmax(emax, fabs(e));
                ni++;
            }
            printf("DIFFUSION model=%s dim=%d nC=%d alpha=%g seed=%d CD=%g dt=%.6e t=%.6g err=%.6e "
                   "max=%.6e\n", lap_name(lp.model), c.dim, o->nc, o->alpha, o->seed, o->cd, dt, t,
                   sqrt(se / (double)(ni ? ni : 1)), emax);
        }
        rows_free(&R);
    }
    free(phi);
    free(nxt);
    cloud_free(&c);
}

/* ---- the three-point problem (Eqs. 31-33) ------------------------------ */
static void run_threepoint(const opts *o)
{
    double ps = o->phistar;
    for (int k = 0; k <= 9; k++) {
        double al = 0.1 * k;
        /* particle at 0, neighbours at 1 and -1 + alpha, r_e = 2 (delta = 1) */
        double h[2] = {1, -1 + al}, phij[2] = {1, ps}, a[2];
        const double *off[1] = {h};
        lap_params lps = {LAP_PS, 2}, lips = {LAP_IPS, 2};
        ump_err err;
        double v[2];
        const lap_params *lp[2] = {&lps, &lips};
        for (int m = 0; m < 2; m++) {
            if (lap_coeffs_d(lp[m], 1, off, 2, 1.0, a, &err) != UMP_OK)
                die(err.msg);
            v[m] = a[0] * phij[0] + a[1] * phij[1]; /* phi_i = 0 */
        }
        double ex = 2 * (1 - al + ps) / ((1 - al) * (2 - al));   /* Eq. 31c */
        double e33b = 1 - 0.75 * al * al + 0.25 * al * al * al;  /* Eq. 33b (tested to round-off
                                                                    in tests/unit/test_laplacian.c) */
        printf("THREEPOINT alpha=%.1f phiStar=%g exact=%.15g PS=%.15g IPS=%.15g realityPS=%.15g "
               "realityIPS=%.15g eq33b=%.15g\n", al, ps, ex, v[0], v[1], v[0] / ex, v[1] / ex, e33b);
    }
}

int main(int argc, char **argv)
{
    const char *usage =
        "usage: laplacianAccuracy operator|diffusion|threePoint [-dim 1|2|3] [-nC N] [-alpha A]\n"
        "       [-seed S] [-reFactor R] [-models CPM,PS,IPS,MPS] [-CD C] [-endTime T]\n"
        "       [-beta B] [-gamma G] [-samples K] [-phiStar P]\n";
    if (argc < 2) {
        fputs(usage, stderr);
        return 1;
    }
    opts o = {2, 32, 1, 10, 0.3, 2.0, 1.0, 0.02, 1.0, 1.0, 2.0, {LAP_CPM, LAP_PS, LAP_IPS, LAP_MPS}, 4};
    for (int i = 2; i < argc; i++) {
        const char *k = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (!v) {
            fprintf(stderr, "laplacianAccuracy: option %s needs a value\n%s", k, usage);
            return 1;
        }
        i++;
        if (!strcmp(k, "-dim")) o.dim = inum(v, k);
        else if (!strcmp(k, "-nC")) o.nc = inum(v, k);
        else if (!strcmp(k, "-alpha")) o.alpha = num(v, k);
        else if (!strcmp(k, "-seed")) o.seed = inum(v, k);
        else if (!strcmp(k, "-reFactor")) o.refac = num(v, k);
        else if (!strcmp(k, "-models")) parse_models(v, &o);
        else if (!strcmp(k, "-CD")) o.cd = num(v, k);
        else if (!strcmp(k, "-endTime")) o.end = num(v, k);
        else if (!strcmp(k, "-beta")) o.beta = num(v, k);
        else if (!strcmp(k, "-gamma")) o.gamma = num(v, k);
        else if (!strcmp(k, "-samples")) o.samples = inum(v, k);
        else if (!strcmp(k, "-phiStar")) o.phistar = num(v, k);
        else {
            fprintf(stderr, "laplacianAccuracy: unknown option %s\n%s", k, usage);
            return 1;
        }
    }
    if (o.dim < 1 || o.dim > 3 || o.nc < 2 || o.nc > 100000 || !(o.alpha >= 0 && o.alpha < 1) ||
        !(o.refac > 1) || !(o.cd > 0) || !(o.end > 0) || o.samples < 1)
        die("expected -dim 1..3, -nC >= 2, 0 <= -alpha < 1, -reFactor > 1, -CD > 0, -endTime > 0, "
            "-samples >= 1");
    if (!strcmp(argv[1], "operator"))
        run_operator(&o);
    else if (!strcmp(argv[1], "diffusion"))
        run_diffusion(&o);
    else if (!strcmp(argv[1], "threePoint"))
        run_threepoint(&o);
    else {
        fputs(usage, stderr);
        return 1;
    }
    return 0;
}
