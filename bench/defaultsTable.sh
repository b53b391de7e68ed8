#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# bench/defaultsTable.sh [-variants "UMPPMstar UMPPM:0.09 UMPPM:0.05"] [-work DIR]
# The table that picks the defaults (issue 14, item 2): accuracy and CPU
# seconds of each management variant (UMPPM:ALPHA is variant UMPPM with
# that alpha) at three Courant numbers on three cases, one thread, one run
# after the other:
#   Re 1000 cavity: OpenFOAM's icoFoam cavity tutorial with scale 1, 40 x 40,
#     nu 0.001, deltaT 0.025 / 0.0125 / 0.00625 (lid Courant number 1 / 0.5
#     / 0.25), t = 40; RMS error against Ghia, Ghia & Shin (1982) of u on
#     x = 0.5 / v on y = 0.5, each the mean over the 21 writes t = 30 ... 40;
#   Taylor-Green: bench/taylorGreen.sh -cfl 0.5 / 0.25 / 0.125 on 1 600
#     crossed triangles, t = 5: L2 rel and Eq. 41 of Ng, Sheu & Hwang (2016);
#   elbow: OpenFOAM's icoFoam elbow tutorial (fluentMeshToFoam, its 0/ and
#     system/), deltaT 0.1 / 0.05 / 0.025 (largest Courant number about 1 /
#     0.5 / 0.25), t = 10: U against icoFoam on the mesh refined three times
#     (tools/reference/elbow_icoFoam_level3_t10), relative L2.
# CPU seconds are the solver's user + sys (Taylor-Green: its ExecutionTime,
# CPU seconds as in OpenFOAM's logs). About 6 minutes for the default three
# variants on an idle machine.
set -eu -o pipefail
top=$(cd "$(dirname "$0")/.." && pwd)
variants="UMPPMstar UMPPM:0.09 UMPPM:0.05" work=""
while [ $# -gt 0 ]; do
    case $1 in
    -variants) variants=$2 ;; -work) work=$2 ;;
    *) echo "usage: bench/defaultsTable.sh [-variants \"UMPPMstar UMPPM:0.09\"] [-work DIR]" >&2; exit 1 ;;
    esac
    shift 2
done
. "$top/bench/cases.sh" # cavity_case, setEntry; exports WM_PROJECT_DIR
export OMP_NUM_THREADS=1
make -C "$top" -s >/dev/null
ex=/usr/share/doc/openfoam-examples/examples/incompressible/icoFoam
[ -d "$ex/cavity/cavity" ] && [ -d "$ex/elbow" ] || { echo "no icoFoam tutorials in $ex" >&2; exit 1; }
work=${work:-$(mktemp -d "${TMPDIR:-/tmp}/umppm-defaults.XXXXXX")}
mkdir -p "$work"
bin=$top/bin

# umppmFoam in DIR with variant V (UMPPMstar or UMPPM:alpha); prints CPU s
umppm() {
    local d=$1 v=$2
    if [ "${v%%:*}" = UMPPM ]; then
        printf 'UMPPM { variant UMPPM; alpha %s; }\n' "${v#*:}" >> "$d/system/fvSolution"
    fi
    (cd "$d" && /usr/bin/time -f "%U %S" -o cpu.txt "$bin/umppmFoam" > log 2>&1) ||
        { echo "umppmFoam failed in $d (see $d/log)" >&2; exit 1; }
    awk '{ printf "%.1f", $1 + $2 }' "$d/cpu.txt"
}

cav=$work/cavity40
rm -rf "$cav"
cavity_case "$cav" 40 0.001 || exit 1
setEntry "$cav/system/controlDict" endTime 40
setEntry "$cav/system/controlDict" writeControl runTime
setEntry "$cav/system/controlDict" writeInterval 0.5
(cd "$cav" && blockMesh > log.blockMesh 2>&1) || { echo "blockMesh failed in $cav" >&2; exit 1; }

elb=$work/elbow
rm -rf "$elb" && cp -r "$ex/elbow" "$elb"
gzip -dc "$elb/elbow.msh.gz" > "$elb/elbow.msh"
setEntry "$elb/system/controlDict" writeControl runTime
setEntry "$elb/system/controlDict" writeInterval 1
(cd "$elb" && fluentMeshToFoam elbow.msh > log.fluentMeshToFoam 2>&1) || { echo "fluentMeshToFoam failed" >&2; exit 1; }
mkdir -p "$elb/conv/10" && cp -r "$elb/constant" "$elb/system" "$elb/conv/" &&
    cp "$top/tools/reference/elbow_icoFoam_level3_t10/U" "$elb/conv/10/"

printf "# %s, revision %s; one thread; CPU s in brackets\n" "$(date -u '+%Y-%m-%d %H:%M UTC')" \
    "$(git -C "$top" rev-parse --short HEAD 2> /dev/null || echo -)"
printf "%-11s | %-23s %-23s %-23s | %-20s %-20s %-20s | %-13s %-13s %-13s\n" variant \
    "Re1000 Co1 u/v" "Co0.5" "Co0.25" "TG CFL0.5 L2/Eq41" "CFL0.25" "CFL0.125" "elbow Co1 U" "Co0.5" "Co0.25"
for v in $variants; do
    row=$(printf "%-11s |" "$v")
    for dt in 0.025 0.0125 0.00625; do
        d=$work/$v-cavity-$dt
        rm -rf "$d" && cp -r "$cav" "$d"
        setEntry "$d/system/controlDict" deltaT "$dt"
        cpu=$(umppm "$d" "$v")
        args=()
        for t in $(foamListTimes -case "$d" 2> /dev/null); do
            awk -v t="$t" 'BEGIN { exit !(t >= 30 - 1e-9) }' && args+=("$d" "$t")
        done
        [ ${#args[@]} -eq 42 ] || { echo "expected 21 writes t = 30..40 in $d" >&2; exit 1; }
        e=$("$bin/ghiaCompare" -Re 1000 "${args[@]}" | awk '$1 !~ /^#/ { u += $3; v += $5; n++ }
            END { printf "%.4f/%.4f", u / n, v / n }')
        row="$row $(printf "%-23s" "$e ($cpu)")"
    done
    row="$row |"
    for cfl in 0.5 0.25 0.125; do
        tw=$work/$v-tg-$cfl
        if [ "${v%%:*}" = UMPPM ]; then
            o=$(BENCH_WORK=$tw "$top/bench/taylorGreen.sh" -variant UMPPM -cfl "$cfl" -umppm "alpha ${v#*:};" 20)
        else
            o=$(BENCH_WORK=$tw "$top/bench/taylorGreen.sh" -variant "$v" -cfl "$cfl" 20)
        fi
        # CPU seconds: the solver's last ExecutionTime (taylorGreen.sh prints wall seconds)
        cpu=$(sed -n 's/^ExecutionTime = \([0-9.e+-]*\) s.*/\1/p' "$tw"/tg20-*/log | tail -1)
        e=$(echo "$o" | awk -v c="$cpu" '$1 == 1600 { printf "%.4f/%.4f (%.1f)", $7, $9, c }')
        row="$row $(printf "%-20s" "$e")"
    done
    row="$row |"
    for dt in 0.1 0.05 0.025; do
        d=$work/$v-elbow-$dt
        rm -rf "$d" && mkdir -p "$d" && cp -r "$elb/0" "$elb/constant" "$elb/system" "$d/"
        setEntry "$d/system/controlDict" deltaT "$dt"
        cpu=$(umppm "$d" "$v")
        e=$("$bin/foamCompare" "$d" 10 "$elb/conv" 10 U | awk '$1 == "U" { printf "%.3f", $4 }')
        row="$row $(printf "%-13s" "$e ($cpu)")"
    done
    echo "$row"
done
echo "# work: $work"
