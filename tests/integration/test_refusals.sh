#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# test_refusals.sh -- "no silent wrong answers": what umppmFoam does not
# implement, and inconsistent settings, are refused by name before the
# first step.
#
# Each check builds a bad copy of the cavity (or an OpenFOAM tutorial from
# openfoam-examples, meshed with blockMesh), runs `$UMPPMFOAM -case DIR`
# (or with -checkMesh, which applies the same checks) and asserts: exit
# status non-zero and < 128, no sanitizer report, and the first line on
# stderr matches a regex naming the real cause.
set -eu -o pipefail

here=$(cd "$(dirname "$0")" && pwd)
. "$here/lib.sh"
[ -n "${UMPPMFOAM:-}" ] && [ -x "$UMPPMFOAM" ] || {
    echo "test_refusals.sh: FAIL: UMPPMFOAM is not set to an executable" >&2
    exit 2
}
of_env || exit 2
examples=${OPENFOAM_EXAMPLES:-/usr/share/doc/openfoam-examples/examples}
work=$(mktemp -d "${TMPDIR:-/tmp}/umppm-refuse.XXXXXX")
good=$work/good
make_case cavity "$good" >/dev/null || { echo "FAIL: cannot build cavity" >&2; exit 1; }
sed -i 's/^endTime .*/endTime 0.01;/' "$good/system/controlDict"

nfail=0
npass=0
# expect LABEL DIR REGEX [umppmFoam options]: run in DIR, check the refusal
expect() {
    local label=$1 dir=$2 want=$3 rc=0 msg
    shift 3
    timeout 120 "$UMPPMFOAM" -case "$dir" "$@" >"$dir/log.refuse.out" 2>"$dir/log.refuse.err" || rc=$?
    msg=$(head -n 1 "$dir/log.refuse.err")
    if [ "$rc" -eq 0 ] || [ "$rc" -ge 128 ]; then
        echo "FAIL  $label: exit $rc"
    elif grep -qE "Sanitizer|runtime error|Segmentation" "$dir/log.refuse.out" "$dir/log.refuse.err"; then
        echo "FAIL  $label: sanitizer/crash report"
    elif ! printf '%s' "$msg" | grep -qE "$want"; then
        echo "FAIL  $label: message '$msg' does not match /$want/"
    elif ls -d "$dir"/0.0* >/dev/null 2>&1; then
        echo "FAIL  $label: a time directory was written"
    else
        echo "PASS  $label: $msg"
        npass=$((npass + 1))
        return 0
    fi
    nfail=$((nfail + 1))
}
# check LABEL REGEX SNIPPET [options]: SNIPPET runs inside a copy of the cavity
check() {
    local label=$1 want=$2 snippet=$3 dir=$work/$1
    shift 3
    cp -R "$good" "$dir"
    (cd "$dir" && eval "$snippet")
    expect "$label" "$dir" "$want" "$@"
}
# dict FILE CLASS BODY: write an OpenFOAM dictionary file
dict() {
    mkdir -p "$(dirname "$1")"
    printf 'FoamFile\n{\n    version 2.0;\n    format ascii;\n    class %s;\n    object %s;\n}\n%s\n' \
        "$2" "$(basename "$1")" "$3" >"$1"
}
export -f dict

# The control run: the intact cavity runs.
if "$UMPPMFOAM" -case "$good" >"$good/log.control" 2>&1 && "$UMPPMFOAM" -case "$good" -checkMesh >/dev/null 2>&1; then
    echo "PASS  control: the intact cavity runs"
    npass=$((npass + 1))
    rm -rf "$good"/0.0*
else
    echo "FAIL  control: the intact cavity does not run"
    nfail=$((nfail + 1))
fi

# --- features umppmFoam does not implement ---------------------------------
src='momentumSource { type vectorSemiImplicitSource; selectionMode all; volumeMode specific; injectionRateSuSp { U ((5 0 0) 0); } }'
check fvOptions-constant "constant/fvOptions:[0-9]+: fvOptions are not implemented.*momentumSource.*vectorSemiImplicitSource.*pimpleFoam" \
    "dict constant/fvOptions dictionary '$src'"
check fvOptions-system-checkMesh "system/fvOptions:[0-9]+: fvOptions are not implemented.*momentumSource" \
    "dict system/fvOptions dictionary '$src'" -checkMesh
check fvConstraints-constant "constant/fvConstraints:[0-9]+: fvConstraints are not implemented.*'limitU'" \
    "dict constant/fvConstraints dictionary 'limitU { type limitVelocity; max 10; }'"
check fvConstraints-system "system/fvConstraints:[0-9]+: fvConstraints are not implemented" \
    "dict system/fvConstraints dictionary 'limitU { type limitVelocity; max 10; }'"
check laminarModel-Maxwell "turbulenceProperties:[0-9]+: laminar \{ laminarModel Maxwell; \}.*Stokes" \
    "dict constant/turbulenceProperties dictionary 'simulationType laminar; laminar { laminarModel Maxwell; MaxwellCoeffs { nuM 1; lambda 5; } }'"
check laminarModel-momentumTransport-checkMesh "momentumTransport:[0-9]+: laminar \{ laminarModel Giesekus; \}" \
    "dict constant/momentumTransport dictionary 'simulationType laminar; laminar { laminarModel Giesekus; }'" -checkMesh
# the later momentumTransport's keys (ran as Newtonian before 2026-12-06)
check laminar-model-Maxwell "momentumTransport:[0-9]+: laminar \{ model Maxwell; \}.*Stokes" \
    "dict constant/momentumTransport dictionary 'simulationType laminar; laminar { model Maxwell; }'"
check laminar-viscosityModel "momentumTransport:[0-9]+: laminar \{ viscosityModel CrossPowerLaw; \}: non-Newtonian viscosity" \
    "dict constant/momentumTransport dictionary 'simulationType laminar; laminar { model generalisedNewtonian; viscosityModel CrossPowerLaw; }'"
check turbulence-RAS "turbulenceProperties:[0-9]+: simulationType 'RAS' is not supported" \
    "dict constant/turbulenceProperties dictionary 'simulationType RAS; RAS { RASModel kEpsilon; }'"
check transportModel-CrossPowerLaw "transportProperties:[0-9]+: transportModel CrossPowerLaw: non-Newtonian" \
    "sed -i '/^nu/d' constant/transportProperties && echo 'transportModel CrossPowerLaw; CrossPowerLawCoeffs { nu0 0.01; nuInf 10; m 0.4; n 3; }' >> constant/transportProperties"
check viscosityModel-BirdCarreau "transportProperties:[0-9]+: viscosityModel BirdCarreau: non-Newtonian" \
    "echo 'viscosityModel BirdCarreau;' >> constant/transportProperties"
check porosity "constant/porosityProperties:[0-9]+: porosity zones are not implemented.*'porosity1'.*DarcyForchheimer" \
    "dict constant/porosityProperties dictionary 'porosity1 { type DarcyForchheimer; cellZone porosity; }'"
check MRF-active "constant/MRFProperties:[0-9]+: MRF \(rotating frame\) zones are not implemented.*'MRF1'" \
    "dict constant/MRFProperties dictionary 'MRF1 { cellZone rotor; active yes; origin (0 0 0); axis (0 0 1); omega 10; }'"
check ddt-steadyState "fvSchemes:[0-9]+: ddtSchemes default steadyState.*Euler, backward" \
    "sed -i 's/default *Euler;/default steadyState;/' system/fvSchemes"
check ddt-CrankNicolson-checkMesh "fvSchemes:[0-9]+: ddtSchemes default CrankNicolson" \
    "sed -i 's/default *Euler;/default CrankNicolson 0.9;/' system/fvSchemes" -checkMesh
check dynamicMesh "dynamicMeshDict:[0-9]+: dynamicFvMesh dynamicMotionSolverFvMesh: moving or topology-changing meshes" \
    "dict constant/dynamicMeshDict dictionary 'dynamicFvMesh dynamicMotionSolverFvMesh; motionSolver solidBody;'"
check dynamicMesh-refine "dynamicMeshDict:[0-9]+: dynamicFvMesh dynamicRefineFvMesh" \
    "dict constant/dynamicMeshDict dictionary 'dynamicFvMesh dynamicRefineFvMesh;'"
check finiteArea-faSchemes "system/faSchemes: finite-area \(faMesh\)" \
    "dict system/faSchemes dictionary 'ddtSchemes { default Euler; }'"
check finiteArea-faMesh "constant/faMesh: finite-area \(faMesh\)" "mkdir -p constant/faMesh"
check multiphase-phases "transportProperties:[0-9]+: entry 'phases' \(water air\): multiphase flow is not implemented" \
    "echo 'phases (water air);' >> constant/transportProperties"
check multiphase-alpha "0/alpha.water: a phase fraction field: multiphase" \
    "sed 's/volVectorField/volScalarField/; s/(0 0 0)/0/g; s/(1 0 0)/0/g' 0/U > 0/alpha.water"

# --- dictionary checks --------------------------------------------------------
check endTime-nan "controlDict:[0-9]+: endTime must be a finite number" \
    "sed -i 's/^endTime .*/endTime nan;/' system/controlDict"
check endTime-1e400 "controlDict:[0-9]+: endTime must be a finite number|controlDict:[0-9]+:.*endTime" \
    "sed -i 's/^endTime .*/endTime 1e400;/' system/controlDict"
check deltaT-negative "controlDict:[0-9]+: deltaT must be positive" \
    "sed -i 's/^deltaT .*/deltaT -0.005;/' system/controlDict"
check deltaT-inf "controlDict:[0-9]+: deltaT must be a finite number|controlDict:[0-9]+: deltaT" \
    "sed -i 's/^deltaT .*/deltaT inf;/' system/controlDict"
check endTime-before-start "controlDict:[0-9]+: endTime -1 is before startTime 0" \
    "sed -i 's/^endTime .*/endTime -1;/' system/controlDict"
check writeInterval-zero "controlDict:[0-9]+: writeInterval must be positive" \
    "sed -i 's/^writeInterval .*/writeInterval 0;/' system/controlDict"
check UMPPM-not-dict "fvSolution:[0-9]+: UMPPM must be a dictionary" "echo 'UMPPM 3;' >> system/fvSolution"
check UMPPM-unknown-key "fvSolution:[0-9]+: UMPPM: unknown key 'alpah'; known keys: variant alpha laplacian reFactor writeQuality ppeSolver predictorSolver cloudName sortInterval" \
    "echo 'UMPPM { alpah 0.1; }' >> system/fvSolution"
check PISO-missing "fvSolution: keyword PISO is undefined" \
    "sed -i 's/^PISO/NOTPISO/' system/fvSolution"
# the cavity's p is fixed nowhere: icoFoam needs pRefCell (or pRefPoint)
# and pRefValue (before, both defaulted to 0 silently)
check pRefCell-missing "system/fvSolution: PISO: unable to set reference cell for field p: no patch fixes p, so its level needs either pRefCell or pRefPoint" \
    "sed -i '/^ *pRefCell /d' system/fvSolution"
check pRefValue-missing "system/fvSolution: PISO: entry 'pRefValue' not found: no patch fixes p" \
    "sed -i '/^ *pRefValue /d' system/fvSolution"
# a cloud in v1912's barycentric format (mapFields, decomposePar) is not
# read: said so by name (before: "has no particle cloud")
check cloud-barycentric "lagrangian/umppmCloud/positions: not found: the cloud 'umppmCloud' of time 0 has only 'coordinates', OpenFOAM's barycentric format" \
    "mkdir -p 0/lagrangian/umppmCloud && echo '0()' > 0/lagrangian/umppmCloud/coordinates"
check pRefPoint-outside "fvSolution: Unable to set reference cell for field p. Reference point pRefPoint \(5 5 0.005\) found on 0 domains" \
    "sed -i 's/^\( *\)pRefCell .*/\1pRefPoint (5 5 0.005);/' system/fvSolution"
check pRefPoint-outside-checkMesh "Unable to set reference cell for field p" \
    "sed -i 's/^\( *\)pRefCell .*/\1pRefPoint (0.05 0.05 7);/' system/fvSolution" -checkMesh
check cloudName-escape "fvSolution:[0-9]+: UMPPM cloudName '../../../escape' is not a plain name" \
    "echo 'UMPPM { cloudName \"../../../escape\"; }' >> system/fvSolution"
check cloudName-empty "fvSolution:[0-9]+: UMPPM cloudName '' is not a plain name" \
    "echo 'UMPPM { cloudName \"\"; }' >> system/fvSolution"
check functionName-slash "controlDict:[0-9]+: function object name 'a/b' is not a plain name" \
    "echo 'functions { \"a/b\" { type surfaceFieldValue; regionType patch; name movingWall; operation sum; fields (p); writeFields false; } }' >> system/controlDict"
check functionName-dotdot "controlDict:[0-9]+: function object name '..' is not a plain name" \
    "echo 'functions { \"..\" { type probes; } }' >> system/controlDict" -checkMesh
mkdir -p "$work/emptycase"
expect case-empty-name "$work/emptycase" "option -case: the directory name is empty" -case ''

# --- empty source dictionaries and inactive MRF are accepted ---------------------
dir=$work/accepted
cp -R "$good" "$dir"
dict "$dir/constant/fvOptions" dictionary ''
dict "$dir/system/fvConstraints" dictionary ''
dict "$dir/constant/MRFProperties" dictionary 'MRF1 { cellZone rotor; active false; }'
dict "$dir/constant/dynamicMeshDict" dictionary 'dynamicFvMesh staticFvMesh;'
sed -i 's/default *Euler;/default backward;/' "$dir/system/fvSchemes"
if "$UMPPMFOAM" -case "$dir" >"$dir/log.run" 2>&1 && grep -q 'Time scheme: ddtSchemes backward' "$dir/log.run"; then
    echo "PASS  accepted: empty fvOptions/fvConstraints, inactive MRF, staticFvMesh, backward"
    npass=$((npass + 1))
else
    echo "FAIL  accepted: empty fvOptions/fvConstraints, inactive MRF, staticFvMesh, backward ($dir/log.run)"
    nfail=$((nfail + 1))
fi

# --- OpenFOAM's own tutorials ---------------------------------------------------
# tutorial LABEL PATH REGEX PREP: copy, gunzip, PREP (in the copy), blockMesh
tutorial() {
    local label=$1 path=$examples/$2 want=$3 prep=$4 dir=$work/tut-$1
    if [ ! -d "$path" ]; then
        echo "FAIL  $label: no tutorial $path (install openfoam-examples)"
        nfail=$((nfail + 1))
        return
    fi
    cp -R "$path" "$dir"
    find "$dir" -name '*.gz' -exec gunzip -f {} +
    (cd "$dir" && eval "$prep") >"$dir/log.prep" 2>&1 || true
    # contaminatedDroplet2D's blockMeshDict comes from m4: without m4 there
    # is no mesh, and the refusal (before the mesh is read) must still come
    if [ ! -f "$dir/system/blockMeshDict" ]; then
        echo "note  $label: no system/blockMeshDict (m4 missing?): run without a mesh"
    elif ! run_in "$dir" blockMesh blockMesh; then
        echo "FAIL  $label: blockMesh failed"
        nfail=$((nfail + 1))
        return
    fi
    expect "$label" "$dir" "$want"
    expect "$label-checkMesh" "$dir" "$want" -checkMesh
}
P=incompressible/pimpleFoam/laminar
tutorial planarPoiseuille-Maxwell $P/planarPoiseuille "turbulenceProperties:[0-9]+: laminar \{ laminarModel Maxwell; \}" \
    "sed 's/END_TIME/2/' system/controlDict.template > system/controlDict &&
     sed 's/LAMINAR_MODEL/Maxwell/' constant/turbulenceProperties.template > constant/turbulenceProperties"
tutorial planarPoiseuille-Stokes $P/planarPoiseuille "constant/fvOptions:[0-9]+: fvOptions are not implemented by umppmFoam \(entry 'momentumSource', type vectorSemiImplicitSource\)" \
    "sed 's/END_TIME/2/' system/controlDict.template > system/controlDict &&
     sed 's/LAMINAR_MODEL/Stokes/' constant/turbulenceProperties.template > constant/turbulenceProperties"
tutorial porousBlockage incompressible/pisoFoam/laminar/porousBlockage \
    "constant/fvOptions:[0-9]+: fvOptions are not implemented.*'porosity1', type explicitPorositySource" ":"
tutorial planarContraction $P/planarContraction "turbulenceProperties:[0-9]+: laminar \{ laminarModel Maxwell; \}" ":"
tutorial offsetCylinder incompressible/nonNewtonianIcoFoam/offsetCylinder \
    "transportProperties:[0-9]+: transportModel CrossPowerLaw: non-Newtonian viscosity is not implemented" ":"
tutorial contactAngleCavity $P/contactAngleCavity "dynamicFvMesh interfaceTrackingFvMesh: free-surface \(multiphase\)" ":"
tutorial sloshing2D $P/sloshing2D "dynamicFvMesh interfaceTrackingFvMesh: free-surface \(multiphase\)" ":"
tutorial contaminatedDroplet2D $P/contaminatedDroplet2D "dynamicFvMesh interfaceTrackingFvMesh: free-surface \(multiphase\)" \
    "! command -v m4 || m4 < system/blockMeshDict.m4 > system/blockMeshDict"

echo "test_refusals.sh: $npass passed, $nfail failed"
if [ "$nfail" -ne 0 ]; then
    echo "test_refusals.sh: work dir $work"
    exit 1
fi
rm -rf "$work"
