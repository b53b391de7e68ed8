#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# test_checkmesh.sh -- `umppmFoam -checkMesh` prints the mesh quality figures
# under OpenFOAM's names, so they must be OpenFOAM's numbers: for OpenFOAM's
# elbow (fluentMeshToFoam: triangles and quadrilaterals) and its cavity
# graded 10:1 and sheared by moving its top vertices (blockMesh), the
# maximum and average non-orthogonality and the maximum skewness of
# `umppmFoam -checkMesh` must equal checkMesh's to 1e-4 relative (before
# 2026-12-06 the average was the mean angle, not the angle of the mean
# cosine, and boundary faces' skewness was normalised by 0.2 |d| instead of
# 0.4 |d|: the elbow's average read 7.89 against 11.19, pitzDaily's
# skewness 0.521 against 0.261).
set -eu -o pipefail
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"
[ -n "${UMPPMFOAM:-}" ] && [ -x "$UMPPMFOAM" ] || { echo "FAIL: UMPPMFOAM not set" >&2; exit 2; }
of_env || exit 2
examples=${OPENFOAM_EXAMPLES:-/usr/share/doc/openfoam-examples/examples}/incompressible/icoFoam
work=$(mktemp -d "${TMPDIR:-/tmp}/umppm-checkmesh.XXXXXX")
fail=0

elbow=$work/elbow
tutorial_copy "$examples/elbow" "$elbow"
run_in "$elbow" fluentMeshToFoam fluentMeshToFoam elbow.msh || exit 1
sheared=$work/sheared
tutorial_copy "$examples/cavity/cavity" "$sheared"
sed -i 's/^ *(1 1 0)/    (1.3 1 0)/; s/^ *(0 1 0)/    (0.3 1 0)/; s/^ *(1 1 0.1)/    (1.3 1 0.1)/; s/^ *(0 1 0.1)/    (0.3 1 0.1)/' \
    "$sheared/system/blockMeshDict"
sed -i 's/simpleGrading (1 1 1)/simpleGrading (10 0.1 1)/' "$sheared/system/blockMeshDict"
run_in "$sheared" blockMesh blockMesh || exit 1

# per case: "max average skewness" of checkMesh, then of umppmFoam -checkMesh
for c in "$elbow" "$sheared"; do
    name=$(basename "$c")
    (cd "$c" && checkMesh > log.checkMesh 2>&1) || true
    of=$(awk '/Mesh non-orthogonality Max:/ { a = $4; b = $6 } /Max skewness =/ { s = $4 }
              END { print a, b, s }' "$c/log.checkMesh")
    (cd "$c" && "$UMPPMFOAM" -checkMesh > log.umppm 2>&1) || { echo "FAIL  $name: umppmFoam -checkMesh"; fail=1; continue; }
    us=$(awk '/non-orthogonality: max/ { a = $3; b = $5 } /max skewness:/ { s = $3 } END { print a, b, s }' \
        "$c/log.umppm")
    if awk -v o="$of" -v u="$us" 'BEGIN { n = split(o, a, " "); if (split(u, b, " ") != 3 || n != 3) exit 1
            for (i = 1; i <= 3; i++) { d = a[i] - b[i]; d = d < 0 ? -d : d; if (!(d <= 1e-4 * (a[i] < 0 ? -a[i] : a[i]) + 1e-12)) exit 1 }
            exit 0 }'; then
        echo "PASS  $name: non-orthogonality max/average and max skewness $us (checkMesh $of)"
    else
        echo "FAIL  $name: umppmFoam -checkMesh '$us', checkMesh '$of'"
        fail=1
    fi
done
[ "$fail" -eq 0 ] && rm -rf "$work" || echo "work dir kept: $work"
exit "$fail"
