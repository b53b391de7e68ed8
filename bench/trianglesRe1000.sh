#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# bench/trianglesRe1000.sh [-umppm "key value; ..."] [-only REGEX] [-work DIR]
# The Re 1000 cavity (icoFoam's `cavity` as a unit square, nu 0.001, lid
# speed 1, t = 40, fixed deltaT, written every 2 s) on gmsh triangles,
# umppmFoam and icoFoam on the same mesh and step (README "Triangles at
# icoFoam's step, more meshes"). Meshes: tools/cavityTriangles.geo with
# h = 0.055, 0.04125 and 0.02578 (854, 1 476 and 3 552 cells) at deltaT
# 0.0125, 0.0125 and 0.01 (the steps of "Triangles at icoFoam's step"; the
# last also at 0.008), and tools/cavityTrianglesGraded.geo (3 588 cells)
# at 0.005. Prints per case the RMS
# errors from Ghia, Ghia & Shin (1982) of u on x = 0.5 and v on y = 0.5,
# each the mean over the writes t = 30 ... 40 (the runs are not yet steady)
# and at t = 40, for both solvers, umppmFoam's / icoFoam's ratio of the
# means, and the CPU seconds of each. -umppm adds entries to the UMPPM
# dictionary (e.g. "refillParticles 2;"); -only runs the cases whose name
# matches REGEX. One thread (OMP_NUM_THREADS=1 unless set); about 5
# minutes on one core. UMPPMFOAM=PATH runs that solver instead.
set -eu -o pipefail
top=$(cd "$(dirname "$0")/.." && pwd)
extra="" only=. work=""
. "$top/bench/cases.sh" # bench_options, bench_prepare, cavity_copy, cavity_triangles, logSeconds
bench_options "umppm extra only only work work" "$@"
bench_prepare trianglesRe1000
export OMP_NUM_THREADS=${OMP_NUM_THREADS:-1}
ghia=$bin/ghiaCompare

# name geo h deltaT
cases="tri854|cavityTriangles.geo|0.055|0.0125
tri1476|cavityTriangles.geo|0.04125|0.0125
tri3552|cavityTriangles.geo|0.02578125|0.01
tri3552dt0.008|cavityTriangles.geo|0.02578125|0.008
graded3588|cavityTrianglesGraded.geo|-|0.005"

# errors DIR: "u_mean v_mean u40 v40" over the writes t = 30, 32 ... 40
errors() {
    local t
    for t in 30 32 34 36 38 40; do
        "$ghia" -Re 1000 "$1" "$t" | tail -1 | awk '{ print $3, $5 }'
    done | awk '{ u += $1; v += $2; k++; lu = $1; lv = $2 }
        END { if (k == 6) printf "%.4f %.4f %.4f %.4f", u / k, v / k, lu, lv; else printf "- - - -" }'
}

printf "# Re 1000 cavity on triangles, t = 40; RMS from Ghia (u on x = 0.5, v on y = 0.5), mean over t = 30..40 and at t = 40\n"
printf "# UMPPM { %s }\n" "${extra:-}"
printf "%-15s %5s %7s | %7s %7s %7s %7s %6s | %7s %7s %7s %7s %6s | %6s %6s\n" case cells deltaT \
    u_mean v_mean u_40 v_40 cpu_s ico_um ico_vm ico_u40 ico_v40 ico_s u_rat v_rat
while IFS='|' read -r name geo h dt; do
    [[ $name =~ $only ]] || continue
    d=$work/$name
    cavity_copy "$d"
    setEntry "$d/constant/transportProperties" nu 0.001
    setEntry "$d/system/controlDict" deltaT "$dt"
    setEntry "$d/system/controlDict" endTime 40
    setEntry "$d/system/controlDict" writeControl runTime
    setEntry "$d/system/controlDict" writeInterval 2
    if [ "$h" = - ]; then cavity_triangles "$d" "$geo" || continue
    else cavity_triangles "$d" "$geo" "$h" || continue; fi
    [ -z "$extra" ] || echo "UMPPM { $extra }" >> "$d/system/fvSolution"
    cells=$(sed -n 's/.*nCells: *\([0-9]*\).*/\1/p' "$d/constant/polyMesh/owner" | head -n 1)
    mkdir -p "$d/ico"
    cp -r "$d/0" "$d/constant" "$d/system" "$d/ico/"
    (cd "$d/ico" && icoFoam > log.icoFoam 2>&1) || { echo "$name: icoFoam failed" >&2; continue; }
    if ! "$umppm" -case "$d" > "$d/log.umppmFoam" 2>&1; then
        echo "$name: umppmFoam failed: $(grep -m1 FATAL "$d/log.umppmFoam" | cut -c1-160)" >&2
        continue
    fi
    read -r um vm u4 v4 <<< "$(errors "$d")"
    read -r ium ivm iu4 iv4 <<< "$(errors "$d/ico")"
    printf "%-15s %5s %7s | %7s %7s %7s %7s %6s | %7s %7s %7s %7s %6s | %6s %6s\n" "$name" "$cells" "$dt" \
        "$um" "$vm" "$u4" "$v4" "$(logSeconds "$d/log.umppmFoam")" "$ium" "$ivm" "$iu4" "$iv4" "$(logSeconds "$d/ico/log.icoFoam")" \
        "$(awk -v a="$um" -v b="$ium" 'BEGIN { printf "%.2f", a / b }')" \
        "$(awk -v a="$vm" -v b="$ivm" 'BEGIN { printf "%.2f", a / b }')"
done <<< "$cases"
echo "# cases in $work"
