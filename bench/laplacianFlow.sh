#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# bench/laplacianFlow.sh [-Re 100] [-endTime 15] [-maxCo 0.25] [-mesh quad|tri]
#                        [-variant UMPPMstar] [-models "CPM IPS PS MPS"] [n ...]
# The lid-driven cavity against Ghia et al. (1982) with each particle
# Laplacian (UMPPM { laplacian ...; }) on n x n quads or gmsh triangles of
# about as many cells (tools/cavityValidate.sh, umppmFoam only), for each n
# (default 20 40 80). Prints one row per run (RMS and max errors of u on
# x = 0.5 and v on y = 0.5, cost), then per model the observed order of the
# RMS errors between successive n: the claim of Hwang, Ng & Sheu (2016)
# Section 4.4 is that CPM/IPS improve with refinement and PS does not.
set -eu -o pipefail
top=$(cd "$(dirname "$0")/.." && pwd)
Re=100 endTime=15 maxCo=0.25 mesh=quad variant=UMPPMstar models="CPM IPS PS MPS"
while [ $# -gt 0 ]; do
    case $1 in
    -Re) Re=$2; shift 2 ;; -endTime) endTime=$2; shift 2 ;; -maxCo) maxCo=$2; shift 2 ;;
    -mesh) mesh=$2; shift 2 ;; -variant) variant=$2; shift 2 ;; -models) models=$2; shift 2 ;;
    -*) echo "unknown option $1" >&2; exit 1 ;;
    *) break ;;
    esac
done
[ $# -gt 0 ] || set -- 20 40 80
make -C "$top" -s >/dev/null
work=${BENCH_WORK:-$(mktemp -d "${TMPDIR:-/tmp}/umppm-lapflow.XXXXXX")}
mkdir -p "$work"
printf "# lid-driven cavity Re=%s %s %s endTime=%s maxCo=%s (errors vs Ghia: u on x=0.5, v on y=0.5)\n" \
    "$Re" "$mesh" "$variant" "$endTime" "$maxCo"
printf "%-5s %4s %6s %7s %6s %8s %8s | %8s %8s %8s %8s\n" model n cells partcl steps seconds us/p-st \
    u_rms u_max v_rms v_max
rows=$work/rows.txt
: > "$rows"
for n in "$@"; do
    for m in $models; do
        d=$work/Re$Re-$mesh-n$n-$variant-$m
        rm -rf "$d"
        "$top/tools/cavityValidate.sh" -dir "$d" -Re "$Re" -mesh "$mesh" -n "$n" -variant "$variant" \
            -laplacian "$m" -endTime "$endTime" -maxCo "$maxCo" -icoFoam no > "$d.log" 2>&1 ||
            { echo "failed: $d.log" >&2; continue; }
        line=$(grep '^RESULT' "$d.log")
        get() { echo "$line" | tr ' ' '\n' | sed -n "s/^$1=//p"; }
        nps=$(grep -o '^Particles: [0-9]*' "$d/log.umppmFoam" | awk '{ s += $2 } END { print s }')
        us=$(awk -v s="$(get seconds)" -v p="$nps" 'BEGIN { printf "%.2f", 1e6 * s / p }')
        printf "%-5s %4s %6s %7s %6s %8s %8s | %8s %8s %8s %8s\n" "$m" "$n" "$(get cells)" \
            "$(get particles)" "$(get steps)" "$(get seconds)" "$us" \
            "$(get u_rms)" "$(get u_max)" "$(get v_rms)" "$(get v_max)"
        echo "$m $n $(get u_rms) $(get v_rms)" >> "$rows"
    done
done
for m in $models; do
    awk -v m="$m" '$1 == m { if (n0) printf "#   %-4s order %s->%s: u_rms %.2f  v_rms %.2f\n", m, n0, $2,
        log(u0 / $3) / log($2 / n0), log(v0 / $4) / log($2 / n0); n0 = $2; u0 = $3; v0 = $4 }' "$rows"
done
echo "# cases in $work"
