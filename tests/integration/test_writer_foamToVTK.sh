#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# test_writer_foamToVTK.sh -- OpenFOAM reads what the umppmFoam writer
# writes. Builds the icoFoam cavity with blockMesh in a scratch directory,
# runs write_cavity_fields (tests/integration/write_cavity_fields.c) to write
# U and p into 0.1 (ascii), 0.2 (binary) and 0.3 (ascii + gzip), then:
#   - foamToVTK must succeed, name its output after our uniform/time index
#     (cavity_20/40/60), and its ascii VTK must hold our cell values and the
#     nonuniform movingWall values;
#   - postProcess -func sample with interpolationScheme cell must return
#     our cell values exactly (row j is cell 10 + 20 j).
# Exits non-zero on any failure or mismatch.
#
# Usage: tests/integration/test_writer_foamToVTK.sh [<path-to-write_cavity_fields>]
#        (default: $WRITE_CAVITY_FIELDS, as run_all.sh passes it)

set -eu

arg=${1:-${WRITE_CAVITY_FIELDS:-}}
if [ -z "$arg" ] || [ ! -x "$arg" ]; then
    echo "FAIL: give the built write_cavity_fields program as argument or in WRITE_CAVITY_FIELDS" >&2
    exit 2
fi
case "$arg" in
    /*) prog=$arg ;;
    *) prog=$(pwd)/$arg ;;
esac

export WM_PROJECT_DIR="${WM_PROJECT_DIR:-/usr/share/openfoam}"
src=/usr/share/doc/openfoam-examples/examples/incompressible/icoFoam/cavity/cavity
for tool in blockMesh foamToVTK postProcess; do
    command -v "$tool" >/dev/null 2>&1 || { echo "FAIL: $tool not found" >&2; exit 1; }
done
[ -d "$src" ] || { echo "FAIL: $src missing" >&2; exit 1; }

tmp=$(mktemp -d "${TMPDIR:-/tmp}/umppm-writer-XXXXXX")
keep=0
cleanup() { if [ "$keep" = 0 ]; then rm -rf "$tmp"; else echo "kept $tmp" >&2; fi; }
trap cleanup EXIT

fail() {
    echo "FAIL: $*" >&2
    keep=1
    exit 1
}

cp -r "$src" "$tmp/cavity"
cd "$tmp/cavity"

blockMesh > log.blockMesh 2>&1 || fail "blockMesh (see log.blockMesh)"
"$prog" . > log.write 2>&1 || fail "write_cavity_fields: $(cat log.write)"

# layout: plain, plain, compressed; no hidden temporary directories left
[ -f 0.1/U ] && [ -f 0.1/p ] && [ -f 0.1/uniform/time ] || fail "0.1 incomplete"
[ -f 0.2/U ] && [ -f 0.2/p ] || fail "0.2 incomplete"
[ -f 0.3/U.gz ] && [ -f 0.3/p.gz ] && [ ! -e 0.3/U ] || fail "0.3 not compressed"
grep -q '^    format      binary;' 0.2/U || fail "0.2/U not binary"
[ -z "$(ls -A | grep '^\.' || true)" ] || fail "hidden leftovers: $(ls -A)"

# ---- foamToVTK ----------------------------------------------------------
# default (binary VTK) output first, then ascii VTK to compare values
foamToVTK -time '0.1:0.3' > log.foamToVTK 2>&1 || fail "foamToVTK (see log.foamToVTK)"
grep -q 'FOAM FATAL' log.foamToVTK && fail "foamToVTK: fatal error"
rm -rf VTK
foamToVTK -ascii -time '0.1:0.3' > log.foamToVTK.ascii 2>&1 \
    || fail "foamToVTK -ascii (see log.foamToVTK.ascii)"

# Values of DataArray <name> in the first <section> (CellData) of a VTK XML file.
vtk_array() { # file section name
    awk -v sec="$2" -v name="$3" -v q="'" '
        index($0, "<" sec ">") { insec = 1 }
        index($0, "</" sec ">") { insec = 0 }
        insec && !done && index($0, "<DataArray") && index($0, "Name=" q name q) { on = 1; next }
        on && index($0, "</DataArray>") { on = 0; done = 1 }
        on { for (i = 1; i <= NF; i++) print $i }
    ' "$1"
}

for idx in 20 40 60; do
    d=VTK/cavity_$idx
    [ -f "$d/internal.vtu" ] || fail "foamToVTK wrote no $d/internal.vtu (uniform/time index not read?)"
    vtk_array "$d/internal.vtu" CellData U | awk '
        { v[NR - 1] = $1 }
        END {
            if (NR != 1200) { print "U: " NR " values, expected 1200"; exit 1 }
            for (c = 0; c < 400; c++)
                if (v[3*c] != c || v[3*c+1] != 2*c || v[3*c+2] != 0) {
                    print "U cell " c ": " v[3*c] " " v[3*c+1] " " v[3*c+2]; exit 1 }
        }' || fail "$d/internal.vtu: U differs"
    vtk_array "$d/internal.vtu" CellData p | awk '
        { v[NR - 1] = $1 }
        END {
            if (NR != 400) { print "p: " NR " values"; exit 1 }
            for (c = 0; c < 400; c++)
                if (v[c] != c + 0.25) { print "p cell " c ": " v[c]; exit 1 }
        }' || fail "$d/internal.vtu: p differs"
    vtk_array "$d/boundary/movingWall.vtp" CellData U | awk '
        { v[NR - 1] = $1 }
        END {
            if (NR != 60) { print "movingWall U: " NR " values"; exit 1 }
            for (i = 0; i < 20; i++)
                if (v[3*i] != 1 + i || v[3*i+1] != 0 || v[3*i+2] != 0) {
                    print "movingWall face " i ": " v[3*i]; exit 1 }
        }' || fail "$d/boundary/movingWall.vtp: U differs"
done

# ---- postProcess -func sample (cell values, no interpolation) -----------
cat > system/sample <<'EOF'
FoamFile { version 2.0; format ascii; class dictionary; object sample; }
type sets;
libs (sampling);
writeControl writeTime;
interpolationScheme cell;
setFormat raw;
fields (U p);
sets
(
    centreline
    {
        type midPoint;
        axis y;
        start (0.0525 0 0.005);
        end (0.0525 0.1 0.005);
    }
);
EOF
postProcess -func sample -time '0.1:0.3' > log.sample 2>&1 || fail "postProcess sample (see log.sample)"
grep -q 'FOAM FATAL' log.sample && fail "postProcess: fatal error"

for t in 0.1 0.2 0.3; do
    dir=postProcessing/sample/$t
    [ -f "$dir/centreline_U.xy" ] && [ -f "$dir/centreline_p.xy" ] || fail "no sample output for $t"
    awk '
        { c = 10 + 20 * (NR - 1)
          if ($2 != c || $3 != 2 * c || $4 != 0) { print "row " NR ": " $0; bad = 1; exit 1 } }
        END { if (!bad && NR != 20) { print NR " rows"; exit 1 } }
    ' "$dir/centreline_U.xy" || fail "$t: sampled U differs"
    awk '
        { c = 10 + 20 * (NR - 1)
          if ($2 != c + 0.25) { print "row " NR ": " $0; bad = 1; exit 1 } }
        END { if (!bad && NR != 20) { print NR " rows"; exit 1 } }
    ' "$dir/centreline_p.xy" || fail "$t: sampled p differs"
done

echo "PASS: foamToVTK and sample read ascii, binary and gzip fields written by umppmFoam"
