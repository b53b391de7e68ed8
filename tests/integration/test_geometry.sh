#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# test_geometry.sh -- our 2-D mesh geometry against OpenFOAM's.
#
# For every case below: build the mesh with OpenFOAM/gmsh (in a mktemp dir),
# optionally convert it to binary and gzip it, write OpenFOAM's cell centres
# and volumes (0/C, 0/V, 17 digits), then run
#     $GEOMCHECK <casedir> 0
# which reads the case with our library and compares centroids and
# area x thickness to 1e-10 relative; it exits non-zero on a mismatch.
#
# Environment:
#   GEOMCHECK   path of the geometry-check program (required)
#   KEEP=1      keep the work directories (failed cases are always kept)
# Prints one PASS/FAIL line per case; exits non-zero if any case fails.
set -eu -o pipefail

here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"

if [ -z "${GEOMCHECK:-}" ]; then
    echo "test_geometry.sh: FAIL: GEOMCHECK is not set (export GEOMCHECK=<path of the geometry-check program>)" >&2
    exit 2
fi
if [ ! -x "$GEOMCHECK" ]; then
    echo "test_geometry.sh: FAIL: GEOMCHECK=$GEOMCHECK is not an executable file" >&2
    exit 2
fi
of_env || { echo "test_geometry.sh: FAIL: OpenFOAM environment not usable" >&2; exit 2; }

# label:template:conversions ("bin" = to_binary, "gz" = gzip_mesh)
cases="
cavity:cavity:
cavityGraded:cavityGraded:
holeHybrid:holeHybrid:
holeHybrid-binary:holeHybrid:bin
holeHybrid-binary-gz:holeHybrid:bin,gz
periodicSquare:periodicSquare:
periodicSquareSep:periodicSquareSep:
orientX:orientX:
orientY:orientY:
"

work=$(mktemp -d "${TMPDIR:-/tmp}/umppm-geom.XXXXXX")
nfail=0
npass=0

# prepare LABEL TEMPLATE CONVERSIONS CASEDIR
prepare() {
    local template=$2 conv=$3 dir=$4
    make_case "$template" "$dir" || return 1
    case ",$conv," in *,bin,*) to_binary "$dir" || return 1 ;; esac
    case ",$conv," in *,gz,*) gzip_mesh "$dir" || return 1 ;; esac
    write_geometry "$dir" || return 1
}

start=$(date +%s)
for spec in $cases; do
    label=${spec%%:*}
    rest=${spec#*:}
    template=${rest%%:*}
    conv=${rest#*:}
    dir=$work/$label
    if ! prepare "$label" "$template" "$conv" "$dir" 2>"$work/$label.setup.err"; then
        printf 'FAIL  %-22s (case setup failed; see below)\n' "$label"
        sed 's/^/      /' "$work/$label.setup.err"
        nfail=$((nfail + 1))
        continue
    fi
    rc=0
    "$GEOMCHECK" "$dir" 0 >"$dir/log.geomcheck" 2>&1 || rc=$?
    if [ "$rc" -eq 0 ]; then
        printf 'PASS  %-22s %s\n      %s\n' "$label" "$(checkmesh_cell_types "$dir")" "$(tail -n 1 "$dir/log.geomcheck")"
        npass=$((npass + 1))
        [ "${KEEP:-0}" = 1 ] || rm -rf "$dir" "$work/$label.setup.err"
    else
        printf 'FAIL  %-22s GEOMCHECK exit %d (case kept in %s)\n' "$label" "$rc" "$dir"
        tail -n 15 "$dir/log.geomcheck" | sed 's/^/      /'
        nfail=$((nfail + 1))
    fi
done

echo "test_geometry.sh: $npass passed, $nfail failed ($(($(date +%s) - start)) s)"
if [ "$nfail" -ne 0 ]; then
    echo "test_geometry.sh: work directory kept: $work"
    exit 1
fi
if [ "${KEEP:-0}" = 1 ]; then
    echo "test_geometry.sh: work directory kept: $work"
else
    rm -rf "$work"
fi
