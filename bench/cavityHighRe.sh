#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# bench/cavityHighRe.sh [-Re 10000] [-n "64 96"] [-endTime 100] [-write W] [-mean T0]
#                       [-runs "umppm ico-linear ico-LUD ico-LLV"] [-work DIR]
# The high-Re lid-driven cavity on coarse meshes (issue 14, item 3): OpenFOAM's
# icoFoam cavity tutorial (blockMesh, its 0/, fvSolution) with scale 1, n x n
# cells, nu = 1/Re, fixed deltaT = 0.5/n (lid Courant number 0.5), endTime,
# run by
#   umppm       umppmFoam with its defaults (UMPPM*, CPM)
#   umppm-UMPPM umppmFoam, variant UMPPM (alpha 0.09)
#   ico-linear  icoFoam, the tutorial's Gauss linear
#   ico-LUD     icoFoam, div(phi,U) Gauss linearUpwind grad(U)
#   ico-LLV     icoFoam, div(phi,U) Gauss limitedLinearV 1
# one thread each, one after the other. Prints per run the RMS and max error
# against Ghia, Ghia & Shin (1982) of u on x = 0.5 and of v on y = 0.5
# (tools/ghiaCompare at the last time written) and the CPU seconds (user + sys of the
# solver). endTime 100 is not the steady state Ghia tabulates at Re 10 000:
# the rows compare the solvers at one instant of a developing flow. With
# -write W (W < endTime) the fields are also written every W, and the last
# two columns give u_rms and v_rms at endTime - W: equal to the endTime
# columns once the flow is steady. With -mean T0 the last two columns are
# instead u_rms and v_rms of the time-averaged field over the writes
# t >= T0 (ghiaCompare -mean), the measure for a run that does not settle
# (a coarse mesh at high Re can stay unsteady where Ghia's flow is steady).
# UMPPM_BIN: the directory of umppmFoam and ghiaCompare (default bin/).
set -eu -o pipefail
top=$(cd "$(dirname "$0")/.." && pwd)
Re=10000 ns="64 96" endTime=100 write="" mean="" runs="umppm ico-linear ico-LUD ico-LLV" work=""
while [ $# -gt 0 ]; do
    case $1 in
    -Re) Re=$2 ;; -n) ns=$2 ;; -endTime) endTime=$2 ;; -write) write=$2 ;; -mean) mean=$2 ;;
    -runs) runs=$2 ;;
    -work) work=$2 ;;
    *) echo "unknown option $1" >&2; exit 1 ;;
    esac
    shift 2
done
write=${write:-$endTime}
make -C "$top" -s >/dev/null
. "$top/bench/cases.sh" # cavity_case, setEntry; exports WM_PROJECT_DIR
work=${work:-$(mktemp -d "${TMPDIR:-/tmp}/umppm-highRe.XXXXXX")}
mkdir -p "$work"
printf "# cavity Re %s, t = %s, lid Courant number 0.5, one thread; errors against Ghia et al. (1982); work %s\n" \
    "$Re" "$endTime" "$work"
if [ -n "$mean" ]; then c1=u_rms_mean c2=v_rms_mean; else c1=u_rms_prev c2=v_rms_prev; fi
printf "%5s %-12s %8s %8s %8s %8s %9s %10s %10s\n" n run u_rms u_max v_rms v_max CPU_s "$c1" "$c2"
for n in $ns; do
    base=$work/mesh$n
    if [ ! -f "$base/constant/polyMesh/owner" ]; then
        rm -rf "$base"
        (cavity_case "$base" "$n" "$(awk -v r="$Re" 'BEGIN { print 1 / r }')" &&
            setEntry "$base/system/controlDict" deltaT "$(awk -v n="$n" 'BEGIN { print 0.5 / n }')" &&
            setEntry "$base/system/controlDict" endTime "$endTime" &&
            setEntry "$base/system/controlDict" writeControl runTime &&
            setEntry "$base/system/controlDict" writeInterval "$write" &&
            cd "$base" && blockMesh > log.blockMesh 2>&1) || { echo "mesh $n failed" >&2; exit 1; }
    fi
    for r in $runs; do
        d=$work/n$n-$r
        if [ ! -f "$d/cpu.txt" ]; then
            rm -rf "$d" && cp -r "$base" "$d"
            case $r in
            umppm) cmd=("${UMPPM_BIN:-$top/bin}/umppmFoam") ;;
            umppm-UMPPM) printf 'UMPPM { variant UMPPM; alpha 0.09; }\n' >> "$d/system/fvSolution"
                cmd=("${UMPPM_BIN:-$top/bin}/umppmFoam") ;;
            ico-linear) cmd=(icoFoam) ;;
            ico-LUD) foamDictionary "$d/system/fvSchemes" -entry divSchemes/div\(phi,U\) \
                    -set "Gauss linearUpwind grad(U)" > /dev/null; cmd=(icoFoam) ;;
            ico-LLV) foamDictionary "$d/system/fvSchemes" -entry divSchemes/div\(phi,U\) \
                    -set "Gauss limitedLinearV 1" > /dev/null; cmd=(icoFoam) ;;
            *) echo "unknown run $r" >&2; exit 1 ;;
            esac
            (cd "$d" && OMP_NUM_THREADS=1 /usr/bin/time -f "%U %S" -o cpu.run "${cmd[@]}" > log.run 2>&1) ||
                { echo "failed: $r on $n (log $d/log.run)" >&2; continue; }
            mv "$d/cpu.run" "$d/cpu.txt"
        fi
        # deltaT 0.5/n: the last time is 99.999936 for n = 96
        times=$(foamListTimes -case "$d" 2> /dev/null)
        t=$(echo "$times" | tail -1) tp=$(echo "$times" | tail -2 | head -1)
        read -r _ _ urms umax vrms vmax < <("${UMPPM_BIN:-$top/bin}/ghiaCompare" -Re "$Re" "$d" "$t" | tail -1)
        up=- vp=-
        if [ -n "$mean" ]; then
            args=()
            for w in $times; do
                awk -v w="$w" -v t0="$mean" 'BEGIN { exit !(w >= t0 - 1e-9) }' && args+=("$d" "$w")
            done
            read -r _ _ _ up _ vp _ < <("${UMPPM_BIN:-$top/bin}/ghiaCompare" -Re "$Re" -mean "${args[@]}" | tail -1)
            up="$up/$((${#args[@]} / 2))"
        elif [ "$tp" != "$t" ]; then
            read -r _ _ up _ vp _ < <("${UMPPM_BIN:-$top/bin}/ghiaCompare" -Re "$Re" "$d" "$tp" | tail -1)
        fi
        printf "%5s %-12s %8s %8s %8s %8s %9s %10s %10s\n" "$n" "$r" "$urms" "$umax" "$vrms" "$vmax" \
            "$(awk '{ printf "%.1f", $1 + $2 }' "$d/cpu.txt")" "$up" "$vp"
    done
done
