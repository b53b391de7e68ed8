#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# test_badmesh_topology.sh -- topology and integer-range errors in polyMesh
# files (issue 15): duplicate faces, open cells, repeated face points,
# out-of-range sizes and labels, a one-cell-wide cyclic mesh, a zero-area
# cell...
#
# Builds the 20x20 cavity and the periodic square, makes broken copies and
# runs `$UMPPMFOAM -case <dir> -checkMesh` on each. A case passes when
#   * the exit status is non-zero and below 128 (no signal, no timeout),
#   * stdout+stderr contain no "Sanitizer", "Segmentation" or "runtime error",
#   * stderr names the offending file and matches the case's message
#     (an extended regular expression).
# Each broken mesh is also given to OpenFOAM's `checkMesh -allTopology`; its
# verdict (fail: "Failed N mesh checks" or FOAM FATAL; ok: "Mesh OK"; crash:
# neither, e.g. a segmentation fault or an abort without a message) must be
# the one recorded in the table, so the table documents where OpenFOAM flags
# the mesh too and where it does not. The one-cell cyclic mesh is also run
# (not only -checkMesh) and must fail with the same message.
#
# Environment: UMPPMFOAM (required), KEEP=1 keeps the work directory,
# BADMESH_TIMEOUT seconds per run (default 60).
set -eu -o pipefail

here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"

if [ -z "${UMPPMFOAM:-}" ] || [ ! -x "$UMPPMFOAM" ]; then
    echo "test_badmesh_topology.sh: FAIL: UMPPMFOAM is not set to an executable" >&2
    exit 2
fi
of_env || { echo "test_badmesh_topology.sh: FAIL: OpenFOAM environment not usable" >&2; exit 2; }

work=$(mktemp -d "${TMPDIR:-/tmp}/umppm-badtopo.XXXXXX")
if ! { make_case cavity "$work/good" && make_case periodicSquare "$work/periodic"; }; then
    echo "test_badmesh_topology.sh: FAIL: could not build the meshes (work dir $work)" >&2
    exit 1
fi
# the periodic square one cell wide between left and right
mkdir -p "$work/cyc1"
cp -R "$work/periodic/0" "$work/periodic/system" "$work/periodic/constant" "$work/cyc1/"
sed -i 's/(16 16 1)/(1 16 1)/' "$work/cyc1/system/blockMeshDict"
run_in "$work/cyc1" blockMesh blockMesh || exit 1
pm=constant/polyMesh
export pm

# list_item_set FILE K VALUE: replace item K (0-based) of a one-item-per-line list.
list_item_set() {
    awk -v k="$2" -v v="$3" '
        !started && $0 == "(" { started = 1; i = -1; print; next }
        started && i < k { i++; if (i == k) { print v; next } }
        { print }' "$1" >"$1.tmp" && mv "$1.tmp" "$1"
}
# list_item_get FILE K
list_item_get() {
    awk -v k="$2" '!started && $0 == "(" { started = 1; i = -1; next }
        started { i++; if (i == k) { print; exit } }' "$1"
}
# list_item_del FILE K: delete item K (the count is left alone).
list_item_del() {
    awk -v k="$2" '
        !started && $0 == "(" { started = 1; i = -1; print; next }
        started && i < k { i++; if (i == k) next }
        { print }' "$1" >"$1.tmp" && mv "$1.tmp" "$1"
}
# list_count_set FILE OLD NEW
list_count_set() {
    grep -qx "$2" "$1" || { echo "no count line '$2' in $1" >&2; return 1; }
    awk -v o="$2" -v n="$3" '!done && $0 == o { print n; done = 1; next } { print }' "$1" >"$1.tmp" &&
        mv "$1.tmp" "$1"
}
# patch_set FILE PATCH KEY VALUE: KEY inside patch PATCH of a boundary file
patch_set() {
    awk -v p="$2" -v k="$3" -v v="$4" '
        $1 == p { inp = 1 } inp && $1 == k { sub(/[^ ]+;$/, v ";"); inp = 0 } { print }' "$1" >"$1.tmp" &&
        mv "$1.tmp" "$1"
}
cut_at() {
    local size keep
    size=$(wc -c <"$1")
    keep=$(awk -v s="$size" -v fr="$2" 'BEGIN { printf "%d", s * fr }')
    head -c "$keep" "$1" >"$1.tmp" && mv "$1.tmp" "$1"
}
export -f list_item_set list_item_get list_item_del list_count_set patch_set cut_at

# label | file named | base | message regex | checkMesh -allTopology | corruption ($d = case)
# shellcheck disable=SC2016
cases='
duplicate-face|faces|good|faces 0 and 1 have the same 4 points: duplicate faces|fail|list_item_set "$d/$pm/faces" 1 "$(list_item_get "$d/$pm/faces" 0)"
duplicate-boundary-face|faces|good|faces 760 and 761 have the same 4 points: duplicate faces|fail|list_item_set "$d/$pm/faces" 761 "$(list_item_get "$d/$pm/faces" 760)"
open-cell-moved-face|owner|good|cell [0-9]+ is open: its edge \([0-9]+ [0-9]+\) is used by [0-9] of its faces|fail|list_item_set "$d/$pm/owner" 780 200
open-cell-flipped-face|faces|good|cell 380 is open: the sum of its outward face area vectors|fail|list_item_set "$d/$pm/faces" 760 "$(list_item_get "$d/$pm/faces" 760 | sed "s/4(\([0-9]*\) \([0-9]*\) \([0-9]*\) \([0-9]*\))/4(\4 \3 \2 \1)/")"
face-repeated-point|faces|good|face 0 uses point 22 twice|crash|list_item_set "$d/$pm/faces" 0 "4(1 22 22 442)"
nFaces-int32-max|boundary|good|patch .movingWall. has startFace 760 and nFaces 2147483647, beyond the 1640 faces|crash|patch_set "$d/$pm/boundary" movingWall nFaces 2147483647
startFace-int32-max|boundary|good|patch .frontAndBack. starts at face 2147483647, expected 840|crash|patch_set "$d/$pm/boundary" frontAndBack startFace 2147483647
startFace-64bit|boundary|good|patch .fixedWalls.: startFace 4294967296 is out of range|fail|patch_set "$d/$pm/boundary" fixedWalls startFace 4294967296
nFaces-negative|boundary|good|patch .movingWall.: nFaces -20 is out of range|crash|patch_set "$d/$pm/boundary" movingWall nFaces -20
list-size-negative|owner|good|expected a list size between 0 and 2147483647, found label -5|fail|list_count_set "$d/$pm/owner" 1640 -5
list-size-beyond-label|faces|good|expected a list size between 0 and 2147483647, found label 3000000000|fail|list_count_set "$d/$pm/faces" 1640 3000000000
point-label-out-of-range|faces|good|face 5 uses point 1000000, but points has 882 entries|crash|list_item_set "$d/$pm/faces" 5 "4(2 1000000 464 443)"
owner-label-64bit|owner|good|label 4294967296 out of range|fail|list_item_set "$d/$pm/owner" 7 4294967296
owner-label-int32-max|owner|good|face 9 has owner 2147483647: out of range \(1640 faces close at most 820 cells\)|fail|sed -i "/note/d" "$d/$pm/owner" && list_item_set "$d/$pm/owner" 9 2147483647
faces-truncated|faces|good|faces|fail|cut_at "$d/$pm/faces" 0.6
owner-size-mismatch|owner|good|owner: 1639 entries, but faces has 1640 faces|crash|list_item_del "$d/$pm/owner" 1639 && list_count_set "$d/$pm/owner" 1640 1639
neighbour-size-mismatch|boundary|good|patch .movingWall. starts at face 760, expected 759|fail|list_item_del "$d/$pm/neighbour" 759 && list_count_set "$d/$pm/neighbour" 760 759
zero-area-cell|points|good|cell 0 has zero area: its face [0-9]+ on empty patch .frontAndBack. has area 0|fail|list_item_set "$d/$pm/points" 21 "(0 0 0)" && list_item_set "$d/$pm/points" 22 "(0.005 0 0)" && list_item_set "$d/$pm/points" 462 "(0 0 0.01)" && list_item_set "$d/$pm/points" 463 "(0.005 0 0.01)"
one-cell-cyclic|boundary|cyc1|the mesh is one cell wide between the pair, so the cell is its own periodic neighbour|ok|true
'

nfail=0
npass=0
n=0
crash_text() {
    grep -h -m 1 -E 'Sanitizer|Segmentation|runtime error' "$@" || true
}

# check_run DIR LABEL FILE REGEX LOGNAME ARGS...: run umppmFoam, judge, print.
check_run() {
    local d=$1 label=$2 file=$3 re=$4 log=$5 rc=0 why="" crash line
    shift 5
    timeout "${BADMESH_TIMEOUT:-60}" "$UMPPMFOAM" -case "$d" "$@" >"$d/$log.out" 2>"$d/$log.err" || rc=$?
    if [ "$rc" -eq 0 ]; then why="exit status 0 (broken mesh accepted)"
    elif [ "$rc" -eq 124 ]; then why="timed out"
    elif [ "$rc" -ge 128 ]; then why="killed by a signal (exit $rc)"; fi
    crash=$(crash_text "$d/$log.out" "$d/$log.err")
    [ -z "$crash" ] || why="${why:+$why; }crash report: $crash"
    line=$(grep -m 1 -E "$re" "$d/$log.err" || true)
    [ -n "$line" ] || why="${why:+$why; }no stderr line matches '$re'"
    if [ -n "$line" ] && ! echo "$line" | grep -qw -F "$file"; then
        why="${why:+$why; }the message does not name '$file'"
    fi
    if [ -z "$why" ]; then
        printf 'PASS  %-26s exit %d: %s\n' "$label" "$rc" "$line"
        npass=$((npass + 1))
    else
        printf 'FAIL  %-26s %s (case in %s)\n' "$label" "$why" "$d"
        sed 's/^/      stderr: /' "$d/$log.err" | head -n 5
        nfail=$((nfail + 1))
    fi
}

# of_verdict DIR: fail / ok / crash from checkMesh -allTopology
of_verdict() {
    local rc=0
    (cd "$1" && timeout 120 checkMesh -allTopology) >"$1/log.checkMesh" 2>&1 || rc=$?
    if grep -q '^Mesh OK' "$1/log.checkMesh"; then echo ok
    elif grep -qE 'Failed [0-9]+ mesh check|FOAM FATAL' "$1/log.checkMesh"; then echo fail
    else echo crash; fi
}

rc=0
"$UMPPMFOAM" -case "$work/good" -checkMesh >"$work/good/log.umppm" 2>&1 || rc=$?
if [ "$rc" -eq 0 ]; then
    printf 'PASS  %-26s exit 0\n' control-intact-cavity
    npass=$((npass + 1))
else
    printf 'FAIL  %-26s intact mesh: exit %d\n' control-intact-cavity "$rc"
    nfail=$((nfail + 1))
fi

while IFS='|' read -r label file base re ofexp corrupt; do
    [ -n "$label" ] || continue
    n=$((n + 1))
    d=$work/case$n
    cp -R "$work/$base" "$d"
    rm -f "$d"/log.*
    if ! (export d; eval "$corrupt") 2>"$d/corrupt.err"; then
        printf 'FAIL  %-26s could not corrupt the mesh: %s\n' "$label" "$(head -n 3 "$d/corrupt.err")"
        nfail=$((nfail + 1))
        continue
    fi
    check_run "$d" "$label" "$file" "$re" log.umppm -checkMesh
    [ "$label" != one-cell-cyclic ] || check_run "$d" "$label(run)" "$file" "$re" log.run
    ofv=$(of_verdict "$d")
    if [ "$ofv" = "$ofexp" ]; then
        printf 'PASS  %-26s checkMesh -allTopology: %s, as recorded\n' "$label" "$ofv"
        npass=$((npass + 1))
    else
        printf 'FAIL  %-26s checkMesh -allTopology: %s, recorded %s (log %s)\n' "$label" "$ofv" "$ofexp" \
            "$d/log.checkMesh"
        nfail=$((nfail + 1))
    fi
done <<EOF
$cases
EOF

echo "test_badmesh_topology.sh: $npass passed, $nfail failed"
if [ "$nfail" -ne 0 ] || [ "${KEEP:-0}" = 1 ]; then
    echo "test_badmesh_topology.sh: work directory kept: $work"
else
    rm -rf "$work"
fi
[ "$nfail" -eq 0 ]
