#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# test_solver_taylorGreen.sh -- the UMPPM solver on the Taylor-Green vortex
# (Section 4.1 of Ng, Sheu & Hwang 2016, Re = 100) on a coarse periodic
# crossed-triangle mesh (400 cells), t = 0.2, dt = 0.005; then a restart from
# t = 0.1. Unless said otherwise the runs use the paper's CPM and Eq. 10
# (laplacian CPM; pressureTheta 0); on this mesh, without walls, the
# defaults are CPM4 and pressureTheta 0.5 (laplacian auto, pressureTheta
# auto). The face fits of u* take 3 cell extents on these triangles
# (faceSupport auto, since 2026-12-08; README, "Face fits on triangles");
# the figures before that change are in brackets where they moved.
# Asserts, against the exact solution U0 exp(-8 pi^2 nu t):
#   - L2 relative velocity error < 0.05 (measured 0.018 [0.018]; 0.032 with
#     mlsSupport 0, 0.051 with the paper's refill, refill centroid),
#   - decay error of the maximum speed (Eq. 41, relative to the initial
#     sampled maximum) < 0.03 (measured 0.0027 [0.0077]; 0.017 with mlsSupport 0,
#     0.033 with refill centroid);
#     no decay at all would be 0.15,
#   - per-cell continuity error after correction < 1e-12 every step,
#   - a restart from the 0.1 directory (particles read from the cloud)
#     reproduces the straight run at 0.2 to 1e-10 relative;
#   - the paper's step, CFL 0.25 (dt = 0.25 l_avg / U, l_avg = 1/40), on
#     N_m = 1600 to t = 5: Eq. 41 < 0.02, the paper's figure (measured
#     0.0085 [0.0128]), and L2 relative error < 0.035 (measured 0.0217
#     [0.0265]: with the
#     fixed MLS support of 2 cell extents, the default, the amplitude is
#     2.6 % too high at t = 5 on this mesh; README, "MLS support");
#   - the same with Eq. 35's own scales (mlsSupport 0): L2 < 0.006
#     (measured 0.00596, the same in the clang ASan build; 0.0043 with the
#     1/d^2 refill weights, refillWeights distance, the default until
#     2026-12-04; 0.0069 with the increment weights' noise factor 0.1
#     instead of 0.15). With the paper's refill (u_P, refill centroid)
#     this was 0.0165 and the check fails (README, "Refill that keeps
#     carried values");
#   - pressureTheta 0.5 on N_m = 1600: the L2 errors at U = 1 and at U =
#     0.01 (Stokes) differ by < 0.01 (measured 0.0017 [0.0032]; 0.039 with
#     pressureTheta 0, the paper's, whose impulse at r* damps turning paths by
#     O(dt); README, "Pressure along the path");
#   - the defaults (laplacian CPM4 with pressureTheta 0.5, which the log
#     names as auto) on N_m = 1600: Stokes (U =
#     0.01) L2 < 0.02 (measured 0.0146 [0.0142]; CPM 0.066: the quadratic fit's
#     O(h^2) under-dissipation), at U = 1 L2 < 0.025 and Eq. 41 < 0.02
#     (measured 0.0117 and 0.00082 [0.0168 and 0.0031]),
#     and the pressure written < 0.08 (measured 0.025 [0.065]; 0.110 while the
#     interpolation error left out the kick of pressureTheta, whose two
#     gradients' difference stayed in p, docs/METHOD.md section 8, "The
#     pressure written");
#   - the pressure written (Eq. 40, each less its mean) at t = 5: relative
#     L2 error < 0.06 on N_m = 1600 (measured 0.0327 [0.0354]; the PPE's own
#     solution, written until 2026-12-04, 0.111: it holds the potential of
#     the interpolation error, docs/METHOD.md section 8, "The pressure
#     written");
#   - N_m = 6400 at the same CFL, the defaults: L2 < 0.007 (measured
#     0.0052 [0.00573]), Eq. 41 < 0.02 (0.0020 [0.0023]), pressure < 0.025
#     (0.011 [0.019]), and the observed L2 order from the defaults' N_m =
#     1600 >= 1 (1.17 [1.55]: the 1 600 figure fell more; with
#     the paper's CPM and Eq. 10 the error fell 0.0265 -> 0.00099 by a
#     cancellation of two errors of opposite sign, then rose to 0.0039 on
#     25 600: README, "Pressure along the path");
#   - variant UMPPM, refill carried, refillParticles 1, mlsSupport 0: L2
#     relative error < 0.02 (measured 0.0114). UMPPM's deletion can empty
#     a cell (its only particle too close to a neighbour's kept one); when
#     the carried values were computed only for the cells empty before the
#     deletion, such cells got stale values (with 5 particles the error
#     was 7).
# In the sanitizer pass (UMPPM_TEST_SHORT=1, lib.sh) the cases to t = 5
# run to t = 0.1 only, and their figures are not checked.
# Needs UMPPMFOAM and TOOLDIR (directory of the built tools).
set -eu -o pipefail
here=$(cd "$(dirname "$0")" && pwd)
top=$(cd "$here/../.." && pwd)
. "$here/lib.sh"
[ -n "${UMPPMFOAM:-}" ] && [ -x "$UMPPMFOAM" ] || { echo "FAIL: UMPPMFOAM not set" >&2; exit 2; }
[ -n "${TOOLDIR:-}" ] && [ -x "$TOOLDIR/makeCrossedTriangleMesh" ] || { echo "FAIL: TOOLDIR not set" >&2; exit 2; }
work=$(mktemp -d "${TMPDIR:-/tmp}/umppm-tg.XXXXXX")
c=$work/tg
mkdir -p "$c/system" "$c/constant"
cat > "$c/system/controlDict" <<'CD'
FoamFile { version 2.0; format ascii; class dictionary; object controlDict; }
application umppmFoam; startFrom startTime; startTime 0; stopAt endTime; endTime 0.2;
deltaT 0.005; writeControl runTime; writeInterval 0.1; writeFormat ascii; writePrecision 15;
CD
cat > "$c/system/fvSolution" <<'FS'
FoamFile { version 2.0; format ascii; class dictionary; object fvSolution; }
PISO { pRefCell 0; pRefValue 0; }
UMPPM { variant UMPPMstar; laplacian CPM; pressureTheta 0; }
FS
echo 'FoamFile { version 2.0; format ascii; class dictionary; object transportProperties; } nu 0.01;' \
    > "$c/constant/transportProperties"
"$TOOLDIR/makeCrossedTriangleMesh" -case "$c" -n 10 > /dev/null
"$TOOLDIR/setTaylorGreen" -case "$c" > /dev/null
"$UMPPMFOAM" -case "$c" > "$c/log" 2>&1 || { echo "FAIL: umppmFoam"; tail -3 "$c/log"; exit 1; }
fail=0
read -r _ l2 _ linf _ < <(python3 "$top/tools/taylorGreenError.py" "$c" 0.2)
echo "Taylor-Green N_m=400 t=0.2: L2 relative error $l2, max-speed decay error $linf"
awk -v a="$l2" 'BEGIN { exit !(a < 0.05) }' || { echo "FAIL: L2 error $l2 >= 0.05"; fail=1; }
awk -v a="$linf" 'BEGIN { exit !(a < 0.03) }' || { echo "FAIL: decay error $linf >= 0.03"; fail=1; }
cmax=$(log_max_continuity "$c/log")
echo "max per-cell continuity error after correction: $cmax"
awk -v a="$cmax" 'BEGIN { exit !(a < 1e-12) }' || { echo "FAIL: continuity $cmax"; fail=1; }
r=$work/restart
cp -r "$c" "$r" && rm -rf "$r/0.2"
sed -i 's/startFrom startTime;/startFrom latestTime;/' "$r/system/controlDict"
"$UMPPMFOAM" -case "$r" > "$r/log" 2>&1 || { echo "FAIL: restart run"; exit 1; }
grep -q "Restart: 400 particles read" "$r/log" || { echo "FAIL: restart did not read the cloud"; fail=1; }
rel=$("$TOOLDIR/foamCompare" "$r" 0.2 "$c" 0.2 U | awk '$1 == "U" { print $4 }')
echo "restart vs straight run at 0.2: U L2 relative difference $rel"
awk -v a="$rel" 'BEGIN { exit !(a < 1e-10) }' || { echo "FAIL: restart differs ($rel)"; fail=1; }
# the paper's CFL 0.25 on N_m = 1600, t = 5
g=$work/tg1600
mkdir -p "$g/system" "$g/constant"
sed 's/endTime 0.2;/endTime 5;/; s/deltaT 0.005;/deltaT 0.00625;/; s/writeInterval 0.1;/writeInterval 5;/' \
    "$c/system/controlDict" > "$g/system/controlDict"
cp "$c/system/fvSolution" "$g/system/" && cp "$c/constant/transportProperties" "$g/constant/"
"$TOOLDIR/makeCrossedTriangleMesh" -case "$g" -n 20 > /dev/null
"$TOOLDIR/setTaylorGreen" -case "$g" > /dev/null
# the short pass (lib.sh): these cases, all copied from this one, run to
# t = 0.1 (16 and 32 steps) and their figures are not checked
short_end "$g" 0.1
# tg_run DIR LABEL L2_BOUND [EQ41_BOUND [P_BOUND]]: run, then check the
# errors at t = 5 (P_BOUND: the pressure's relative L2 error, Eq. 40)
tg_run() {
    if short_runs; then
        short_run "$1" "" log "$2" "$UMPPMFOAM"
    elif "$UMPPMFOAM" -case "$1" > "$1/log" 2>&1; then
        read -r _ l2 _ _ _ e41 _ _ _ _ _ pl2 _ < <(python3 "$top/tools/taylorGreenError.py" "$1" 5)
        echo "Taylor-Green $2 t=5: L2 relative error $l2, Eq. 41 $e41, pressure $pl2"
        check_below "$2: L2 relative error" "$l2" "$3"
        [ -z "${4:-}" ] || check_below "$2: Eq. 41" "$e41" "$4"
        [ -z "${5:-}" ] || check_below "$2: pressure, relative L2 error" "$pl2" "$5"
    else
        echo "FAIL: umppmFoam ($2)"; tail -3 "$1/log"; fail=1
    fi
}
tg_run "$g" "N_m 1600, CFL 0.25" 0.035 0.02 0.06
# the same with Eq. 35's own MLS scales: the carried refill's accuracy
m0=$work/tg1600-eq35
mkdir -p "$m0" && cp -r "$g/0" "$g/constant" "$g/system" "$m0/"
sed -i 's/UMPPM { variant UMPPMstar; laplacian CPM; pressureTheta 0; }/UMPPM { variant UMPPMstar; laplacian CPM; pressureTheta 0; mlsSupport 0; }/' \
    "$m0/system/fvSolution"
grep -q 'mlsSupport 0' "$m0/system/fvSolution" || { echo "FAIL: could not set mlsSupport 0"; fail=1; }
tg_run "$m0" "N_m 1600, CFL 0.25, mlsSupport 0" 0.006
# pressureTheta 0.5 (trapezoidal pressure impulse along the path): the
# damping of order dt that the paper's impulse at r* adds to a turning
# path is gone, so the run at U = 1 and a Stokes run at U = 0.01 (particles
# hardly move; the error is the Laplacian's and implicit Euler's) end with
# the same error: measured 0.0694 and 0.0662 (pressureTheta 0: 0.026 and 0.065).
# With laplacian CPM4 (quartic basis) the Laplacian's part of that error
# goes: Stokes L2 0.0142 (implicit Euler's alone is about 0.0098), and at
# U = 1 L2 0.0168 and Eq. 41 0.0031 (README, "CPM4")
# CPM4 with 0.5 are the defaults on this periodic mesh (laplacian auto and
# pressureTheta auto: no wall, inlet or outlet), so those runs name neither.
for lap in CPM CPM4; do
    for u in 1 0.01; do
        t=$work/tg1600-theta-$lap-$u
        mkdir -p "$t" && cp -r "$g/constant" "$g/system" "$t/"
        if [ $lap = CPM ]; then set_umppm="variant UMPPMstar; laplacian CPM; pressureTheta 0.5;"
        else set_umppm="variant UMPPMstar;"; fi
        sed -i "s/UMPPM { variant UMPPMstar; laplacian CPM; pressureTheta 0; }/UMPPM { $set_umppm }/" \
            "$t/system/fvSolution"
        grep -q "UMPPM { $set_umppm }" "$t/system/fvSolution" || { echo "FAIL: could not set UMPPM { $set_umppm }"; fail=1; }
        "$TOOLDIR/makeCrossedTriangleMesh" -case "$t" -n 20 > /dev/null
        "$TOOLDIR/setTaylorGreen" -case "$t" -U "$u" > /dev/null
        "$UMPPMFOAM" -case "$t" > "$t/log" 2>&1 || { echo "FAIL: umppmFoam (pressureTheta, $lap, U $u)"; tail -3 "$t/log"; fail=1; }
    done
done
if short_runs; then
    # (their exit status is checked where they run)
    for t in "$work"/tg1600-theta-*; do short_ran "$t" log "${t##*/}" 0; done
elif [ "$fail" = 0 ]; then
    read -r _ t1 _ _ < <(python3 "$top/tools/taylorGreenError.py" "$work/tg1600-theta-CPM-1" 5)
    read -r _ t0 _ _ < <(python3 "$top/tools/taylorGreenError.py" "$work/tg1600-theta-CPM-0.01" 5)
    d=$(awk -v a="$t1" -v b="$t0" 'BEGIN { d = a - b; print d < 0 ? -d : d }')
    echo "pressureTheta 0.5, N_m 1600: L2 error at U = 1 $t1, at U = 0.01 $t0"
    check_below "pressureTheta 0.5: |L2(U = 1) - L2(U = 0.01)|" "$d" 0.01
    read -r _ q1 _ _ _ e41 _ _ _ _ _ qp _ < <(python3 "$top/tools/taylorGreenError.py" "$work/tg1600-theta-CPM4-1" 5) ||
        { q1=nan e41=nan qp=nan; }
    read -r _ q0 _ _ < <(python3 "$top/tools/taylorGreenError.py" "$work/tg1600-theta-CPM4-0.01" 5)
    echo "CPM4, pressureTheta 0.5, N_m 1600: L2 error at U = 1 $q1 (Eq. 41 $e41), at U = 0.01 $q0"
    check_below "CPM4, pressureTheta 0.5, Stokes: L2 relative error" "$q0" 0.02
    check_below "CPM4, pressureTheta 0.5: L2 relative error" "$q1" 0.025
    check_below "CPM4, pressureTheta 0.5: Eq. 41" "$e41" 0.02
    check_below "CPM4, pressureTheta 0.5: pressure, relative L2 error" "$qp" 0.08
fi
grep -q 'laplacian CPM4 (auto), pressureTheta 0.5 (auto)' "$work/tg1600-theta-CPM4-1/log" ||
    { echo "FAIL: the defaults on a periodic mesh are not laplacian CPM4 (auto), pressureTheta 0.5 (auto)"; fail=1; }
# N_m = 6400 (n = 40), the same CFL (dt = 0.25 / 80), the defaults: the
# error falls at first order or better from 1 600 (measured 0.0168 ->
# 0.00573, order 1.55; with the paper's CPM and Eq. 10, 0.0265 -> 0.00099,
# a cancellation of two errors that turns at 25 600: 0.0039)
g64=$work/tg6400
mkdir -p "$g64/system" "$g64/constant"
sed 's/deltaT 0.00625;/deltaT 0.003125;/' "$g/system/controlDict" > "$g64/system/controlDict"
printf 'FoamFile { version 2.0; format ascii; class dictionary; object fvSolution; }\nPISO { pRefCell 0; pRefValue 0; }\n' \
    > "$g64/system/fvSolution"
cp "$c/constant/transportProperties" "$g64/constant/"
"$TOOLDIR/makeCrossedTriangleMesh" -case "$g64" -n 40 > /dev/null
"$TOOLDIR/setTaylorGreen" -case "$g64" > /dev/null
tg_run "$g64" "N_m 6400, CFL 0.25, defaults" 0.007 0.02 0.025
if [ "$fail" = 0 ] && ! short_runs; then
    read -r _ l64 _ _ < <(python3 "$top/tools/taylorGreenError.py" "$g64" 5) || l64=nan
    ord=$(awk -v a="$q1" -v b="$l64" 'BEGIN { print (a > 0 && b > 0) ? log(a / b) / log(2) : "nan" }')
    echo "defaults: observed L2 order from N_m 1600 to 6400: $ord"
    awk -v o="$ord" 'BEGIN { exit !(o >= 1) }' || { echo "FAIL: observed L2 order $ord < 1"; fail=1; }
fi
a=$work/tg1600-umppm
mkdir -p "$a" && cp -r "$g/0" "$g/constant" "$g/system" "$a/"
sed -i 's/UMPPM { variant UMPPMstar; laplacian CPM; pressureTheta 0; }/UMPPM { variant UMPPM; laplacian CPM; pressureTheta 0; refill carried; refillParticles 1; mlsSupport 0; }/' \
    "$a/system/fvSolution"
grep -q 'refill carried' "$a/system/fvSolution" || { echo "FAIL: could not set refill carried"; fail=1; }
if short_runs; then
    short_run "$a" "" log "N_m 1600, UMPPM, refill carried (1)" "$UMPPMFOAM"
elif "$UMPPMFOAM" -case "$a" > "$a/log" 2>&1; then
    read -r _ l2 _ _ _ _ _ < <(python3 "$top/tools/taylorGreenError.py" "$a" 5)
    check_below "N_m 1600, CFL 0.25, UMPPM, refill carried (1): L2 relative error" "$l2" 0.02
else
    echo "FAIL: umppmFoam (UMPPM, refill carried)"; tail -3 "$a/log"; fail=1
fi
[ "$fail" = 0 ] || { echo "work dir kept: $work"; exit 1; }
rm -rf "$work"
echo "PASS"
