#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# mesh_io.sh -- cost of reading an OpenFOAM case and building the 2-D UMPPM
# pressure mesh (umppmFoam -checkMesh), against OpenFOAM's own checkMesh on
# the same mesh. Prints a table: case, cells, format, seconds, peak RSS.
#   bench/mesh_io.sh [N...]     (N x N cavity meshes; default 100 200 400)
set -eu
here=$(cd "$(dirname "$0")" && pwd)
top=$(cd "$here/.." && pwd)
UMPPMFOAM=${UMPPMFOAM:-$top/bin/umppmFoam}
export WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam}
sizes=${*:-100 200 400}
work=$(mktemp -d /tmp/umppm-bench-XXXXXX)
trap 'rm -rf "$work"' EXIT
printf "%-14s %9s %-7s %12s %9s %12s %9s\n" case cells format "umppm [s]" "RSS[MiB]" "checkMesh[s]" "RSS[MiB]"
for n in $sizes; do
    c="$work/cavity$n"
    cp -r "$top/tests/cases/cavity" "$c"
    sed -i "s/(20 20 1)/($n $n 1)/" "$c/system/blockMeshDict"
    (cd "$c" && blockMesh > log.blockMesh 2>&1)
    for fmt in ascii binary; do
        if [ "$fmt" = binary ]; then
            sed -i 's/^writeFormat .*/writeFormat binary;/' "$c/system/controlDict"
            (cd "$c" && foamFormatConvert -constant -noZero > log.convert 2>&1)
        fi
        read -r tu ru rcu < <(python3 "$here/run_measured.py" "$UMPPMFOAM" -case "$c" -checkMesh)
        read -r to ro rco < <(python3 "$here/run_measured.py" checkMesh -case "$c" -constant)
        [ "$rcu" = 0 ] || echo "umppmFoam failed on $c ($fmt)" >&2
        printf "%-14s %9d %-7s %12s %9s %12s %9s\n" "cavity$n" $((n * n)) "$fmt" "$tu" "$ru" "$to" "$ro"
    done
done
