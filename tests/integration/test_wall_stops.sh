#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# test_wall_stops.sh -- no particle is lost through a wall on a high-Re run.
# The Re = 10000 lid-driven cavity of tutorials/cavityRe10000 on 32 x 32
# quads, UMPPM (alpha 0.09), CFL 0.1 (dt = 0.1/32), t = 1 (320 steps).
# Particles are pushed into the walls there by the first-order moves on
# curved paths; before wall stops (src/solver.c wall_stop) this run deleted
# such particles every few steps (170 in 800 steps on 80 x 80 to t = 1).
# Asserts, from the log:
#   - no particle left the closed cavity ("left through outlets" sums to 0);
#   - moves were stopped at walls (> 0: the case exercises the stop);
#   - the end-of-run summary line reports the same two totals;
#   - the run stays bounded: max |U| of the written cells <= 1.05 x lid speed.
# Needs UMPPMFOAM.
set -eu -o pipefail
here=$(cd "$(dirname "$0")" && pwd)
[ -n "${UMPPMFOAM:-}" ] && [ -x "$UMPPMFOAM" ] || { echo "FAIL: UMPPMFOAM not set" >&2; exit 2; }
. "$here/lib.sh"
of_env
work=$(mktemp -d "${TMPDIR:-/tmp}/umppm-wallstops.XXXXXX")
fail=0
c=$work/cavityRe10000
cp -r "$here/../../tutorials/cavityRe10000" "$c"
rm -rf "$c/0" && cp -r "$c/0.orig" "$c/0"
foam_set "$c" system/blockMeshDict n 32
foam_set "$c" system/controlDict deltaT 0.003125
foam_set "$c" system/controlDict endTime 1
foam_set "$c" system/controlDict writeInterval 1
run_in "$c" blockMesh blockMesh
if run_in "$c" umppmFoam "$UMPPMFOAM"; then
    log=$c/log.umppmFoam
    left=$(log_particles_left "$log")
    stops=$(log_wall_stops "$log")
    check_range "particles that left the closed cavity" "$left" 0 0
    check_range "moves stopped at walls" "$stops" 1 1e9
    summary=$(grep '^Particles over' "$log" || true)
    echo "  $summary"
    check_range "summary: left through outlets" "$(echo "$summary" | awk '{ print $5 }')" "$left" "$left"
    check_range "summary: moves stopped at walls" "$(echo "$summary" | awk '{ print $9 }')" "$stops" "$stops"
    umax=$(field_values "$c/1/U" | awk '{ u = sqrt($1 * $1 + $2 * $2); if (u > m) m = u } END { printf "%.4g", m }')
    check_range "max |U| / lid speed at t = 1" "$umax" 0 1.05
else
    echo "  FAIL umppmFoam failed"
    fail=1
fi
if [ $fail -eq 0 ]; then
    rm -rf "$work"
else
    echo "work dir kept: $work"
fi
exit $fail
