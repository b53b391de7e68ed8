#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# bench/laplacianAccuracy.sh [-out DIR] [-seed 1]
# The particle-Laplacian experiments of Hwang, Ng & Sheu (2016) [HNS16],
# Section 4, for CPM, IPS, PS and MPS with tools/laplacianAccuracy, on
# irregular clouds x = (i + alpha (chi - 0.5)) dx (Eqs. 35, 41, 45), r_e = 2 dx.
# Prints tables and writes gnuplot PNGs to DIR (default build/bench/laplacian):
#   1. Laplacian of prod sin(2 pi x_d), relative L2 error vs nC (alpha 0.3),
#      1-, 2-, 3-D, with observed orders ([HNS16] Figs. 5a, 13a, 18a):
#      lap_operator_<d>D.png
#   2. the same vs alpha (nC 128, 64, 32; Figs. 5b, 13b, 18b):
#      lap_alpha_<d>D.png
#   3. PS artificial cell Reynolds number and IPS diffusivity vs alpha
#      (Figs. 3b, 4, 8, 17) in the table of 2.
#   4. pure diffusion, explicit Euler, C_D = 1, error (Eq. 40) vs time
#      (Figs. 7, 14, 19): lap_diffusion_<d>D.png, and vs nC at t = 0.02.
#   5. the three-point problem (Fig. 1b): reality factor vs alpha,
#      lap_threepoint.png.
set -eu -o pipefail
top=$(cd "$(dirname "$0")/.." && pwd)
out=$top/build/bench/laplacian seed=1
while [ $# -gt 0 ]; do
    case $1 in
    -out) out=$2; shift 2 ;; -seed) seed=$2; shift 2 ;;
    *) echo "unknown option $1" >&2; exit 1 ;;
    esac
done
make -C "$top" -s >/dev/null
la=$top/bin/laplacianAccuracy
mkdir -p "$out"
models="CPM IPS PS MPS"
kv() { tr ' ' '\n' | sed -n "s/^$1=//p"; }
have_gnuplot=yes
command -v gnuplot >/dev/null || { have_gnuplot=no; echo "# gnuplot not found: tables only"; }

plot() { # plot PNG TITLE XLABEL YLABEL LOGX LOGY DATA USING...
    [ "$have_gnuplot" = yes ] || return 0
    local png=$1 title=$2 xl=$3 yl=$4 lx=$5 ly=$6 data=$7
    shift 7
    {
        echo "set terminal pngcairo size 800,560; set output '$png'"
        echo "set title '$title'; set xlabel '$xl'; set ylabel '$yl'; set key outside right; set grid"
        [ "$lx" = yes ] && echo "set logscale x 2"
        [ "$ly" = yes ] && echo "set logscale y"
        printf 'plot '
        local first=1
        for u in "$@"; do
            [ $first = 1 ] || printf ', '
            printf "'%s' %s" "$data" "$u"
            first=0
        done
        echo
    } | gnuplot
}

echo "# 1. Laplacian of prod sin(2 pi x_d): relative L2 error vs nC, alpha 0.3, seed $seed"
for d in 1 2 3; do
    case $d in 1) ns="8 16 32 64 128 256" ;; 2) ns="8 16 32 64 128" ;; 3) ns="8 16 32 64" ;; esac
    dat=$out/operator_${d}D.dat
    echo "# nC points nbrs $models ReN tauxx" > "$dat"
    printf "%dD %5s %8s %6s | %10s %10s %10s %10s | %8s %8s\n" "$d" nC points nbrs $models ReN tau_xx
    for n in $ns; do
        res=$("$la" operator -dim "$d" -nC "$n" -alpha 0.3 -seed "$seed")
        row="$n $(echo "$res" | head -1 | kv points) $(echo "$res" | head -1 | kv nbrs)"
        for m in $models; do row="$row $(echo "$res" | grep "model=$m " | kv L2rel)"; done
        row="$row $(echo "$res" | head -1 | kv ReN) $(echo "$res" | head -1 | kv tauxx)"
        echo "$row" >> "$dat"
        echo "$row" | awk -v d="$d" '{ printf "%dD %5s %8s %6.2f | %10.3e %10.3e %10.3e %10.3e | %8.4f %8.4f\n", d, $1, $2, $3, $4, $5, $6, $7, $8, $9 }'
    done
    awk -v d="$d" 'NR > 1 { if (n0) { printf "#   %dD order %s->%s:", d, n0, $1; split("CPM IPS PS MPS", M, " ")
        for (k = 1; k <= 4; k++) printf " %s %.2f", M[k], log(e[k] / $(k + 3)) / log($1 / n0); print "" }
        n0 = $1; for (k = 1; k <= 4; k++) e[k] = $(k + 3) }' "$dat"
    plot "$out/lap_operator_${d}D.png" "${d}-D Laplacian of a sine product, alpha = 0.3" nC "relative L2 error" yes yes "$dat" \
        "u 1:4 w lp t 'CPM'" "u 1:5 w lp t 'IPS'" "u 1:6 w lp t 'PS'" "u 1:7 w lp t 'MPS'"
done

echo
echo "# 2./3. the same vs the irregularity alpha (PS artificial cell Reynolds number ReN, IPS tau)"
for d in 1 2 3; do
    case $d in 1) n=128 ;; 2) n=64 ;; 3) n=32 ;; esac
    dat=$out/alpha_${d}D.dat
    echo "# alpha $models ReN tauxx tauxxdev tauxy" > "$dat"
    printf "%dD nC=%-4s %5s | %10s %10s %10s %10s | %8s %8s %9s %9s\n" "$d" "$n" alpha $models ReN tau_xx rms_xx-1 rms_xy
    for a in 0 0.1 0.2 0.3 0.4 0.5 0.6 0.7 0.8 0.9; do
        res=$("$la" operator -dim "$d" -nC "$n" -alpha "$a" -seed "$seed")
        row="$a"
        for m in $models; do row="$row $(echo "$res" | grep "model=$m " | kv L2rel)"; done
        l=$(echo "$res" | head -1)
        row="$row $(echo "$l" | kv ReN) $(echo "$l" | kv tauxx) $(echo "$l" | kv tauxxdev) $(echo "$l" | kv tauxy)"
        echo "$row" >> "$dat"
        echo "$row" | awk -v d="$d" -v n="$n" '{ printf "%dD nC=%-4s %5s | %10.3e %10.3e %10.3e %10.3e | %8.4f %8.4f %9.3e %9.3e\n", d, n, $1, $2, $3, $4, $5, $6, $7, $8, $9 }'
    done
    plot "$out/lap_alpha_${d}D.png" "${d}-D Laplacian of a sine product, nC = $n" "alpha" "relative L2 error" no yes "$dat" \
        "u 1:2 w lp t 'CPM'" "u 1:3 w lp t 'IPS'" "u 1:4 w lp t 'PS'" "u 1:5 w lp t 'MPS'"
done

echo
echo "# 4. pure diffusion (Eqs. 39, 44, 48), alpha 0.3, C_D 1, explicit Euler: error (Eq. 40) at t = 0.02"
for d in 1 2 3; do
    case $d in 1) ns="32 64 128" ;; 2) ns="16 32 64" ;; 3) ns="8 16 32" ;; esac
    printf "%dD %5s %11s | %10s %10s %10s %10s\n" "$d" nC dt $models
    for n in $ns; do
        res=$("$la" diffusion -dim "$d" -nC "$n" -alpha 0.3 -CD 1 -endTime 0.02 -samples 20 -seed "$seed")
        row="$n $(echo "$res" | head -1 | kv dt)"
        for m in $models; do row="$row $(echo "$res" | grep "model=$m " | tail -1 | kv err)"; done
        echo "$row" | awk -v d="$d" '{ printf "%dD %5s %11.3e | %10.3e %10.3e %10.3e %10.3e\n", d, $1, $2, $3, $4, $5, $6 }'
        hist=$out/diffusion_${d}D_nC$n.dat
        : > "$hist"
        for m in $models; do
            echo "# $m: t err" >> "$hist"
            echo "$res" | grep "model=$m " | while read -r l; do echo "$(echo "$l" | kv t) $(echo "$l" | kv err)"; done >> "$hist"
            printf "\n\n" >> "$hist"
        done
        last=$hist
    done
    plot "$out/lap_diffusion_${d}D.png" "${d}-D pure diffusion, alpha = 0.3, C_D = 1, nC = ${ns##* }" t "error (Eq. 40)" no yes "$last" \
        "index 0 w lp t 'CPM'" "index 1 w lp t 'IPS'" "index 2 w lp t 'PS'" "index 3 w lp t 'MPS'"
done

echo
echo "# 5. three-point problem (Eqs. 31-33), phi* = 2: reality factor <phi_xx>/exact"
dat=$out/threepoint.dat
"$la" threePoint -phiStar 2 | while read -r l; do
    echo "$(echo "$l" | kv alpha) $(echo "$l" | kv realityPS) $(echo "$l" | kv realityIPS) $(echo "$l" | kv eq33b)"
done > "$dat"
printf "%5s %10s %10s %10s\n" alpha PS IPS Eq33b
awk '{ printf "%5s %10.5f %10.5f %10.5f\n", $1, $2, $3, $4 }' "$dat"
plot "$out/lap_threepoint.png" "Three-point problem, phi* = 2 (Hwang et al. 2016, Fig. 1b)" alpha "reality factor" no no "$dat" \
    "u 1:2 w lp t 'PS'" "u 1:3 w lp t 'IPS'" "u 1:4 w l dt 2 t 'Eq. 33b'"
echo "# data and PNGs in $out"
