#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# test_badfields.sh -- broken case files (fields, controlDict,
# transportProperties) are refused cleanly and never destroy data.
#
# For each broken copy of the cavity, `$UMPPMFOAM -case <dir> -checkMesh
# -writeFields` must exit non-zero (< 128, no sanitizer report), print one
# error line naming the offending file (and line for text files), and leave
# the 0/ directory byte-for-byte as it was.
set -eu -o pipefail

here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"
[ -n "${UMPPMFOAM:-}" ] && [ -x "$UMPPMFOAM" ] || {
    echo "test_badfields.sh: FAIL: UMPPMFOAM is not set to an executable" >&2
    exit 2
}
of_env || exit 2
work=$(mktemp -d "${TMPDIR:-/tmp}/umppm-badf.XXXXXX")
good=$work/good
make_case cavity "$good" >/dev/null || { echo "FAIL: cannot build cavity" >&2; exit 1; }

nfail=0
# check LABEL EXPECTED-REGEX SNIPPET: SNIPPET runs inside a copy of the case
check() {
    local label=$1 want=$2 snippet=$3 dir=$work/$1
    cp -R "$good" "$dir"
    (cd "$dir" && eval "$snippet")
    local before after rc=0
    before=$(cd "$dir/0" && cat ./* | md5sum)
    timeout 60 "$UMPPMFOAM" -case "$dir" -checkMesh -writeFields >"$dir/log.out" 2>"$dir/log.err" || rc=$?
    after=$(cd "$dir/0" && cat ./* | md5sum)
    local msg
    msg=$(head -n 1 "$dir/log.err")
    if [ "$rc" -eq 0 ] || [ "$rc" -ge 128 ]; then
        echo "FAIL  $label: exit $rc"
    elif grep -qE "Sanitizer|runtime error|Segmentation" "$dir/log.out" "$dir/log.err"; then
        echo "FAIL  $label: sanitizer/crash report"
    elif ! printf '%s' "$msg" | grep -qE "$want"; then
        echo "FAIL  $label: message '$msg' does not match /$want/"
    elif [ "$before" != "$after" ]; then
        echo "FAIL  $label: 0/ was modified by a failed run"
    elif [ "$(wc -l < "$dir/log.err")" -ne 1 ]; then
        echo "FAIL  $label: expected one error line, got $(wc -l < "$dir/log.err")"
    else
        echo "PASS  $label: $msg"
        rm -rf "$dir"
        return 0
    fi
    nfail=$((nfail + 1))
}

check U-unbalanced-brace  '0/U:[0-9]+: '        "sed -i 's/^    movingWall$/    movingWall {/' 0/U"
check U-wrong-count       '0/U:[0-9]+: .*values for 400 cells' \
    "sed -i 's/^internalField .*/internalField nonuniform List<vector> 2((0 0 0) (0 0 0));/' 0/U"
check U-unknown-bc        "0/U:[0-9]+: patch 'fixedWalls': boundary condition type 'partialSlip'" \
    "sed -i 's/noSlip/partialSlip/' 0/U"
check U-missing-patch     "0/U:[0-9]+: boundaryField has no entry for patch 'fixedWalls'" \
    "sed -i 's/fixedWalls/otherWalls/' 0/U"
check U-scalar-value      "0/U:[0-9]+: internalField: expected a vector \\(x y z\\) after 'uniform', found label 1" \
    "sed -i 's/^internalField .*/internalField uniform 1;/' 0/U"
check p-bad-number        '0/p:[0-9]+: '        "sed -i 's/^internalField .*/internalField uniform 1.2.3;/' 0/p"
check p-missing           '0/p'                 "rm 0/p"
check p-wrong-class       '0/p: class'          "sed -i 's/volScalarField/volVectorField/' 0/p"
check U-unterminated-str  '0/U:[0-9]+: '        "sed -i 's/^    object .*/    object \"U;/' 0/U"
check U-binary-cut        '0/U:[0-9]+: binary' \
    "awk 'BEGIN{print \"400(\"; for(i=0;i<400;i++) print \"(\" i \" 0 0)\"; print \")\"}' > list &&
     sed -i 's/^internalField .*/internalField nonuniform List<vector> #include \"..\\/list\";/' 0/U &&
     sed -i 's/^writeFormat .*/writeFormat binary;/' system/controlDict &&
     $UMPPMFOAM -case . -checkMesh -writeFields >/dev/null &&
     head -c \$((\$(stat -c %s 0/U) - 3000)) 0/U > 0/U.cut && mv 0/U.cut 0/U"
check controlDict-missing 'system/controlDict'  "rm system/controlDict"
check controlDict-bad-enum 'system/controlDict:[0-9]+: writeControl' \
    "sed -i 's/^writeControl .*/writeControl sometimes;/' system/controlDict"
check controlDict-no-deltaT 'system/controlDict.*deltaT' "sed -i '/^deltaT/d' system/controlDict"
check macro-undefined     'fvSolution|controlDict|0/U' "sed -i 's/^endTime .*/endTime \$nowhere;/' system/controlDict"

# An empty patch may be left out of a field file, and a regular expression
# does not reach it: OpenFOAM's GeometricBoundaryField gives such a patch
# `empty` before it tries the regular expressions. Both copies must run and
# write the same fields as the unmodified case.
omit=$work/omitEmpty
cp -R "$good" "$omit"
python3 - "$omit" <<'PYEOF'
import re, sys
d = sys.argv[1]
u = open(d + '/0/U').read()
u = re.sub(r'\n    frontAndBack\n    \{[^}]*\}\n', '\n', u)
open(d + '/0/U', 'w').write(u)
p = open(d + '/0/p').read()
p = re.sub(r'\n    frontAndBack\n    \{[^}]*\}\n', '\n    ".*"\n    {\n        type zeroGradient;\n    }\n', p)
open(d + '/0/p', 'w').write(p)
PYEOF
for c in "$good" "$omit"; do
    foam_set "$c" system/controlDict endTime 0.05 && foam_set "$c" system/controlDict writeInterval 10
done
if grep -q frontAndBack "$omit/0/U" || ! grep -q '".\*"' "$omit/0/p"; then
    echo "FAIL  omitted-empty: the copy was not edited as meant"
    nfail=$((nfail + 1))
elif ! timeout 60 "$UMPPMFOAM" -case "$good" >"$work/good.log" 2>&1 ||
     ! timeout 60 "$UMPPMFOAM" -case "$omit" >"$omit/log.out" 2>&1; then
    echo "FAIL  omitted-empty: a run failed: $(grep -m1 -i error "$omit/log.out" "$work/good.log")"
    nfail=$((nfail + 1))
elif ! cmp -s "$good/0.05/U" "$omit/0.05/U" || ! cmp -s "$good/0.05/p" "$omit/0.05/p"; then
    echo "FAIL  omitted-empty: fields differ from the unmodified case's"
    nfail=$((nfail + 1))
else
    echo "PASS  omitted-empty: an empty patch left out of 0/U and 0/p runs as empty (same fields)"
fi

if [ "$nfail" -ne 0 ]; then
    echo "test_badfields.sh: $nfail failed (work dir $work)"
    exit 1
fi
rm -rf "$work"
echo "test_badfields.sh: all passed"
