#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# cavityValidate.sh -- the unit lid-driven cavity (lid u = 1, nu = 1/Re) run
# by umppmFoam and by icoFoam on the same mesh, both compared with Ghia et
# al. (1982) and with each other cell by cell.
#
#   cavityValidate.sh -dir DIR [-Re 100] [-mesh quad|tri] [-n 20]
#                     [-variant UMPPMstar] [-laplacian CPM] [-alpha 0.09]
#                     [-endTime 10] [-maxCo 0.25] [-icoFoam yes|no]
#                     [-lid fixedValue|movingWallVelocity]
#
# -mesh quad: n x n uniform quadrilaterals (blockMesh); -mesh tri: gmsh
# Delaunay triangles of size 1.65/n (about as many cells as n x n quads),
# converted by gmshToFoam. umppmFoam runs with adjustTimeStep at maxCo;
# icoFoam (PISO, 2 correctors, Gauss linear, corrected Laplacian) with the
# fixed deltaT that puts the lid's Courant number at 0.5. DIR is created
# (must not exist); umppmFoam's case is DIR, icoFoam's DIR/icoFoam.
# Needs umppmFoam ($UMPPMFOAM, else $BINDIR/umppmFoam), foamCompare and
# ghiaCompare ($TOOLDIR, else $BINDIR; BINDIR defaults to the repository's
# bin/) and OpenFOAM v1912 on PATH.
# Prints the two logs' last lines, the ghiaCompare and foamCompare tables,
# and one summary line:
#   RESULT mesh=quad cells=400 particles=... steps=... seconds=... rss_MiB=...
#          u_rms=... u_max=... v_rms=... v_max=... (umppmFoam vs Ghia)
#          ico_u_rms=... ico_u_max=... ico_v_rms=... ico_v_max=...
#          ico_seconds=... ico_steps=... UvsIco_L2rel=... UvsIco_Linfrel=...
set -eu -o pipefail
top=$(cd "$(dirname "$0")/.." && pwd)
: "${BINDIR:=$top/bin}"
umppm=${UMPPMFOAM:-$BINDIR/umppmFoam}
tooldir=${TOOLDIR:-$BINDIR}
export WM_PROJECT_DIR="${WM_PROJECT_DIR:-/usr/share/openfoam}"
dir="" Re=100 mesh=quad n=20 variant=UMPPMstar lap=CPM alpha=0.09 endTime=10 maxCo=0.25 ico=yes lid=fixedValue
usage() {
    sed -n '5,9p' "$0" | sed 's/^# \{0,1\}//' >&2
    exit 1
}
while [ $# -gt 0 ]; do
    [ $# -ge 2 ] || usage
    case $1 in
    -dir) dir=$2 ;; -Re) Re=$2 ;; -mesh) mesh=$2 ;; -n) n=$2 ;; -variant) variant=$2 ;;
    -laplacian) lap=$2 ;; -alpha) alpha=$2 ;; -endTime) endTime=$2 ;; -maxCo) maxCo=$2 ;;
    -icoFoam) ico=$2 ;; -lid) lid=$2 ;;
    *) usage ;;
    esac
    shift 2
done
[ -n "$dir" ] || usage
case $mesh in quad | tri) ;; *) echo "cavityValidate.sh: -mesh must be quad or tri" >&2; exit 1 ;; esac
case $lid in fixedValue | movingWallVelocity) ;; *) echo "cavityValidate.sh: -lid must be fixedValue or movingWallVelocity" >&2; exit 1 ;; esac
[ ! -e "$dir" ] || { echo "cavityValidate.sh: $dir exists" >&2; exit 1; }
for b in "$umppm" "$tooldir/foamCompare" "$tooldir/ghiaCompare"; do
    [ -x "$b" ] || { echo "cavityValidate.sh: $b missing (run make)" >&2; exit 1; }
done
nu=$(awk -v r="$Re" 'BEGIN { printf "%.10g", 1 / r }')
dtico=$(awk -v n="$n" 'BEGIN { printf "%.6g", 0.5 / n }')
# a first deltaT well inside the CFL limit; adjustTimeStep takes over
dt0=$(awk -v n="$n" -v c="$maxCo" 'BEGIN { printf "%.6g", c / (2 * n) }')
wi=$(awk -v t="$endTime" 'BEGIN { printf "%.10g", t / 2 }')

header() { printf 'FoamFile { version 2.0; format ascii; class %s; object %s; }\n' "$1" "$2"; }

mkdir -p "$dir/system" "$dir/constant" "$dir/0"
header dictionary controlDict > "$dir/system/controlDict"
cat >> "$dir/system/controlDict" <<EOF
application umppmFoam; startFrom startTime; startTime 0; stopAt endTime; endTime $endTime;
deltaT $dt0; adjustTimeStep yes; maxCo $maxCo; maxDeltaT 1;
writeControl adjustableRunTime; writeInterval $wi; purgeWrite 0;
writeFormat ascii; writePrecision 10; writeCompression off; timeFormat general; timePrecision 6;
runTimeModifiable false;
EOF
header dictionary fvSchemes > "$dir/system/fvSchemes"
cat >> "$dir/system/fvSchemes" <<'EOF'
ddtSchemes { default Euler; }
gradSchemes { default Gauss linear; }
divSchemes { default none; div(phi,U) Gauss linear; }
laplacianSchemes { default Gauss linear corrected; }
interpolationSchemes { default linear; }
snGradSchemes { default corrected; }
EOF
header dictionary fvSolution > "$dir/system/fvSolution"
cat >> "$dir/system/fvSolution" <<EOF
solvers
{
    p { solver PCG; preconditioner DIC; tolerance 1e-8; relTol 0.05; }
    pFinal { \$p; relTol 0; }
    U { solver smoothSolver; smoother symGaussSeidel; tolerance 1e-8; relTol 0; }
}
PISO { nCorrectors 2; nNonOrthogonalCorrectors 1; pRefCell 0; pRefValue 0; }
UMPPM { variant $variant; laplacian $lap; alpha $alpha; }
EOF
header dictionary transportProperties > "$dir/constant/transportProperties"
echo "nu [0 2 -1 0 0 0 0] $nu;" >> "$dir/constant/transportProperties"
header volVectorField U > "$dir/0/U"
cat >> "$dir/0/U" <<EOF
dimensions [0 1 -1 0 0 0 0];
internalField uniform (0 0 0);
boundaryField
{
    movingWall { type $lid; value uniform (1 0 0); }
    fixedWalls { type noSlip; }
    frontAndBack { type empty; }
}
EOF
header volScalarField p > "$dir/0/p"
cat >> "$dir/0/p" <<'EOF'
dimensions [0 2 -2 0 0 0 0];
internalField uniform 0;
boundaryField
{
    movingWall { type zeroGradient; }
    fixedWalls { type zeroGradient; }
    frontAndBack { type empty; }
}
EOF

run() { # run LOG CMD...: output in LOG, fail with its tail
    local log=$1
    shift
    if ! "$@" > "$log" 2>&1; then
        echo "cavityValidate.sh: $* failed (log $log):" >&2
        tail -5 "$log" >&2
        exit 1
    fi
}
if [ "$mesh" = quad ]; then
    header dictionary blockMeshDict > "$dir/system/blockMeshDict"
    cat >> "$dir/system/blockMeshDict" <<EOF
vertices ((0 0 0) (1 0 0) (1 1 0) (0 1 0) (0 0 0.1) (1 0 0.1) (1 1 0.1) (0 1 0.1));
blocks (hex (0 1 2 3 4 5 6 7) ($n $n 1) simpleGrading (1 1 1));
boundary
(
    movingWall { type wall; faces ((3 7 6 2)); }
    fixedWalls { type wall; faces ((0 4 7 3) (2 6 5 1) (1 5 4 0)); }
    frontAndBack { type empty; faces ((0 3 2 1) (4 5 6 7)); }
);
EOF
    run "$dir/log.blockMesh" blockMesh -case "$dir"
else
    h=$(awk -v n="$n" 'BEGIN { printf "%.6g", 1.65 / n }')
    cp "$top/tools/cavityTriangles.geo" "$dir/cavity.geo"
    run "$dir/log.gmsh" gmsh -3 -format msh2 -setnumber h "$h" "$dir/cavity.geo" -o "$dir/cavity.msh"
    run "$dir/log.gmshToFoam" gmshToFoam -case "$dir" "$dir/cavity.msh"
    # the patch types the geo file lists as "// foam-patch-type: <patch> <type>"
    # (geoPatchTypes of tutorials/RunFunctions, in a subshell: its defaults
    # stay out of this script)
    while read -r pt ty; do
        [ -n "$pt" ] || continue
        run "$dir/log.foamDictionary" foamDictionary "$dir/constant/polyMesh/boundary" \
            -entry "entry0/$pt/type" -set "$ty"
    done < <(. "$top/tutorials/RunFunctions" && geoPatchTypes "$dir/cavity.geo")
fi
run "$dir/log.checkMesh" checkMesh -case "$dir"
grep -q '^Mesh OK' "$dir/log.checkMesh" || { echo "cavityValidate.sh: checkMesh failed ($dir/log.checkMesh)" >&2; exit 1; }
cells=$(awk '/^ *cells:/ { print $2; exit }' "$dir/log.checkMesh")

read -r secs rss rc < <(python3 "$top/bench/run_measured.py" -o "$dir/log.umppmFoam" "$umppm" -case "$dir")
if [ "$rc" != 0 ]; then
    echo "cavityValidate.sh: umppmFoam failed (log $dir/log.umppmFoam):" >&2
    tail -5 "$dir/log.umppmFoam" >&2
    exit 1
fi
last=$(ls -d "$dir"/[0-9]* | sed 's|.*/||' | sort -g | tail -1)
steps=$(grep -c '^Time = ' "$dir/log.umppmFoam")
np=$(grep -o '^Particles: [0-9]*' "$dir/log.umppmFoam" | tail -1 | awk '{ print $2 }')
cmax=$(grep -o 'max = [0-9.e+-]*' "$dir/log.umppmFoam" | awk '{ if ($3 > m) m = $3 } END { print m + 0 }')
read -r _ _ u_rms u_max v_rms v_max < <("$tooldir/ghiaCompare" -Re "$Re" "$dir" "$last" | tail -1)
echo "umppmFoam: $cells cells, $np particles at the end, $steps steps, $secs s; max per-cell continuity error $cmax"
"$tooldir/ghiaCompare" -Re "$Re" "$dir" "$last"
result="RESULT mesh=$mesh cells=$cells particles=$np steps=$steps seconds=$secs rss_MiB=$rss u_rms=$u_rms u_max=$u_max v_rms=$v_rms v_max=$v_max cont_max=$cmax"
if [ "$ico" = yes ]; then
    ic=$dir/icoFoam
    mkdir -p "$ic"
    cp -r "$dir/system" "$dir/constant" "$ic/"
    mkdir -p "$ic/0" && cp "$dir/0/U" "$dir/0/p" "$ic/0/"
    sed -i "s/^deltaT [^;]*; adjustTimeStep yes;/deltaT $dtico; adjustTimeStep no;/; s/^application umppmFoam/application icoFoam/" \
        "$ic/system/controlDict"
    t1=$(date +%s.%N)
    run "$ic/log.icoFoam" icoFoam -case "$ic"
    isecs=$(awk -v a="$t1" -v b="$(date +%s.%N)" 'BEGIN { printf "%.2f", b - a }')
    ilast=$(ls -d "$ic"/[0-9]* | sed 's|.*/||' | sort -g | tail -1)
    "$tooldir/ghiaCompare" -Re "$Re" "$ic" "$ilast" | tail -1
    read -r _ _ i_u_rms i_u_max i_v_rms i_v_max < <("$tooldir/ghiaCompare" -Re "$Re" "$ic" "$ilast" | tail -1)
    "$tooldir/foamCompare" "$dir" "$last" "$ic" "$ilast" U p | tee "$dir/log.foamCompare"
    read -r l2r linfr < <(awk '$1 == "U" { print $4, $5 }' "$dir/log.foamCompare")
    result="$result ico_u_rms=$i_u_rms ico_u_max=$i_u_max ico_v_rms=$i_v_rms ico_v_max=$i_v_max ico_seconds=$isecs ico_steps=$(grep -c '^Time = ' "$ic/log.icoFoam") UvsIco_L2rel=$l2r UvsIco_Linfrel=$linfr"
fi
echo "$result"
