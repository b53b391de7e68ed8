#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# bench/re1000Steps.sh [-n 40] [-deltaT "0.005 0.008 0.01 0.0125 0.015 0.02"]
#                      [-ico "0.01 0.0125 0.02"] [-umppm "key value; ..."] [-work DIR]
# How issue 14's Re 1000 figure (the 40^2 cavity at deltaT 0.0125: RMS from
# Ghia <= 0.015 on both centrelines) depends on the step: OpenFOAM's
# icoFoam `cavity` tutorial as a unit square (scale 1, nu 0.001, lid speed
# 1) on N x N blockMesh quads, to t = 40, written every 2 s; umppmFoam at
# each fixed deltaT of -deltaT, icoFoam at each of -ico, the same mesh.
# Prints per run the lid Courant number (deltaT N), the RMS errors from
# Ghia, Ghia & Shin (1982) of u on x = 0.5 and v on y = 0.5, each the mean
# over the writes t = 30 ... 40 (a step that does not divide 2 writes at
# the step after; every write from t = 29.9 on is taken), the largest
# single write's, and the CPU seconds. README "Re 1000 cavity, 40², and
# the step". One thread (OMP_NUM_THREADS=1 unless set); about 2 minutes
# on one core with the defaults. UMPPMFOAM=PATH runs that solver instead.
set -eu -o pipefail
top=$(cd "$(dirname "$0")/.." && pwd)
n=40 steps="0.005 0.008 0.01 0.0125 0.015 0.02" ico="0.01 0.0125 0.02" extra="" work=""
. "$top/bench/cases.sh" # bench_options, bench_prepare, cavity_case, ghia_writes, setEntry, logSeconds
bench_options "n n deltaT steps ico ico umppm extra work work" "$@"
bench_prepare re1000Steps
export OMP_NUM_THREADS=${OMP_NUM_THREADS:-1}

# errors DIR: "u_mean v_mean u_max v_max" over the writes t = 30 ... 40
errors() {
    ghia_writes "$1" 29.9 40.1 | awk '{ u += $2; v += $3; k++; if ($2 > mu) mu = $2; if ($3 > mv) mv = $3 }
        END { if (k >= 6) printf "%.4f %.4f %.4f %.4f", u / k, v / k, mu, mv; else printf "- - - -" }'
}

printf "# Re 1000 cavity, %d x %d quads, t = 40; RMS from Ghia (u on x = 0.5, v on y = 0.5): mean and largest over the writes t = 30..40\n" "$n" "$n"
printf "# UMPPM { %s }\n" "$extra"
row="%-9s %7s %5s | %7s %7s | %7s %7s | %7s\n"
printf "$row" solver deltaT Co u_mean v_mean u_max v_max cpu_s
run() { # solver deltaT
    local d=$work/$1-$2
    cavity_case "$d" "$n" 0.001 || return 1
    setEntry "$d/system/controlDict" deltaT "$2"
    setEntry "$d/system/controlDict" endTime 40
    setEntry "$d/system/controlDict" writeControl runTime
    setEntry "$d/system/controlDict" writeInterval 2
    (cd "$d" && blockMesh > log.blockMesh 2>&1) || { echo "$d: blockMesh failed" >&2; return 1; }
    if [ "$1" = icoFoam ]; then
        (cd "$d" && icoFoam > log.icoFoam 2>&1) || { echo "$d: icoFoam failed" >&2; return 1; }
    else
        [ -z "$extra" ] || echo "UMPPM { $extra }" >> "$d/system/fvSolution"
        "$umppm" -case "$d" > "$d/log.umppmFoam" 2>&1 ||
            { echo "$d: umppmFoam failed: $(grep -m1 FATAL "$d/log.umppmFoam" | cut -c1-160)" >&2; return 1; }
    fi
    printf "$row" "$1" "$(awk -v d="$2" 'BEGIN { printf "%.4g", d }')" "$(awk -v d="$2" -v n="$n" 'BEGIN { printf "%.3g", d * n }')" \
        $(errors "$d") "$(logSeconds "$d/log.$1")"
}
for dt in $steps; do run umppmFoam "$dt" || true; done
for dt in $ico; do run icoFoam "$dt" || true; done
echo "# cases in $work"
