#!/usr/bin/env python3
# cloudProbe.py -- time series from meshlessFoam's written particle clouds
# (<time>/lagrangian/meshlessCloud: positions, p), standard library only.
#   cloudProbe.py eta <case> <x0> <x1>
#       the highest particle with x0 <= x <= x1 at each written time: the
#       free-surface elevation there
# x0, x1, xwall and y are in the container's frame: a swaying container's
# cloud is written where it is (moved with <time>/polyMesh/points), and
# moved back here by that mesh's displacement (its first point's against
# constant/polyMesh/points)
#   cloudProbe.py p <case> <xwall> <y> <l0>
#       the mean pressure of the particles within l0 of the wall x = xwall
#       and within l0 of height y: a pressure gauge on the wall
#   cloudProbe.py period <file> <level>
#       the period from the crossings of column 2 through level (linear
#       interpolation; 2 (t_last - t_first) / (crossings - 1))
import os
import re
import sys


def numbers(path):
    s = open(path).read()
    m = re.search(r"\n(\d+)\s*\n\(", s)
    return s[m.end():]


def vectors(path):
    return [(float(a), float(b)) for a, b, _ in
            re.findall(r"\(([-\d.eE+]+) ([-\d.eE+]+) ([-\d.eE+]+)\)", numbers(path))]


def scalars(path):
    return [float(x) for x in numbers(path).split(")")[0].split()]


def shift(case, d):
    """The container's displacement at time d (0, 0 for a fixed mesh)."""
    moved = os.path.join(case, d, "polyMesh/points")
    if not os.path.exists(moved):
        return 0.0, 0.0
    a, b = vectors(os.path.join(case, "constant/polyMesh/points"))[0], vectors(moved)[0]
    return b[0] - a[0], b[1] - a[1]


def times(case):
    out = []
    for d in os.listdir(case):
        if re.match(r"^[0-9][0-9.eE+-]*$", d) and os.path.isdir(os.path.join(case, d, "lagrangian")):
            out.append(d)
    return sorted(out, key=float)


mode = sys.argv[1]
if mode == "eta":
    case, x0, x1 = sys.argv[2], float(sys.argv[3]), float(sys.argv[4])
    for d in times(case):
        sx, sy = shift(case, d)
        P = [(x - sx, y - sy) for x, y in vectors(os.path.join(case, d, "lagrangian/meshlessCloud/positions"))]
        ys = [y for x, y in P if x0 <= x <= x1]
        if ys:
            print(d, max(ys))
elif mode == "p":
    case, xw, yg, l0 = sys.argv[2], float(sys.argv[3]), float(sys.argv[4]), float(sys.argv[5])
    for d in times(case):
        c = os.path.join(case, d, "lagrangian/meshlessCloud")
        sx, sy = shift(case, d)
        P, p = [(x - sx, y - sy) for x, y in vectors(c + "/positions")], scalars(c + "/p")
        sel = [q for (x, y), q in zip(P, p) if abs(x - xw) <= l0 and abs(y - yg) <= l0]
        print(d, sum(sel) / len(sel) if sel else 0.0)
elif mode == "period":
    rows = [tuple(map(float, l.split()[:2])) for l in open(sys.argv[2]) if l.strip() and l[0] != "#"]
    lev = float(sys.argv[3])
    z = []
    for (t0, h0), (t1, h1) in zip(rows, rows[1:]):
        if (h0 - lev) * (h1 - lev) < 0:
            z.append(t0 + (t1 - t0) * (h0 - lev) / (h0 - h1))
    if len(z) < 3:
        print("nan 0")
    else:
        print("%.5f %d" % (2 * (z[-1] - z[0]) / (len(z) - 1), len(z)))
else:
    sys.exit("usage: cloudProbe.py eta|p|period ...")
