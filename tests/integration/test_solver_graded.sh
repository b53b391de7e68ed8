#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# test_solver_graded.sh -- stretched cells: OpenFOAM's icoFoam cavity on 8x8
# cells graded in x (blockMesh simpleGrading), Re 10, deltaT 0.005, t = 0.5,
# umppmFoam at its defaults beside icoFoam on the same mesh, both against
# the converged flow (icoFoam on 160x160 uniform cells, deltaT 0.00025,
# mapped onto each graded mesh by mapFields -consistent; stored in
# tools/reference/graded_cavity_icoFoam160_t0.5). README, "Anisotropic
# cells".
#   - simpleGrading (1000 1 1), (10000 1 1), (100000 1 1): cell aspect
#     ratios 199, 1 708 and 15 491. The default (anisotropicCells
#     auto) turns the anisotropic operators on (the log says so); each run
#     reaches t = 0.5 with max |U| <= 1.05 x the lid speed at each write,
#     every 0.025 s (measured 0.718, 0.728, 0.725 with gcc -O2 since the
#     positive rows' penalty floor and the refills within range of
#     2026-12-07, 0.727, 0.712, 0.705 before; ASan
#     0.725, 0.702, 0.673; before the walls in the correction the gcc 1 708:1 run
#     reached 0.98), and U, the mean over the nine writes t = 0.3 ... 0.5,
#     is within 0.40 (relative L2) of the converged flow at t = 0.5
#     (measured 0.300, 0.307, 0.252 with gcc -O2 since 2026-12-07, 0.323,
#     0.298, 0.252 before, 0.322, 0.272, 0.261 in the clang
#     ASan build; before the transpose correction (f) 0.342, 0.314, 0.333 in
#     ASan, where a single write ranged 0.30-0.42; icoFoam on the same
#     meshes 0.51, 0.43, 0.32). Before
#     (the paper's operators, and the old anisotropicCells yes): max |U|
#     25 on the first, the divergence guard at t = 0.015 / 0.005 on the
#     others. U against icoFoam's own run on the graded mesh is printed,
#     not asserted (the issue's 10 % is not met: 0.29, 0.25, 0.22 at
#     t = 0.5; icoFoam is itself 30-50 % from the converged flow on these
#     meshes);
#   - anisotropicCells no on the 199:1 mesh: a warning names the most
#     stretched cell before the first step, and the closed-flow bound
#     (2 x the lid speed) stops the run at its first step;
#   - graded only 10:1 toward all four walls (20x20 cells, two-sided
#     simpleGrading, cells at most 10:1, so anisotropicCells auto stays
#     off), deltaT 0.0005, t = 0.1 written every 0.005: max |U| <= 1.05 x
#     the lid speed at every written time, and the largest Courant number
#     of the run within 1.5 x icoFoam's on the same mesh and step
#     (measured 0.958 and 0.159, icoFoam 0.179). With positiveRows no (the
#     paper's CPM) max |U| is 6.9 and the Courant number 3.3: CPM rows
#     that lost the predictor's diagonal dominance (README, "Positive rows");
#   - graded toward the lid's corners, deltaT 0.005, written every 0.025
#     s: max |U| <= 1.05 x the lid speed at every write on 20x20 and 8x8
#     cells graded 1000:1 toward the lid's downstream corner
#     (simpleGrading (0.001 0.001 1)), 8x8 cells graded 10 000:1 that way,
#     20x20 cells graded 1000:1 toward all four walls (two-sided
#     simpleGrading) and 8x8 cells graded 3 000:1 that way; measured 1.000,
#     0.865, 1.000, 1.000, 0.983 with gcc -O2 and the first four also
#     in the clang ASan build (icoFoam 0.999, 0.998, 1.000, 0.999; 1.000:
#     a lid cell held at the lid's speed by the limit of the written U,
#     README (f)). Before the walls in the
#     correction (README "Graded toward the lid's downstream corner"):
#     1.050, 1.168, 1.093, 1.068. On the 20x20 corner mesh also U within
#     0.45 of the converged flow at t = 0.5 (measured 0.266 since
#     2026-12-07, 0.277 before, ASan build 0.297; icoFoam 0.284). The
#     8x8 3 000:1 run stopped at t = 0.265 before the positive rows' penalty
#     floor (README, "Positive rows that
#     failed"); so did the 10 000:1 one, at t = 0.05, which now runs to
#     t = 0.5 (0.995 at the writes since the refills within their samples'
#     range, 1.072 before them; 1.100 at a step between writes, with the
#     end-of-run warning): checked that it ends and that, if a write is
#     above 1.05 x, the end-of-run warning names a largest at least that;
#   - without icoFoam, written every 0.025 s: 40x40 cells graded 1000:1 in
#     x (simpleGrading (1000 1 1)) at deltaT 0.005, and the 8x8 corner
#     mesh at deltaT 0.00005 (10 000 steps): max |U| <= 1.05 at every
#     write (measured 1.003 and 0.999 with gcc -O2 since 2026-12-07, 0.903
#     before, 0.870 and 0.999 in the
#     ASan build; before the damped correction of the particles next to
#     walls, (e) of README "Graded toward the lid's downstream corner",
#     1.152 and 2.27);
#   - the 8x8 meshes graded (1000 1 1) and (10000 1 1) at deltaT 0.00005
#     (10 000 steps each): max |U| <= 1.05 at every write and U, the mean
#     of the nine writes, within 0.40 of the converged flow (measured
#     0.737 / 0.737, U 0.304 / 0.333 with gcc -O2 since 2026-12-07 (0.750 /
#     0.716, U 0.305 / 0.273 before); ASan 0.727 / 0.765, U
#     0.317 / 0.302; before the transpose correction of the interpolation
#     error's pressure, (f) of the same section, 1.139 / 0.974 and U 1.07
#     / 0.77).
#     Before boundedFits (MLS values and refills limited near their
#     samples' range) the 20x20 corner run diverged in the first step
#     (README, "Bounded fits").
# In the sanitizer pass (UMPPM_TEST_SHORT=1, lib.sh) the three cases at
# deltaT 0.00005 (10 000 steps each) run 100 steps, their figures not
# checked; the others run as in the plain pass.
# Needs UMPPMFOAM and TOOLDIR (foamCompare); OpenFOAM's blockMesh, icoFoam.
set -eu -o pipefail
here=$(cd "$(dirname "$0")" && pwd)
[ -n "${UMPPMFOAM:-}" ] && [ -x "$UMPPMFOAM" ] || { echo "FAIL: UMPPMFOAM not set" >&2; exit 2; }
[ -n "${TOOLDIR:-}" ] && [ -x "$TOOLDIR/foamCompare" ] || { echo "FAIL: TOOLDIR not set" >&2; exit 2; }
. "$here/lib.sh"
of_env
ex=/usr/share/doc/openfoam-examples/examples/incompressible/icoFoam/cavity/cavity
[ -d "$ex" ] || { echo "FAIL: $ex missing (package openfoam-examples)"; exit 1; }
refdir=$(cd "$here/../../tools/reference/graded_cavity_icoFoam160_t0.5" && pwd)
work=$(mktemp -d "${TMPDIR:-/tmp}/umppm-graded.XXXXXX")
fail=0

# max_speed FILE: max |U| of the internal field of FILE
max_speed() { max_speed_files "$1" | cut -d' ' -f1; }
# max_over DIR...: the largest max |U| over the U files of the time
# directories DIR (one awk for all: lib.sh max_speed_files)
max_over() {
    local t f=()
    for t in "$@"; do f+=("$t/U"); done
    max_speed_files "${f[@]}" | cut -d' ' -f1
}
# rel_l2 CASE_A CASE_B: relative L2 of U at t = 0.5 (foamCompare)
rel_l2() { "$TOOLDIR/foamCompare" "$1" 0.5 "$2" 0.5 U | awk '$1 == "U" { print $4 }'; }
# mean_l2 CASE REF: the mean over the nine writes t = 0.3 ... 0.5 of CASE of
# the relative L2 of U against REF at t = 0.5
mean_l2() {
    for t in 0.3 0.325 0.35 0.375 0.4 0.425 0.45 0.475 0.5; do
        "$TOOLDIR/foamCompare" "$1" "$t" "$2" 0.5 U | awk '$1 == "U" { print $4 }'
    done | awk '{ s += $1; n++ } END { if (n == 9) printf "%.4f\n", s / n; else print "missing" }'
}

# with_icoFoam DIR: icoFoam's run of the case in DIR/ico
with_icoFoam() {
    mkdir -p "$1/ico"
    cp -r "$1/0" "$1/constant" "$1/system" "$1/ico/"
    run_in "$1/ico" icoFoam icoFoam
}
# with_reference DIR NAME: the converged flow NAME of $refdir at t = 0.5 in DIR/ref
with_reference() {
    mkdir -p "$1/ref/0.5"
    cp -r "$1/constant" "$1/system" "$1/ref/"
    cp "$refdir/$2/U" "$1/ref/0.5/U"
}

# graded_case DIR GRADING: the tutorial cavity on 8x8 cells graded in x,
# with icoFoam's run in DIR/ico and the converged flow in DIR/ref
graded_case() {
    tutorial_copy "$ex" "$1"
    sed -i "s/(20 20 1)/(8 8 1)/; s/simpleGrading (1 1 1)/simpleGrading ($2 1 1)/" "$1/system/blockMeshDict"
    sed -i "s/^deltaT .*/deltaT 0.005;/; s/^writeControl .*/writeControl runTime;/" "$1/system/controlDict"
    sed -i 's/^writeInterval .*/writeInterval 0.025;/' "$1/system/controlDict"
    grep -q "simpleGrading ($2 1 1)" "$1/system/blockMeshDict" || { echo "  FAIL: could not grade the mesh"; return 1; }
    run_in "$1" blockMesh blockMesh
    with_reference "$1" "grading$2"
    with_icoFoam "$1"
}

for spec in 1000:199 10000:1708 100000:15491; do
    g=${spec%%:*} ar=${spec#*:}
    c=$work/g$g
    graded_case "$c" "$g" || { fail=1; continue; }
    if ! "$UMPPMFOAM" -case "$c" > "$c/log.umppmFoam" 2>&1; then
        echo "  FAIL aspect ratio $ar: umppmFoam failed: $(grep -m1 'FATAL' "$c/log.umppmFoam" | cut -c1-200)"
        fail=1
        continue
    fi
    grep -q "is stretched $ar:1 .*anisotropicCells on (auto" "$c/log.umppmFoam" ||
        { echo "  FAIL aspect ratio $ar: the log does not say that anisotropicCells auto is on"; fail=1; }
    # max |U| over the writes every 0.025 s, not only the last
    umax=$(max_over "$c"/0.*)
    nw=$(find "$c" -maxdepth 1 -name '0.*' | wc -l)
    echo "aspect ratio $ar: max |U| over the $nw writes $umax, at t = 0.5 $(max_speed "$c/0.5/U") (icoFoam $(max_speed "$c/ico/0.5/U")); U vs converged" \
        "(mean of t = 0.3 ... 0.5): umppmFoam $(mean_l2 "$c" "$c/ref"), icoFoam $(mean_l2 "$c/ico" "$c/ref"); at t = 0.5:" \
        "umppmFoam $(rel_l2 "$c" "$c/ref"), icoFoam $(rel_l2 "$c/ico" "$c/ref"), umppmFoam vs icoFoam $(rel_l2 "$c" "$c/ico")" \
        "(not asserted; the issue's target is 0.1)"
    check_range "aspect ratio $ar: writes every 0.025 s" "$nw" 20 20
    check_range "aspect ratio $ar: max |U| / lid speed over the writes" "$umax" 0 1.05
    check_below "aspect ratio $ar: U vs the converged flow (rel. L2, mean of t = 0.3 ... 0.5)" "$(mean_l2 "$c" "$c/ref")" 0.40
done

d=$work/no
graded_case "$d" 1000
printf 'UMPPM\n{\n    anisotropicCells no;\n}\n' >> "$d/system/fvSolution"
sed -i 's/^endTime .*/endTime 0.005;/' "$d/system/controlDict"
# (its first step reaches 2.6 x the lid speed: since 2026-12-06 the
# closed-flow bound stops it, where it had ended with exit 0)
rc=0
"$UMPPMFOAM" -case "$d" > "$d/log.umppmFoam" 2>&1 || rc=$?
if grep -q 'umppmFoam Warning: cell [0-9]* at ([^)]*) is stretched 199:1' "$d/log.umppmFoam"; then
    echo "  ok   anisotropicCells no on the 199:1 mesh: $(grep -o 'cell [0-9]* at ([^)]*) is stretched 199:1' "$d/log.umppmFoam")"
else
    echo "  FAIL anisotropicCells no on the 199:1 mesh: no stretched-cell warning"; tail -3 "$d/log.umppmFoam"; fail=1
fi
if [ "$rc" -eq 1 ] && grep -q 'diverged at time 0.005: |U| = .* exceeds the bound 2 (2 x the largest wall or start speed 1 of a flow driven by its walls alone' "$d/log.umppmFoam"; then
    echo "  ok   anisotropicCells no on the 199:1 mesh: stopped by the closed-flow bound"
else
    echo "  FAIL anisotropicCells no on the 199:1 mesh: exit $rc, not stopped by the closed-flow bound"; tail -1 "$d/log.umppmFoam"; fail=1
fi

b=$work/walls10
tutorial_copy "$ex" "$b"
sed -i 's/simpleGrading (1 1 1)/simpleGrading (((0.5 0.5 10) (0.5 0.5 0.1)) ((0.5 0.5 10) (0.5 0.5 0.1)) 1)/' \
    "$b/system/blockMeshDict"
sed -i 's/^deltaT .*/deltaT 0.0005;/; s/^endTime .*/endTime 0.1;/; s/^writeControl .*/writeControl runTime;/;
        s/^writeInterval .*/writeInterval 0.005;/' "$b/system/controlDict"
run_in "$b" blockMesh blockMesh
with_icoFoam "$b"
if "$UMPPMFOAM" -case "$b" > "$b/log.umppmFoam" 2>&1; then
    writes=$(find "$b" -maxdepth 1 -name '0.*' | wc -l)
    umax=$(max_over "$b"/0.*)
    co=$(awk '/^Courant/ { if ($6 > m) m = $6 } END { print m + 0 }' "$b/log.umppmFoam")
    ico=$(awk '/^Courant/ { if ($6 > m) m = $6 } END { print m + 0 }' "$b/ico/log.icoFoam")
    check_range "graded 10:1 toward the walls, deltaT 0.0005: writes" "$writes" 20 20
    check_range "graded 10:1 toward the walls: max |U| / lid speed over the writes" "$umax" 0 1.05
    check_below "graded 10:1 toward the walls: max Courant / icoFoam's ($co / $ico)" \
        "$(awk -v a="$co" -v b="$ico" 'BEGIN { print a / b }')" 1.5
else
    echo "  FAIL graded 10:1 toward the walls: umppmFoam failed: $(grep -m1 'FATAL' "$b/log.umppmFoam" | cut -c1-200)"
    fail=1
fi

# corner_mesh DIR N GRADING [DT]: the tutorial cavity on NxN cells with
# simpleGrading GRADING, deltaT DT (default 0.005), written every 0.025 s
corner_mesh() {
    tutorial_copy "$ex" "$1"
    sed -i "s/(20 20 1)/($2 $2 1)/; s/simpleGrading (1 1 1)/simpleGrading $3/" "$1/system/blockMeshDict"
    sed -i "s/^deltaT .*/deltaT ${4:-0.005};/; s/^writeControl .*/writeControl runTime;/" "$1/system/controlDict"
    sed -i 's/^writeInterval .*/writeInterval 0.025;/' "$1/system/controlDict"
    grep -q "simpleGrading $3" "$1/system/blockMeshDict" || { echo "  FAIL: could not grade the mesh"; return 1; }
    run_in "$1" blockMesh blockMesh
}
# corner_case DIR N GRADING: corner_mesh at deltaT 0.005 and icoFoam's run
# in DIR/ico
corner_case() {
    corner_mesh "$1" "$2" "$3" || return 1
    with_icoFoam "$1"
}

# run_umppm DIR LABEL: umppmFoam on the case DIR; says FAIL and returns 1
# if it fails
run_umppm() {
    "$UMPPMFOAM" -case "$1" > "$1/log.umppmFoam" 2>&1 && return 0
    echo "  FAIL $2: umppmFoam failed: $(grep -m1 'FATAL' "$1/log.umppmFoam" | cut -c1-200)"
    return 1
}
# check_bounded DIR LABEL: 20 writes every 0.025 s, max |U| <= 1.05 x the
# lid speed at each
check_bounded() {
    check_range "$2: writes every 0.025 s" "$(find "$1" -maxdepth 1 -name '0.*' | wc -l)" 20 20
    check_range "$2: max |U| / lid speed over the writes" "$(max_over "$1"/0.*)" 0 1.05
}

# the meshes graded toward the lid's corners, each at every write
# two_sided R: simpleGrading R:1 toward both walls in x and in y
two_sided() {
    local ir
    ir=$(awk -v r="$1" 'BEGIN { printf "%.9g", 1 / r }')
    echo "(((0.5 0.5 $1) (0.5 0.5 $ir)) ((0.5 0.5 $1) (0.5 0.5 $ir)) 1)"
}
two=$(two_sided 1000)
for spec in "corner:20:(0.001 0.001 1):1000:1 toward the lid's downstream corner" \
    "corner8:8:(0.001 0.001 1):1000:1 toward the lid's downstream corner" \
    "corner8e:8:(0.0001 0.0001 1):10 000:1 toward the lid's downstream corner" \
    "walls20:20:$two:1000:1 toward all four walls" \
    "walls8t:8:$(two_sided 3000):3 000:1 toward all four walls"; do
    IFS=: read -r name n grading what <<< "$spec"
    k=$work/$name
    label="${n}x$n graded $what"
    corner_case "$k" "$n" "$grading" || { fail=1; continue; }
    run_umppm "$k" "$label" || { fail=1; continue; }
    echo "$label: max |U| over the writes umppmFoam $(max_over "$k"/0.*), icoFoam $(max_over "$k/ico"/0.*)"
    check_bounded "$k" "$label"
    if [ "$name" = corner ]; then
        with_reference "$k" corner20
        echo "$label: U vs converged: umppmFoam $(rel_l2 "$k" "$k/ref"), icoFoam $(rel_l2 "$k/ico" "$k/ref");" \
            "umppmFoam vs icoFoam $(rel_l2 "$k" "$k/ico") (not asserted)"
        check_below "$label: U vs the converged flow (rel. L2)" "$(rel_l2 "$k" "$k/ref")" 0.45
    fi
done

# 8x8 graded 10 000:1 toward all four walls: runs to t = 0.5, and where
# a write passes 1.05 x the lid speed (1.072 at t = 0.05 before the refills
# within range; 1.100 at a step between writes now) it says so: the
# end-of-run warning's count and largest
k=$work/walls8e
label="8x8 graded 10 000:1 toward all four walls"
if corner_case "$k" 8 "$(two_sided 10000)" && run_umppm "$k" "$label"; then
    m=$(max_over "$k"/0.*)
    echo "$label: max |U| over the writes umppmFoam $m, icoFoam $(max_over "$k/ico"/0.*)"
    check_range "$label: writes every 0.025 s" "$(find "$k" -maxdepth 1 -name '0.*' | wc -l)" 20 20
    check_range "$label: max |U| / lid speed over the writes" "$m" 0 2
    # (no warning: grep finds nothing, which is no failure here)
    warned=$({ grep -o 'above 1.05 x the largest wall or start speed 1 in [0-9]* of [0-9]* steps.*largest [0-9.e+-]*' \
        "$k/log.umppmFoam" || true; } | sed 's/.*largest //')
    if awk -v m="$m" 'BEGIN { exit !(m > 1.05) }'; then
        if [ -n "$warned" ] && awk -v m="$m" -v w="$warned" 'BEGIN { exit !(w >= m * (1 - 1e-6)) }'; then
            echo "  ok   $label: above 1.05 x ($m), and the end-of-run warning says so (largest $warned)"
        else
            echo "  FAIL $label: max |U| $m above 1.05 x without the end-of-run warning (largest '$warned')"
            fail=1
        fi
    else
        echo "  ok   $label: max |U| $m within 1.05 x"
    fi
else
    fail=1
fi

# short_small_step DIR LABEL: in the short pass (lib.sh), run the case of
# 10 000 steps for its first 100 only, check that it ran, and return 0 (the
# caller skips its checks); in the plain pass return 1
short_small_step() {
    short_runs || return 1
    if [ "$(sed -n 's/^deltaT *\([^;]*\);/\1/p' "$1/system/controlDict")" = 0.00005 ]; then
        short_run "$1" 0.005 log.umppmFoam "$2" "$UMPPMFOAM"
        return 0
    fi
    return 1
}

# without icoFoam (which diverges on the first at deltaT 0.005 / 10, and
# whose step the second is not): 40x40 cells graded 1000:1 in x, the
# smallest at the lid's upstream corner, at deltaT 0.005, and the 8x8
# corner mesh at deltaT 0.00005 (10 000 steps); max |U| at every write
for spec in "x40:40:(1000 1 1):0.005:40x40 graded 1000:1 in x, deltaT 0.005" \
    "corner8s:8:(0.001 0.001 1):0.00005:8x8 graded 1000:1 toward the lid's downstream corner, deltaT 0.00005"; do
    IFS=: read -r name n grading dt label <<< "$spec"
    k=$work/$name
    corner_mesh "$k" "$n" "$grading" "$dt" || { fail=1; continue; }
    short_small_step "$k" "$label" && continue
    run_umppm "$k" "$label" || { fail=1; continue; }
    check_bounded "$k" "$label"
done

# small steps on the 8x8 meshes graded in x (10 000 steps): max |U| at
# every write and U against the converged flow, as at deltaT 0.005
for g in 1000 10000; do
    k=$work/xs$g
    label="8x8 graded ($g 1 1), deltaT 0.00005"
    corner_mesh "$k" 8 "($g 1 1)" 0.00005 || { fail=1; continue; }
    short_small_step "$k" "$label" && continue
    with_reference "$k" "grading$g"
    run_umppm "$k" "$label" || { fail=1; continue; }
    echo "$label: max |U| over the writes $(max_over "$k"/0.*), U vs converged (mean of t = 0.3 ... 0.5) $(mean_l2 "$k" "$k/ref")"
    check_bounded "$k" "$label"
    check_below "$label: U vs the converged flow (rel. L2, mean of t = 0.3 ... 0.5)" "$(mean_l2 "$k" "$k/ref")" 0.40
done

[ "$fail" = 0 ] || { echo "work dir kept: $work"; exit 1; }
rm -rf "$work"
echo "PASS"
