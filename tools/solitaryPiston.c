/* SPDX-License-Identifier: GPL-3.0-or-later
 * solitaryPiston -- the piston wave-maker motion that generates a solitary
 * wave of height H on still water of depth d, by the first-order Boussinesq
 * theory (Goring 1978), as in Lu et al. (2019), Eqs. 30-33:
 *
 *   C     = sqrt(g (H + d))                          celerity
 *   kappa = sqrt(3 H / (4 d^3))                      wave number
 *   S     = 2 d sqrt(4 H / (3 d))                    stroke (Eq. 31)
 *   T     = (2 / C) sqrt(4 d^3 / (3 H)) (3.8 + H/d)  duration (Eq. 32)
 *   xi(t) = (S/2) { 1 + tanh( kappa [ C (t - T/2) - (xi - S/2) ] ) }   (Eq. 33)
 *
 * Eq. 33 is implicit in xi; it is solved at each t by Newton's method kept
 * inside the bracket [0, S] (f(xi) = xi - rhs(xi) is increasing, f(0) < 0 <
 * f(S), so the root is unique). The velocity follows from differentiating
 * Eq. 33: dxi/dt = C (H/d) s / (1 + (H/d) s), s = sech^2(kappa [...]), i.e.
 * the piston moves with the depth-averaged fluid velocity C eta / (d + eta)
 * of the wave eta = H s (since (S/2) kappa = H/d).
 * For t > T the piston stays at xi(T).
 *
 * By default the displacement printed is xi(t) - xi(0), so that the piston
 * starts exactly at its initial position: at t = 0 the tanh argument of
 * Eq. 33 is exactly -3.8 (C T/2 = (3.8 + H/d)/kappa, kappa S/2 = H/d), so
 * xi(0) = (S/2)(1 + tanh(-3.8)) = 1.0e-3 S/2 (7.7e-5 m for H = 0.03,
 * d = 0.15), and a mesh displacement jumping by that much in the first time
 * step would push the water with a spurious velocity xi(0)/dt. -noshift
 * prints Eq. 33 as it is.
 *
 *   solitaryPiston -H 0.03 -d 0.15 [-g 9.81] [-dt 0.002] [-end TEND]
 *                  [-columns] [-noshift]
 *
 * stdout, default: an OpenFOAM Function1 table of the displacement vector
 *   (
 *       (t (xi 0 0))
 *       ...
 *   )
 * for pointDisplacement (uniformFixedValue with "uniformValue tableFile;
 * uniformValueCoeffs { file "..."; }", or the list pasted after
 * "uniformValue table"), preceded by // comment lines with the parameters.
 * With -columns: "# t xi dxi/dt" and one line per time instead.
 * The times are 0, dt, 2 dt, ... up to TEND (default T), plus T itself if it
 * falls between two of them.
 * stderr: H, d, g, C, kappa, S, T, xi(0), xi(T).
 *
 * Exit 0 on success, 1 on bad options.
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

struct wave {
    double H, d, g;
    double C, kappa, S, T;
};

static void usage(void)
{
    fprintf(stderr,
            "usage: solitaryPiston -H HEIGHT -d DEPTH [-g 9.81] [-dt 0.002] [-end TEND] [-columns] [-noshift]\n"
            "  prints the piston displacement table ((t (xi 0 0)) ...) of the first-order\n"
            "  solitary-wave generation (Lu et al. 2019, Eqs. 30-33); -columns: t xi dxi/dt;\n"
            "  -noshift: xi of Eq. 33 without subtracting xi(0)\n");
}

/* a strictly positive finite number from argument s, or 0 on error */
static int parse_positive(const char *opt, const char *s, double *out)
{
    char *end = NULL;
    errno = 0;
    double v = strtod(s, &end);
    if (end == s || *end != '\0' || errno != 0 || !isfinite(v) || v <= 0.0) {
        fprintf(stderr, "solitaryPiston: %s needs a positive number, got '%s'\n", opt, s);
        return 0;
    }
    *out = v;
    return 1;
}

static void wave_init(struct wave *w, double H, double d, double g)
{
    w->H = H;
    w->d = d;
    w->g = g;
    w->C = sqrt(g * (H + d));
    w->kappa = sqrt(3.0 * H / (4.0 * d * d * d));
    w->S = 2.0 * d * sqrt(4.0 * H / (3.0 * d));
    w->T = (2.0 / w->C) * sqrt(4.0 * d * d * d / (3.0 * H)) * (3.8 + H / d);
}

/* the argument kappa [C (t - T/2) - (xi - S/2)] of tanh in Eq. 33 */
static double phase(const struct wave *w, double t, double xi)
{
    return w->kappa * (w->C * (t - 0.5 * w->T) - (xi - 0.5 * w->S));
}

/* xi(t) of Eq. 33 (t clamped to [0, T]) */
static double piston_xi(const struct wave *w, double t)
{
    if (t > w->T)
        t = w->T;
    if (t < 0.0)
        t = 0.0;
    const double a = 0.5 * w->S;
    double lo = 0.0, hi = w->S;
    double x = a * (1.0 + tanh(w->kappa * w->C * (t - 0.5 * w->T)));
    for (int it = 0; it < 200; it++) {
        const double th = tanh(phase(w, t, x));
        const double f = x - a * (1.0 + th);
        const double df = 1.0 + a * w->kappa * (1.0 - th * th);
        if (f < 0.0)
            lo = x;
        else
            hi = x;
        double xn = x - f / df;
        if (!(xn > lo && xn < hi)) /* outside the bracket: bisect */
            xn = 0.5 * (lo + hi);
        const double step = fabs(xn - x);
        x = xn;
        if (step <= 1e-15 * w->S || hi - lo <= 1e-15 * w->S)
            break;
    }
    return x;
}

/* dxi/dt at t (0 after T), from Eq. 33 differentiated in t */
static double piston_u(const struct wave *w, double t)
{
    if (t > w->T || t < 0.0)
        return 0.0;
    const double th = tanh(phase(w, t, piston_xi(w, t)));
    const double s = 1.0 - th * th; /* sech^2 */
    const double e = w->H / w->d;
    return w->C * e * s / (1.0 + e * s);
}

static void print_row(const struct wave *w, double t, double shift, int columns)
{
    const double xi = piston_xi(w, t) - shift;
    if (columns)
        printf("%.10g %.12e %.12e\n", t, xi, piston_u(w, t));
    else
        printf("    (%.10g (%.12e 0 0))\n", t, xi);
}

int main(int argc, char **argv)
{
    double H = -1.0, d = -1.0, g = 9.81, dt = 0.002, tEnd = -1.0;
    int columns = 0, noshift = 0;
    for (int i = 1; i < argc; i++) {
        const char *o = argv[i];
        double *target = NULL;
        if (strcmp(o, "-H") == 0)
            target = &H;
        else if (strcmp(o, "-d") == 0)
            target = &d;
        else if (strcmp(o, "-g") == 0)
            target = &g;
        else if (strcmp(o, "-dt") == 0)
            target = &dt;
        else if (strcmp(o, "-end") == 0)
            target = &tEnd;
        else if (strcmp(o, "-columns") == 0) {
            columns = 1;
            continue;
        } else if (strcmp(o, "-noshift") == 0) {
            noshift = 1;
            continue;
        } else if (strcmp(o, "-h") == 0 || strcmp(o, "-help") == 0 || strcmp(o, "--help") == 0) {
            usage();
            return 0;
        } else {
            fprintf(stderr, "solitaryPiston: unknown option '%s'\n", o);
            usage();
            return 1;
        }
        if (i + 1 >= argc) {
            fprintf(stderr, "solitaryPiston: %s needs a value\n", o);
            return 1;
        }
        if (!parse_positive(o, argv[++i], target))
            return 1;
    }
    if (H <= 0.0 || d <= 0.0) {
        fprintf(stderr, "solitaryPiston: -H and -d are required\n");
        usage();
        return 1;
    }
    struct wave w;
    wave_init(&w, H, d, g);
    if (tEnd <= 0.0)
        tEnd = w.T;
    const double xi0 = piston_xi(&w, 0.0);
    const double xiT = piston_xi(&w, w.T);
    const double shift = noshift ? 0.0 : xi0;
    long n = (long)ceil(tEnd / dt - 1e-9);
    if (n < 1)
        n = 1;
    if (n > 50000000L) {
        fprintf(stderr, "solitaryPiston: too many rows (%ld): raise -dt\n", n);
        return 1;
    }

    fprintf(stderr,
            "H = %.6g m, d = %.6g m, H/d = %.6g, g = %.6g m/s^2\n"
            "C = sqrt(g (H + d)) = %.6f m/s, kappa = %.6f 1/m\n"
            "S (stroke, Eq. 31) = %.6f m, T (duration, Eq. 32) = %.6f s\n"
            "xi(0) = %.6e m, xi(T) = %.6f m%s\n",
            H, d, H / d, g, w.C, w.kappa, w.S, w.T, xi0, xiT,
            noshift ? "" : " (printed: xi - xi(0))");

    if (columns)
        printf("# solitaryPiston -H %g -d %g -g %g: C %.6f S %.6f T %.6f%s\n# t xi dxi/dt\n", H, d, g, w.C, w.S,
               w.T, noshift ? "" : "; xi printed as xi - xi(0)");
    else {
        printf("// solitaryPiston -H %g -d %g -g %g -dt %g -end %g\n", H, d, g, dt, tEnd);
        printf("// piston displacement (t (xi 0 0)), Lu et al. (2019) Eqs. 30-33%s\n",
               noshift ? "" : ", xi - xi(0)");
        printf("// C = %.6f m/s, S = %.6f m, T = %.6f s; xi held at xi(T) for t > T\n", w.C, w.S, w.T);
        printf("(\n");
    }
    for (long k = 0; k <= n; k++) {
        double t = (double)k * dt;
        if (k == n)
            t = tEnd;
        const double tPrev = (double)(k - 1) * dt;
        if (k > 0 && tPrev < w.T - 1e-12 && t > w.T + 1e-12 && w.T < tEnd)
            print_row(&w, w.T, shift, columns);
        print_row(&w, t, shift, columns);
    }
    if (!columns)
        printf(")\n");
    return 0;
}
