#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# test_solver_icoFoamTutorials.sh -- OpenFOAM's own icoFoam tutorials
# (openfoam-examples), copied unmodified, run by umppmFoam:
#   - cavity (blockMesh, Re = 10, t = 0.5): runs, writes 0.1 .. 0.5 with a
#     cloud in each, continuity < 1e-12; icoFoam on the same case agrees,
#     U relative L2 difference < 0.15 (measured 0.12);
#   - elbow (fluentMeshToFoam: 918 triangles and quads, two fixedValue
#     inlets, zeroGradient U / fixedValue p outlet, t = 10): runs to the end,
#     continuity < 1e-12, particles leave through the outlet and the count
#     stays within 10% of the cell count; against icoFoam on a copy
#     (postProcess patchAverage of p on each inlet every 0.2 s from t = 5
#     to 10, 26 samples: writeInterval 4 steps instead of the tutorial's
#     20, nothing else changed) and against the converged flow, icoFoam on
#     the mesh refined three times (58 752 cells, tools/reference/; inlet
#     means 0.466 and 2.359, where icoFoam on this mesh gives 0.221 and
#     0.939: this mesh is far from converged, README "The pressure
#     written"). Asserted: the inlet pressure's standard deviation over
#     the 26 times < 1.5 (measured 0.29 and 1.00 before the zero-gradient
#     outlet rows of 2026-12-05, 0.32 and 1.01 with them; the PPE's own solution,
#     written until 2026-12-04, swung by 1.78 and 3.23, icoFoam 0.01 and
#     0.06); the mean inlet-5 p within 0.5..2.5 of the converged (measured
#     0.685, 1.47; 0.697, 1.50 with the zero-gradient outlet rows, 0.716,
#     1.54 with them by images: not the issue's 15 %) and inlet-6 within
#     0.5..1.35 (2.753, 1.17 with them; 2.772, 1.18 by images)
#     (2.741, 1.16; with refillWeights increment and its noise factor 0.1
#     instead of 0.15, 3.350, 1.42, and the check fails; with the 1/d^2
#     weights 2.635, 1.12); U relative L2 at t = 10 < 0.30 against icoFoam
#     on this mesh (measured 0.173) and < 0.21 against the converged
#     (0.150; 0.156 with the 1/d^2 refill weights; icoFoam on this mesh
#     0.179); p against the converged < 1.0 (0.804;
#     0.856 with the zero-gradient outlet rows; the PPE's solution 3.23,
#     icoFoam on this mesh 0.686); at a quarter
#     of the step (deltaT 0.0125) p < 3.0 against the converged at t = 10
#     (measured 0.70, 0.54 with the zero-gradient outlet rows; 1.56,
#     0.61..1.90 over t = 5..10 with the 1/d^2
#     refill weights; 7.05 before the outlets'
#     fixed pressures entered the particles' gradient, docs/METHOD.md
#     section 8; U is not asserted there: one time swings from 0.14 to
#     0.29, measured 0.193), and its mean inlet pressures over the 26
#     writes t = 5..10 within 0.8..1.2 of the converged (measured 0.435
#     and 2.039, 0.93 and 0.86, where the tutorial's step gives 1.54 and
#     1.18: the time-step error of the convective part, README "Elbow:
#     where the inlet pressures' error is"). With the
#     paper's refill (`refill centroid`) U was 0.354 from icoFoam's;
#   - cavity: the defaults laplacian auto and pressureTheta auto are the
#     paper's CPM and Eq. 10 on this mesh with walls (the log's UMPPM line);
#   - cavityGrade (starts at 0.5, which its Allrun maps from cavity): refused
#     with one error line naming the controlDict, as icoFoam refuses it.
# Needs UMPPMFOAM and TOOLDIR (foamCompare).
set -eu -o pipefail
here=$(cd "$(dirname "$0")" && pwd)
top=$(cd "$here/../.." && pwd)
[ -n "${UMPPMFOAM:-}" ] && [ -x "$UMPPMFOAM" ] || { echo "FAIL: UMPPMFOAM not set" >&2; exit 2; }
[ -n "${TOOLDIR:-}" ] && [ -x "$TOOLDIR/foamCompare" ] || { echo "FAIL: TOOLDIR not set" >&2; exit 2; }
. "$here/lib.sh"
of_env
ex=/usr/share/doc/openfoam-examples/examples/incompressible/icoFoam
[ -d "$ex/cavity/cavity" ] || { echo "FAIL: $ex missing (package openfoam-examples)"; exit 1; }
work=$(mktemp -d "${TMPDIR:-/tmp}/umppm-icotut.XXXXXX")
fail=0

c=$work/cavity
cp -r "$ex/cavity/cavity" "$c"
run_in "$c" blockMesh blockMesh
if "$UMPPMFOAM" -case "$c" > "$c/log.umppmFoam" 2>&1; then
    for t in 0.1 0.2 0.3 0.4 0.5; do
        [ -f "$c/$t/U" ] && [ -f "$c/$t/lagrangian/umppmCloud/positions" ] ||
            { echo "  FAIL cavity: $t/U or its cloud missing"; fail=1; }
    done
    check_range "cavity: max continuity error" "$(log_max_continuity "$c/log.umppmFoam")" 0 1e-12
    # no UMPPM dictionary: laplacian auto and pressureTheta auto take the
    # paper's CPM and Eq. 10 on a mesh with walls
    grep -q '^UMPPM: .*laplacian CPM (auto), PPE' "$c/log.umppmFoam" ||
        { echo "  FAIL cavity: the log does not name laplacian CPM (auto) without pressureTheta"; fail=1; }
    mkdir -p "$c/ico" && cp -r "$ex/cavity/cavity/0" "$c/constant" "$c/system" "$c/ico/"
    run_in "$c/ico" icoFoam icoFoam || fail=1
    rel=$("$TOOLDIR/foamCompare" "$c" 0.5 "$c/ico" 0.5 U | awk '$1 == "U" { print $4 }')
    check_range "cavity: U vs icoFoam, relative L2" "$rel" 0 0.15
else
    echo "  FAIL cavity: umppmFoam failed"; tail -3 "$c/log.umppmFoam"; fail=1
fi

e=$work/elbow
cp -r "$ex/elbow" "$e"
gzip -dc "$e/elbow.msh.gz" > "$e/elbow.msh"
sed -i 's/^writeInterval .*/writeInterval 4;/' "$e/system/controlDict" # every 0.2 s
grep -q '^writeInterval 4;' "$e/system/controlDict" || { echo "  FAIL elbow: could not set writeInterval"; fail=1; }
run_in "$e" fluentMeshToFoam fluentMeshToFoam elbow.msh
if "$UMPPMFOAM" -case "$e" > "$e/log.umppmFoam" 2>&1; then
    [ -f "$e/10/U" ] || { echo "  FAIL elbow: 10/U missing"; fail=1; }
    check_range "elbow: max continuity error" "$(log_max_continuity "$e/log.umppmFoam")" 0 1e-12
    check_range "elbow: particles that left through the outlet" "$(log_particles_left "$e/log.umppmFoam")" 1 1e9
    np=$(grep -o '^Particles: [0-9]*' "$e/log.umppmFoam" | awk '{ if (!lo || $2 < lo) lo = $2; if ($2 > hi) hi = $2 }
        END { print lo, hi }')
    check_range "elbow: fewest particles" "${np% *}" 826 1010
    check_range "elbow: most particles" "${np#* }" 826 1010
    # the converged reference: icoFoam on the mesh refined three times,
    # mapped onto this mesh (tools/reference/README.md)
    mkdir -p "$e/conv/10" && cp -r "$e/constant" "$e/system" "$e/conv/" &&
        cp "$top/tools/reference/elbow_icoFoam_level3_t10/U" "$top/tools/reference/elbow_icoFoam_level3_t10/p" \
            "$e/conv/10/"
    mkdir -p "$e/ico" && cp -r "$e/0" "$e/constant" "$e/system" "$e/ico/"
    declare -A conv=([5]=0.466 [6]=2.359) # the reference's inlet p means over t = 5..10
    # inlet_stats LOG K: mean and standard deviation of inlet-K's p in the
    # log of postProcess patchAverage over the writes t = 5, 5.2, ..., 10
    # ("nan nan" unless there are 26)
    inlet_stats() {
        sed -n 's/.*areaAverage(velocity-inlet-'"$2"') of p = //p' "$1" |
            awk '{ s += $1; q += $1 * $1; n++ } END { if (n != 26) { print "nan nan"; exit }
                   m = s / n; v = q / n - m * m; print m, sqrt(v > 0 ? v : 0) }'
    }
    if run_in "$e/ico" icoFoam icoFoam; then
        for k in 5 6; do
            for d in "$e" "$e/ico"; do
                run_in "$d" "patchAverage$k" postProcess -func "patchAverage(name=velocity-inlet-$k,p)" \
                    -time '5:10' || fail=1
            done
            read -r pu su < <(inlet_stats "$e/log.patchAverage$k" $k)
            read -r pi si < <(inlet_stats "$e/ico/log.patchAverage$k" $k)
            echo "  elbow inlet-$k p over t = 5..10 (26 times): umppmFoam mean $pu (std $su), icoFoam $pi ($si)," \
                "icoFoam on the mesh refined 3 times ${conv[$k]}"
            check_below "elbow: inlet-$k p, standard deviation over t = 5..10" "$su" 1.5
            check_range "elbow: mean inlet-$k p / the refined icoFoam's" \
                "$(awk -v a="$pu" -v b="${conv[$k]}" 'BEGIN { print a / b }')" 0.5 $([ $k = 5 ] && echo 2.5 || echo 1.35)
        done
        rel=$("$TOOLDIR/foamCompare" "$e" 10 "$e/ico" 10 U | awk '$1 == "U" { print $4 }')
        check_below "elbow: U vs icoFoam, relative L2" "$rel" 0.30
        for f in U p; do
            ru=$("$TOOLDIR/foamCompare" "$e" 10 "$e/conv" 10 $f | awk -v f=$f '$1 == f { print $4 }')
            ri=$("$TOOLDIR/foamCompare" "$e/ico" 10 "$e/conv" 10 $f | awk -v f=$f '$1 == f { print $4 }')
            echo "  elbow $f at t = 10 against icoFoam refined 3 times, relative L2: umppmFoam $ru, icoFoam $ri"
            check_below "elbow: $f vs icoFoam refined 3 times, relative L2" "$ru" $([ $f = U ] && echo 0.21 || echo 1.0)
        done
    else
        fail=1
    fi
    # a quarter of the tutorial's step: the error must not grow as the step
    # falls, and the inlet pressures come to the converged flow's
    q=$e/dt4
    mkdir -p "$q" && cp -r "$e/0" "$e/constant" "$e/system" "$q/"
    sed -i 's/^deltaT .*/deltaT 0.0125;/; s/^writeInterval .*/writeInterval 16;/' "$q/system/controlDict"
    if grep -q '^deltaT 0.0125;' "$q/system/controlDict" && "$UMPPMFOAM" -case "$q" > "$q/log.umppmFoam" 2>&1; then
        r=$("$TOOLDIR/foamCompare" "$q" 10 "$e/conv" 10 p | awk '$1 == "p" { print $4 }')
        check_below "elbow at deltaT/4: p vs icoFoam refined 3 times, relative L2" "$r" 3.0
        for k in 5 6; do
            run_in "$q" "patchAverage$k" postProcess -func "patchAverage(name=velocity-inlet-$k,p)" \
                -time '5:10' || fail=1
            read -r mq _ < <(inlet_stats "$q/log.patchAverage$k" $k)
            echo "  elbow at deltaT/4: inlet-$k p over t = 5..10 (26 times): mean $mq, icoFoam refined 3 times ${conv[$k]}"
            check_range "elbow at deltaT/4: mean inlet-$k p / the refined icoFoam's" \
                "$(awk -v a="$mq" -v b="${conv[$k]}" 'BEGIN { print a / b }')" 0.8 1.2
        done
    else
        echo "  FAIL elbow at deltaT/4: umppmFoam failed"; tail -3 "$q/log.umppmFoam"; fail=1
    fi
else
    echo "  FAIL elbow: umppmFoam failed"; tail -3 "$e/log.umppmFoam"; fail=1
fi

g=$work/cavityGrade
cp -r "$ex/cavity/cavityGrade" "$g"
run_in "$g" blockMesh blockMesh
if "$UMPPMFOAM" -case "$g" > "$g/log.umppmFoam" 2>&1; then
    echo "  FAIL cavityGrade: ran without its 0.5 directory"; fail=1
elif grep -q 'FATAL ERROR: .*system/controlDict: startTime 0.5 has no time directory' "$g/log.umppmFoam"; then
    echo "  ok   cavityGrade: refused ($(grep 'FATAL' "$g/log.umppmFoam"))"
else
    echo "  FAIL cavityGrade: unexpected output"; tail -3 "$g/log.umppmFoam"; fail=1
fi
[ "$fail" = 0 ] || { echo "work dir kept: $work"; exit 1; }
rm -rf "$work"
echo "PASS"
