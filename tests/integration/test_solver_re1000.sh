#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# test_solver_re1000.sh -- the issue's Re 1000 cavity: OpenFOAM's icoFoam
# `cavity` tutorial with scale 1, 40 x 40 cells, nu 0.001 (Re 1000), its
# fixed deltaT 0.0125 (lid Courant number 0.5), t = 40, umppmFoam at its
# defaults beside icoFoam on the same mesh and step. Asserted, against
# Ghia, Ghia & Shin (1982) on the centrelines (ghiaCompare, 15 interior
# points each):
#   - the RMS error of u on x = 0.5 and of v on y = 0.5, each averaged over
#     the 21 writes t = 30, 30.5 ... 40 (the run is not steady: single
#     writes swing by about +-30 %), at most 0.015 (the issue's bound;
#     measured 0.0106 / 0.0112 with gcc -O2 and in the clang ASan build,
#     one or two threads alike; with the step changed by 1-4 % (0.012 ..
#     0.013) u 0.0102-0.0107, v 0.0126-0.0165. With the 1/d^2 refill
#     weights, the default until 2026-12-04 (refillWeights distance):
#     0.0180 / 0.0088, and the check fails. README, "Refill weights by the
#     increment");
#   - umppmFoam's RMS errors at t = 40 below icoFoam's on the same mesh
#     (measured 0.0110 / 0.0131 against 0.0347 / 0.0338);
#   - ghiaCompare -mean (the error of the time-averaged field, printed:
#     0.0100 / 0.0100) is at most the mean of the writes' errors, over one
#     time equals that time's errors, and equals (to 0.1 %) the errors of
#     the field averaged here by awk over the same writes;
#   - no closed-flow |U| warning: its corner cell's overshoot (1.105 at
#     the first warning of the binary before 2026-12-07, which fails this)
#     is left out of it.
# In the sanitizer pass (UMPPM_TEST_SHORT=1, lib.sh) each case runs to
# t = 0.5 without icoFoam: its log lines are checked, its figures are not.
# Needs UMPPMFOAM and TOOLDIR (ghiaCompare); OpenFOAM's blockMesh, icoFoam.
set -eu -o pipefail
here=$(cd "$(dirname "$0")" && pwd)
top=$(cd "$here/../.." && pwd)
[ -n "${UMPPMFOAM:-}" ] && [ -x "$UMPPMFOAM" ] || { echo "FAIL: UMPPMFOAM not set" >&2; exit 2; }
[ -n "${TOOLDIR:-}" ] && [ -x "$TOOLDIR/ghiaCompare" ] || { echo "FAIL: TOOLDIR not set" >&2; exit 2; }
. "$here/lib.sh"
of_env
ex=/usr/share/doc/openfoam-examples/examples/incompressible/icoFoam/cavity/cavity
[ -d "$ex" ] || { echo "FAIL: $ex missing (package openfoam-examples)"; exit 1; }
work=$(mktemp -d "${TMPDIR:-/tmp}/umppm-re1000.XXXXXX")
fail=0

# re1000_case DIR DELTAT WRITEINTERVAL [NX NY]: icoFoam's cavity at Re 1000
# (nu 0.001) in DIR, to t = 40 at DELTAT, written every WRITEINTERVAL
# steps; with NX NY its blockMesh a unit square of NX x NY cells, meshed
re1000_case() {
    local d=$1 dt=$2 wi=$3
    tutorial_copy "$ex" "$d"
    sed -i 's/^nu .*/nu              0.001;/' "$d/constant/transportProperties"
    sed -i "s/^deltaT .*/deltaT $dt;/; s/^endTime .*/endTime 40;/; s/^writeControl .*/writeControl timeStep;/;
            s/^writeInterval .*/writeInterval $wi;/" "$d/system/controlDict"
    grep -q "^writeInterval $wi;" "$d/system/controlDict" && grep -q '^nu  *0.001;' "$d/constant/transportProperties" ||
        { echo "  FAIL: could not set up the Re 1000 case $d"; exit 1; }
    [ $# -eq 5 ] || return 0
    sed -i "s/^scale .*/scale 1;/; s/(20 20 1)/($4 $5 1)/" "$d/system/blockMeshDict"
    grep -q "($4 $5 1)" "$d/system/blockMeshDict" && grep -q '^scale 1;' "$d/system/blockMeshDict" ||
        { echo "  FAIL: could not set up the $4 x $5 mesh of $d"; exit 1; }
    run_in "$d" blockMesh blockMesh
}
# run_both DIR WHAT: icoFoam on a copy of the case in DIR/ico, umppmFoam in
# DIR (log.umppmFoam); the test stops if umppmFoam fails (WHAT names the
# case). In the short pass (lib.sh) umppmFoam alone, to t = 0.5, checked
# by short_run.
run_both() {
    if short_runs; then
        short_run "$1" 0.5 log.umppmFoam "Re 1000$2" "$UMPPMFOAM"
        return 0
    fi
    mkdir -p "$1/ico"
    cp -r "$1/0" "$1/constant" "$1/system" "$1/ico/"
    run_in "$1/ico" icoFoam icoFoam
    if ! "$UMPPMFOAM" -case "$1" > "$1/log.umppmFoam" 2>&1; then
        echo "  FAIL umppmFoam failed$2: $(grep -m1 'FATAL' "$1/log.umppmFoam" | cut -c1-200)"
        exit 1
    fi
}

c=$work/cavity
# writes every 40 steps = 0.5 s
re1000_case "$c" 0.0125 40 40 40
run_both "$c" ""
# u_rms v_rms of CASE at TIME
ghia() { "$TOOLDIR/ghiaCompare" -Re 1000 "$1" "$2" | tail -1 | awk '{ print $3, $5 }'; }
if ! short_runs; then
    times=$(ls "$c" | grep -E '^[0-9.]+$' | awk '$1 >= 30' | sort -g)
    n=$(echo "$times" | wc -w)
    [ "$n" -eq 21 ] || { echo "  FAIL expected 21 writes t = 30 .. 40, found $n"; fail=1; }
    means=$(for t in $times; do ghia "$c" "$t"; done | awk '{ u += $1; v += $2; k++ } END { printf "%.5f %.5f\n", u / k, v / k }')
    read -r mu mv <<< "$means"
    read -r u40 v40 <<< "$(ghia "$c" 40)"
    read -r iu iv <<< "$(ghia "$c/ico" 40)"
    echo "Re 1000, 40^2, deltaT 0.0125: umppmFoam RMS vs Ghia, mean over t = 30..40: u $mu, v $mv;" \
        "t = 40: $u40 / $v40 (icoFoam $iu / $iv)"
    # ghiaCompare -mean: the error of the time-averaged field. The RMS of the
    # mean profile cannot exceed the mean of the per-write RMS (Minkowski), and
    # the mean of one time is that time's own error.
    args=()
    for t in $times; do args+=("$c" "$t"); done
    read -r au av <<< "$("$TOOLDIR/ghiaCompare" -Re 1000 -mean "${args[@]}" | tail -1 | awk '$1 == "mean" { print $4, $6 }')"
    read -r su sv <<< "$("$TOOLDIR/ghiaCompare" -Re 1000 -mean "$c" 40 | tail -1 | awk '$1 == "mean" { print $4, $6 }')"
    echo "time-averaged field over t = 30..40: u $au, v $av"
    check_below "ghiaCompare -mean u / the mean of the writes' u" "$(awk -v a="$au" -v b="$mu" 'BEGIN { print a / b }')" 1.000001
    check_below "ghiaCompare -mean v / the mean of the writes' v" "$(awk -v a="$av" -v b="$mv" 'BEGIN { print a / b }')" 1.000001
    if [ "$su $sv" = "$u40 $v40" ]; then
        echo "  ok   ghiaCompare -mean of t = 40 alone = t = 40's errors ($su $sv)"
    else
        echo "  FAIL ghiaCompare -mean of t = 40 alone: $su $sv, not $u40 $v40"
        fail=1
    fi
    # and against a field averaged here, independently of ghiaCompare: the
    # cell values of U averaged over the same writes (awk) into a time of its
    # own; sampling is linear in U, so its errors are -mean's to round-off (a
    # -mean that averaged the writes' RMS errors instead would be 6-11 % off)
    avg=1000
    mkdir -p "$c/$avg"
    last=$c/$(echo "$times" | tail -1)/U
    cells=$(field_values "$last" | wc -l)
    {
        sed -n '1,/^($/p' "$last" | sed "s/^\( *location *\).*/\1\"$avg\";/"
        for t in $times; do field_values "$c/$t/U"; done |
            awk -v n="$n" -v m="$cells" '{ k = (NR - 1) % m; u[k] += $1; v[k] += $2; w[k] += $3 }
                END { for (k = 0; k < m; k++) printf "(%.10g %.10g %.10g)\n", u[k] / n, v[k] / n, w[k] / n }'
        sed -n '/^)$/,$p' "$last"
    } > "$c/$avg/U"
    read -r fu fv <<< "$(ghia "$c" "$avg")"
    echo "the field averaged by awk: u $fu, v $fv"
    check_below "|ghiaCompare -mean u / the awk-averaged field's u - 1|" \
        "$(awk -v a="$au" -v b="$fu" 'BEGIN { d = a / b - 1; print d < 0 ? -d : d }')" 0.001
    check_below "|ghiaCompare -mean v / the awk-averaged field's v - 1|" \
        "$(awk -v a="$av" -v b="$fv" 'BEGIN { d = a / b - 1; print d < 0 ? -d : d }')" 0.001
    # a converged run whose one cell at the lid's downstream corner overshoots
    # (1.28 x the lid speed at its largest) is not warned of: the closed-flow warning leaves
    # out the cells at corners of walls of different velocity (it fired on
    # this case until 2026-12-07)
    if grep -q 'Warning: |U|' "$c/log.umppmFoam"; then
        echo "  FAIL the converged cavity warned: $(grep -m 1 'Warning: |U|' "$c/log.umppmFoam" | cut -c1-160)"
        fail=1
    else
        echo "  ok   no |U| warning (the largest written |U|: $(for t in $times; do field_values "$c/$t/U"; done |
            awk '{ s = sqrt($1 * $1 + $2 * $2); if (s > m) m = s } END { printf "%.4g", m }'))"
    fi
    check_below "u RMS vs Ghia, mean over t = 30..40" "$mu" 0.015
    check_below "v RMS vs Ghia, mean over t = 30..40" "$mv" 0.015
    check_below "u RMS at t = 40 / icoFoam's" "$(awk -v a="$u40" -v b="$iu" 'BEGIN { print a / b }')" 1
    check_below "v RMS at t = 40 / icoFoam's" "$(awk -v a="$v40" -v b="$iv" 'BEGIN { print a / b }')" 1
fi

# The same cavity on gmsh triangles (tools/cavityTriangles.geo, size
# 1.65 / 40: 1 476 cells, the mesh of tools/cavityValidate.sh -mesh tri
# -n 40) at icoFoam's step, 0.0125 (Courant number up to 0.5), t = 40, written every 2 s: umppmFoam's RMS
# errors, each the mean over the writes t = 30 ... 40, at most icoFoam's
# on the same mesh and step (the issue's "triangles at Re 1000: no worse
# than icoFoam on the same mesh"). pressureTheta auto is 0.5 here (a flow
# driven by its walls alone on triangles), and the log must say so.
# faceSupport auto is 3 at the triangles' faces, and the log must say so.
# Measured (gcc -O2, one thread): 0.0279 / 0.0244 against icoFoam's
# 0.0652 / 0.0550 (at t = 40 0.0240 / 0.0229 against 0.0602 / 0.0513);
# with faceSupport 2, the default before 2026-12-08, 0.0610 / 0.0514.
# With pressureTheta 0, the default before 2026-12-07 (README, "Triangles
# at icoFoam's step"): 0.0592 / 0.0619, v 1.13 x icoFoam's, and the check
# fails.
tc=$work/triangles
re1000_case "$tc" 0.0125 160
cp "$top/tools/cavityTriangles.geo" "$tc/cavity.geo"
mesh_from_geo "$tc" "$tc/cavity.geo" 0.04125
ncells=$(sed -n 's/.*nCells: *\([0-9]*\).*/\1/p' "$tc/constant/polyMesh/owner" | head -n 1)
run_both "$tc" " on triangles"
if grep -q '^UMPPM: .*pressureTheta 0.5 (auto)' "$tc/log.umppmFoam"; then
    echo "  ok   pressureTheta auto is 0.5 on the closed triangle mesh"
else
    echo "  FAIL the log does not say pressureTheta 0.5 (auto): $(grep -m1 '^UMPPM:' "$tc/log.umppmFoam")"
    fail=1
fi
# mean_errors CASE: the mean over the writes t = 30 ... 40 of the u and v RMS errors
mean_errors() {
    local t
    for t in $(ls "$1" | grep -E '^[0-9.]+$' | awk '$1 >= 30' | sort -g); do ghia "$1" "$t"; done |
        awk '{ u += $1; v += $2; k++ } END { if (k != 6) print "nan nan"; else printf "%.5f %.5f\n", u / k, v / k }'
}
# no_worse CASE LABEL [BOUND]: umppmFoam's mean errors (mean_errors) in
# CASE at most BOUND (1) x icoFoam's in CASE/ico, u and v
no_worse() {
    local u v iu iv b=${3:-1}
    read -r u v <<< "$(mean_errors "$1")"
    read -r iu iv <<< "$(mean_errors "$1/ico")"
    echo "Re 1000, $2: RMS vs Ghia, mean over t = 30..40 (6 writes):" \
        "umppmFoam u $u, v $v; icoFoam $iu / $iv; t = 40: umppmFoam $(ghia "$1" 40), icoFoam $(ghia "$1/ico" 40)"
    check_below "$2: u RMS / icoFoam's (mean over t = 30..40)" "$(awk -v a="$u" -v b="$iu" 'BEGIN { print a / b }')" "$b"
    check_below "$2: v RMS / icoFoam's (mean over t = 30..40)" "$(awk -v a="$v" -v b="$iv" 'BEGIN { print a / b }')" "$b"
}
if grep -q '^A flow driven by its walls alone on a mesh with triangles: faceSupport auto (3 cell extents at the faces beside a triangle, 2 elsewhere' "$tc/log.umppmFoam"; then
    echo "  ok   faceSupport auto is 3 at the triangles' faces, and the log says so"
else
    echo "  FAIL the log does not say faceSupport auto (3 ...): $(grep -m1 'faceSupport' "$tc/log.umppmFoam")"
    fail=1
fi
if ! short_runs; then
    check_range "triangle cells" "$ncells" 1400 1550
    no_worse "$tc" "$ncells triangles, deltaT 0.0125"
fi

# A coarser triangle mesh the defaults were not tuned on (size 0.05: 944
# cells, about 20 across), at icoFoam's step 0.0125, t = 40. With the face
# fits of u* at 2 cell extents (faceSupport 2, the default before
# 2026-12-08; README, "Face fits on triangles") the floor's and the right
# wall's layers were far too slow and the corner eddies too large: 0.1147 /
# 0.0925 from Ghia against icoFoam's 0.0706 / 0.0605 (1.62 / 1.53 x), and
# this check fails. Measured with faceSupport auto (3 at the triangles'
# faces; gcc -O2, one thread): 0.0728 / 0.0664 (1.03 / 1.10 x). The bound
# here is 1.2 x icoFoam's, not the issue's "no worse" (1 x), which this
# mesh still misses in v.
cc=$work/coarseTriangles
re1000_case "$cc" 0.0125 160
cp "$top/tools/cavityTriangles.geo" "$cc/cavity.geo"
mesh_from_geo "$cc" "$cc/cavity.geo" 0.05
ncc=$(sed -n 's/.*nCells: *\([0-9]*\).*/\1/p' "$cc/constant/polyMesh/owner" | head -n 1)
if ! short_runs; then
    run_both "$cc" " on coarse triangles"
    check_range "coarse triangle cells" "$ncc" 900 990
    no_worse "$cc" "$ncc triangles, deltaT 0.0125" 1.2
fi

# The same cavity on 30 x 45 cells (1.5:1, blockMesh), deltaT 0.005 (the
# Courant number up to 0.2), t = 40, written every 2 s: variant auto is
# the adaptive UMPPM on quadrilaterals that are not square in a flow
# driven by its walls alone, and the log must say so; its RMS errors, each
# the mean over the writes t = 30 ... 40, at most icoFoam's on the same
# mesh and step. Measured (gcc -O2, one thread) at t = 40: 0.0222 /
# 0.0207 against icoFoam's 0.0395 / 0.0426. With UMPPM*, the default
# before 2026-12-07 (README, "Non-square cells at Re 1000"): 0.0836 /
# 0.0800 at t = 40, twice icoFoam's, and the check fails.
qc=$work/quads
re1000_case "$qc" 0.005 400 30 45
run_both "$qc" " on 30 x 45 cells"
if grep -q '^UMPPM: variant UMPPM (auto),' "$qc/log.umppmFoam" &&
    grep -q '^A flow driven by its walls alone on quadrilaterals that are not square (1350 of 1350 cells stretched beyond 1.15:1): variant auto (UMPPM' "$qc/log.umppmFoam"; then
    echo "  ok   variant auto is UMPPM on the 1.5:1 cells, and the log says why"
else
    echo "  FAIL the log does not say variant UMPPM (auto): $(grep -m1 '^UMPPM:' "$qc/log.umppmFoam")"
    fail=1
fi
if ! short_runs; then
    no_worse "$qc" "30 x 45 cells, deltaT 0.005"
    if grep -q 'Warning: |U|' "$qc/log.umppmFoam"; then
        echo "  FAIL the 30 x 45 cavity warned: $(grep -m 1 'Warning: |U|' "$qc/log.umppmFoam" | cut -c1-160)"
        fail=1
    else
        echo "  ok   no |U| warning on the 30 x 45 cavity"
    fi
fi
[ "$fail" -eq 0 ] && rm -rf "$work"
exit "$fail"
