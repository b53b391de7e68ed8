#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# bench/closedFlowSweep.sh [-umppm "key value; ..."] [-icoFoam yes] [-only REGEX] [-work DIR]
# Boundedness of lid-driven cavities on non-square, graded and coarse
# cells (README "Unbounded on coarse stretched cells at high Re"): 19
# cases of the user trial of 2026-12-06 that the tests do not run, on
# OpenFOAM's icoFoam cavity (blockMesh, lid speed 1). Re 1000 (unit
# cavity, nu 0.001, to t = 10): uniform cells of aspect ratio 2 to 5, and
# 20^2 graded toward the floor or the lid; Re 10 (the tutorial's, to
# t = 0.5): 8^2 and 20^2 graded toward all four walls 1 000:1 to 10 000:1,
# and graded in one direction. Prints per case umppmFoam's largest cell and
# particle |U| over the writes, its exit (the closed-flow guard stops above
# 2 x the lid speed), the largest |U| of its end-of-run warning (above
# 1.05 x; of its first warning, marked "(first)", when it stopped), and with -icoFoam yes icoFoam's largest cell |U| on the same mesh
# and step. -umppm adds entries to the UMPPM dictionary of every case
# (e.g. "variant UMPPM; anisotropicCells yes;"); -only runs the cases whose
# name matches REGEX. About 5 minutes on one core (10 with icoFoam).
# UMPPMFOAM=PATH runs that solver instead of bin/umppmFoam (another build).
set -eu -o pipefail
top=$(cd "$(dirname "$0")/.." && pwd)
extra="" ico=no only=. work=""
. "$top/bench/cases.sh" # bench_options, bench_prepare, cavity_copy, max_speed
bench_options "umppm extra icoFoam ico only only work work" "$@"
bench_prepare closed
all() { # two-sided grading R toward both walls, in x and in y
    local r=$1 ir
    ir=$(awk -v r="$1" 'BEGIN { printf "%.9g", 1 / r }')
    echo "((0.5 0.5 $r) (0.5 0.5 $ir)) ((0.5 0.5 $r) (0.5 0.5 $ir)) 1"
}
# name nx ny grading deltaT endTime writeInterval(steps) nu scale
cases="U20x4|20|4|1 1 1|0.005|10|20|0.001|1
U20x5|20|5|1 1 1|0.005|10|20|0.001|1
U40x8|40|8|1 1 1|0.0025|10|40|0.001|1
U20x10|20|10|1 1 1|0.005|10|20|0.001|1
U40x20|40|20|1 1 1|0.0025|10|40|0.001|1
floor1000|20|20|1 1000 1|0.005|10|20|0.001|1
floor1000dt1e-3|20|20|1 1000 1|0.001|10|100|0.001|1
lid1000|20|20|1 0.001 1|0.005|10|20|0.001|1
lid7495|20|20|1 0.00013342 1|0.005|10|20|0.001|1
floor58.7|20|20|1 58.6804 1|0.005|10|20|0.001|1
all1000_8|8|8|$(all 1000)|0.005|0.5|1|0.01|0.1
all3000_8|8|8|$(all 3000)|0.005|0.5|1|0.01|0.1
all10000_8|8|8|$(all 10000)|0.005|0.5|1|0.01|0.1
all1000_8dt5e-5|8|8|$(all 1000)|0.00005|0.5|50|0.01|0.1
all1000_20dt5e-5|20|20|$(all 1000)|0.00005|0.5|50|0.01|0.1
all10000_20|20|20|$(all 10000)|0.005|0.5|1|0.01|0.1
x1000_8|8|8|1000 1 1|0.005|0.5|1|0.01|0.1
x10000_8|8|8|10000 1 1|0.005|0.5|1|0.01|0.1
y1000_20|20|20|1 1000 1|0.005|0.5|1|0.01|0.1"
# largest |U| over the writes of case $1: cells (max_speed) and particles
max_cells() {
    local f
    for f in "$1"/[0-9]*/U; do
        case $f in "$1"/0/U) continue ;; esac
        max_speed "$f" '%.4f\n'
    done | sort -g | tail -1
}
max_particles() {
    local f
    for f in "$1"/[0-9]*/lagrangian/*/U; do
        [ -f "$f" ] || continue
        awk '/^\(/ && NF == 3 { gsub(/[()]/, ""); s = sqrt($1 * $1 + $2 * $2); if (s > m) m = s }
             END { printf "%.4f\n", m }' "$f"
    done | sort -g | tail -1
}
printf "%-18s %5s %-9s %8s %9s %-22s %16s %8s\n" case Re deltaT "cell U" "particle" "umppmFoam" "warned" icoFoam
while IFS='|' read -r name nx ny g dt et wi nu sc; do
    [[ $name =~ $only ]] || continue
    c=$work/$name
    cavity_copy "$c" || exit 1
    sed -i "s/(20 20 1) simpleGrading (1 1 1)/($nx $ny 1) simpleGrading ($g)/; s/^scale .*/scale $sc;/" \
        "$c/system/blockMeshDict"
    sed -i "s/^nu .*/nu              $nu;/" "$c/constant/transportProperties"
    sed -i "s/^deltaT .*/deltaT $dt;/; s/^endTime .*/endTime $et;/; s/^writeControl .*/writeControl timeStep;/;
            s/^writeInterval .*/writeInterval $wi;/" "$c/system/controlDict"
    (cd "$c" && blockMesh > log.blockMesh 2>&1) || { echo "blockMesh failed in $c" >&2; exit 1; }
    if [ "$ico" = yes ]; then
        mkdir -p "$c/ico" && cp -r "$c/0" "$c/constant" "$c/system" "$c/ico/"
    fi
    [ -z "$extra" ] || printf 'UMPPM { %s }\n' "$extra" >> "$c/system/fvSolution"
    status="ran to the end"
    if ! "$umppm" -case "$c" > "$c/log.umppmFoam" 2>&1; then
        t=$(grep -o 'diverged at time [0-9.e+-]*' "$c/log.umppmFoam" | head -1 | awk '{ print $4 }' || true)
        status="stopped at t = ${t:-?}"
        [ -n "$t" ] || status="failed: see $c/log.umppmFoam"
    fi
    # the end-of-run warning's largest, or (a run stopped after warning) the first warning's |U|
    warned=$(sed -n 's/.*|U| above [0-9.]* x the largest wall or start speed.*; largest \([0-9.e+-]*\) (.*/\1/p' \
        "$c/log.umppmFoam" | tail -1)
    [ -n "$warned" ] || warned=$(sed -n 's/^--> umppmFoam Warning: |U| = \([0-9.e+-]*\) in cell .*/\1 (first)/p' \
        "$c/log.umppmFoam" | head -1)
    iu=-
    if [ "$ico" = yes ]; then
        (cd "$c/ico" && icoFoam > log.icoFoam 2>&1) && iu=$(max_cells "$c/ico") || iu=diverged
    fi
    re=$(awk -v s="$sc" -v n="$nu" 'BEGIN { printf "%g", s / n }')
    printf "%-18s %5s %-9s %8s %9s %-22s %16s %8s\n" "$name" "$re" "$dt" "$(max_cells "$c")" \
        "$(max_particles "$c")" "$status" "${warned:--}" "$iu"
done <<< "$cases"
echo "work directory: $work"
