#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# bench/gradedCavity.sh [-gradings "1000 10000 100000"] [-fine 0|N] [-umppm "key value; ..."] [-work DIR]
# Stretched cells (README "Anisotropic cells"): OpenFOAM's icoFoam cavity
# (Re 10) on 8x8 cells graded in x by blockMesh simpleGrading (G 1 1)
# (G = 1000, 10000, 100000: cells stretched 199:1, 1 708:1, 15 491:1),
# deltaT 0.005, t = 0.5; umppmFoam (its defaults, plus -umppm entries in
# the UMPPM dictionary) and icoFoam on the same mesh and step, one run
# after the other, each against the converged flow: by default the one
# stored in tools/reference/graded_cavity_icoFoam160_t0.5 (icoFoam on
# 160x160 uniform cells, deltaT 0.00025, mapped by mapFields -consistent);
# -fine N recomputes it on N x N cells (deltaT 0.04 / N; N = 160 takes
# about 2 min on the 2-core VM). Prints one row per grading:
#   G  aspect  solver  max|U|  U_vs_converged  U_vs_icoFoam  CPU_s  us/particle-step  RSS_MiB
# (U: relative L2, area-weighted, foamCompare; CPU s from the solver's
# ExecutionTime; RSS from bench/run_measured.py).
# UMPPMFOAM=PATH runs that solver instead of bin/umppmFoam (another build).
set -eu -o pipefail
top=$(cd "$(dirname "$0")/.." && pwd)
gradings="1000 10000 100000" fine=0 extra="" work=""
. "$top/bench/cases.sh" # bench_options, bench_prepare, cavity_copy, max_speed
bench_options "gradings gradings fine fine umppm extra work work" "$@"
bench_prepare graded
quiet() { "$@" > /dev/null 2>&1 || { echo "failed: $* (in $PWD)" >&2; exit 1; }; }
tutorial() { cavity_copy "$1" || exit 1; }
rel() { "$bin/foamCompare" "$1" 0.5 "$2" 0.5 U | awk '$1 == "U" { print $4 }'; }
cpu() { awk '/^ExecutionTime/ { t = $3 } END { print t }' "$1"; }
if [ "$fine" != 0 ]; then
    f=$work/fine$fine
    if [ ! -f "$f/0.5/U" ]; then
        tutorial "$f"
        sed -i "s/(20 20 1)/($fine $fine 1)/" "$f/system/blockMeshDict"
        dt=$(awk -v n="$fine" 'BEGIN { print 0.04 / n }')
        sed -i "s/^deltaT .*/deltaT $dt;/; s/^writeControl .*/writeControl runTime;/; s/^writeInterval .*/writeInterval 0.1;/" \
            "$f/system/controlDict"
        (cd "$f" && quiet blockMesh && quiet icoFoam)
    fi
fi
printf "%7s %7s %-10s %8s %10s %10s %8s %10s %8s\n" G aspect solver "max|U|" U_vs_conv U_vs_ico CPU_s us/p-step RSS_MiB
for G in $gradings; do
    c=$work/g$G
    tutorial "$c"
    sed -i "s/(20 20 1)/(8 8 1)/; s/simpleGrading (1 1 1)/simpleGrading ($G 1 1)/" "$c/system/blockMeshDict"
    sed -i "s/^deltaT .*/deltaT 0.005;/" "$c/system/controlDict"
    (cd "$c" && quiet blockMesh)
    [ -z "$extra" ] || printf 'UMPPM\n{\n    %s\n}\n' "$extra" >> "$c/system/fvSolution"
    mkdir -p "$c/ico" "$c/ref/0.5"
    cp -r "$c/0" "$c/constant" "$c/system" "$c/ico/"
    cp -r "$c/constant" "$c/system" "$c/ref/"
    if [ "$fine" != 0 ]; then
        (cd "$c/ref" && cp -r "$c/0" . && quiet mapFields "$work/fine$fine" -consistent -sourceTime 0.5 && cp 0/U 0.5/U)
    else
        cp "$top/tools/reference/graded_cavity_icoFoam160_t0.5/grading$G/U" "$c/ref/0.5/U" ||
            { echo "no stored reference for grading $G: use -fine 160" >&2; exit 1; }
    fi
    read -r _ irss _ < <(cd "$c/ico" && python3 "$top/bench/run_measured.py" -o log.icoFoam icoFoam)
    read -r _ rss rc < <(cd "$c" && python3 "$top/bench/run_measured.py" -o log.umppmFoam "$umppm")
    aspect=$(sed -n 's/.* is stretched \([0-9]*\):1.*/\1/p' "$c/log.umppmFoam" | head -1)
    if [ "$rc" != 0 ]; then
        printf "%7s %7s %-10s %s\n" "$G" "${aspect:--}" umppmFoam "failed: $(grep -m1 'FATAL' "$c/log.umppmFoam" | cut -c1-120)"
    else
        steps=$(grep -c '^Time = ' "$c/log.umppmFoam")
        np=$(grep -o 'Particles: [0-9]*' "$c/log.umppmFoam" | awk '{ s += $2; k++ } END { print int(s / k) }')
        sec=$(cpu "$c/log.umppmFoam")
        us=$(awk -v s="$sec" -v p="$np" -v k="$steps" 'BEGIN { printf "%.2f", 1e6 * s / (p * k) }')
        printf "%7s %7s %-10s %8s %10s %10s %8s %10s %8.0f\n" "$G" "${aspect:--}" umppmFoam "$(max_speed "$c/0.5/U")" \
            "$(rel "$c" "$c/ref")" "$(rel "$c" "$c/ico")" "$sec" "$us" "$rss"
    fi
    iu=$(awk -v s="$(cpu "$c/ico/log.icoFoam")" 'BEGIN { printf "%.2f", 1e6 * s / (64 * 100) }')
    printf "%7s %7s %-10s %8s %10s %10s %8s %10s %8.0f\n" "$G" "${aspect:--}" icoFoam "$(max_speed "$c/ico/0.5/U")" \
        "$(rel "$c/ico" "$c/ref")" 0 "$(cpu "$c/ico/log.icoFoam")" "$iu" "$irss"
done
echo "# cases in $work"
