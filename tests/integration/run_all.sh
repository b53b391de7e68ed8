#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# run_all.sh -- run every tests/integration/test_*.sh, print a summary.
#
# The tests get this script's environment, in particular
#   UMPPMFOAM   path of the umppmFoam binary
#   GEOMCHECK   path of the geometry-check program
# A test that needs a variable that is unset fails (it never passes silently).
# Exits non-zero if any test fails.
set -eu

here=$(cd "$(dirname "$0")" && pwd)

echo "run_all.sh: UMPPMFOAM=${UMPPMFOAM:-<unset>}"
echo "run_all.sh: GEOMCHECK=${GEOMCHECK:-<unset>}"

passed=""
failed=""
found=0
for t in "$here"/test_*.sh; do
    [ -f "$t" ] || continue
    found=$((found + 1))
    name=$(basename "$t")
    echo "== $name"
    start=$(date +%s)
    rc=0
    bash "$t" || rc=$?
    secs=$(($(date +%s) - start))
    if [ "$rc" -eq 0 ]; then
        passed="$passed $name"
        echo "== $name: PASS (${secs} s)"
    else
        failed="$failed $name(exit $rc)"
        echo "== $name: FAIL, exit $rc (${secs} s)"
    fi
done

if [ "$found" -eq 0 ]; then
    echo "run_all.sh: FAIL: no test_*.sh in $here" >&2
    exit 1
fi
echo "run_all.sh: summary"
echo "  passed:${passed:- none}"
echo "  failed:${failed:- none}"
[ -z "$failed" ]
