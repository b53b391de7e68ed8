#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# test_solver_graded.sh -- stretched cells: OpenFOAM's icoFoam cavity on 8x8
# cells graded in x (blockMesh simpleGrading), Re 10, deltaT 0.005, t = 0.5,
# umppmFoam with UMPPM { anisotropicCells yes; } beside icoFoam on the same
# mesh (the default, the paper's Eq. 26 and plain CPM, runs the first case
# to the end with max |U| 25 and stops the second at t = 0.015: README,
# "Anisotropic cells"):
#   - simpleGrading (1000 1 1), cell aspect ratio 199: runs to the end and
#     max |U| <= 1.05 x the lid speed (measured 0.772 with gcc -O2, 0.980
#     in the clang ASan build; icoFoam 0.702). With the paper's plain CPM
#     weights and unweighted LS gradient, Eq. 26, max |U| was 25. The
#     difference to icoFoam's U is printed, not asserted: it is 0.52 (gcc)
#     and 1.82 (clang ASan), so on this mesh rounding changes the answer
#     at O(1), and the issue's target, 10 %, is not met (README,
#     "Anisotropic cells");
#   - simpleGrading (10000 1 1), aspect ratio 1707: not run wrong silently.
#     It either finishes with max |U| <= 1.05 or is stopped by the
#     divergence guard with the time, the cell or particle and the value
#     named (today it is stopped at t = 0.055 with gcc, 0.43 with clang
#     ASan).
#   - the default on the 199:1 mesh says so before the first step: a
#     warning names the most stretched cell (the default's answer there is
#     wrong, max |U| 25, without diverging).
# Needs UMPPMFOAM and TOOLDIR (foamCompare); OpenFOAM's blockMesh, icoFoam.
set -eu -o pipefail
here=$(cd "$(dirname "$0")" && pwd)
[ -n "${UMPPMFOAM:-}" ] && [ -x "$UMPPMFOAM" ] || { echo "FAIL: UMPPMFOAM not set" >&2; exit 2; }
[ -n "${TOOLDIR:-}" ] && [ -x "$TOOLDIR/foamCompare" ] || { echo "FAIL: TOOLDIR not set" >&2; exit 2; }
. "$here/lib.sh"
of_env
ex=/usr/share/doc/openfoam-examples/examples/incompressible/icoFoam/cavity/cavity
[ -d "$ex" ] || { echo "FAIL: $ex missing (package openfoam-examples)"; exit 1; }
work=$(mktemp -d "${TMPDIR:-/tmp}/umppm-graded.XXXXXX")
fail=0

# max |U| of the internal field of FILE (lib.sh field_values)
max_speed() {
    field_values "$1" | awk '{ s = sqrt($1 * $1 + $2 * $2); if (s > m) m = s } END { printf "%.6g\n", m }'
}

# graded_case DIR GRADING: the tutorial cavity on 8x8 cells graded in x
graded_case() {
    cp -r "$ex" "$1"
    find "$1" -name '*.gz' -exec gzip -d {} +
    sed -i "s/(20 20 1)/(8 8 1)/; s/simpleGrading (1 1 1)/simpleGrading ($2 1 1)/" "$1/system/blockMeshDict"
    sed -i "s/^deltaT .*/deltaT 0.005;/" "$1/system/controlDict"
    grep -q "simpleGrading ($2 1 1)" "$1/system/blockMeshDict" || { echo "  FAIL: could not grade the mesh"; return 1; }
    run_in "$1" blockMesh blockMesh
}
# with_option DIR: UMPPM { anisotropicCells yes; } (after icoFoam's copy)
with_option() {
    printf 'UMPPM\n{\n    anisotropicCells yes;\n}\n' >> "$1/system/fvSolution"
}

g=$work/ar199
graded_case "$g" 1000
mkdir -p "$g/ico" && cp -r "$g/0" "$g/constant" "$g/system" "$g/ico/"
run_in "$g/ico" icoFoam icoFoam || fail=1
d=$work/ar199-default
cp -r "$g" "$d" && rm -rf "$d/ico"
sed -i 's/^endTime .*/endTime 0.005;/' "$d/system/controlDict"
if "$UMPPMFOAM" -case "$d" > "$d/log.umppmFoam" 2>&1 &&
    grep -q 'umppmFoam Warning: cell [0-9]* at ([^)]*) is stretched 199:1' "$d/log.umppmFoam"; then
    echo "  ok   default on the 199:1 mesh: $(grep -o 'cell [0-9]* at ([^)]*) is stretched 199:1' "$d/log.umppmFoam")"
else
    echo "  FAIL default on the 199:1 mesh: no stretched-cell warning"; tail -3 "$d/log.umppmFoam"; fail=1
fi
with_option "$g"
if "$UMPPMFOAM" -case "$g" > "$g/log.umppmFoam" 2>&1; then
    echo "aspect ratio 199: max |U| $(max_speed "$g/0.5/U") (icoFoam $(max_speed "$g/ico/0.5/U"))"
    check_range "aspect ratio 199: max |U| / lid speed" "$(max_speed "$g/0.5/U")" 0 1.05
    rel=$("$TOOLDIR/foamCompare" "$g" 0.5 "$g/ico" 0.5 U | awk '$1 == "U" { print $4 }')
    echo "aspect ratio 199: U vs icoFoam, relative L2 = $rel (not asserted; the target is 0.1)"
else
    echo "  FAIL aspect ratio 199: umppmFoam failed"; tail -2 "$g/log.umppmFoam"; fail=1
fi

h=$work/ar1707
graded_case "$h" 10000
with_option "$h"
if "$UMPPMFOAM" -case "$h" > "$h/log.umppmFoam" 2>&1; then
    check_range "aspect ratio 1707: max |U| / lid speed" "$(max_speed "$h/0.5/U")" 0 1.05
else
    msg=$(grep 'FATAL ERROR' "$h/log.umppmFoam" || true)
    echo "aspect ratio 1707: ${msg:0:200}"
    printf '%s' "$msg" | grep -Eq 'diverged at time [0-9.e+-]+: \|U\| = [0-9.e+-]+ (in cell [0-9]+|of particle [0-9]+) at \([^)]*\) exceeds the bound' ||
        { echo "  FAIL aspect ratio 1707: failed without the divergence guard's message"; fail=1; }
    echo "  ok   aspect ratio 1707: stopped by the divergence guard, not run wrong silently"
fi

[ "$fail" = 0 ] || { echo "work dir kept: $work"; exit 1; }
rm -rf "$work"
echo "PASS"
