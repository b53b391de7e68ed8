#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# bench/trianglesRe1000.sh [-umppm "key value; ..."] [-only REGEX] [-mesh "H DT"] [-work DIR]
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
# -mesh "H DT": instead of the list, one mesh of tools/cavityTriangles.geo
# with h = H at deltaT DT (a mesh the README's figures were not tuned on).
# -steady yes: neither run has settled at t = 30 ... 40 (icoFoam's error
# still falls by 10-20 % there), so this runs both to t = 120, written
# every 10, and prints the RMS errors of umppmFoam's time-averaged field
# over the writes t = 50 ... 120 (ghiaCompare -mean: umppmFoam's field
# does not settle, its writes scatter by about 10 %) and of the mean of
# its single writes, beside icoFoam's at t = 120 (settled: the same to 4
# digits from t = 80 on); about 25 minutes on one core.
set -eu -o pipefail
top=$(cd "$(dirname "$0")/.." && pwd)
extra="" only=. work="" steady=no mesh=""
. "$top/bench/cases.sh" # bench_options, bench_prepare, cavity_copy, cavity_triangles, logSeconds
bench_options "umppm extra only only work work steady steady mesh mesh" "$@"
case $steady in yes | no) ;; *) echo "-steady must be yes or no" >&2; exit 1 ;; esac
bench_prepare trianglesRe1000
export OMP_NUM_THREADS=${OMP_NUM_THREADS:-1}
ghia=$bin/ghiaCompare

# name geo h deltaT
cases="tri854|cavityTriangles.geo|0.055|0.0125
tri1476|cavityTriangles.geo|0.04125|0.0125
tri3552|cavityTriangles.geo|0.02578125|0.01
tri3552dt0.008|cavityTriangles.geo|0.02578125|0.008
graded3588|cavityTrianglesGraded.geo|-|0.005"
if [ -n "$mesh" ]; then
    read -r mh mdt <<< "$mesh"
    [ -n "${mdt:-}" ] || { echo "-mesh needs \"H DT\"" >&2; exit 1; }
    cases="h$mh|cavityTriangles.geo|$mh|$mdt"
fi

# errors DIR: "u_mean v_mean u40 v40" over the writes t = 30 ... 40 (the
# last one's as u40 v40)
errors() {
    ghia_writes "$1" 29.9 40.1 | awk '{ u += $2; v += $3; k++; lu = $2; lv = $3 }
        END { if (k >= 6) printf "%.4f %.4f %.4f %.4f", u / k, v / k, lu, lv; else printf "- - - -" }'
}

# steady_errors DIR: "u_avg v_avg u_single v_single": the errors of the
# field averaged over the writes t = 50, 60 ... 120 and the mean of the
# single writes' errors
steady_errors() {
    local t a=() times="50 60 70 80 90 100 110 120"
    for t in $times; do a+=("$1" "$t"); done
    {
        "$ghia" -Re 1000 -mean "${a[@]}" | tail -1 | awk '$1 == "mean" && $2 == 8 { print "avg", $4, $6 }'
        for t in $times; do "$ghia" -Re 1000 "$1" "$t" | tail -1; done |
            awk '{ u += $3; v += $5; k++ } END { if (k == 8) print "single", u / k, v / k }'
    } | awk '$1 == "avg" { ua = $2; va = $3 } $1 == "single" { us = $2; vs = $3 }
        END { if (ua == "" || us == "") printf "- - - -"; else printf "%.4f %.4f %.4f %.4f", ua, va, us, vs }'
}

if [ "$steady" = yes ]; then
    printf "# Re 1000 cavity on triangles, t = 120; RMS from Ghia (u on x = 0.5, v on y = 0.5): umppmFoam's field averaged over the writes t = 50..120 and the mean of its single writes' errors; icoFoam's at t = 120\n"
else
    printf "# Re 1000 cavity on triangles, t = 40; RMS from Ghia (u on x = 0.5, v on y = 0.5), mean over t = 30..40 and at t = 40\n"
fi
printf "# UMPPM { %s }\n" "${extra:-}"
row="%-15s %5s %7s | %7s %7s %7s %7s %6s | %7s %7s %7s %7s %6s | %6s %6s\n"
if [ "$steady" = yes ]; then
    printf "$row" case cells deltaT u_avg v_avg u_single v_single cpu_s ico_u ico_v ico_u ico_v ico_s u_rat v_rat
else
    printf "$row" case cells deltaT u_mean v_mean u_40 v_40 cpu_s ico_um ico_vm ico_u40 ico_v40 ico_s u_rat v_rat
fi
while IFS='|' read -r name geo h dt; do
    [[ $name =~ $only ]] || continue
    d=$work/$name
    cavity_copy "$d"
    setEntry "$d/constant/transportProperties" nu 0.001
    setEntry "$d/system/controlDict" deltaT "$dt"
    setEntry "$d/system/controlDict" writeControl runTime
    if [ "$steady" = yes ]; then
        setEntry "$d/system/controlDict" endTime 120
        setEntry "$d/system/controlDict" writeInterval 10
    else
        setEntry "$d/system/controlDict" endTime 40
        setEntry "$d/system/controlDict" writeInterval 2
    fi
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
    if [ "$steady" = yes ]; then
        # columns: averaged field, mean of the single writes; icoFoam at t = 120 twice
        read -r um vm u4 v4 <<< "$(steady_errors "$d")"
        read -r ium ivm <<< "$("$ghia" -Re 1000 "$d/ico" 120 | tail -1 | awk '{ printf "%.4f %.4f", $3, $5 }')"
        iu4=$ium iv4=$ivm
    else
        read -r um vm u4 v4 <<< "$(errors "$d")"
        read -r ium ivm iu4 iv4 <<< "$(errors "$d/ico")"
    fi
    printf "$row" "$name" "$cells" "$dt" \
        "$um" "$vm" "$u4" "$v4" "$(logSeconds "$d/log.umppmFoam")" "$ium" "$ivm" "$iu4" "$iv4" "$(logSeconds "$d/ico/log.icoFoam")" \
        "$(awk -v a="$um" -v b="$ium" 'BEGIN { printf "%.2f", a / b }')" \
        "$(awk -v a="$vm" -v b="$ivm" 'BEGIN { printf "%.2f", a / b }')"
done <<< "$cases"
echo "# cases in $work"
