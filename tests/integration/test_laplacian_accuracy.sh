#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# test_laplacian_accuracy.sh -- the operator experiments of Hwang, Ng &
# Sheu (2016), Section 4, with tools/laplacianAccuracy on irregular clouds
# (alpha = 0.3, Eqs. 35, 41, 45), for the four Laplacians of src/laplacian.c.
# Asserts (measured values in the comments, fixed seed 1):
#   Laplacian of prod sin(2 pi x_d) on periodic clouds:
#   nC 16 -> 128 (1-D), 16 -> 64 (2-D, 3-D):
#   - PS: the error grows as the cloud is refined, order <= -0.8 in 1-, 2-
#     and 3-D (O(1/delta), Eq. 12; measured -1.03, -0.99, -1.00);
#   - IPS: error below 10 % and flat (|order| <= 0.3; measured 6.4 %, 7.8 %,
#     6.4 % at the finest, orders 0.09, 0.10, 0.16);
#   - CPM: converges, order >= 1 (measured 1.06, 1.28, 1.44) and below IPS;
#   - on the regular lattice (alpha = 0) PS and IPS coincide and are second
#     order (measured 1.98);
#   - the artificial cell Reynolds number of PS (Eq. 42a) does not depend on
#     the spacing (within 10 %) and the IPS diffusivity tau_xx lies in
#     [0.9, 1);
#   pure diffusion (Eqs. 39, 44, 48; explicit Euler, C_D = 1, t = 0.02):
#   - IPS's error is below half of PS's in 1-, 2- and 3-D, CPM's below
#     IPS's (measured IPS/PS 0.30, 0.29, 0.11); CPM is second order in 2-D
#     (32 -> 64; measured 2.23).
# Needs TOOLDIR (directory of the built tools).
set -eu -o pipefail
here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"
[ -n "${TOOLDIR:-}" ] && [ -x "$TOOLDIR/laplacianAccuracy" ] || { echo "FAIL: TOOLDIR not set" >&2; exit 2; }
la=$TOOLDIR/laplacianAccuracy
fail=0
out=$(mktemp "${TMPDIR:-/tmp}/umppm-lap.XXXXXX")
trap 'rm -f "$out"' EXIT

# op DIM NC ALPHA MODEL KEY: one number of an operator run (cached per run)
op() {
    local f=$out.op$1-$2-$3
    [ -s "$f" ] || "$la" operator -dim "$1" -nC "$2" -alpha "$3" > "$f"
    kv_get "$(grep "model=$4 " "$f")" "$5"
}
for spec in "1 16 128" "2 16 64" "3 16 64"; do
    set -- $spec
    d=$1 n0=$2 n1=$3
    echo "== operator, $d-D, alpha 0.3, nC $n0 -> $n1"
    for m in CPM IPS PS MPS; do
        echo "  $m: L2rel $(op $d $n0 0.3 $m L2rel) -> $(op $d $n1 0.3 $m L2rel)"
    done
    check_below "PS order ($d-D)" "$(observed_order "$(op $d $n0 0.3 PS L2rel)" "$(op $d $n1 0.3 PS L2rel)" $n0 $n1)" -0.8
    po=$(observed_order "$(op $d $n0 0.3 IPS L2rel)" "$(op $d $n1 0.3 IPS L2rel)" $n0 $n1)
    check_range "IPS order ($d-D)" "$po" -0.3 0.3
    check_below "IPS L2rel ($d-D, nC $n1)" "$(op $d $n1 0.3 IPS L2rel)" 0.10
    check_range "CPM order ($d-D)" "$(observed_order "$(op $d $n0 0.3 CPM L2rel)" "$(op $d $n1 0.3 CPM L2rel)" $n0 $n1)" 1.0 3
    check_below "CPM L2rel / IPS L2rel ($d-D, nC $n1)" \
        "$(awk -v a="$(op $d $n1 0.3 CPM L2rel)" -v b="$(op $d $n1 0.3 IPS L2rel)" 'BEGIN { print a / b }')" 1
    r0=$(op $d $n0 0.3 PS ReN) r1=$(op $d $n1 0.3 PS ReN)
    check_range "PS Re_N ratio nC $n1 / nC $n0 ($d-D)" "$(awk -v a="$r1" -v b="$r0" 'BEGIN { print a / b }')" 0.9 1.1
    check_range "IPS mean tau_xx ($d-D)" "$(op $d $n1 0.3 IPS tauxx)" 0.9 0.99999
done
echo "== operator, regular lattice (alpha 0), 2-D, nC 16 -> 32"
check_below "|PS - IPS| (alpha 0)" "$(awk -v a="$(op 2 32 0 PS L2)" -v b="$(op 2 32 0 IPS L2)" 'BEGIN { d = a - b; print (d < 0 ? -d : d) }')" 1e-9
check_range "PS order (alpha 0)" "$(observed_order "$(op 2 16 0 PS L2rel)" "$(op 2 32 0 PS L2rel)" 16 32)" 1.8 2.2
check_below "PS Re_N (alpha 0)" "$(op 2 32 0 PS ReN)" 1e-12

# diff DIM NC MODEL: error at t = 0.02
diffusion() {
    local f=$out.diff$1-$2
    [ -s "$f" ] || "$la" diffusion -dim "$1" -nC "$2" -alpha 0.3 -CD 1 -endTime 0.02 -samples 1 > "$f"
    kv_get "$(grep "model=$3 " "$f")" err
}
for spec in "1 128" "2 64" "3 32"; do
    set -- $spec
    echo "== diffusion, $1-D, nC $2, alpha 0.3, C_D 1, t 0.02"
    for m in CPM IPS PS MPS; do echo "  $m: err $(diffusion $1 $2 $m)"; done
    check_below "IPS err / PS err ($1-D)" "$(awk -v a="$(diffusion $1 $2 IPS)" -v b="$(diffusion $1 $2 PS)" 'BEGIN { print a / b }')" 0.5
    check_below "CPM err / IPS err ($1-D)" "$(awk -v a="$(diffusion $1 $2 CPM)" -v b="$(diffusion $1 $2 IPS)" 'BEGIN { print a / b }')" 1
done
check_range "CPM diffusion order (2-D, 32 -> 64)" "$(observed_order "$(diffusion 2 32 CPM)" "$(diffusion 2 64 CPM)" 32 64)" 1.7 3

echo "== bad input"
if "$la" operator -dim 4 > /dev/null 2> "$out.err"; then echo "  FAIL -dim 4 accepted"; fail=1
else echo "  ok   -dim 4 refused: $(cat "$out.err")"; fi
if "$la" operator -dim 1.5 > /dev/null 2> "$out.err"; then echo "  FAIL -dim 1.5 accepted"; fail=1
else echo "  ok   -dim 1.5 refused: $(cat "$out.err")"; fi
if "$la" operator -models CPM,XYZ > /dev/null 2> "$out.err"; then echo "  FAIL -models XYZ accepted"; fail=1
else echo "  ok   -models XYZ refused: $(cat "$out.err")"; fi
rm -f "$out".*
exit $fail
