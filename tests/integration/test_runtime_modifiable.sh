#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# test_runtime_modifiable.sh -- runTimeModifiable (issue 15, item 4): an
# edit of system/controlDict during a run is picked up at the next time
# step, as OpenFOAM v1912 does.
#
# The edits are deterministic: $EDITSHIM (tests/integration/editshim.c,
# LD_PRELOAD) renames a prepared controlDict over the case's when the
# solver creates the directory of a chosen write time, so the solver sees
# it at the start of the following step. The same shim drives icoFoam, which
# serves as the oracle: on the 20x20 cavity (deltaT 0.005, endTime 0.1,
# writeInterval 2) with the same edit, umppmFoam must write the same time
# directories with the same uniform/time (value to 18 digits, index,
# deltaT, deltaT0), for
#   1. stopAt writeNow, noWriteNow, nextWrite; endTime later, and earlier
#      than the current time (the run ends at once);
#   2. deltaT (writeControl timeStep and runTime), writeInterval (runTime:
#      the count of writes so far is rescaled), purgeWrite;
#   3. runTimeModifiable false from the start (the edit is ignored), and
#      switched off by an edit (a later edit is ignored);
#   4. a surfaceFieldValue function object added mid-run (its rows start
#      at the re-read time, as OpenFOAM's) while an unchanged one continues
#      its series in the same file.
# umppmFoam only:
#   5. bad edits (endTime nan, stopAt foo, deltaT -1, a syntax error, a
#      function object on a patch that does not exist): one warning naming
#      the file, the line and the entry, the run goes on with the settings
#      it had (also not taking the good entries of the bad file), and a
#      later good edit is still picked up;
#   6. writeFormat binary + writePrecision: the times after the edit are
#      binary;
#   7. the re-read line and the change summary in the log, right before the
#      step after the edited write time; stopAt's closing line.
# Every umppmFoam run: exit 0, "End", no sanitizer report, every edit
# consumed by the shim.
set -eu -o pipefail

here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"
for v in UMPPMFOAM EDITSHIM; do
    if [ -z "${!v:-}" ] || [ ! -e "${!v}" ]; then
        echo "test_runtime_modifiable.sh: FAIL: $v is not set to an existing file" >&2
        exit 2
    fi
done
of_env || exit 2
command -v icoFoam >/dev/null || { echo "test_runtime_modifiable.sh: FAIL: icoFoam not on PATH" >&2; exit 2; }
# the shim is not sanitized: ASan must accept a preloaded library before it
export ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}verify_asan_link_order=0"
# the re-read is outside the numerics; one thread keeps the runs short on a
# shared machine (test_threads.sh covers the threads)
export OMP_NUM_THREADS=1
work=$(mktemp -d "${TMPDIR:-/tmp}/umppm-rtm.XXXXXX")
base=$work/base
make_case cavity "$base" >/dev/null || { echo "FAIL: cannot build cavity" >&2; exit 1; }
setctl() { sed -i "s/^$2 .*/$2 $3;/" "$1"; }
setctl "$base/system/controlDict" endTime 0.1
setctl "$base/system/controlDict" writeInterval 2

fail=0
ok() { echo "  ok   $*"; }
bad() { echo "  FAIL $*"; fail=1; }

# prepare DIR BASESED T1 SED1 [T2 SED2 ...]: a copy of the base case in DIR
# with BASESED applied to its controlDict, and the edits edit.1, edit.2 ...
# (each is the base controlDict with its SED applied); sets $edits to the
# shim's "T=FILE ..." list. The mtimes are set apart by minutes, in the
# order of the edits: OpenFOAM takes a file as modified only when its mtime
# is later than the one it read by fileModificationSkew (10 s).
prepare() {
    local d=$1 bsed=$2 k=0
    shift 2
    rm -rf "$d"
    mkdir -p "$d"
    cp -R "$base/0" "$base/constant" "$base/system" "$d/"
    [ -z "$bsed" ] || sed -i "$bsed" "$d/system/controlDict"
    touch -d '-3 hours' "$d/system/controlDict"
    edits=""
    while [ $# -ge 2 ]; do
        k=$((k + 1))
        cp "$d/system/controlDict" "$d/edit.$k"
        sed -i "$2" "$d/edit.$k"
        touch -d "-$((120 - 10 * k)) minutes" "$d/edit.$k"
        edits="$edits $1=$d/edit.$k"
        shift 2
    done
    edits=${edits# }
}

# run_ump DIR: umppmFoam with the edits; log DIR/log, stderr DIR/err; rc
run_ump() {
    rc=0
    LD_PRELOAD=$EDITSHIM UMPPM_EDIT_TARGET="$1/system/controlDict" UMPPM_EDIT_AT="$edits" \
        timeout 300 "$UMPPMFOAM" -case "$1" >"$1/log" 2>"$1/err" || rc=$?
}
# run_ico DIR: the same with icoFoam
run_ico() {
    local r=0
    (cd "$1" && LD_PRELOAD=$EDITSHIM UMPPM_EDIT_TARGET="$1/system/controlDict" UMPPM_EDIT_AT="$edits" \
        timeout 300 icoFoam >log 2>&1) || r=$?
    if [ "$r" -ne 0 ] || grep -q 'FOAM FATAL' "$1/log"; then
        echo "  (icoFoam failed in $1, exit $r:)"
        tail -n 5 "$1/log" | sed 's/^/    /'
        return 1
    fi
}

# times DIR: "name value index deltaT deltaT0" per time directory (0 has no
# uniform/time), sorted by time
times() {
    local t
    for t in $(cd "$1" && ls -d [0-9]* | sort -g); do
        printf '%s' "$t"
        [ -f "$1/$t/uniform/time" ] &&
            sed -n 's/^\(value\|index\|deltaT\|deltaT0\)[[:space:]]\+\([^;]*\);.*/ \2/p' "$1/$t/uniform/time" |
            tr -d '\n'
        echo
    done
}
names() { (cd "$1" && ls -d [0-9]* | sort -g | tr '\n' ' ' | sed 's/ $//'); }

# ump_sane DIR: exit 0, End, no sanitizer report, every edit consumed
ump_sane() {
    local d=$1 e f
    if [ "$rc" -ne 0 ] || [ "$(tail -n 2 "$d/log" | head -n 1)" != End ] ||
        grep -qE 'Sanitizer|runtime error|Segmentation' "$d/err" "$d/log"; then
        echo "  (umppmFoam in $d: exit $rc)"
        tail -n 3 "$d/err" "$d/log" | sed 's/^/    /'
        return 1
    fi
    for e in $edits; do
        f=${e#*=}
        [ ! -e "$f" ] || { echo "  ($f was not consumed: the shim did not fire)"; return 1; }
    done
}
# rereads DIR: the number of re-read lines
rereads() { grep -c '^regIOobject::readIfModified() : Re-reading object controlDict from file "' "$1/log" || true; }
# step_after_reread DIR N: "T0 T1", the Time = before and after the N-th re-read
step_around_reread() {
    awk -v n="$2" '/^Time = /{ last = $3; if (seen == n) { print prev, $3; exit } }
                   /Re-reading object controlDict/{ seen++; if (seen == n) prev = last }' "$1/log"
}

# pair NAME WANT BASESED T SED ...: umppmFoam and icoFoam with the same
# edits; the same time directories and uniform/time, equal to WANT (names)
pair() {
    local name=$1 want=$2 bsed=$3
    shift 3
    prepare "$work/$name.ico" "$bsed" "$@"
    run_ico "$work/$name.ico" || { bad "$name: icoFoam did not run"; return 0; }
    prepare "$work/$name" "$bsed" "$@"
    run_ump "$work/$name"
    if ! ump_sane "$work/$name"; then
        bad "$name: umppmFoam run"
        return 0
    fi
    local tu ti
    tu=$(times "$work/$name")
    ti=$(times "$work/$name.ico")
    if [ "$tu" = "$ti" ] && [ "$(names "$work/$name")" = "$want" ]; then
        ok "$name: times as icoFoam's ($want), uniform/time equal"
    else
        bad "$name: umppmFoam $(names "$work/$name") vs icoFoam $(names "$work/$name.ico") (want $want)"
        diff <(echo "$ti") <(echo "$tu") | head -n 6 | sed 's/^/    /' || true
    fi
}

echo "== 1. stopAt and endTime"
pair writeNow "0 0.01 0.02 0.03 0.035" "" 0.03 's/^stopAt .*/stopAt writeNow;/'
d=$work/writeNow
[ "$(step_around_reread "$d" 1)" = "0.03 0.035" ] && grep -q '^controlDict: stopAt endTime -> writeNow$' "$d/log" &&
    grep -q '^stopAt writeNow: time 0.035 written, stopping$' "$d/log" &&
    grep -A1 'Re-reading object controlDict' "$d/log" | grep -q "from file \"$d/system/controlDict\"" &&
    ok "writeNow: re-read between 0.03 and 0.035, change and stop logged" ||
    bad "writeNow log: '$(step_around_reread "$d" 1)'"
pair noWriteNow "0 0.01 0.02 0.03" "" 0.03 's/^stopAt .*/stopAt noWriteNow;/'
grep -q '^stopAt noWriteNow: time 0.035 not written, stopping$' "$work/noWriteNow/log" &&
    ok "noWriteNow: step 0.035 run, not written (as icoFoam)" || bad "noWriteNow log"
pair nextWrite "0 0.01 0.02 0.03 0.04" "" 0.03 's/^stopAt .*/stopAt nextWrite;/'
pair endTimeLater "0 0.01 0.02 0.03 0.04 0.05" "" 0.03 's/^endTime .*/endTime 0.05;/'
grep -q '^controlDict: endTime 0.1 -> 0.05$' "$work/endTimeLater/log" && ok "endTime change logged" ||
    bad "endTime change line"
pair endTimePast "0 0.01 0.02 0.03" "" 0.03 's/^endTime .*/endTime 0.01;/'
d=$work/endTimePast
grep -q '^endTime 0.01 is not after the current time 0.03: the run ends$' "$d/log" &&
    [ "$(sed -n 's/^Time = //p' "$d/log" | tail -n 1)" = 0.03 ] &&
    ok "endTime before the current time: no further step" || bad "endTimePast log"

echo "== 2. deltaT, writeInterval, purgeWrite"
pair deltaT "0 0.01 0.02 0.03 0.034 0.038 0.042 0.046 0.05 0.054 0.058 0.062 0.066 0.07 0.074 0.078 0.082 0.086 0.09 0.094 0.098" \
    "" 0.03 's/^deltaT .*/deltaT 0.002;/'
rt='s/^writeControl .*/writeControl runTime;/; s/^writeInterval .*/writeInterval 0.01;/'
pair deltaTRunTime "0 0.01 0.02 0.03 0.039 0.051 0.06 0.069 0.081 0.09 0.099" "$rt" 0.03 's/^deltaT .*/deltaT 0.003;/'
pair writeIntervalRunTime "0 0.01 0.02 0.03 0.05 0.075 0.1" "$rt" 0.03 's/^writeInterval .*/writeInterval 0.025;/'
pair purgeWrite "0 0.01 0.02 0.03 0.04 0.05 0.09 0.1" "" 0.05 's/^purgeWrite .*/purgeWrite 2;/'

echo "== 3. runTimeModifiable false"
pair off "0 0.01 0.02 0.03 0.04 0.05 0.06 0.07 0.08 0.09 0.1" 's/^runTimeModifiable .*/runTimeModifiable false;/' \
    0.03 's/^endTime .*/endTime 0.05;/'
[ "$(rereads "$work/off")" = 0 ] && ok "runTimeModifiable false: the edit is not read" || bad "off: re-read"
pair switchedOff "0 0.01 0.02 0.03 0.04 0.05 0.06 0.07 0.08 0.09 0.1" "" \
    0.02 's/^runTimeModifiable .*/runTimeModifiable false;/' 0.04 's/^endTime .*/endTime 0.05;/'
d=$work/switchedOff
[ "$(rereads "$d")" = 1 ] && grep -q '^runTimeModifiable false: system/controlDict is no longer watched$' "$d/log" &&
    grep -q '^controlDict: runTimeModifiable true -> false$' "$d/log" &&
    ok "switched off by an edit: the later edit is not read" || bad "switchedOff: $(rereads "$d") re-reads"

echo "== 4. function objects"
# fo_file FILE [patch=P] NAME...: a functions dictionary with a
# surfaceFieldValue per NAME (areaAverage of p on the lid, or on P, every
# step)
fo_file() {
    local f=$1 patch=movingWall n
    shift
    echo "functions" >"$f"
    echo "{" >>"$f"
    for n in "$@"; do
        case $n in
        patch=*) patch=${n#patch=} ;;
        *) printf '    %s\n    {\n        type surfaceFieldValue;\n        libs ("libfieldFunctionObjects.so");\n        regionType patch;\n        name %s;\n        operation areaAverage;\n        fields (p);\n        writeFields false;\n        writeControl timeStep;\n        writeInterval 1;\n    }\n' "$n" "$patch" >>"$f" ;;
        esac
    done
    echo "}" >>"$f"
}
fo_file "$work/fo_a" pA
fo_file "$work/fo_ab" pA pB
fo_file "$work/fo_bad" patch=nowhere pA
fo_a="/^runTimeModifiable/r $work/fo_a"
fo_ab="/^functions/,\$d; /^runTimeModifiable/r $work/fo_ab"
pair functions "0 0.01 0.02 0.03 0.04 0.05 0.06 0.07 0.08 0.09 0.1" "$fo_a" 0.03 "$fo_ab"
d=$work/functions
col1() { grep -v '^#' "$1" | awk '{ print $1 }' | tr '\n' ' '; }
for f in pA pB; do
    u=$d/postProcessing/$f/0/surfaceFieldValue.dat i=$work/functions.ico/postProcessing/$f/0/surfaceFieldValue.dat
    if [ -f "$u" ] && [ -f "$i" ] && [ "$(col1 "$u")" = "$(col1 "$i")" ] && [ -n "$(col1 "$u")" ]; then
        ok "$f: rows at the times of icoFoam's ($(col1 "$u" | awk '{ print $1 " ... " $NF }'))"
    else
        bad "$f: rows '$(col1 "$u" 2>/dev/null)' vs icoFoam '$(col1 "$i" 2>/dev/null)'"
    fi
done
[ "$(find "$d/postProcessing" -type f | wc -l)" = 2 ] &&
    grep -q '^Function objects: pA (surfaceFieldValue, continued), pB (surfaceFieldValue, new)$' "$d/log" &&
    ok "pA continued in its file, pB new" || bad "function objects: $(find "$d/postProcessing" -type f)"

echo "== 5. bad edits: a warning, the settings kept, a later edit still read"
all="0 0.01 0.02 0.03 0.04 0.05 0.06 0.07 0.08 0.09 0.1"
# badedit NAME SED MESSAGE: SED at 0.02 is refused with MESSAGE; endTime 0.07
# at 0.04 is then taken
badedit() {
    local name=$1 sed1=$2 msg=$3 d=$work/$1
    prepare "$d" "" 0.02 "$sed1" 0.04 's/^endTime .*/endTime 0.07;/'
    run_ump "$d"
    if ! ump_sane "$d"; then
        bad "$name: umppmFoam run"
        return 0
    fi
    local w
    w=$(grep -m 1 '^--> umppmFoam Warning: ' "$d/log" || true)
    if [ "$(names "$d")" = "0 0.01 0.02 0.03 0.04 0.05 0.06 0.07" ] && [ "$(rereads "$d")" = 2 ] &&
        [[ "$w" == *"$d/system/controlDict:"*"$msg"*"; the re-read controlDict is not used: the run continues with the settings it has" ]] &&
        [ "$(step_around_reread "$d" 1)" = "0.02 0.025" ]; then
        ok "$name: '${w#--> umppmFoam Warning: $d/}'"
    else
        bad "$name: times $(names "$d"), $(rereads "$d") re-reads, warning '$w'"
    fi
}
badedit endTimeNan 's/^endTime .*/endTime nan;/' "endTime must be a finite number, found nan"
badedit stopAtFoo 's/^stopAt .*/stopAt foo;/' "stopAt 'foo' is not one of: endTime writeNow noWriteNow nextWrite"
badedit deltaTNegative 's/^deltaT .*/deltaT -1;/' "deltaT must be positive, found -1"
badedit syntax 's/^deltaT .*/deltaT 0.005/' "deltaT"
badedit badPatch "s/^endTime .*/endTime 0.05;/; /^runTimeModifiable/r $work/fo_bad" \
    "function object 'pA': no patch 'nowhere'"
grep -q '^controlDict: endTime 0.1 -> 0.07$' "$work/badPatch/log" &&
    ok "badPatch: its endTime 0.05 was not taken either" || bad "badPatch took part of the bad file"

echo "== 6. writeFormat, writePrecision"
d=$work/format
prepare "$d" "" 0.05 's/^writeFormat .*/writeFormat binary;/; s/^writePrecision .*/writePrecision 12;/'
run_ump "$d"
fmt() { sed -n 's/^ *format *\([a-z]*\);.*/\1/p' "$1" | head -n 1; }
if ump_sane "$d" && [ "$(fmt "$d/0.05/U")" = ascii ] && [ "$(fmt "$d/0.06/U")" = binary ] &&
    [ "$(fmt "$d/0.1/p")" = binary ] &&
    grep -q '^controlDict: writeFormat ascii -> binary, writePrecision 6 -> 12$' "$d/log"; then
    ok "writeFormat binary from 0.06 on (0.05 ascii)"
else
    bad "format: 0.05 $(fmt "$d/0.05/U"), 0.06 $(fmt "$d/0.06/U")"
fi

rm -rf "$work"
[ "$fail" -eq 0 ]
