#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# bench/taylorGreen.sh [-variant UMPPMstar] [-maxCo 0.25 | -deltaT DT | -cfl C] [-endTime 5]
#                      [-laplacian auto] [-paper] [-U 1] [-umppm "key value; ..."] [-icoFoam no] [n ...]
# The Taylor-Green vortex of Section 4.1 of Ng, Sheu & Hwang (2016) (Re = 100,
# periodic unit square, crossed triangles of Fig. 7: N_m = 4 n^2) for each n
# (default 20 40 80: N_m = 1600 6400 25600), CFL maxCo (adjustTimeStep,
# OpenFOAM's Courant number of the current flow), a fixed deltaT, or -cfl C:
# the paper's fixed step dt = C l_avg / U with U = 1 and l_avg = sqrt(mean cell
# area) = 1/(2n), to endTime. Prints per run: N_m, particles, steps, seconds,
# us per particle-step, peak RSS, and the errors at endTime
# (tools/taylorGreenError.py): L2rel, decay error vs the sampled max, Eq. 41,
# Eq. 42, and the signed amplitude error amp (> 0: decays too slowly); then
# the observed orders between successive meshes. -U scales the initial vortex
# (the step stays the one for U = 1: -U 0.01 is nearly Stokes flow, which
# isolates the viscous errors); -umppm adds entries to the UMPPM dictionary.
# On this periodic mesh the defaults (laplacian auto, pressureTheta auto) are
# CPM4 and 0.5; -paper runs the paper's CPM and Eq. 10 (laplacian CPM;
# pressureTheta 0), the defaults before 2026-12-06. With -icoFoam
# yes, icoFoam runs the same case (same mesh and 0/, fixed deltaT = the mean of
# umppmFoam's steps, skewCorrected linear interpolation) and its errors and time are printed below each row.
set -eu -o pipefail
top=$(cd "$(dirname "$0")/.." && pwd)
variant=UMPPMstar maxCo=0.25 deltaT="" cfl="" endTime=5 lap=auto ico=no U0=1 extra= paper=
while [ $# -gt 0 ]; do
    case $1 in
    -variant) variant=$2; shift 2 ;;
    -maxCo) maxCo=$2; shift 2 ;;
    -deltaT) deltaT=$2; shift 2 ;;
    -cfl) cfl=$2; shift 2 ;;
    -endTime) endTime=$2; shift 2 ;;
    -laplacian) lap=$2; shift 2 ;;
    -paper) paper="pressureTheta 0;" lap=CPM; shift ;;
    -icoFoam) ico=$2; shift 2 ;;
    -U) U0=$2; shift 2 ;;
    -umppm) extra=$2; shift 2 ;;
    -*) echo "unknown option $1" >&2; exit 1 ;;
    *) break ;;
    esac
done
[ $# -gt 0 ] || set -- 20 40 80
make -C "$top" -s >/dev/null
bin=$top/bin
work=${BENCH_WORK:-$(mktemp -d "${TMPDIR:-/tmp}/umppm-tgbench.XXXXXX")}
if [ -n "$cfl" ]; then steprule="fixed deltaT = $cfl l_avg / U"
elif [ -n "$deltaT" ]; then steprule="fixed deltaT = $deltaT"
else steprule="adjustTimeStep maxCo = $maxCo"; fi
printf "# Taylor-Green Re=100 %s %s, %s, endTime=%s\n" "$variant" "$lap" "$steprule" "$endTime"
printf "# U = %s, UMPPM { %s }\n" "$U0" "$paper $extra"
printf "%6s %7s %6s %8s %8s %7s %9s %9s %9s %9s %9s %9s\n" N_m particles steps seconds us/p-step RSS_MiB L2rel decay Eq41 Eq42 amp pL2rel
prev=""
for n in "$@"; do
    c=$work/tg$n-$variant
    rm -rf "$c"; mkdir -p "$c/system" "$c/constant"
    if [ -n "$cfl" ]; then
        adj="deltaT $(awk -v n="$n" -v c="$cfl" 'BEGIN { printf "%.10g", c / (2 * n) }'); adjustTimeStep no;"
    elif [ -n "$deltaT" ]; then
        adj="deltaT $deltaT; adjustTimeStep no;"
    else
        # first step at the CFL limit: h = 1/n, |U| <= 1
        adj="deltaT $(awk -v n="$n" -v c="$maxCo" 'BEGIN { print c / (2 * n) }'); adjustTimeStep yes; maxCo $maxCo;"
    fi
    cat > "$c/system/controlDict" <<CD
FoamFile { version 2.0; format ascii; class dictionary; object controlDict; }
application umppmFoam; startFrom startTime; startTime 0; stopAt endTime; endTime $endTime;
$adj writeControl adjustableRunTime; writeInterval $endTime; writeFormat ascii; writePrecision 15;
CD
    cat > "$c/system/fvSchemes" <<FS
FoamFile { version 2.0; format ascii; class dictionary; object fvSchemes; }
ddtSchemes { default Euler; } gradSchemes { default Gauss linear; }
divSchemes { default none; div(phi,U) Gauss linear; }
laplacianSchemes { default Gauss linear corrected; } interpolationSchemes { default linear; }
snGradSchemes { default corrected; }
FS
    cat > "$c/system/fvSolution" <<FS
FoamFile { version 2.0; format ascii; class dictionary; object fvSolution; }
solvers { p { solver PCG; preconditioner DIC; tolerance 1e-10; relTol 0; } pFinal { \$p; }
          U { solver smoothSolver; smoother symGaussSeidel; tolerance 1e-10; relTol 0; } }
PISO { nCorrectors 2; nNonOrthogonalCorrectors 1; pRefCell 0; pRefValue 0; }
UMPPM { variant $variant; laplacian $lap; $paper $extra }
FS
    echo 'FoamFile { version 2.0; format ascii; class dictionary; object transportProperties; } nu 0.01;' \
        > "$c/constant/transportProperties"
    "$bin/makeCrossedTriangleMesh" -case "$c" -n "$n" >/dev/null
    "$bin/setTaylorGreen" -case "$c" -U "$U0" >/dev/null
    read -r sec rss rc < <(cd "$c" && python3 "$top/bench/run_measured.py" sh -c "$bin/umppmFoam > log 2>&1")
    [ "$rc" = 0 ] || { echo "umppmFoam failed in $c (see $c/log)" >&2; exit 1; }
    last=$(ls -d "$c"/[0-9]* | sed 's|.*/||' | sort -g | tail -1)
    steps=$(grep -c '^Time = ' "$c/log")
    np=$(grep -o 'Particles: [0-9]*' "$c/log" | awk '{ s += $2; k++ } END { print int(s / k) }')
    read -r _ l2 _ dec _ e41 _ e42 _ amp _ pl2 _ < <(python3 "$top/tools/taylorGreenError.py" "$c" "$last")
    us=$(awk -v s="$sec" -v p="$np" -v k="$steps" 'BEGIN { printf "%.2f", 1e6 * s / (p * k) }')
    printf "%6d %7d %6d %8.2f %8s %7.0f %9.4g %9.4g %9.4g %9.4g %+9.4f %9s\n" $((4 * n * n)) "$np" "$steps" "$sec" "$us" "$rss" "$l2" "$dec" "$e41" "$e42" "$amp" "$pl2"
    if [ -n "$prev" ]; then
        set -- $prev
        awk -v n0="$1" -v n1="$n" -v a0="$2" -v a1="$l2" -v b0="$3" -v b1="$e42" -v c0="$4" -v c1="$dec" 'BEGIN {
            r = log(n1 / n0); printf "#   order %d->%d: L2rel %.2f  Eq42 %.2f  decay %.2f\n", n0, n1, log(a0 / a1) / r, log(b0 / b1) / r, log(c0 / c1) / r }'
    fi
    if [ "$ico" = yes ]; then
        ic=$c/icoFoam
        rm -rf "$ic"; mkdir -p "$ic"
        cp -r "$c/system" "$c/constant" "$c/0" "$ic/"
        dtm=$(awk -v t="$endTime" -v k="$steps" 'BEGIN { printf "%.8g", t / k }')
        cat > "$ic/system/controlDict" <<CD
FoamFile { version 2.0; format ascii; class dictionary; object controlDict; }
application icoFoam; startFrom startTime; startTime 0; stopAt endTime; endTime $endTime;
deltaT $dtm; writeControl runTime; writeInterval $endTime; writeFormat ascii; writePrecision 15;
CD
        # the crossed triangles are skewed (the line between two centroids
        # misses the face centre by O(h)): with plain linear interpolation
        # icoFoam's vortex loses 12 % of its amplitude per unit time on
        # every mesh (L2 0.43 at t = 5 on 1 600 and 6 400 cells); with
        # skewCorrected linear it converges (README, "Taylor-Green beside
        # icoFoam")
        sed -i 's/interpolationSchemes { default linear; }/interpolationSchemes { default skewCorrected linear; }/; s/div(phi,U) Gauss linear;/div(phi,U) Gauss skewCorrected linear;/' \
            "$ic/system/fvSchemes"
        grep -q 'default skewCorrected linear' "$ic/system/fvSchemes" || { echo "could not set skewCorrected" >&2; exit 1; }
        export WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam}
        read -r isec irss irc < <(python3 "$top/bench/run_measured.py" -o "$ic/log" icoFoam -case "$ic")
        [ "$irc" = 0 ] || { echo "icoFoam failed in $ic (see $ic/log)" >&2; exit 1; }
        ilast=$(ls -d "$ic"/[0-9]* | sed 's|.*/||' | sort -g | tail -1)
        read -r _ il2 _ idec _ ie41 _ ie42 _ < <(python3 "$top/tools/taylorGreenError.py" "$ic" "$ilast")
        isteps=$(grep -c '^Time = ' "$ic/log")
        printf "%6s %7s %6d %8.2f %8s %7.0f %9.4g %9.4g %9.4g %9.4g  icoFoam (umppmFoam/icoFoam time %.1f)\n" "" "" "$isteps" "$isec" "" "$irss" "$il2" "$idec" "$ie41" "$ie42" \
            "$(awk -v a="$sec" -v b="$isec" 'BEGIN { print a / b }')"
    fi
    prev="$n $l2 $e42 $dec"
done
echo "# cases in $work"
