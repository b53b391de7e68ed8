#!/usr/bin/env python3
# solitaryAnalyse.py <case> <l0> <d> <H> -- the solitary wave in meshlessFoam's
# written clouds (<time>/lagrangian/meshlessCloud/positions), standard
# library only: the surface elevation eta = (highest particle) + l0/2 - d
# in a window of width l0 at the gauges x = 0.5, 0.75, ..., 2.0 m and at
# the wall (the last 1.5 l0 before x = 2.25 m); per gauge the crest (the
# largest eta before the run-up maximum) and its time; the celerity, the
# least-squares slope of x against the crest time over 0.75..1.5 m (as
# reference/README.md does for interFoam); the run-up R, the largest eta at
# the wall, against R/d = 2 (H/d) + (H/d)^2 / 2. Writes <case>/eta.dat
# (t and eta per gauge) and prints a table and one line
#   celerity C_meas C ratio runup R R_formula ratio celerity_xcorr C_x ratio
# (celerity_xcorr: 0.75 m over the delay that best aligns the signal at
# 1.5 m with that at 0.75 m, cross-correlation of eta > 0 up to the run-up)
import os
import re
import sys

case, l0, d, H = sys.argv[1], float(sys.argv[2]), float(sys.argv[3]), float(sys.argv[4])
g, Lx = 9.81, 2.25
gx = [0.5, 0.75, 1.0, 1.25, 1.5, 1.75, 2.0]
win = [(x - l0 / 2, x + l0 / 2) for x in gx] + [(Lx - 1.5 * l0, Lx)]


def positions(path):
    s = open(path).read()
    m = re.search(r"\n(\d+)\s*\n\(", s)
    return [(float(a), float(b)) for a, b, _ in
            re.findall(r"\(([-\d.eE+]+) ([-\d.eE+]+) ([-\d.eE+]+)\)", s[m.end():])]


times = sorted((t for t in os.listdir(case) if re.match(r"^[0-9][0-9.eE+-]*$", t) and
                os.path.isdir(os.path.join(case, t, "lagrangian"))), key=float)
rows = []
for t in times:
    P = positions(os.path.join(case, t, "lagrangian/meshlessCloud/positions"))
    eta = []
    for a, b in win:
        ys = [y for x, y in P if a <= x <= b and y < 3 * d]  # spray above 3 d is not the surface
        eta.append(max(ys) + l0 / 2 - d if ys else float("nan"))
    rows.append((float(t), eta))
with open(os.path.join(case, "eta.dat"), "w") as f:
    f.write("# t eta at x = %s and the wall [m] (meshlessFoam, l0 = %g m)\n" % (" ".join(map(str, gx)), l0))
    for t, e in rows:
        f.write("%g %s\n" % (t, " ".join("%.5f" % v for v in e)))
C = (g * (H + d)) ** 0.5
Rf = d * (2 * H / d + 0.5 * (H / d) ** 2)
if not rows:
    print("celerity nan %.4f nan runup nan %.5f nan" % (C, Rf))
    sys.exit(0)
# run-up: the largest eta at the wall and its time
iw = len(gx)
tR, R = max(((t, e[iw]) for t, e in rows if e[iw] == e[iw]), key=lambda r: r[1], default=(float("nan"), float("nan")))
crest = []
print("gauge x [m]  crest eta [m]  eta/H  crest time [s]")
for k, x in enumerate(gx):
    cand = [(e[k], t) for t, e in rows if t <= tR and e[k] == e[k]]
    if not cand:
        continue
    c, tc = max(cand)
    crest.append((x, c, tc))
    print("%-11g  %.5f        %.3f  %.3f" % (x, c, c / H, tc))
print("wall         %.5f        %.3f  %.3f" % (R, R / H, tR))
fit = [(x, tc) for x, c, tc in crest if 0.74 <= x <= 1.51 and c > 0.5 * H]
if len(fit) >= 3:
    n = len(fit)
    mt = sum(t for _, t in fit) / n
    mx = sum(x for x, _ in fit) / n
    cm = sum((t - mt) * (x - mx) for x, t in fit) / sum((t - mt) ** 2 for _, t in fit)
else:
    cm = float("nan")
# the delay that best aligns the whole signal at 1.5 m with that at
# 0.75 m (cross-correlation up to the run-up, eta interpolated linearly,
# delays in steps of 1 ms): averages the particles' surface noise over the
# wave instead of reading one sample, the crest's
def at(ts, es, t):
    if t <= ts[0] or t >= ts[-1]:
        return 0.0
    lo, hi = 0, len(ts) - 1
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if ts[mid] <= t:
            lo = mid
        else:
            hi = mid
    return es[lo] + (es[hi] - es[lo]) * (t - ts[lo]) / (ts[hi] - ts[lo])


def xcorr_delay(k1, k2):
    pts = [(t, e[k1], e[k2]) for t, e in rows if t <= tR and e[k1] == e[k1] and e[k2] == e[k2]]
    if len(pts) < 10:
        return float("nan")
    ts = [p[0] for p in pts]
    e2 = [max(p[2], 0.0) for p in pts]
    best, bt = -1.0, float("nan")
    for m in range(1, 2000):
        tau = 0.001 * m
        v = sum(max(p[1], 0.0) * at(ts, e2, p[0] + tau) for p in pts)
        if v > best:
            best, bt = v, tau
    return bt


k1, k2 = gx.index(0.75), gx.index(1.5)
tau = xcorr_delay(k1, k2)
cx = (gx[k2] - gx[k1]) / tau if tau == tau else float("nan")
print("celerity %.4f %.4f %.4f runup %.5f %.5f %.4f celerity_xcorr %.4f %.4f" % (cm, C, cm / C, R, Rf, R / Rf, cx,
                                                                                  cx / C))
