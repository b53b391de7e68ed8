#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# bench/elbowConvergence.sh [-levels 3] [-umppm "0 1"] [-deltaT "DT ..."] [-work DIR] [-reference DIR]
# OpenFOAM's icoFoam `elbow` tutorial (unmodified: fluentMeshToFoam, its
# 0/, constant/, system/, t = 10) against icoFoam on the same geometry
# refined: level L is `refineMesh -overwrite` applied L times (each splits
# every cell in four) with deltaT 0.05 / 2^L and the same write times
# (every 0.2 s). icoFoam runs on every level 0..levels; umppmFoam on the
# levels of -umppm, at the tutorial's own deltaT 0.05 (the refineMesh copy
# of the issue) and at 0.05 / 2^L. The finest icoFoam is mapped onto each
# coarser mesh by mapFields -consistent (cell-volume weighted) and each
# run's t = 10 fields are compared with it (foamCompare: relative L2 of U
# and p). Prints one row per run:
#   level cells solver deltaT  U_L2 p_L2  inlet-5 p mean std  inlet-6 p mean std  CPU s
# (inlet pressures: areaAverage over the patch by postProcess
# patchAverage, mean and standard deviation over the 26 writes t = 5..10).
# -reference DIR: also copy the finest icoFoam's t = 10 U and p mapped onto
# the tutorial's mesh to DIR (the data of test_solver_icoFoamTutorials.sh).
# Cost on the 2-core VM: icoFoam at level 3 (58 752 cells, 1 600 steps)
# about 25 min; level 2 one minute.
set -eu -o pipefail
top=$(cd "$(dirname "$0")/.." && pwd)
levels=3 umppm_levels="0 1" umppm_dts="" work="" refdir=""
while [ $# -gt 0 ]; do
    case $1 in
    -levels) levels=$2 ;; -umppm) umppm_levels=$2 ;; -deltaT) umppm_dts=$2 ;; -work) work=$2 ;;
    -reference) refdir=$2 ;;
    *) echo "unknown option $1" >&2; exit 1 ;;
    esac
    shift 2
done
make -C "$top" -s >/dev/null
export WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam}
ex=/usr/share/doc/openfoam-examples/examples/incompressible/icoFoam/elbow
[ -d "$ex" ] || { echo "no $ex (openfoam-examples)" >&2; exit 1; }
work=${work:-$(mktemp -d "${TMPDIR:-/tmp}/umppm-elbow.XXXXXX")}
mkdir -p "$work"
quiet() { "$@" > /dev/null 2>&1 || { echo "failed: $* (in $PWD)" >&2; exit 1; }; }
# mesh LEVEL: $work/mesh$L, the tutorial refined L times, deltaT 0.05/2^L
for L in $(seq 0 "$levels"); do
    m=$work/mesh$L
    [ -f "$m/constant/polyMesh/owner" ] && continue
    rm -rf "$m" && cp -r "$ex" "$m"
    (cd "$m" && gzip -dc elbow.msh.gz > elbow.msh && quiet fluentMeshToFoam elbow.msh &&
        for _ in $(seq 1 "$L"); do quiet refineMesh -overwrite; done
        dt=$(awk -v L="$L" 'BEGIN { print 0.05 / 2 ^ L }')
        foamDictionary system/controlDict -entry deltaT -set "$dt" > /dev/null
        foamDictionary system/controlDict -entry writeInterval -set "$((4 << L))" > /dev/null)
done
cpu() { awk '/^ExecutionTime/ { t = $3 } END { print t }' "$1"; }
# run DIR SOLVER: in its own copy of the mesh case
run() {
    local d=$1 solver=$2
    [ -f "$d/10/U" ] && return 0
    (cd "$d" && "$solver" > "log.$(basename "$solver")" 2>&1) || { echo "failed: $solver in $d" >&2; exit 1; }
}
for L in $(seq 0 "$levels"); do
    d=$work/ico$L
    [ -d "$d" ] || { cp -r "$work/mesh$L" "$d"; }
    run "$d" icoFoam
done
for L in $umppm_levels; do
    for dt in ${umppm_dts:-0.05 $(awk -v L="$L" 'BEGIN { print 0.05 / 2 ^ L }')}; do
        d=$work/umppm$L-dt$dt
        [ -d "$d" ] && [ -f "$d/10/U" ] && continue
        rm -rf "$d" && cp -r "$work/mesh$L" "$d"
        wi=$(awk -v dt="$dt" 'BEGIN { printf "%d", 0.2 / dt + 0.5 }')
        (cd "$d" && foamDictionary system/controlDict -entry deltaT -set "$dt" > /dev/null &&
            foamDictionary system/controlDict -entry writeInterval -set "$wi" > /dev/null)
        run "$d" "$top/bin/umppmFoam"
    done
done
# the finest icoFoam mapped onto every coarser mesh: $work/ref$L/10
fine=$work/ico$levels
for L in $(seq 0 "$levels"); do
    r=$work/ref$L
    [ -f "$r/10/U" ] && continue
    rm -rf "$r" && cp -r "$work/mesh$L" "$r"
    if [ "$L" = "$levels" ]; then
        mkdir -p "$r/10" && cp "$fine/10/U" "$fine/10/p" "$r/10/"
    else
        (cd "$r" && quiet mapFields "$fine" -consistent -sourceTime 10 && mkdir -p 10 && cp 0/U 0/p 10/)
    fi
done
inlet() { # inlet CASE K: mean and std of the inlet-K pressure over t = 5..10
    postProcess -case "$1" -func "patchAverage(name=velocity-inlet-$2,p)" -time '5:10' 2> /dev/null |
        sed -n "s/.*areaAverage(velocity-inlet-$2) of p = //p" |
        awk '{ s += $1; q += $1 * $1; n++ } END { m = s / n; v = q / n - m * m;
               printf "%.3f %.3f", m, sqrt(v > 0 ? v : 0) }'
}
printf "# elbow, t = 10, against icoFoam on level %s (%s cells) mapped onto each mesh; work %s\n" \
    "$levels" "$(awk '/^ *cells:/ { print $2 }' <(checkMesh -case "$fine" 2> /dev/null))" "$work"
printf "%5s %6s %-9s %9s %7s %7s %8s %6s %8s %6s %8s\n" level cells solver deltaT U_L2 p_L2 in5_p std in6_p std CPU_s
row() { # row LEVEL CASE LABEL
    local cells u p
    cells=$(awk '/^ *cells:/ { print $2 }' <(checkMesh -case "$2" 2> /dev/null))
    u=$("$top/bin/foamCompare" "$2" 10 "$work/ref$1" 10 U | awk '$1 == "U" { print $4 }')
    p=$("$top/bin/foamCompare" "$2" 10 "$work/ref$1" 10 p | awk '$1 == "p" { print $4 }')
    printf "%5s %6s %-9s %9s %7.4f %7.4f %8s %6s %8s %6s %8s\n" "$1" "$cells" "$3" \
        "$(foamDictionary "$2/system/controlDict" -entry deltaT -value)" "$u" "$p" \
        $(inlet "$2" 5) $(inlet "$2" 6) "$(cpu "$2/log.$4")"
}
for L in $(seq 0 "$levels"); do
    row "$L" "$work/ico$L" icoFoam icoFoam
    for U in $umppm_levels; do
        [ "$U" = "$L" ] || continue
        for d in "$work"/umppm$L-dt*; do row "$L" "$d" umppmFoam umppmFoam; done
    done
done
if [ -n "$refdir" ]; then
    mkdir -p "$refdir"
    cp "$work/ref0/10/U" "$work/ref0/10/p" "$refdir/"
    echo "# wrote $refdir/U, $refdir/p (icoFoam level $levels at t = 10 on the tutorial's mesh)"
fi
