#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# bench/meshless.sh -- meshlessFoam (MPS and FPM) cost per particle-step against
# interFoam, on the Martin & Moyce dam break (tutorials/damBreakMartinMoyce:
# a 0.3 x 0.15 m tank, a water column a x 2a, a = 0.05715 m).
#
#   bench/meshless.sh [-n "10000 100000"] [-endTime 0.01] [-threads "1 2"]
#                     [-methods "MPS FPM"] [-work DIR] [-o FILE]
#
# For each target particle count N: the particle spacing l0 = sqrt(2 a^2 / N)
# and a blockMesh of square cells of side 2 l0 (meshlessFoam's default
# spacing, half the cell size, is then l0: about 4 particles per cell, the
# "matching resolution" of both solvers); setFields; meshlessFoam to endTime
# with each method (meshless { method ...; }, other settings at their
# defaults; FPM takes longer steps, Eqs. 26-27) on each thread count, interFoam (serial, the tutorial's settings) on the
# same mesh to the same time. Printed per run: particles (or cells), steps,
# set-up seconds (meshlessFoam's "Set-up" line), the wall seconds of the
# time loop (ClockTime of the last step minus the set-up, from the log),
# microseconds per particle-step (loop wall / steps / particles), peak RSS
# (/usr/bin/time -v), and the ratio of meshlessFoam's wall time to
# interFoam's for the same simulated time. Wall times are noisy here: run on
# an idle machine and compare ratios measured in one run.
set -eu -o pipefail
here=$(cd "$(dirname "$0")" && pwd)
top=$(cd "$here/.." && pwd)
ns="10000 100000" endTime=0.01 threads="1 2" methods="MPS FPM" work="" out=""
while [ $# -gt 0 ]; do
    case $1 in
        -n) ns=$2; shift 2 ;;
        -endTime) endTime=$2; shift 2 ;;
        -threads) threads=$2; shift 2 ;;
        -methods) methods=$2; shift 2 ;;
        -work) work=$2; shift 2 ;;
        -o) out=$2; shift 2 ;;
        *) echo "usage: bench/meshless.sh [-n \"10000 100000\"] [-endTime 0.01] [-threads \"1 2\"] [-methods \"MPS FPM\"] [-work DIR] [-o FILE]" >&2
           exit 1 ;;
    esac
done
ML=${MESHLESSFOAM:-$top/bin/meshlessFoam}
[ -x "$ML" ] || { echo "bench/meshless.sh: $ML missing (run make)" >&2; exit 1; }
export WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam}
[ -n "$work" ] || work=$(mktemp -d "${TMPDIR:-/tmp}/meshless-bench.XXXXXX")
mkdir -p "$work"
[ -z "$out" ] || exec > >(tee "$out")
a=0.05715
echo "# meshlessFoam vs interFoam, dam break (Martin & Moyce n^2 = 2), endTime $endTime s, $(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc --all) cores"
printf '%-12s %8s %7s %6s %9s %9s %12s %9s %8s\n' solver N steps thr setup_s loop_s us/part-step rss_MB vs_inter

# rss LOG: peak resident set of a /usr/bin/time -v log, in MB
rss() { awk '/Maximum resident set size/ { printf "%.0f", $NF / 1024 }' "$1"; }

for n in $ns; do
    l0=$(awk -v n="$n" -v a="$a" 'BEGIN { printf "%.6g", sqrt(2 * a * a / n) }')
    nx=$(awk -v l="$l0" 'BEGIN { printf "%d", 0.3 / (2 * l) + 0.5 }')
    ny=$(awk -v l="$l0" 'BEGIN { printf "%d", 0.15 / (2 * l) + 0.5 }')
    c=$work/n$n
    rm -rf "$c" && mkdir -p "$c"
    cp -r "$top/tutorials/damBreakMartinMoyce/"{0.orig,constant,system} "$c/"
    cp -r "$c/0.orig" "$c/0"
    sed -i "s/^nx .*/nx $nx;/; s/^ny .*/ny $ny;/" "$c/system/blockMeshDict"
    sed -i "s/^endTime .*/endTime $endTime;/; s/^writeInterval .*/writeInterval 100;/" "$c/system/controlDict"
    (cd "$c" && blockMesh > log.blockMesh 2>&1 && setFields > log.setFields 2>&1)
    cp -r "$c" "$c.interFoam"
    (cd "$c.interFoam" && /usr/bin/time -v interFoam > log.interFoam 2> log.time)
    isteps=$(grep -c '^Time = ' "$c.interFoam/log.interFoam")
    iwall=$(sed -n 's/.*ClockTime = \([0-9.]*\) s.*/\1/p' "$c.interFoam/log.interFoam" | tail -n 1)
    iexec=$(sed -n 's/^ExecutionTime = \([0-9.e+-]*\) s.*/\1/p' "$c.interFoam/log.interFoam" | tail -n 1)
    ncell=$((nx * ny))
    printf '%-12s %8d %7d %6d %9s %9s %12s %9s %8s\n' interFoam "$ncell" "$isteps" 1 - "$iexec" \
        "$(awk -v t="$iexec" -v s="$isteps" -v c="$ncell" 'BEGIN { printf "%.3g", 1e6 * t / s / c }')" \
        "$(rss "$c.interFoam/log.time")" 1
    for meth in $methods; do
    sed -i '/^meshless/,/^}/d' "$c/system/fvSolution"
    printf 'meshless\n{\n    method %s;\n}\n' "$meth" >> "$c/system/fvSolution"
    for th in $threads; do
        (cd "$c" && OMP_NUM_THREADS=$th /usr/bin/time -v "$ML" > "log.meshlessFoam.$meth.$th" 2> "log.time.$meth.$th")
        log=$c/log.meshlessFoam.$meth.$th
        np=$(sed -n 's/^    fluid: *\([0-9]*\).*/\1/p' "$log" | head -n 1)
        steps=$(grep -c '^Time = ' "$log")
        setup=$(sed -n 's/^Set-up: \([0-9.e+-]*\) s/\1/p' "$log")
        # the loop's wall time: the time loop's own stage total (wall column)
        loop=$(awk '/^    total/ { print $3 }' "$log" | tail -n 1)
        printf '%-12s %8d %7d %6d %9s %9s %12s %9s %8s\n' "meshless.$meth" "$np" "$steps" "$th" "$setup" "$loop" \
            "$(awk -v t="$loop" -v s="$steps" -v p="$np" 'BEGIN { printf "%.3g", 1e6 * t / s / p }')" \
            "$(rss "$c/log.time.$meth.$th")" \
            "$(awk -v m="$loop" -v i="$iexec" 'BEGIN { printf "%.2f", m / i }')"
    done
    done
done
echo "# work dir: $work"
