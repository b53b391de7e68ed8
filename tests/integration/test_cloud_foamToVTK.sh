#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# test_cloud_foamToVTK.sh -- the particle cloud umppmFoam writes is a genuine
# OpenFOAM v1912 lagrangian cloud: foamToVTK converts it, with every particle
# and its U, and our reader reads it back (done inside write_cloud).
#   WRITE_CLOUD=<path of the built write_cloud program>
set -eu -o pipefail
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"
[ -n "${WRITE_CLOUD:-}" ] && [ -x "$WRITE_CLOUD" ] || { echo "FAIL: WRITE_CLOUD not set" >&2; exit 2; }
of_env || exit 2
work=$(mktemp -d "${TMPDIR:-/tmp}/umppm-cloud.XXXXXX")
make_case cavity "$work/c" >/dev/null
cp -r "$work/c/0" "$work/c/0.5"
n=37
"$WRITE_CLOUD" "$work/c" 0.5 $n
(cd "$work/c" && foamToVTK -time 0.5 > log.foamToVTK 2>&1) || { echo "FAIL: foamToVTK"; exit 1; }
vtp=$(find "$work/c/VTK" -name '*.vtp' | head -1)
[ -n "$vtp" ] || { echo "FAIL: foamToVTK wrote no .vtp for the cloud"; exit 1; }
got=$(grep -o "NumberOfPoints=[\"'][0-9]*" "$vtp" | head -1 | tr -dc 0-9)
[ "$got" = "$n" ] || { echo "FAIL: $vtp has $got points, expected $n"; exit 1; }
# decode the base64 Float32 points and U (UInt64 byte-count header) and
# compare with what write_cloud wrote: particle i at the centre of cell 7i mod 400
python3 - "$vtp" "$n" <<'PY' || exit 1
import base64, re, struct, sys
text = open(sys.argv[1]).read(); n = int(sys.argv[2])
def arr(name):
    m = re.search(r"Name='%s'[^>]*>\s*([A-Za-z0-9+/=]+)" % name, text)
    if not m: sys.exit("FAIL: no %s array" % name)
    raw = base64.b64decode(m.group(1)); nb = struct.unpack('<Q', raw[:8])[0]
    return struct.unpack('<%df' % (nb // 4), raw[8:8 + nb])
P, U = arr('Points'), arr('U')
for i in range(n):
    c = (7 * i) % 400
    want = (0.0025 + 0.005 * (c % 20), 0.0025 + 0.005 * (c // 20), 0.005)
    if any(abs(P[3*i+k] - want[k]) > 1e-6 for k in range(3)) or abs(U[3*i] - i) > 1e-4 or abs(U[3*i+1] + i) > 1e-4:
        sys.exit("FAIL: particle %d: %s / %s" % (i, P[3*i:3*i+3], U[3*i:3*i+3]))
PY
echo "PASS: foamToVTK converted the $n-particle cloud with U ($vtp)"
rm -rf "$work"
