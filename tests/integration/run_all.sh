#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# run_all.sh -- run every tests/integration/test_*.sh, print a summary.
#
# The tests get this script's environment, in particular
#   UMPPMFOAM   path of the umppmFoam binary
#   GEOMCHECK   path of the geometry-check program
# A test that needs a variable that is unset fails (it never passes silently).
# Exits non-zero if any test fails.
#
# UMPPM_TEST_JOBS (default: the number of processors) tests run at once,
# each with OMP_NUM_THREADS=1: two OpenMP programs with a thread per core
# each slow each other down 10-70x on a shared core (README "Runs sharing
# the cores"), and one thread per test keeps the cores busy without that.
# The runs that set their own thread count (test_threads.sh and
# test_meshless.sh compare 1 and 2 threads bit for bit) share the cores
# with the other tests too: OMP_WAIT_POLICY=passive makes their threads
# sleep at the barriers instead of spinning (measured: test_meshless.sh
# 41 s beside another test, 34 s alone; they ran alone, one after the
# other, until 2026-12-07). Every test writes into its own mktemp
# directory; its output is printed whole when it ends, so the log reads
# as with UMPPM_TEST_JOBS=1 (only the order differs).
set -eu

here=$(cd "$(dirname "$0")" && pwd)
jobs=${UMPPM_TEST_JOBS:-$(nproc 2>/dev/null || echo 1)}
case $jobs in '' | *[!0-9]* | 0) echo "run_all.sh: UMPPM_TEST_JOBS must be a positive integer, not '$jobs'" >&2; exit 1 ;; esac

echo "run_all.sh: UMPPMFOAM=${UMPPMFOAM:-<unset>}"
echo "run_all.sh: GEOMCHECK=${GEOMCHECK:-<unset>}"
echo "run_all.sh: $jobs at once"
echo "run_all.sh: UMPPM_TEST_SHORT=${UMPPM_TEST_SHORT:-<unset>} (1: the long accuracy runs short, lib.sh)"

# Started first, so that the longest do not end up last on one core (the
# CI of 2026-12-07: 90-250 s each in the plain pass, the others 1-60 s;
# in the sanitizer pass's short runs, lib.sh, 25-110 s)
LONGEST="test_nothing_lost.sh test_buoyant.sh test_tutorials.sh test_solver_re1000.sh
         test_solver_graded.sh test_solver_taylorGreen.sh test_meshless.sh"

pooled=""
for name in $LONGEST; do
    [ -f "$here/$name" ] && pooled="$pooled $name"
done
found=0
for t in "$here"/test_*.sh; do
    [ -f "$t" ] || continue
    found=$((found + 1))
    name=$(basename "$t")
    case " $pooled " in *" $name "*) continue ;; esac
    pooled="$pooled $name"
done
if [ "$found" -eq 0 ]; then
    echo "run_all.sh: FAIL: no test_*.sh in $here" >&2
    exit 1
fi

out=$(mktemp -d "${TMPDIR:-/tmp}/umppm-run_all.XXXXXX")
# on the way out (an interrupt included): no test left running, no files
cleanup() {
    local rc=$? pids
    pids=$(jobs -p)
    [ -z "$pids" ] || kill $pids 2>/dev/null || true
    rm -rf "$out"
    exit "$rc"
}
trap cleanup EXIT
passed=""
failed=""
declare -A name_of start_of

# finish PID RC: print the test's output and its verdict
finish() {
    local name=${name_of[$1]} secs=$(($(date +%s) - ${start_of[$1]}))
    echo "== $name"
    cat "$out/$name.log"
    if [ "$2" -eq 0 ]; then
        passed="$passed $name"
        echo "== $name: PASS (${secs} s)"
    else
        failed="$failed $name(exit $2)"
        echo "== $name: FAIL, exit $2 (${secs} s)"
    fi
}

# start NAME [ENV...]: the test in the background, its output to a file
start() {
    local name=$1
    shift
    env "$@" bash "$here/$name" > "$out/$name.log" 2>&1 &
    name_of[$!]=$name
    start_of[$!]=$(date +%s)
}

running=0
reap() {
    local pid rc=0
    wait -n -p pid || rc=$?
    finish "$pid" "$rc"
    running=$((running - 1))
}
for name in $pooled; do
    [ "$running" -lt "$jobs" ] || reap
    if [ "$jobs" -gt 1 ]; then
        start "$name" OMP_NUM_THREADS=1 OMP_WAIT_POLICY=passive
    else
        start "$name"
    fi
    running=$((running + 1))
done
while [ "$running" -gt 0 ]; do reap; done

echo "run_all.sh: summary"
echo "  passed:${passed:- none}"
echo "  failed:${failed:- none}"
[ -z "$failed" ]
