#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# bench/cavityGhia.sh [-Re 100] [-n 32] [-endTime 20] [-maxCo 0.25] [-meshes "quad tri"] [-variants "UMPPMstar UMPPM"]
# Lid-driven cavity against Ghia et al. (1982) for each mesh type and UMPPM
# variant (tools/cavityValidate.sh: umppmFoam and icoFoam on the same mesh).
# Prints one row per run: errors on the centrelines (RMS and max of u on
# x = 0.5 and of v on y = 0.5), the same for icoFoam, the cell-by-cell
# difference of U to icoFoam (relative L2, Linf), cost and continuity.
set -eu -o pipefail
top=$(cd "$(dirname "$0")/.." && pwd)
Re=100 n=32 endTime=20 maxCo=0.25 meshes="quad tri" variants="UMPPMstar UMPPM"
while [ $# -gt 0 ]; do
    case $1 in
    -Re) Re=$2 ;; -n) n=$2 ;; -endTime) endTime=$2 ;; -maxCo) maxCo=$2 ;;
    -meshes) meshes=$2 ;; -variants) variants=$2 ;;
    *) echo "unknown option $1" >&2; exit 1 ;;
    esac
    shift 2
done
make -C "$top" -s >/dev/null
work=${BENCH_WORK:-$(mktemp -d "${TMPDIR:-/tmp}/umppm-ghia.XXXXXX")}
mkdir -p "$work"
printf "# lid-driven cavity Re=%s n=%s endTime=%s maxCo=%s (errors vs Ghia: u on x=0.5, v on y=0.5)\n" "$Re" "$n" "$endTime" "$maxCo"
printf "%-5s %-9s %6s %7s %6s %8s %8s %7s | %7s %7s %7s %7s | %7s %7s %7s %7s %6s %7s | %7s %7s | %8s\n" \
    mesh variant cells partcl steps seconds us/p-st RSS_MiB u_rms u_max v_rms v_max ico_urms ico_umax ico_vrms ico_vmax \
    ico_s ratio UvIcoL2 UvIcoLi cont_max
for mesh in $meshes; do
    for v in $variants; do
        d=$work/Re$Re-$mesh-n$n-$v
        rm -rf "$d"
        "$top/tools/cavityValidate.sh" -dir "$d" -Re "$Re" -mesh "$mesh" -n "$n" -variant "$v" \
            -endTime "$endTime" -maxCo "$maxCo" > "$d.log" 2>&1 || { echo "failed: $d.log" >&2; continue; }
        line=$(grep '^RESULT' "$d.log")
        get() { echo "$line" | tr ' ' '\n' | sed -n "s/^$1=//p"; }
        nps=$(grep -o '^Particles: [0-9]*' "$d/log.umppmFoam" | awk '{ s += $2 } END { print s }')
        us=$(awk -v s="$(get seconds)" -v p="$nps" 'BEGIN { printf "%.2f", 1e6 * s / p }')
        rss=$(get rss_MiB)
        ratio=$(awk -v a="$(get seconds)" -v b="$(get ico_seconds)" 'BEGIN { printf "%.1f", a / b }')
        printf "%-5s %-9s %6s %7s %6s %8s %8s %7s | %7s %7s %7s %7s | %7s %7s %7s %7s %6s %7s | %7.4f %7.4f | %8.2g\n" \
            "$mesh" "$v" "$(get cells)" "$(get particles)" "$(get steps)" "$(get seconds)" "$us" "${rss:--}" \
            "$(get u_rms)" "$(get u_max)" "$(get v_rms)" "$(get v_max)" \
            "$(get ico_u_rms)" "$(get ico_u_max)" "$(get ico_v_rms)" "$(get ico_v_max)" "$(get ico_seconds)" "$ratio" \
            "$(get UvsIco_L2rel)" "$(get UvsIco_Linfrel)" "$(get cont_max)"
    done
done
echo "# cases in $work"
