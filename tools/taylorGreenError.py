#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
# taylorGreenError.py CASE TIME [nu]: Taylor-Green errors (Section 4.1 of
# Ng, Sheu & Hwang 2016) of a run whose 0/U is the exact field at the
# centroids (written by setTaylorGreen), so the exact field at time t is
# U0 exp(b t), b = -8 pi^2 nu (U = L = 1). Prints one line:
#   L2rel    ||U - Uex||_2 / ||Uex||_2 over cells (both components)
#   Linf_decay  |max|U| / max|U0| - e^{bt}| / e^{bt}: the decay error of the
#            maximum speed against the maximum the mesh samples at t = 0
#   Linf41   Eq. 41 as printed: |max|U| - e^{bt}| / e^{bt}
#   L2_42    Eq. 42: sqrt(sum (u - u_theo)^2 / N_m), x-velocity
#   amp      signed amplitude error: (sum U.U0 / sum U0.U0) / e^{bt} - 1, the
#            fit of the field onto the initial one (> 0: decays too slowly)
#   pL2rel   ||p - p_ex||_2 / ||p_ex||_2 over cells, each less its mean,
#            p_ex = p0 e^{2bt} (Eq. 40; p0 = 0/p); "-" without a TIME/p
import math, re, sys
case, tname = sys.argv[1], sys.argv[2]
nu = float(sys.argv[3]) if len(sys.argv) > 3 else 0.01
def read(path, kind='vector'):
    """The internalField of an ascii vol<kind>Field: tuples (vector) or floats."""
    t = open(path).read()
    m = re.search(r'internalField\s+nonuniform List<' + kind + r'>\s*\n?(\d+)\s*\(', t)
    if not m:
        raise ValueError(f"{path}: expected 'internalField nonuniform List<{kind}>' (ascii)")
    n, body = int(m.group(1)), t[m.end():]
    if kind == 'scalar':
        return [float(x) for x in body.split(None, n)[:n]]
    return [tuple(map(float, x.group(1).split())) for x in re.finditer(r'\(([^()]*)\)', body)][:n]
try:
    U0, U = read(f'{case}/0/U'), read(f'{case}/{tname}/U')
except (OSError, ValueError) as e:
    sys.exit(str(e))
g = math.exp(-8 * math.pi ** 2 * nu * float(tname))
num = sum((u[0] - g * a[0]) ** 2 + (u[1] - g * a[1]) ** 2 for u, a in zip(U, U0))
den = sum((g * a[0]) ** 2 + (g * a[1]) ** 2 for a in U0)
m0 = max(math.hypot(a[0], a[1]) for a in U0)
m1 = max(math.hypot(u[0], u[1]) for u in U)
l2x = math.sqrt(sum((u[0] - g * a[0]) ** 2 for u, a in zip(U, U0)) / len(U))
amp = sum(u[0] * a[0] + u[1] * a[1] for u, a in zip(U, U0)) / sum(a[0] ** 2 + a[1] ** 2 for a in U0)
perr = "-"
try:
    P0, P = read(f'{case}/0/p', 'scalar'), read(f'{case}/{tname}/p', 'scalar')
    q0, q1 = sum(P0) / len(P0), sum(P) / len(P)
    e = sum((b - q1 - g * g * (a - q0)) ** 2 for a, b in zip(P0, P))
    r = sum((g * g * (a - q0)) ** 2 for a in P0)
    perr = f"{math.sqrt(e / r):.6g}"
except (OSError, ValueError):
    pass
print(f"L2rel {math.sqrt(num/den):.6g} Linf_decay {abs(m1/m0 - g)/g:.6g} "
      f"Linf41 {abs(m1 - g)/g:.6g} L2_42 {l2x:.6g} amp {amp / g - 1:+.6g} pL2rel {perr}")
