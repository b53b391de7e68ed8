#!/usr/bin/env python3
# setStandingWave.py <case> [a] -- the first standing wave of the tank at the
# instant its surface is flat: 0/U gets, in every cell below the still water
# level, the velocity of linear (Airy) theory,
#   u = -a w cosh(k (y - y0 + h)) / sinh(k h) sin(k x),
#   v =  a w sinh(k (y - y0 + h)) / sinh(k h) cos(k x),
# with k = pi / L, w^2 = g k tanh(k h) (y0 the still level, h the depth, x
# from the left wall), so that the surface then moves as a cos(k x) sin(w t)
# (amplitude a, default 0.003 m). Reads the cell centres 0/C (postProcess
# -func writeCellCentres), writes 0/U with the same boundaryField. Standard
# library only.
import math
import re
import sys

case = sys.argv[1]
a = float(sys.argv[2]) if len(sys.argv) > 2 else 0.003
L, h, g, x0, ybot = 0.6, 0.12, 9.81, 0.0, 0.0
k = math.pi / L
w = math.sqrt(g * k * math.tanh(k * h))


def cells(path):
    s = open(path).read()
    i = s.index("internalField")
    m = re.search(r"nonuniform\s+List<vector>\s*(\d+)\s*\(", s[i:])
    n = int(m.group(1))
    body = s[i + m.end():]
    pts = re.findall(r"\(\s*([-\d.eE+]+)\s+([-\d.eE+]+)\s+([-\d.eE+]+)\s*\)", body)[:n]
    return [(float(p[0]), float(p[1])) for p in pts]


C = cells(case + "/0/C")
U = open(case + "/0/U").read()
vals = []
for x, y in C:
    z = y - ybot  # height above the floor
    if z > h:
        vals.append("(0 0 0)")
        continue
    u = -a * w * math.cosh(k * z) / math.sinh(k * h) * math.sin(k * (x - x0))
    v = a * w * math.sinh(k * z) / math.sinh(k * h) * math.cos(k * (x - x0))
    vals.append("(%.9g %.9g 0)" % (u, v))
field = "internalField   nonuniform List<vector>\n%d\n(\n%s\n)\n;\n" % (len(vals), "\n".join(vals))
U = re.sub(r"internalField\s+uniform\s*\([^)]*\)\s*;", lambda m_: field, U, count=1)
open(case + "/0/U", "w").write(U)
print("standing wave: a %g m, k %.6g 1/m, omega %.6g rad/s, period %.6g s (linear theory, h %g m, L %g m)"
      % (a, k, w, 2 * math.pi / w, h, L))
