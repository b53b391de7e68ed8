# SPDX-License-Identifier: GPL-3.0-or-later
# bench/cases.sh -- case set-up shared by the bench scripts; sourced, it
# also sources tutorials/RunFunctions (setEntry; exports WM_PROJECT_DIR).
#
#   cavity_case DIR N NU
# OpenFOAM's icoFoam `cavity` tutorial copied into DIR (created if missing;
# gzipped files unpacked), its block set to N x N cells, scale 1 (the unit
# square with lid speed 1, so Re = 1/NU) and the kinematic viscosity NU.
# The caller sets controlDict and runs blockMesh. Returns 1, with a message,
# if the tutorial is missing or its block is not the (20 20 1) this expects.
. "$(dirname "${BASH_SOURCE[0]}")/../tutorials/RunFunctions"

cavity_tutorial=/usr/share/doc/openfoam-examples/examples/incompressible/icoFoam/cavity/cavity

cavity_case() {
    local tut=$cavity_tutorial
    [ -d "$tut" ] || { echo "no OpenFOAM cavity tutorial in $tut (package openfoam-examples)" >&2; return 1; }
    mkdir -p "$1" && cp -r "$tut/0" "$tut/constant" "$tut/system" "$1/" || return 1
    find "$1/0" "$1/constant" "$1/system" -name '*.gz' -exec gunzip -f {} + || return 1
    grep -Eq '\( *20 +20 +1 *\)' "$1/system/blockMeshDict" ||
        { echo "$tut/system/blockMeshDict: no block (20 20 1)" >&2; return 1; }
    sed -i -E "s/\( *20 +20 +1 *\)/($2 $2 1)/" "$1/system/blockMeshDict"
    setEntry "$1/system/blockMeshDict" scale 1 && setEntry "$1/constant/transportProperties" nu "$3"
}
