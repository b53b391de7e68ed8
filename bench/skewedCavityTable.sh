#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# bench/skewedCavityTable.sh [-endTime 10] [-alpha 0.05] [-work DIR] [lc ...]
# Table 1 of Ng, Sheu & Hwang (2016): CPU time and particle count
# at t = endTime of the lid-driven skewed cavity (Re 1000, 15 deg,
# tutorials/skewedCavity) for UMPPM* and UMPPM (alpha 0.05), maxCo 0.5, for
# each average cell size lc (default 0.04 0.02 0.01 0.005), plus icoFoam on
# the same mesh (fixed deltaT = UMPPM's last adjusted step, Courant ~0.5).
# One mesh per lc (tutorials/skewedCavity/skewedCavity.geo), the three runs
# on copies of it. CPU seconds = user + system time of the process and peak
# RSS, from /usr/bin/time -v when installed (else umppmFoam's/icoFoam's own
# ExecutionTime and no RSS); U L2rel = foamCompare's relative L2 of U
# against icoFoam at endTime. Cases are kept in DIR (default a new
# directory under /tmp).
set -eu -o pipefail
top=$(cd "$(dirname "$0")/.." && pwd)
tut=$top/tutorials/skewedCavity
endTime=10 alpha=0.05 work=""
usage() {
    sed -n '3p' "$0" | sed 's/^# \{0,1\}//' >&2
    exit 1
}
while [ $# -gt 0 ]; do
    case $1 in
    -endTime | -alpha | -work) [ $# -ge 2 ] || usage ;;&
    -endTime) endTime=$2; shift 2 ;;
    -alpha) alpha=$2; shift 2 ;;
    -work) work=$2; shift 2 ;;
    -*) usage ;;
    *) break ;;
    esac
done
[ $# -gt 0 ] || set -- 0.04 0.02 0.01 0.005
. "$tut/../RunFunctions"
[ -x "$UMPPMFOAM" ] || { echo "skewedCavityTable.sh: $UMPPMFOAM missing (run make)" >&2; exit 1; }
work=${work:-$(mktemp -d "${TMPDIR:-/tmp}/umppm-skewed.XXXXXX")}
mkdir -p "$work"
timev=no
/usr/bin/time -v true > /dev/null 2>&1 && timev=yes

# measure DIR APP LOG: run APP in DIR with output in DIR/LOG; prints
# "<cpu seconds> <peak RSS MiB or ->"
measure() {
    local dir=$1 app=$2 log=$3 exe=$2
    [ "$app" = umppmFoam ] && exe=$UMPPMFOAM
    if [ $timev = yes ]; then
        (cd "$dir" && /usr/bin/time -v -o time.log "$exe" > "$log" 2>&1) ||
            { echo "skewedCavityTable.sh: $app failed in $dir" >&2; tail -5 "$dir/$log" >&2; return 1; }
        awk -F': ' '/User time/ { u = $2 } /System time/ { s = $2 } /Maximum resident/ { r = $2 }
            END { printf "%.2f %.1f\n", u + s, r / 1024 }' "$dir/time.log"
    else
        (cd "$dir" && "$exe" > "$log" 2>&1) ||
            { echo "skewedCavityTable.sh: $app failed in $dir" >&2; tail -5 "$dir/$log" >&2; return 1; }
        echo "$(grep '^ExecutionTime = ' "$dir/$log" | tail -1 | awk '{ print $3 }') -"
    fi
}

echo "# lid-driven skewed cavity, Re 1000, 15 deg, maxCo 0.5, t = $endTime s; UMPPM alpha = $alpha"
echo "# machine: $(lscpu | sed -n 's/^Model name: *//p' | awk 'NR == 1'), $(nproc) CPUs; serial runs, one at a time"
echo "# CPU s = user + sys$([ $timev = yes ] || echo ' (ExecutionTime: /usr/bin/time -v not installed)'); N_p = particles at t = $endTime; RSS = peak MiB; L2 = relative L2 of U vs icoFoam"
echo "# paper (Xeon E5-1640V2 3.7 GHz): lc 0.04: 16.22 s/157, 18.02 s/199; 0.02: 45.04/589, 53.63/825;"
echo "#   0.01: 229.17/2549, 328.64/3964; 0.005: 1792.86/9920, 2557.11/16802; 0.0025: 25987.41/39395, 35355.43/71246"
printf "%7s %7s %6s | %9s %7s %6s %6s | %9s %7s %6s %6s | %8s %6s %6s\n" \
    lc l_avg N_m "UMPPM*_s" N_p RSS L2 "UMPPM_s" N_p RSS L2 ico_s RSS ico_dt
for lc in "$@"; do
    d=$work/lc$lc
    rm -rf "$d" && mkdir -p "$d/mesh"
    cp -r "$tut/0.orig" "$tut/constant" "$tut/system" "$tut/skewedCavity.geo" "$d/mesh/"
    (cd "$d/mesh" && runGmshMesh skewedCavity.geo "$lc" > /dev/null &&
        foamDictionary system/controlDict -entry endTime -set "$endTime" > /dev/null &&
        foamDictionary system/controlDict -entry writeInterval -set "$endTime" > /dev/null &&
        foamDictionary system/fvSolution -entry UMPPM/alpha -set "$alpha" > /dev/null)
    declare -A cpu rss np l2
    for v in UMPPMstar UMPPM; do
        c=$d/$v
        cp -r "$d/mesh" "$c" && cp -r "$c/0.orig" "$c/0"
        foamDictionary "$c/system/fvSolution" -entry UMPPM/variant -set "$v" > /dev/null
        read -r cpu[$v] rss[$v] < <(measure "$c" umppmFoam log.umppmFoam)
        np[$v]=$(grep '^Particles: ' "$c/log.umppmFoam" | tail -1 | awk '{ print $2 }')
    done
    cells=$(awk '/^\$Elements/ { f = 1; getline; next } /^\$EndElements/ { f = 0 }
        f && ($2 == 5 || $2 == 6) { n++ } END { print n }' "$d/mesh/skewedCavity.msh")
    lavg=$(awk -v n="$cells" 'BEGIN { printf "%.4f", sqrt(sin(15 * atan2(0, -1) / 180) / n) }')
    dtU=$(sed -n 's/^deltaT = //p' "$d/UMPPM/log.umppmFoam" | tail -1)
    dtI=$(awk -v t="$endTime" -v dd="$dtU" 'BEGIN { n = int(t / dd); if (n * dd < t) n++; printf "%.10g", t / n }')
    (cd "$d/mesh" && referenceCase ../icoFoam)
    # sed: foamDictionary -set would round deltaT to 6 digits
    sed -i -e "s/^application .*/application     icoFoam;/" -e "s/^adjustTimeStep .*/adjustTimeStep  no;/" \
        -e "s/^deltaT .*/deltaT          $dtI;/" "$d/icoFoam/system/controlDict"
    read -r icpu irss < <(measure "$d/icoFoam" icoFoam log.icoFoam)
    ilast=$(ls -d "$d/icoFoam"/[0-9]* | sed 's|.*/||' | sort -g | tail -1)
    for v in UMPPMstar UMPPM; do
        last=$(ls -d "$d/$v"/[0-9]* | sed 's|.*/||' | sort -g | tail -1)
        l2[$v]=$("$UMPPM_BIN/foamCompare" "$d/$v" "$last" "$d/icoFoam" "$ilast" U | awk '$1 == "U" { print $4 }')
    done
    printf "%7s %7s %6s | %9s %7s %6s %6s | %9s %7s %6s %6s | %8s %6s %6s\n" "$lc" "$lavg" "$cells" \
        "${cpu[UMPPMstar]}" "${np[UMPPMstar]}" "${rss[UMPPMstar]}" "${l2[UMPPMstar]}" \
        "${cpu[UMPPM]}" "${np[UMPPM]}" "${rss[UMPPM]}" "${l2[UMPPM]}" "$icpu" "$irss" "$(printf %.4g "$dtI")"
done
echo "# cases in $work"
