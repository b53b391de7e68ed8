#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# bench/timeToAccuracy.sh [-endTime 40] [-ico "40 80 160"] [-umppm "40 64 80"]
#                         [-variants "UMPPMstar UMPPM"] [-work DIR] [-o FILE]
# Error against CPU seconds on the lid-driven cavity at Re 1000: OpenFOAM's
# icoFoam/cavity/cavity tutorial as bench/vsOpenFOAM.sh sets it (unit
# square, nu 0.001, its own fvSchemes/fvSolution/0/; scale 1), on N x N
# blockMesh quads, fixed deltaT = 0.5/N (lid Courant number 0.5), to
# endTime (default 40, close to steady). icoFoam (serial, the tutorial's
# PCG) on each N of -ico, umppmFoam (OMP_NUM_THREADS=1) with each variant on
# each N of -umppm (alpha 0.09 for UMPPM). Per run: N, solver, steps, mean
# particles, CPU s (user+sys, bench/run_usage.py), and the RMS error of u on
# x = 0.5 and of v on y = 0.5 against Ghia, Ghia & Shin (1982) (bin/ghiaCompare
# -Re 1000, the same sampling for both solvers); then, per solver, the
# cheapest run whose two RMS errors are both <= 0.01.
set -eu -o pipefail
top=$(cd "$(dirname "$0")/.." && pwd)
. "$top/bench/cases.sh" # cavity_case, setEntry; exports WM_PROJECT_DIR
endTime=40 ico="40 80 160" ump="40 64 80" variants="UMPPMstar UMPPM" work="" out=""
while [ $# -gt 0 ]; do
    case $1 in
    -endTime) endTime=$2; shift 2 ;;
    -ico) ico=$2; shift 2 ;;
    -umppm) ump=$2; shift 2 ;;
    -variants) variants=$2; shift 2 ;;
    -work) work=$2; shift 2 ;;
    -o) out=$2; shift 2 ;;
    *) echo "usage: bench/timeToAccuracy.sh [-endTime T] [-ico \"N ...\"] [-umppm \"N ...\"]" \
            "[-variants \"UMPPMstar UMPPM\"] [-work DIR] [-o FILE]" >&2; exit 1 ;;
    esac
done
make -C "$top" -s >/dev/null
work=${work:-$(mktemp -d "${TMPDIR:-/tmp}/umppm-tta.XXXXXX")}
mkdir -p "$work"
table=$work/table.txt
: > "$table"
base() { # base DIR N
    rm -rf "$1"
    cavity_case "$1" "$2" 0.001 || exit 1
    local dt steps
    dt=$(awk -v n="$2" 'BEGIN { printf "%.10g", 0.5 / n }')
    steps=$(awk -v t="$endTime" -v d="$dt" 'BEGIN { printf "%d", t / d + 0.5 }')
    setEntry "$1/system/controlDict" deltaT "$dt"
    setEntry "$1/system/controlDict" endTime "$endTime"
    setEntry "$1/system/controlDict" writeControl timeStep
    setEntry "$1/system/controlDict" writeInterval "$steps"
    (cd "$1" && blockMesh > log.blockMesh 2>&1) || { echo "blockMesh failed in $1" >&2; exit 1; }
}
run() { # run NAME DIR CMD...
    local name=$1 dir=$2
    shift 2
    read -r wall cpu rss _ rc < <(cd "$dir" && python3 "$top/bench/run_usage.py" -o log "$@")
    [ "$rc" = 0 ] || { echo "$name failed (exit $rc): see $dir/log" >&2; exit 1; }
    local steps np e
    steps=$(grep -c '^Time = ' "$dir/log")
    np=$({ grep -o 'Particles: [0-9]*' "$dir/log" || true; } | awk '{ s += $2; k++ } END { print k ? int(s / k) : "-" }')
    e=$("$top/bin/ghiaCompare" -Re 1000 "$dir" latestTime | awk '!/^#/ { print $3, $5 }')
    printf "%-22s %6s %9s %10.1f %8s %8s\n" "$name" "$steps" "$np" "$cpu" $e | tee -a "$table"
}
printf "# Re 1000 cavity, deltaT 0.5/N, endTime %s; %s\n" "$endTime" "$(date -u '+%F %T UTC')"
printf "%-22s %6s %9s %10s %8s %8s\n" run steps particles CPU_s u_rms v_rms
for n in $ico; do
    d=$work/ico-$n
    base "$d" "$n"
    run "icoFoam $n" "$d" icoFoam
done
for v in $variants; do
    for n in $ump; do
        d=$work/$v-$n
        base "$d" "$n"
        printf 'UMPPM { variant %s; alpha 0.09; }\n' "$v" >> "$d/system/fvSolution"
        run "umppmFoam $v $n" "$d" env OMP_NUM_THREADS=1 "$top/bin/umppmFoam"
    done
done
echo "# cheapest run with u_rms <= 0.01 and v_rms <= 0.01, per solver:"
for s in icoFoam umppmFoam; do
    awk -v s="$s" '$1 == s && $(NF-1) <= 0.01 && $NF <= 0.01 { if (!b || $(NF-2) < c) { b = $0; c = $(NF-2) } }
                   END { print "#   " s ": " (b ? b : "none reaches it") }' "$table"
done
[ -z "$out" ] || cp "$table" "$out"
echo "# work: $work"
