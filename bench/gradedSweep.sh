#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# bench/gradedSweep.sh [-n "10 16 24 32 48 64"] [-gradings "1000 1 1|..."] [-dt 0.005]
#                      [-icoFoam yes] [-umppm "key value; ..."] [-work DIR]
# Boundedness on stretched cells (README "Graded toward the lid's
# downstream corner"): OpenFOAM's icoFoam cavity (Re 10, lid speed 1) on
# N x N cells for each N and each blockMesh simpleGrading of the list
# (separated by |; default: the smallest cells at the lid's upstream corner
# (1000 1 1), (10000 1 1); at the downstream wall (0.001 1 1); at the lid
# (1 0.001 1); at the lid's downstream corner (0.001 0.001 1); at the
# bottom-left corner (1000 1000 1); toward all four walls, two-sided
# ((0.5 0.5 1000) (0.5 0.5 0.001)) in x and in y), run to t = 0.5 at
# deltaT DT, written every 0.025 s. Prints per mesh the largest cell aspect ratio, max |U| over
# the writes (the issue's bound: 1.05 x the lid speed), with -icoFoam yes
# icoFoam's on the same mesh and step ("diverged" when it stops early), and
# at the end the count of meshes above 1.05.
# UMPPMFOAM=PATH runs that solver instead of bin/umppmFoam (another build).
set -eu -o pipefail
top=$(cd "$(dirname "$0")/.." && pwd)
sizes="10 16 24 32 48 64" dt=0.005 ico=no extra="" work=""
allwalls="((0.5 0.5 1000) (0.5 0.5 0.001)) ((0.5 0.5 1000) (0.5 0.5 0.001)) 1"
gradings="1000 1 1|10000 1 1|0.001 1 1|1 0.001 1|0.001 0.001 1|1000 1000 1|$allwalls"
. "$top/bench/cases.sh" # bench_options, bench_prepare, cavity_copy, max_speed
bench_options "n sizes gradings gradings dt dt icoFoam ico umppm extra work work" "$@"
bench_prepare sweep
# max |U| over the time directories 0.* of case $1
max_over() {
    local f
    for f in "$1"/0.*/U; do
        if [ -f "$f" ]; then max_speed "$f" '%.4f\n'; fi
    done | sort -g | tail -1
}
printf "%-5s %-16s %8s %10s %10s\n" N simpleGrading aspect umppmFoam icoFoam
over=0 total=0
IFS='|' read -r -a glist <<< "$gradings"
for n in $sizes; do
    for g in "${glist[@]}"; do
        c=$work/n${n}_$(echo "$g" | tr -d '()' | tr ' .' '_p')
        cavity_copy "$c" || exit 1
        sed -i "s/(20 20 1)/($n $n 1)/; s/simpleGrading (1 1 1)/simpleGrading ($g)/" "$c/system/blockMeshDict"
        sed -i "s/^deltaT .*/deltaT $dt;/; s/^writeControl .*/writeControl runTime;/; s/^writeInterval .*/writeInterval 0.025;/" \
            "$c/system/controlDict"
        [ -z "$extra" ] || printf 'UMPPM { %s }\n' "$extra" >> "$c/system/fvSolution"
        (cd "$c" && blockMesh > log.blockMesh 2>&1) || { echo "blockMesh failed in $c" >&2; exit 1; }
        if [ "$ico" = yes ]; then
            mkdir -p "$c/ico" && cp -r "$c/0" "$c/constant" "$c/system" "$c/ico/"
        fi
        "$umppm" -case "$c" > "$c/log.umppmFoam" 2>&1 || { echo "umppmFoam failed in $c" >&2; exit 1; }
        aspect=$(awk '/is stretched/ { for (i = 1; i <= NF; i++) if ($i ~ /^[0-9.]+:1$/) { sub(/:1/, "", $i); print $i; exit } }
                      END {}' "$c/log.umppmFoam")
        um=$(max_over "$c")
        ic=-
        if [ "$ico" = yes ]; then
            if (cd "$c/ico" && icoFoam > log.icoFoam 2>&1) 2> /dev/null && [ -d "$c/ico/0.5" ]; then ic=$(max_over "$c/ico"); else ic=diverged; fi
        fi
        shown="($g)"
        [ "$g" != "$allwalls" ] || shown="all four walls"
        printf "%-5s %-16s %8s %10s %10s\n" "$n" "$shown" "${aspect:-<20}" "$um" "$ic"
        total=$((total + 1))
        over=$((over + $(awk -v u="$um" 'BEGIN { print (u > 1.05) }')))
    done
done
echo "meshes above 1.05 x the lid speed: $over of $total (work dir $work)"
