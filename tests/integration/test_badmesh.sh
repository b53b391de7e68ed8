#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# test_badmesh.sh -- umppmFoam must reject broken meshes cleanly.
#
# Builds the cavity mesh once (ascii, and a binary copy), makes broken copies
# and runs `$UMPPMFOAM -case <dir> -checkMesh` on each. A case passes when
#   * the exit status is non-zero and below 128 (no signal, no timeout),
#   * stdout+stderr contain no "Sanitizer", "Segmentation" or "runtime error",
#   * at least one line on stderr names the offending file (owner, points...).
# A control run on the intact cavity must exit 0.
#
# Environment:
#   UMPPMFOAM   path of the umppmFoam binary (required)
#   KEEP=1      keep the work directory (it is also kept when a case fails)
#   BADMESH_TIMEOUT  seconds allowed per umppmFoam run (default 60)
# Prints one PASS/FAIL line per case; exits non-zero if any case fails.
set -eu -o pipefail

here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"

if [ -z "${UMPPMFOAM:-}" ]; then
    echo "test_badmesh.sh: FAIL: UMPPMFOAM is not set (export UMPPMFOAM=<path of the umppmFoam binary>)" >&2
    exit 2
fi
if [ ! -x "$UMPPMFOAM" ]; then
    echo "test_badmesh.sh: FAIL: UMPPMFOAM=$UMPPMFOAM is not an executable file" >&2
    exit 2
fi
of_env || { echo "test_badmesh.sh: FAIL: OpenFOAM environment not usable" >&2; exit 2; }

work=$(mktemp -d "${TMPDIR:-/tmp}/umppm-bad.XXXXXX")
good=$work/good
goodbin=$work/goodbin
if ! { make_case cavity "$good" && cp -R "$good" "$goodbin" && to_binary "$goodbin"; }; then
    echo "test_badmesh.sh: FAIL: could not build the cavity mesh (work dir $work)" >&2
    exit 1
fi
pm=constant/polyMesh   # used by the corruption snippets (eval)
export pm

# --- corruption helpers (ASCII polyMesh files as blockMesh writes them) ------

# list_item_set FILE K VALUE: replace item K (0-based) of a one-item-per-line
# list (the lines after the first line that is exactly "(").
list_item_set() {
    local f=$1
    awk -v k="$2" -v v="$3" '
        !started && $0 == "(" { started = 1; i = -1; print; next }
        started && i < k { i++; if (i == k) { print v; next } }
        { print }' "$f" >"$f.tmp" && mv "$f.tmp" "$f"
}

# list_count_set FILE OLD NEW: change the list size line OLD to NEW.
list_count_set() {
    local f=$1
    grep -qx "$2" "$f" || { echo "no count line '$2' in $f" >&2; return 1; }
    awk -v o="$2" -v n="$3" '!done && $0 == o { print n; done = 1; next } { print }' "$f" >"$f.tmp" &&
        mv "$f.tmp" "$f"
}

# cut_at FILE FRACTION: keep the first FRACTION (e.g. 0.5) of the bytes.
cut_at() {
    local f=$1 size keep
    size=$(wc -c <"$f")
    keep=$(awk -v s="$size" -v fr="$2" 'BEGIN { printf "%d", s * fr }')
    head -c "$keep" "$f" >"$f.tmp" && mv "$f.tmp" "$f"
}

# --- the cases: label | offending file | base case | corruption --------------
# Each corruption is a shell snippet run with $d = the broken case directory.

# shellcheck disable=SC2016
cases='
missing-owner|owner|good|rm "$d/$pm/owner"
points-truncated|points|good|cut_at "$d/$pm/points" 0.5
owner-count-1641|owner|good|list_count_set "$d/$pm/owner" 1640 1641
points-nan|points|good|list_item_set "$d/$pm/points" 1 "(nan 0 0)"
owner-index-ge-nCells|owner|good|list_item_set "$d/$pm/owner" 1639 400
neighbour-out-of-range|neighbour|good|list_item_set "$d/$pm/neighbour" 5 1000000
boundary-unbalanced-brace|boundary|good|awk "/^    }/ && !done { done = 1; next } { print }" "$d/$pm/boundary" >"$d/b.tmp" && mv "$d/b.tmp" "$d/$pm/boundary"
binary-points-cut|points|goodbin|cut_at "$d/$pm/points" 0.5
3d-no-empty|boundary|good|foam_set "$d" $pm/boundary entry0/frontAndBack/inGroups "1(patch)" && foam_set "$d" $pm/boundary entry0/frontAndBack/type patch
wedge-patch|boundary|good|foam_set "$d" $pm/boundary entry0/frontAndBack/inGroups "1(wedge)" && foam_set "$d" $pm/boundary entry0/frontAndBack/type wedge
'

nfail=0
npass=0
n=0

# run_umppm DIR: run the checker, sets rc, out (stdout+stderr), err (stderr).
run_umppm() {
    local d=$1
    rc=0
    timeout "${BADMESH_TIMEOUT:-60}" "$UMPPMFOAM" -case "$d" -checkMesh >"$d/log.umppm.out" 2>"$d/log.umppm.err" || rc=$?
}

crash_text() {
    grep -h -m 1 -E 'Sanitizer|Segmentation|runtime error' "$1/log.umppm.out" "$1/log.umppm.err" || true
}

# Control: the intact mesh must pass.
run_umppm "$good"
crash=$(crash_text "$good")
if [ "$rc" -eq 0 ] && [ -z "$crash" ]; then
    printf 'PASS  %-26s exit 0\n' "control-intact-cavity"
    npass=$((npass + 1))
else
    printf 'FAIL  %-26s intact mesh: exit %d %s\n' "control-intact-cavity" "$rc" "$crash"
    sed 's/^/      /' "$good/log.umppm.err" | tail -n 5
    nfail=$((nfail + 1))
fi

while IFS='|' read -r label file base corrupt; do
    [ -n "$label" ] || continue
    n=$((n + 1))
    d=$work/case$n                # neutral name: must not contain "$file"
    cp -R "$work/$base" "$d"
    rm -f "$d"/log.*
    if ! eval "$corrupt" 2>"$d/corrupt.err"; then
        printf 'FAIL  %-26s could not corrupt the mesh: %s\n' "$label" "$(head -n 3 "$d/corrupt.err")"
        nfail=$((nfail + 1))
        continue
    fi
    run_umppm "$d"
    why=""
    if [ "$rc" -eq 0 ]; then
        why="exit status 0 (broken mesh accepted)"
    elif [ "$rc" -eq 124 ]; then
        why="timed out after ${BADMESH_TIMEOUT:-60} s"
    elif [ "$rc" -ge 128 ]; then
        why="killed by a signal (exit $rc)"
    fi
    crash=$(crash_text "$d")
    [ -z "$crash" ] || why="${why:+$why; }crash report: $crash"
    line=$(grep -w -m 1 -F "$file" "$d/log.umppm.err" || true)
    [ -n "$line" ] || why="${why:+$why; }no stderr line names '$file'"
    if [ -z "$why" ]; then
        printf 'PASS  %-26s exit %d: %s\n' "$label" "$rc" "$line"
        npass=$((npass + 1))
    else
        printf 'FAIL  %-26s %s (case in %s)\n' "$label" "$why" "$d"
        sed 's/^/      stderr: /' "$d/log.umppm.err" | head -n 5
        nfail=$((nfail + 1))
    fi
done <<EOF
$cases
EOF

echo "test_badmesh.sh: $npass passed, $nfail failed"
if [ "$nfail" -ne 0 ] || [ "${KEEP:-0}" = 1 ]; then
    echo "test_badmesh.sh: work directory kept: $work"
else
    rm -rf "$work"
fi
[ "$nfail" -eq 0 ]
