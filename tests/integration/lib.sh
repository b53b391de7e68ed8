# shellcheck shell=bash
# SPDX-License-Identifier: GPL-3.0-or-later
# lib.sh -- shell helpers for the OpenFOAM integration tests (bash).
#
# Source it:   . "$(dirname "$0")/lib.sh"
#
#   of_env                     export WM_PROJECT_DIR, check the OpenFOAM and
#                              gmsh binaries are on PATH
#   make_case NAME DEST        copy tests/cases/NAME to DEST and build its mesh
#                              (blockMesh, or gmsh + gmshToFoam + patch types);
#                              checkMesh must say "Mesh OK"; logs in DEST/log.*
#   to_binary CASE             rewrite constant/polyMesh in binary
#                              (foamFormatConvert, writeFormat binary)
#   gzip_mesh CASE             gzip points, faces, owner, neighbour in place
#   write_geometry CASE        write 0/C and 0/V (cell centres and volumes) in
#                              ascii with writePrecision 17
#   checkmesh_cell_types CASE  one line "hexahedra:N prisms:M ..." from
#                              CASE/log.checkMesh (non-zero counts only)
#   short_runs                 true in the sanitizer pass (UMPPM_TEST_SHORT=1)
#   short_end CASE END         in that pass, end CASE's run at END
#   short_ran CASE LOG WHAT RC in that pass, check the short run ended
#   short_run CASE END LOG WHAT CMD...  both, around CMD run in CASE
#
# The short pass. `make check` runs every test twice: built by gcc -O2,
# then by clang under AddressSanitizer and UBSan (`make asan`), which runs
# 3-10 x slower. The accuracy cases (hundreds to thousands of steps, their
# figures measured on the whole run) would take most of the time of the
# second pass and find nothing more than in their first steps: the
# sanitizers need each code path run, not run long. So `make asan` sets
# UMPPM_TEST_SHORT=1, and there the long tests run each of their
# umppmFoam cases, with the same mesh and settings, for a few steps
# (short_end), check that it ended cleanly (short_ran), and skip the
# figures, which the plain pass asserts on the full runs; nor do they run
# the OpenFOAM solvers that only give reference figures (but for the
# annulus tutorial's Allrun -test in test_buoyant.sh).
#
# Every function returns non-zero after printing "lib.sh: ..." to stderr when
# something fails (they do not rely on set -e, which bash ignores inside
# functions called from 'if' or '||'). Commands' output goes to CASE/log.<cmd>;
# on failure the tail of that log is printed.

# Directory of this file, and of the case templates.
UMPPM_INTEGRATION_DIR=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
UMPPM_CASES_DIR=$(cd "$UMPPM_INTEGRATION_DIR/../cases" && pwd)

lib_err() {
    printf 'lib.sh: error: %s\n' "$*" >&2
}

# of_env: OpenFOAM environment. WM_PROJECT_DIR defaults to the Debian location.
of_env() {
    export WM_PROJECT_DIR="${WM_PROJECT_DIR:-/usr/share/openfoam}"
    if [ ! -d "$WM_PROJECT_DIR" ]; then
        lib_err "WM_PROJECT_DIR=$WM_PROJECT_DIR is not a directory (OpenFOAM v1912 not installed?)"
        return 1
    fi
    local b missing=""
    for b in blockMesh gmshToFoam checkMesh postProcess foamFormatConvert foamDictionary gmsh gzip; do
        command -v "$b" >/dev/null 2>&1 || missing="$missing $b"
    done
    if [ -n "$missing" ]; then
        lib_err "missing on PATH:$missing (install the Debian packages 'openfoam' and 'gmsh': make deps)"
        return 1
    fi
}

short_runs() {
    [ "${UMPPM_TEST_SHORT:-0}" = 1 ]
}
# short_end CASE END: in the short pass, CASE/system/controlDict's endTime
# becomes END and its run writes there (writeInterval END; writeControl
# runTime unless it is adjustableRunTime, which hits END exactly with
# adjustTimeStep); in the plain pass nothing changes.
short_end() {
    short_runs || return 0
    local f=$1/system/controlDict
    # (the first entry of each: the top-level one, not a function object's;
    # comment lines are left alone)
    sed -i -E "/^[[:space:]]*\/\//b;
               0,/(^|[; ])endTime +[^;]*;/s//\1endTime $2;/;
               0,/(^|[; ])writeControl +[^;]*;/s/(^|[; ])writeControl +(timeStep|cpuTime|clockTime);/\1writeControl runTime;/;
               0,/(^|[; ])writeInterval +[^;]*;/s//\1writeInterval $2;/" "$f"
    if [ "$(short_endtime "$1")" != "$2" ] ||
        ! grep -v '^[[:space:]]*//' "$f" | grep -Eq "(^|[; ])writeInterval $2;"; then
        lib_err "short_end: could not set endTime and writeInterval $2 in $f"
        return 1
    fi
}
short_endtime() {
    grep -v '^[[:space:]]*//' "$1/system/controlDict" | sed -n -E 's/(^|.*[; ])endTime +([^;]*);.*/\2/p' | head -n 1
}
# short_ran CASE LOG WHAT RC: the short pass's check of a run that exited
# with RC: RC 0, its log CASE/LOG has "End" and no sanitizer report (a
# leak is reported after "End", at exit), and the end time is written;
# prints "ok" or "FAIL" (WHAT names the case) and sets the caller's fail=1
# on failure.
short_ran() {
    local end
    end=$(short_endtime "$1")
    if [ "$4" -eq 0 ] && grep -q '^End$' "$1/$2" 2>/dev/null && [ -d "$1/$end" ] &&
        ! grep -Eq 'Sanitizer|runtime error:' "$1/$2"; then
        echo "  ok   short pass: $3 ran to t = $end ($(grep -c '^Time = ' "$1/$2") steps)"
    else
        echo "  FAIL short pass: $3: exit $4, t = $end: $(grep -m 1 -E 'FATAL|ERROR|Sanitizer|runtime error:' "$1/$2" | cut -c1-200)"
        fail=1
    fi
}

# short_run CASE END LOG WHAT CMD...: the short pass's run of a case:
# short_end CASE END (not if END is empty), CMD run in CASE with its
# output in CASE/LOG, and short_ran on its exit status.
short_run() {
    local d=$1 end=$2 log=$3 what=$4 rc=0
    shift 4
    [ -z "$end" ] || short_end "$d" "$end" || { fail=1; return 0; }
    (cd "$d" && "$@") > "$d/$log" 2>&1 || rc=$?
    short_ran "$d" "$log" "$what" "$rc"
}

# run_in CASE LOGNAME CMD...: run CMD inside CASE, output to CASE/log.LOGNAME.
# Fails if CMD fails or the log contains "FOAM FATAL".
run_in() {
    local dir=$1 log=$2
    shift 2
    if ! (cd "$dir" && "$@") >"$dir/log.$log" 2>&1; then
        lib_err "'$*' failed in $dir (log: $dir/log.$log):"
        tail -n 20 "$dir/log.$log" | sed 's/^/    /' >&2
        return 1
    fi
    if grep -q 'FOAM FATAL' "$dir/log.$log"; then
        lib_err "'$*' reported FOAM FATAL in $dir (log: $dir/log.$log):"
        grep -A 8 'FOAM FATAL' "$dir/log.$log" | sed 's/^/    /' >&2
        return 1
    fi
}

# foam_set CASE FILE ENTRY VALUE: foamDictionary -entry ENTRY -set VALUE.
foam_set() {
    local dir=$1 file=$2 entry=$3 value=$4
    run_in "$dir" foamDictionary foamDictionary "$file" -entry "$entry" -set "$value"
}

# geo_patch_types GEO: the "<patch> <type>" pairs GEO lists as comment lines
# "// foam-patch-type: <patch> <type>", read by the tutorials' own
# geoPatchTypes (tutorials/RunFunctions, sourced in a subshell: its defaults
# for UMPPMFOAM and the like stay out of the tests).
geo_patch_types() {
    (. "$(dirname "${BASH_SOURCE[0]}")/../../tutorials/RunFunctions" && geoPatchTypes "$1")
}

# mesh_from_geo CASE GEO [H]: gmsh (GEO in CASE; with H, -setnumber h H) ->
# msh2 -> gmshToFoam, then the patch types of geo_patch_types GEO.
mesh_from_geo() {
    local dir=$1 geo=$2 base patch type
    local -a size=()
    [ $# -lt 3 ] || size=(-setnumber h "$3")
    base=$(basename "$geo" .geo)
    run_in "$dir" gmsh gmsh -3 -format msh2 "${size[@]}" "$base.geo" -o "$base.msh" || return 1
    run_in "$dir" gmshToFoam gmshToFoam "$base.msh" || return 1
    while read -r patch type; do
        [ -n "$patch" ] || continue
        if ! grep -Eq "^[[:space:]]*${patch}[[:space:]]*\$" "$dir/constant/polyMesh/boundary"; then
            lib_err "$geo names patch '$patch' but gmshToFoam wrote no such patch"
            return 1
        fi
        foam_set "$dir" constant/polyMesh/boundary "entry0/$patch/type" "$type" || return 1
    done <<EOF
$(geo_patch_types "$geo")
EOF
}

# make_case NAME DEST: DEST must not exist or be an empty directory.
make_case() {
    local name=${1:-} dest=${2:-} src geo
    if [ -z "$name" ] || [ -z "$dest" ]; then
        lib_err "usage: make_case NAME DESTDIR"
        return 1
    fi
    src=$UMPPM_CASES_DIR/$name
    if [ ! -d "$src" ]; then
        lib_err "no case template '$name' in $UMPPM_CASES_DIR"
        return 1
    fi
    if [ -e "$dest" ] && [ -n "$(ls -A "$dest")" ]; then
        lib_err "make_case: $dest exists and is not empty"
        return 1
    fi
    if ! { mkdir -p "$dest" && cp -R "$src/." "$dest/"; }; then
        lib_err "cannot copy $src to $dest"
        return 1
    fi
    if [ -f "$dest/system/blockMeshDict" ]; then
        run_in "$dest" blockMesh blockMesh || return 1
    else
        set -- "$dest"/*.geo
        if [ $# -ne 1 ] || [ ! -f "$1" ]; then
            lib_err "case $name has neither system/blockMeshDict nor exactly one .geo file"
            return 1
        fi
        mesh_from_geo "$dest" "$1" || return 1
    fi
    run_in "$dest" checkMesh checkMesh || return 1
    if ! grep -q '^Mesh OK' "$dest/log.checkMesh"; then
        lib_err "checkMesh did not report 'Mesh OK' for $name (log: $dest/log.checkMesh):"
        grep -E '\*\*\*|Failed' "$dest/log.checkMesh" | sed 's/^/    /' >&2
        return 1
    fi
}

# tutorial_copy SRC DEST: an OpenFOAM tutorial case (openfoam-examples,
# some files gzipped) copied to DEST with its files unpacked.
tutorial_copy() {
    cp -r "$1" "$2" && find "$2" -name '*.gz' -exec gzip -d {} +
}

# checkmesh_cell_types CASE: e.g. "hexahedra:160 prisms:664".
checkmesh_cell_types() {
    sed -n '/Overall number of cells of each type/,/polyhedra/p' "$1/log.checkMesh" |
        awk 'NF == 2 && $2 + 0 > 0 { printf "%s%s%s", sep, $1, $2; sep = " " } END { print "" }'
}

# polymesh_format FILE: the 'format' word in a FoamFile header (plain or .gz).
polymesh_format() {
    local f=$1
    if [ -f "$f.gz" ] && [ ! -f "$f" ]; then
        gzip -dc "$f.gz"
    else
        cat "$f"
    fi 2>/dev/null | head -c 2000 | tr -d '\0' |
        sed -n 's/^[[:space:]]*format[[:space:]]*\([a-z]*\);.*/\1/p' | head -n 1 || true
}

# to_binary CASE
to_binary() {
    local dir=${1:?usage: to_binary CASEDIR} f fmt
    foam_set "$dir" system/controlDict writeFormat binary || return 1
    run_in "$dir" foamFormatConvert foamFormatConvert -constant -noZero || return 1
    for f in points faces owner neighbour; do
        fmt=$(polymesh_format "$dir/constant/polyMesh/$f")
        if [ "$fmt" != binary ]; then
            lib_err "to_binary: constant/polyMesh/$f has format '$fmt', expected binary"
            return 1
        fi
    done
}

# gzip_mesh CASE
gzip_mesh() {
    local dir=${1:?usage: gzip_mesh CASEDIR} f
    for f in points faces owner neighbour; do
        if [ ! -f "$dir/constant/polyMesh/$f" ]; then
            lib_err "gzip_mesh: no constant/polyMesh/$f in $dir"
            return 1
        fi
        gzip -f "$dir/constant/polyMesh/$f" || { lib_err "gzip_mesh: gzip $f failed"; return 1; }
    done
}

# write_geometry CASE: 0/C (+Cx, Cy, Cz) and 0/V, ascii, 17 digits.
# writeFormat is set to ascii so the reference values are text even when the
# mesh itself was converted to binary.
write_geometry() {
    local dir=${1:?usage: write_geometry CASEDIR} f
    foam_set "$dir" system/controlDict writePrecision 17 || return 1
    foam_set "$dir" system/controlDict writeFormat ascii || return 1
    run_in "$dir" postProcess.writeCellCentres postProcess -func writeCellCentres -time 0 || return 1
    run_in "$dir" postProcess.writeCellVolumes postProcess -func writeCellVolumes -time 0 || return 1
    for f in C V; do
        if [ ! -f "$dir/0/$f" ]; then
            lib_err "write_geometry: postProcess did not write 0/$f in $dir"
            return 1
        fi
    done
}

# Checks of measured figures for the solver tests: print "ok"/"FAIL" with
# the value and set the caller's variable fail=1 on failure (a non-number
# fails too).
#   check_range NAME VALUE LOW HIGH    LOW <= VALUE <= HIGH
#   check_below NAME VALUE BOUND       VALUE < BOUND
check_range() {
    if awk -v a="$2" -v l="$3" -v h="$4" 'BEGIN { exit !(a + 0 == a && a >= l && a <= h) }'; then
        echo "  ok   $1 = $2 (in [$3, $4])"
    else
        echo "  FAIL $1 = $2 (expected [$3, $4])"
        fail=1
    fi
}
check_below() {
    if awk -v a="$2" -v b="$3" 'BEGIN { exit !(a + 0 == a && a < b) }'; then
        echo "  ok   $1 = $2 (< $3)"
    else
        echo "  FAIL $1 = $2 (bound $3)"
        fail=1
    fi
}

# From a umppmFoam log: the largest per-cell continuity error after the
# correction over all steps ("... max = X"), and the number of particles
# that left through open boundaries (outlets).
log_max_continuity() {
    grep -o 'max = [0-9.e+-]*' "$1" | awk '{ if ($3 > m) m = $3 } END { print m + 0 }'
}
# (0 when the log has no such line: the caller's check then says so,
# instead of pipefail ending the test without a word)
log_particles_left() {
    { grep -o 'left through outlets [0-9]*' "$1" || true; } | awk '{ s += $4 } END { print s + 0 }'
}
log_wall_stops() {
    { grep -o 'stopped at walls [0-9]*' "$1" || true; } | awk '{ s += $4 } END { print s + 0 }'
}

# kv_get LINE KEY: the value of KEY=value in a line of such pairs (the
# RESULT/OPERATOR/DIFFUSION lines of the tools); empty if absent.
kv_get() {
    echo "$1" | tr ' ' '\n' | sed -n "s/^$2=//p"
}
# observed_order E0 E1 N0 N1: log(E0/E1) / log(N1/N0), the order of an error
# going from resolution N0 to N1 (negative when it grows).
observed_order() {
    awk -v a="$1" -v b="$2" -v n0="$3" -v n1="$4" 'BEGIN { printf "%.3f", log(a / b) / log(n1 / n0) }'
}

# field_values FILE: the internalField entries of an ascii field file, one
# per line, vectors as "x y z" (a uniform field prints nothing).
field_values() {
    grep -q '^internalField *nonuniform' "$1" || return 0
    sed -n '/^internalField/,/^)/p' "$1" | sed '1,3d;$d' | tr -d '()'
}

# max_speed_files FILE...: "max file", the largest |U| (of the first two
# components) over the internal fields of the ascii vector field files
# FILE, uniform or not, and the file that holds it; "nan file..." if a file
# has no value. One awk over every file: a process pipeline per file took
# 11 s for the 80 writes of a buoyant case (test_buoyant.sh).
max_speed_files() {
    awk '
        BEGIN { best = -1 }
        function done_file() { if (n == 0) bad = bad " " f; else if (m > best) { best = m; at = f } }
        FNR == 1 { if (NR > 1) done_file(); f = FILENAME; st = 0; m = 0; n = 0 }
        st == 0 && /^internalField/ {
            if ($2 == "uniform") { v = $0; sub(/^[^(]*\(/, "", v); sub(/\).*/, "", v); split(v, a, " ")
                m = sqrt(a[1] * a[1] + a[2] * a[2]); n = 1; st = 3 }
            else st = 1
            next }
        st == 1 && /^\($/ { st = 2; next }
        st == 2 { if (/^\)/) { st = 3; next }
            v = $0; gsub(/[()]/, "", v); split(v, a, " "); u = sqrt(a[1] * a[1] + a[2] * a[2])
            if (u > m) m = u; n++ }
        END { done_file(); if (bad != "") print "nan" bad; else printf "%.6g %s\n", best, at }
    ' "$@"
}

# last_value FILE COLUMN: COLUMN of the last non-comment line (the
# postProcessing .dat files).
last_value() {
    grep -v '^#' "$1" | tail -n 1 | awk -v c="$2" '{ print $c }'
}
