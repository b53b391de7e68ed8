#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# test_phi_log.sh -- the written phi is OpenFOAM's and correct, and the log
# parses like icoFoam's.
#
# On the cavity (ascii and binary) and on the periodic square (cyclic
# patches): OpenFOAM's `postProcess -func CourantNo` reads umppmFoam's phi
# and its Co maximum equals the Courant number umppmFoam prints at the start
# of the next step (the same fluxes); per cell the fluxes of phi sum to zero
# (continuity, walls at zero flux, both sides of cyclic pairs); every step
# has a pressure line in OpenFOAM's solver-line form with a final residual
# at round-off, and continuity lines whose values foamLog's default
# selectors (`sum local =`, `global =`, `cumulative =`) all find. And
# -noFunctionObjects reads controlDict's functions but does not run them.
set -eu -o pipefail

here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"
[ -n "${UMPPMFOAM:-}" ] && [ -x "$UMPPMFOAM" ] || {
    echo "test_phi_log.sh: FAIL: UMPPMFOAM is not set to an executable" >&2
    exit 2
}
of_env || exit 2
work=$(mktemp -d "${TMPDIR:-/tmp}/umppm-phi.XXXXXX")
nfail=0

# run_case LABEL TEMPLATE FORMAT: write at step 5, stop after step 6
run_case() {
    local label=$1 tpl=$2 fmt=$3 c=$work/$1
    make_case "$tpl" "$c" >/dev/null || { echo "FAIL  $label: cannot build $tpl"; nfail=$((nfail + 1)); return; }
    local dt
    dt=$(sed -n 's/^deltaT[[:space:]]*\([^;]*\);.*/\1/p' "$c/system/controlDict")
    local tw te
    tw=$(awk -v d="$dt" 'BEGIN { printf "%.6g", 5 * d }')
    te=$(awk -v d="$dt" 'BEGIN { printf "%.6g", 6 * d }')
    sed -i -e "s/^endTime .*/endTime $te;/" -e "s/^writeControl .*/writeControl timeStep;/" \
        -e "s/^writeInterval .*/writeInterval 5;/" -e "s/^writeFormat .*/writeFormat $fmt;/" \
        -e "s/^adjustTimeStep .*/adjustTimeStep no;/" "$c/system/controlDict"
    if ! (cd "$c" && "$UMPPMFOAM") >"$c/log.umppmFoam" 2>&1; then
        echo "FAIL  $label: umppmFoam failed (log: $c/log.umppmFoam)"; nfail=$((nfail + 1)); return
    fi
    if ! run_in "$c" postProcess postProcess -func CourantNo -time "$tw"; then
        echo "FAIL  $label: postProcess -func CourantNo on time $tw"; nfail=$((nfail + 1)); return
    fi
    # OpenFOAM wrote phi's neighbour Co in the case's format: back to ascii
    # (foamFormatConvert converts to the controlDict's writeFormat) to read
    if [ "$fmt" != ascii ]; then
        sed -i "s/^writeFormat .*/writeFormat ascii;/" "$c/system/controlDict"
        run_in "$c" foamFormatConvert foamFormatConvert -time "$tw" ||
            { echo "FAIL  $label: foamFormatConvert"; nfail=$((nfail + 1)); return; }
    fi
    if python3 - "$c" "$tw" "$te" "$label" <<'PY'
import re, sys
case, tw, te, label = sys.argv[1:]
def body(path):
    return open(path, errors="replace").read()
def lst(text, key):
    m = re.search(key + r"\s+nonuniform List<scalar>\s*\n?(\d+)\s*\(\s*(.*?)\)\s*;", text, re.S)
    if m:
        return [float(x) for x in m.group(2).split()]
    m = re.search(key + r"\s+uniform\s+([^;]+);", text)
    return None if not m else float(m.group(1))
def labels(path):
    t = body(path)
    m = re.search(r"\n(\d+)\s*\(\s*(.*?)\)", t[t.index("}"):], re.S)
    return [int(x) for x in m.group(2).split()]
bad = []
own = labels(case + "/constant/polyMesh/owner")
nb = labels(case + "/constant/polyMesh/neighbour")
phit = body(case + "/" + tw + "/phi")
if "surfaceScalarField" not in phit or "oriented        oriented;" not in phit:
    bad.append("phi header/oriented line")
phi = lst(phit, "internalField")
if not isinstance(phi, list) or len(phi) != len(nb):
    bad.append("phi internalField has %s values, %d internal faces" % (len(phi) if isinstance(phi, list) else phi, len(nb)))
else:
    ncell = max(own) + 1
    s = [0.0] * ncell
    for f, v in enumerate(phi):
        s[own[f]] += v
        s[nb[f]] -= v
    # boundary patches, in the boundary file's order
    bt = body(case + "/constant/polyMesh/boundary")
    patches = re.findall(r"\n\s*(\w+)\s*\n\s*\{(.*?)\}", bt[bt.index("(", bt.index("}")):], re.S)
    bf = phit[phit.index("boundaryField"):]
    for name, d in patches:
        n = int(re.search(r"nFaces\s+(\d+);", d).group(1))
        st = int(re.search(r"startFace\s+(\d+);", d).group(1))
        if re.search(r"type\s+empty;", d):
            continue
        m = re.search(r"\n\s*" + name + r"\s*\{(.*?)\}", bf, re.S)
        v = lst(m.group(1), "value") if m else None
        if v is None:
            bad.append("patch %s: no value in phi" % name)
            continue
        vals = v if isinstance(v, list) else [v] * n
        for k in range(n):
            s[own[st + k]] += vals[k]
    scale = max(abs(x) for x in phi) or 1.0
    worst = max(abs(x) for x in s) / scale
    if not worst < 2e-5:
        bad.append("per-cell sum of phi %.3g of max |phi| (continuity)" % worst)
co = lst(body(case + "/" + tw + "/Co"), "internalField")
log = body(case + "/log.umppmFoam")
m = re.search(r"Courant Number mean: (\S+) max: (\S+)\nTime = " + re.escape(te) + r"\n", log)
if not isinstance(co, list) or not m:
    bad.append("no Co field or no Courant line before Time = " + te)
else:
    a, b = max(co), float(m.group(2))
    if not abs(a - b) <= 1e-4 * max(b, 1e-30):
        bad.append("CourantNo max %.6g vs log %.6g" % (a, b))
steps = len(re.findall(r"^Time = ", log, re.M))
pl = re.findall(r"^([A-Za-z]+):  Solving for (p|p_rgh), Initial residual = (\S+), Final residual = (\S+), No Iterations 1$", log, re.M)
if len(pl) != steps or any(not float(r[3].rstrip(",")) < 1e-10 for r in pl):
    bad.append("%d pressure solver lines for %d steps (or a final residual >= 1e-10)" % (len(pl), steps))
for key in ("sum local =", "global =", "cumulative ="):
    vals = re.findall(r"^time step continuity errors :.*" + key + r" (\S+)", log, re.M)
    try:
        [float(v.rstrip(",")) for v in vals]
    except ValueError:
        vals = []
    if len(vals) != steps:
        bad.append("foamLog selector '%s' found %d values for %d steps" % (key, len(vals), steps))
if bad:
    print("FAIL  %s: %s" % (label, "; ".join(bad)))
    sys.exit(1)
print("ok    %s: CourantNo max %.6g = log %.6g, phi continuity %.2g, %d p lines" % (label, max(co), float(m.group(2)), worst, len(pl)))
PY
    then :; else nfail=$((nfail + 1)); fi
}

run_case cavity-ascii cavity ascii
run_case cavity-binary cavity binary
run_case periodic periodicSquare ascii

# -noFunctionObjects: a function object of controlDict is read but not run
c=$work/nofo
if make_case cavity "$c" >/dev/null; then
    sed -i -e "s/^endTime .*/endTime 0.01;/" "$c/system/controlDict"
    echo 'functions { pLid { type surfaceFieldValue; libs ("libfieldFunctionObjects.so"); regionType patch;
        name movingWall; operation areaAverage; fields (p); writeFields false; writeControl timeStep; } }' \
        >> "$c/system/controlDict"
    rc=0
    (cd "$c" && "$UMPPMFOAM" -noFunctionObjects) >"$c/log.nofo" 2>&1 || rc=$?
    if [ "$rc" -ne 0 ] || [ -e "$c/postProcessing" ] || ! grep -q "not run (-noFunctionObjects)" "$c/log.nofo"; then
        echo "FAIL  -noFunctionObjects: exit $rc, postProcessing $( [ -e "$c/postProcessing" ] && echo written || echo absent)"
        nfail=$((nfail + 1))
    elif ! (cd "$c" && "$UMPPMFOAM") >"$c/log.fo" 2>&1 || [ ! -d "$c/postProcessing/pLid" ]; then
        echo "FAIL  function object without -noFunctionObjects: no postProcessing/pLid"
        nfail=$((nfail + 1))
    else
        echo "ok    -noFunctionObjects: not run; without it postProcessing/pLid is written"
    fi
else
    echo "FAIL  -noFunctionObjects: cannot build the cavity"; nfail=$((nfail + 1))
fi

if [ "$nfail" -gt 0 ]; then
    echo "test_phi_log.sh: $nfail FAILED (cases in $work)"
    exit 1
fi
rm -rf "$work"
echo "test_phi_log.sh: PASS"
