#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# test_solver_cavity.sh -- lid-driven cavity, Re = 100, t = 10 (close to
# steady), on a 20 x 20 quad mesh (UMPPM* and UMPPM; lid fixedValue) and a
# ~400-cell gmsh triangle mesh (UMPPM*; lid movingWallVelocity), each also
# run by icoFoam on the same mesh
# (tools/cavityValidate.sh). Asserts, against Ghia et al. (1982) Table I/II
# on the centrelines (15 interior points each):
#   - RMS error of u and of v < 0.012 on quads (measured 0.003..0.006),
#     < 0.010 on triangles (measured 0.0044, 0.0026 since pressureTheta
#     auto is 0.5 on closed triangle meshes, 2026-12-07; 0.0058, 0.0052
#     with pressureTheta 0; earlier 0.0059, 0.0050, and 0.0067, 0.0042
#     with Eq. 35's MLS scales, mlsSupport 0), and at most twice icoFoam's RMS
#     error on the same mesh on quads (measured ratios 0.43..0.82), 1.5
#     times on triangles (measured 0.60 for u, 0.49 for v; 0.81 and 0.95
#     before 2026-12-07).
#     With the paper's refill (u_P, refill centroid) the triangle errors
#     were 0.0116 and 0.0125, 1.59 and 2.38 times icoFoam's, and the
#     check fails (README, "Refill that keeps carried values").
#     The triangle bound was 2 (measured 1.94 for v) while particles that
#     crossed a wall were deleted; stopping them at the wall (src/solver.c
#     wall_stop) raised this case's v error from 0.0102 to 0.0125. On the
#     944-triangle mesh of bench/cavityGhia.sh (Re 100, t = 20) the same
#     change moved v_rms from 0.00188 to 0.00198 and u_rms from 0.00424 to
#     0.00405 (README, "Wall stops");
#     the Re = 10 solution (a wrong viscosity) scores 0.018 / 0.028 and a
#     fluid at rest 0.41 / 0.14;
#   - max error of u and v < 0.03 (measured 0.009..0.024);
#   - U against icoFoam's U on the same mesh, cell by cell: relative L2 of
#     the difference < 0.1 (measured 0.055..0.07);
#   - per-cell continuity error after correction < 1e-12 every step.
# Needs UMPPMFOAM and TOOLDIR (foamCompare, ghiaCompare).
set -eu -o pipefail
here=$(cd "$(dirname "$0")" && pwd)
top=$(cd "$here/../.." && pwd)
[ -n "${UMPPMFOAM:-}" ] && [ -x "$UMPPMFOAM" ] || { echo "FAIL: UMPPMFOAM not set" >&2; exit 2; }
[ -n "${TOOLDIR:-}" ] && [ -x "$TOOLDIR/ghiaCompare" ] || { echo "FAIL: TOOLDIR not set" >&2; exit 2; }
. "$here/lib.sh"
of_env
work=$(mktemp -d "${TMPDIR:-/tmp}/umppm-cavity.XXXXXX")
fail=0
for run in "quad UMPPMstar fixedValue" "quad UMPPM fixedValue" "tri UMPPMstar movingWallVelocity"; do
    set -- $run
    d=$work/$1-$2
    if ! "$top/tools/cavityValidate.sh" -dir "$d" -Re 100 -mesh "$1" -n 20 -variant "$2" -lid "$3" -endTime 10 \
        > "$d.log" 2>&1; then
        echo "FAIL: cavityValidate.sh $run:"
        tail -5 "$d.log"
        fail=1
        continue
    fi
    line=$(grep '^RESULT' "$d.log")
    echo "$run: $line"
    get() { kv_get "$line" "$1"; }
    bound=0.012
    [ "$1" = tri ] && bound=0.010
    for k in u_rms v_rms; do
        check_below "$run $k" "$(get $k)" $bound
        check_below "$run $k / icoFoam's" "$(awk -v a="$(get $k)" -v b="$(get ico_$k)" 'BEGIN { print a / b }')" \
            "$([ "$1" = tri ] && echo 1.5 || echo 2)"
    done
    for k in u_max v_max; do check_below "$run $k" "$(get $k)" 0.03; done
    check_below "$run U vs icoFoam L2rel" "$(get UvsIco_L2rel)" 0.1
    check_below "$run continuity" "$(get cont_max)" 1e-12
done
[ "$fail" = 0 ] || { echo "work dir kept: $work"; exit 1; }
rm -rf "$work"
echo "PASS"
