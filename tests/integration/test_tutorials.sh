#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# test_tutorials.sh -- tutorials/Alltest: every tutorial's Allrun -test (a
# coarse mesh and a few steps through every stage: meshing with blockMesh or
# gmsh + gmshToFoam, umppmFoam, the OpenFOAM reference solver on a copy of
# the mesh, postProcess sampling, foamCompare, gnuplot PNGs, log.result) on
# scratch copies of the cases. Fails if any Allrun fails or leaves no
# RESULT line or no plot.
# Needs UMPPMFOAM and TOOLDIR (the C tools).
set -eu -o pipefail
here=$(cd "$(dirname "$0")" && pwd)
[ -n "${UMPPMFOAM:-}" ] && [ -x "$UMPPMFOAM" ] || { echo "FAIL: UMPPMFOAM not set" >&2; exit 2; }
[ -n "${TOOLDIR:-}" ] && [ -x "$TOOLDIR/foamCompare" ] || { echo "FAIL: TOOLDIR not set" >&2; exit 2; }
. "$here/lib.sh"
of_env
UMPPM_BIN=$TOOLDIR "$here/../../tutorials/Alltest"
