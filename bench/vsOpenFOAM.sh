#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# bench/vsOpenFOAM.sh [-cases "cavity40 cavity80 cavity160 cavity320 taylorGreen6400 makeRunCavity"]
#                     (more: buoyantCavity40 buoyantCavity80)
#                     [-steps N | -steps "CASE=N ..."] [-threads "1 2"] [-work DIR]
#                     [-umppm PATH] [-decompose simple|scotch] [-o FILE]
# umppmFoam against icoFoam (OpenFOAM v1912), and on the buoyant cases
# against buoyantBoussinesqPimpleFoam (the OpenFOAM solver below), side by
# side in one run: for
# each case one mesh (made once) and one fixed deltaT (adjustTimeStep no),
# a fixed number of steps, and these runs, each in its own copy of the case
# (WORK/CASE/<run>, log in WORK/CASE/<run>/log):
#   umppm-ompT  umppmFoam with OMP_NUM_THREADS=T for each T of -threads
#   ico-PCG     the OpenFOAM solver serial, the case's own p/pFinal (p_rgh)
#               solver (PCG, DIC)
#   ico-GAMG    the same, p/pFinal by GAMG (smoother GaussSeidel) with the
#               PCG's tolerance and relTol (pFinal inherits $p)
#   ico-mpi2    decomposePar (2 subdomains, -decompose method, default simple
#               (2 1 1)) then mpirun -np 2 of it with -parallel (PCG)
# Cases:
#   cavityN          (N = 40 80 160 320) OpenFOAM's icoFoam/cavity/cavity
#                    tutorial with its own fvSchemes/fvSolution/0/, blocks
#                    (N N 1), nu 0.001 and, as the one change beyond that,
#                    scale 1 instead of 0.1 (unit square: lid U = 1 gives
#                    Re = 1000 and deltaT = 0.0125*40/N a lid Courant number
#                    0.5; with 0.1 m it would be Re 100 and Courant 5).
#                    Default steps 160 80 40 20.
#   taylorGreen6400  bench/taylorGreen.sh's case: bin/makeCrossedTriangleMesh
#                    -n 40 (6400 crossed triangles), bin/setTaylorGreen, its
#                    fvSchemes/fvSolution (UMPPMstar; the defaults, on this
#                    periodic mesh CPM4 and pressureTheta 0.5 since
#                    2026-12-06, the paper's CPM before), nu 0.01, fixed
#                    deltaT = 0.25/(2n) = 0.003125 (its -cfl 0.25). 160 steps.
#   makeRunCavity    `make run`'s tutorials/cavity as its Allrun defaults set
#                    it (40x40, Re 100, UMPPMstar), its controlDict with
#                    adjustTimeStep no at its deltaT 0.003125 (maxCo 0.25 /
#                    (2n), Allrun's first step; umppmFoam and icoFoam alike).
#                    160 steps.
#   buoyantCavityN   (N = 40 80; not run by default) the de Vahl Davis
#                    cavity of tests/cases/buoyantCavity (Ra 1e4, Pr 0.71,
#                    unit square, as test_buoyant.sh runs it), blocks
#                    (N N 1), from rest, fixed deltaT 10/N s (Courant number
#                    about 0.4 at the steady flow's 16-20 alpha/L), against
#                    buoyantBoussinesqPimpleFoam with the case's own
#                    fvSchemes/fvSolution (PIMPLE, 2 correctors); umppmFoam
#                    with its defaults (UMPPMstar, CPM, balanced buoyancy).
#                    Default steps 200 100.
# All cases: endTime = steps*deltaT, writeControl timeStep, writeInterval =
# steps (only the end time is written, by every run). A run that fails or
# does not make exactly the steps asked stops the script (exit 1, the run
# and its log named).
# Measured, per run (bench/run_usage.py around the solver command only; the
# mesh, decomposePar and the copies are outside it):
#   wall s      launch to exit of the solver command (mpirun: of mpirun)
#   CPU s       user+sys of all processes of the run (the rusage of the
#               wait4 on the command, i.e. RUSAGE_CHILDREN of that one
#               child): for mpirun the sum over both ranks and mpirun
#               (Open MPI's ranks busy-poll while waiting)
#   particles   umppmFoam: the mean of its `Particles: N` lines; icoFoam: -
#   us/pc-step  1e6 CPU s / (particles*steps) for umppmFoam, / (cells*steps)
#               for icoFoam; CPU s includes the start-up
#   startup s   wall from the launch to the first `Time = ` line of the
#               output, read through a pipe as it comes (umppmFoam under
#               stdbuf -oL; OpenFOAM flushes that line itself): umppmFoam's
#               reading, pressure mesh, PPE factorization and seeding;
#               icoFoam's libraries, mesh and fields (+ MPI start for
#               mpirun; GAMG's agglomeration is made in the first step, not
#               here). Included in wall s and CPU s.
#   RSS MiB     peak resident set of the largest single process (its
#               ru_maxrss, or when that is only python's own peak, which
#               the kernel carries over the exec, VmHWM sampled from /proc
#               every 20 ms): for mpirun the max over the ranks and
#               mpirun, not the sum
#   CPU/PCG CPU/GAMG  umppmFoam rows: its CPU s / icoFoam PCG's, / GAMG's
#   wall/mpi2   umppmFoam rows: its wall s / mpirun -np 2's wall s
# -umppm PATH: that binary, the repository is not built (only if
# taylorGreen6400 needs bin/makeCrossedTriangleMesh or bin/setTaylorGreen
# and they are missing); default: `make -s` in the repository top, then
# its bin/umppmFoam. -steps N sets every case; "CASE=N ..." single ones.
# Prints date, uname -m, CPU model, nproc and the revision first; the table
# also goes to FILE with -o. WORK (default a new mktemp -d) is kept.
# As root mpirun gets --allow-run-as-root; with fewer than 2 CPUs also
# --oversubscribe. Debian's OpenFOAM v1912 ships only a stub of
# libscotchDecomp (decomposePar fails: -decompose scotch needs a real one).
set -eu -o pipefail
top=$(cd "$(dirname "$0")/.." && pwd)
. "$top/bench/cases.sh" # cavity_case; setEntry, logSteps; exports WM_PROJECT_DIR
defcases="cavity40 cavity80 cavity160 cavity320 taylorGreen6400 makeRunCavity"
allcases="$defcases buoyantCavity40 buoyantCavity80"
cases=$defcases stepsopt="" threads="1 2" work="" umppm="" decompose=simple out=""
usage() {
    echo "usage: bench/vsOpenFOAM.sh [-cases \"$allcases\"] [-steps N | -steps \"CASE=N ...\"]" \
        "[-threads \"1 2\"] [-work DIR] [-umppm PATH] [-decompose simple|scotch] [-o FILE]" >&2
    exit 1
}
while [ $# -gt 0 ]; do
    [ $# -ge 2 ] || usage
    case $1 in
    -cases) cases=$2 ;; -steps) stepsopt=$2 ;; -threads) threads=$2 ;; -work) work=$2 ;;
    -umppm) umppm=$2 ;; -decompose) decompose=$2 ;; -o) out=$2 ;;
    *) usage ;;
    esac
    shift 2
done
die() { echo "vsOpenFOAM.sh: $*" >&2; exit 1; }
declare -A nsteps=([cavity40]=160 [cavity80]=80 [cavity160]=40 [cavity320]=20 [taylorGreen6400]=160 [makeRunCavity]=160
    [buoyantCavity40]=200 [buoyantCavity80]=100)
for c in $cases; do [ -n "${nsteps[$c]:-}" ] || die "unknown case '$c' (one of: $allcases)"; done
for s in $stepsopt; do
    case $s in
    *=*) [ -n "${nsteps[${s%%=*}]:-}" ] || die "-steps: unknown case '${s%%=*}'"; nsteps[${s%%=*}]=${s#*=} ;;
    *) for c in $allcases; do nsteps[$c]=$s; done ;;
    esac
done
for c in $cases; do
    case ${nsteps[$c]} in '' | *[!0-9]* | 0) die "-steps: '${nsteps[$c]}' for $c is not a positive integer" ;; esac
done
case $decompose in simple | scotch) ;; *) die "-decompose: simple or scotch, not '$decompose'" ;; esac
case " $cases " in *" cavity"[0-9]*) [ -d "$cavity_tutorial" ] || die "no OpenFOAM cavity tutorial in $cavity_tutorial (package openfoam-examples)" ;; esac
if [ -z "$umppm" ]; then
    make -C "$top" -s >/dev/null || die "make in $top failed"
    umppm=$top/bin/umppmFoam
fi
case " $cases " in *" taylorGreen6400 "*)
    [ -x "$top/bin/makeCrossedTriangleMesh" ] && [ -x "$top/bin/setTaylorGreen" ] ||
        make -C "$top" -s >/dev/null || die "make in $top failed (bin/makeCrossedTriangleMesh, bin/setTaylorGreen)" ;;
esac
[ -x "$umppm" ] || die "no umppmFoam at $umppm"
umppm=$(cd "$(dirname "$umppm")" && pwd)/$(basename "$umppm")
apps=icoFoam
case " $cases " in *" buoyantCavity"[0-9]*) apps="$apps buoyantBoussinesqPimpleFoam" ;; esac
for t in $apps blockMesh decomposePar mpirun stdbuf; do command -v "$t" >/dev/null || die "$t not on PATH"; done
mpiflags=""
[ "$(id -u)" != 0 ] || mpiflags="--allow-run-as-root"
[ "$(nproc)" -ge 2 ] || mpiflags="$mpiflags --oversubscribe"
[ -n "$work" ] || work=$(mktemp -d "${TMPDIR:-/tmp}/umppm-vsof.XXXXXX")
mkdir -p "$work"
work=$(cd "$work" && pwd)
[ -z "$out" ] || : > "$out"
emit() { printf '%s\n' "$1"; [ -z "$out" ] || printf '%s\n' "$1" >> "$out"; }
fmt="%-15s %-40s %6s %9s %5s %8s %8s %10s %9s %7s %7s %8s %9s"

rev=$(git -C "$top" describe --always --dirty 2>/dev/null || echo unknown)
emit "# bench/vsOpenFOAM.sh: umppmFoam vs icoFoam (buoyant cases: buoyantBoussinesqPimpleFoam), same mesh, same fixed deltaT, fixed steps"
emit "# date: $(date '+%Y-%m-%d %H:%M:%S %z')  machine: $(uname -m)  CPU: $(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -1)  nproc: $(nproc)"
emit "# umppmFoam: $umppm (repo $rev)  OpenFOAM v1912: $(for a in $apps; do printf '%s ' "$(command -v "$a")"; done) mpirun: $(mpirun --version 2>/dev/null | head -1)"
emit "# CPU = user+sys of the run's processes (mpirun: sum over ranks); RSS = peak of the largest process (mpirun: max over ranks);"
emit "# us/pc-st = CPU per particle-step (umppmFoam) or per cell-step (the OpenFOAM solver); startup = wall to the first 'Time = ' line"
emit "# cases in $work"
emit "$(printf "$fmt" case solver/config cells particles steps wall_s CPU_s us/pc-st startup_s RSS_MiB CPU/PCG CPU/GAMG wall/mpi2)"

# base_taylorGreen DIR n: bench/taylorGreen.sh's case (its dictionaries, -cfl 0.25)
base_taylorGreen() {
    mkdir -p "$1/system" "$1/constant"
    cat > "$1/system/controlDict" <<CD
FoamFile { version 2.0; format ascii; class dictionary; object controlDict; }
application umppmFoam;
startFrom startTime;
startTime 0;
stopAt endTime;
endTime 1;
deltaT 1;
adjustTimeStep no;
writeControl timeStep;
writeInterval 1;
writeFormat ascii;
writePrecision 15;
CD
    cat > "$1/system/fvSchemes" <<FS
FoamFile { version 2.0; format ascii; class dictionary; object fvSchemes; }
ddtSchemes { default Euler; } gradSchemes { default Gauss linear; }
divSchemes { default none; div(phi,U) Gauss linear; }
laplacianSchemes { default Gauss linear corrected; } interpolationSchemes { default linear; }
snGradSchemes { default corrected; }
FS
    cat > "$1/system/fvSolution" <<FS
FoamFile { version 2.0; format ascii; class dictionary; object fvSolution; }
solvers { p { solver PCG; preconditioner DIC; tolerance 1e-10; relTol 0; } pFinal { \$p; }
          U { solver smoothSolver; smoother symGaussSeidel; tolerance 1e-10; relTol 0; } }
PISO { nCorrectors 2; nNonOrthogonalCorrectors 1; pRefCell 0; pRefValue 0; }
UMPPM { variant UMPPMstar; }
FS
    echo 'FoamFile { version 2.0; format ascii; class dictionary; object transportProperties; } nu 0.01;' \
        > "$1/constant/transportProperties"
    "$top/bin/makeCrossedTriangleMesh" -case "$1" -n "$2" > "$1/log.makeCrossedTriangleMesh" 2>&1 ||
        die "makeCrossedTriangleMesh failed: see $1/log.makeCrossedTriangleMesh"
    "$top/bin/setTaylorGreen" -case "$1" > "$1/log.setTaylorGreen" 2>&1 ||
        die "setTaylorGreen failed: see $1/log.setTaylorGreen"
}

# base_makeRun DIR: tutorials/cavity with its Allrun's defaults (n 40, Re 100)
base_makeRun() {
    cp -r "$top/tutorials/cavity/system" "$top/tutorials/cavity/constant" "$1/"
    cp -r "$top/tutorials/cavity/0.orig" "$1/0"
    setEntry "$1/system/blockMeshDict" n 40
    setEntry "$1/constant/transportProperties" nu 0.01
    setEntry "$1/system/controlDict" adjustTimeStep no
    setEntry "$1/system/fvSolution" variant UMPPMstar
    setEntry "$1/system/fvSolution" alpha 0.09
}

# measure NAME DIR EXPECTED_STEPS CMD...: run CMD in DIR (log DIR/log) by
# run_usage.py; sets wall cpu rss first; fails loudly on an exit status
# other than 0 or a step count other than EXPECTED_STEPS.
measure() {
    local name=$1 dir=$2 want=$3 rc got
    shift 3
    read -r wall cpu rss first rc < <(cd "$dir" && python3 "$top/bench/run_usage.py" -o log "$@") ||
        die "$name: no measurement from bench/run_usage.py (see $dir/log)"
    if [ "$rc" != 0 ]; then
        echo "vsOpenFOAM.sh: $name failed (exit status $rc): see $dir/log" >&2
        tail -5 "$dir/log" >&2
        exit 1
    fi
    got=$(logSteps "$dir/log" || true)
    [ "$got" = "$want" ] || die "$name made $got steps, not $want: see $dir/log"
}

for c in $cases; do
    steps=${nsteps[$c]}
    d=$work/$c
    rm -rf "$d"
    mkdir -p "$d/base"
    b=$d/base
    app=icoFoam
    case $c in
    cavity*)
        n=${c#cavity}
        dt=$(awk -v n="$n" 'BEGIN { printf "%.10g", 0.0125 * 40 / n }')
        cavity_case "$b" "$n" 0.001 || exit 1
        what="OpenFOAM icoFoam/cavity tutorial, unit square, Re 1000, ${n}x$n quads"
        ;;
    taylorGreen6400)
        dt=$(awk 'BEGIN { printf "%.10g", 0.25 / (2 * 40) }')
        base_taylorGreen "$b" 40
        what="Taylor-Green Re 100 (bench/taylorGreen.sh), periodic unit square, 6400 crossed triangles"
        ;;
    makeRunCavity)
        dt=$(sed -n 's/^deltaT[[:space:]]*\([^;]*\);.*/\1/p' "$top/tutorials/cavity/system/controlDict")
        base_makeRun "$b"
        what="make run's tutorials/cavity, Re 100, 40x40 quads, UMPPMstar"
        ;;
    buoyantCavity*)
        n=${c#buoyantCavity}
        app=buoyantBoussinesqPimpleFoam
        dt=$(awk -v n="$n" 'BEGIN { printf "%.10g", 10 / n }')
        cp -r "$top/tests/cases/buoyantCavity/0" "$top/tests/cases/buoyantCavity/constant" \
            "$top/tests/cases/buoyantCavity/system" "$b/"
        grep -Eq '\( *20 +20 +1 *\)' "$b/system/blockMeshDict" ||
            die "$top/tests/cases/buoyantCavity/system/blockMeshDict: no block (20 20 1)"
        sed -i -E "s/\( *20 +20 +1 *\)/($n $n 1)/" "$b/system/blockMeshDict"
        setEntry "$b/system/controlDict" adjustTimeStep no
        what="de Vahl Davis cavity Ra 1e4 (tests/cases/buoyantCavity), from rest, ${n}x$n quads"
        ;;
    esac
    endTime=$(awk -v s="$steps" -v d="$dt" 'BEGIN { printf "%.10g", s * d }')
    setEntry "$b/system/controlDict" deltaT "$dt"
    setEntry "$b/system/controlDict" endTime "$endTime"
    setEntry "$b/system/controlDict" writeControl timeStep
    setEntry "$b/system/controlDict" writeInterval "$steps"
    if [ "$c" != taylorGreen6400 ]; then
        blockMesh -case "$b" > "$b/log.blockMesh" 2>&1 || die "blockMesh failed: see $b/log.blockMesh"
    fi
    cells=$(grep -o 'nCells: *[0-9]*' "$b/constant/polyMesh/owner" | head -1 | grep -o '[0-9]*$' || true)
    [ -n "$cells" ] || die "no nCells in the header of $b/constant/polyMesh/owner"
    emit "# $c: $what; $cells cells, deltaT $dt, $steps steps (endTime $endTime)"
    newrun() { rm -rf "${d:?}/$1" && mkdir "$d/$1" && cp -r "$b/system" "$b/constant" "$b/0" "$d/$1/"; }
    rows=()
    # umppmFoam, one run per OMP_NUM_THREADS
    for t in $threads; do
        r=umppm-omp$t
        newrun "$r"
        OMP_NUM_THREADS=$t measure "$c $r" "$d/$r" "$steps" stdbuf -oL "$umppm"
        np=$(sed -n 's/^Particles: \([0-9]*\).*/\1/p' "$d/$r/log" | awk '{ s += $1; k++ } END { if (k) printf "%.0f", s / k }')
        [ -n "$np" ] || die "$c $r: no 'Particles:' lines in $d/$r/log"
        us=$(awk -v s="$cpu" -v p="$np" -v k="$steps" 'BEGIN { printf "%.2f", 1e6 * s / (p * k) }')
        rows+=("umppmFoam_omp$t $np $wall $cpu $us $first $rss")
    done
    # the OpenFOAM solver serial, the case's PCG
    newrun ico-PCG
    measure "$c ico-PCG" "$d/ico-PCG" "$steps" "$app"
    us=$(awk -v s="$cpu" -v p="$cells" -v k="$steps" 'BEGIN { printf "%.2f", 1e6 * s / (p * k) }')
    rows+=("${app}_PCG - $wall $cpu $us $first $rss")
    pcg=$cpu
    # the same, GAMG for p (p_rgh) and its Final, the PCG's tolerances
    newrun ico-GAMG
    f=$d/ico-GAMG/system/fvSolution
    sed -i -E 's/(solver[[:space:]]+)PCG;/\1GAMG;/; s/preconditioner([[:space:]]+)DIC;/smoother\1GaussSeidel;/' "$f"
    { grep -q GAMG "$f" && ! grep -Eq 'PCG|DIC' "$f"; } || die "could not switch p to GAMG in $f"
    foamDictionary -expand -entry solvers "$f" > "$d/ico-GAMG/log.solvers" 2>&1 || true
    measure "$c ico-GAMG" "$d/ico-GAMG" "$steps" "$app"
    grep -q 'GAMG:  Solving for p' "$d/ico-GAMG/log" || die "$c ico-GAMG: no GAMG solve of p in $d/ico-GAMG/log"
    us=$(awk -v s="$cpu" -v p="$cells" -v k="$steps" 'BEGIN { printf "%.2f", 1e6 * s / (p * k) }')
    rows+=("${app}_GAMG - $wall $cpu $us $first $rss")
    gamg=$cpu
    # the OpenFOAM solver on 2 MPI ranks
    r=ico-mpi2
    newrun "$r"
    cat > "$d/$r/system/decomposeParDict" <<DP
FoamFile { version 2.0; format ascii; class dictionary; object decomposeParDict; }
numberOfSubdomains 2; method $decompose; simpleCoeffs { n (2 1 1); delta 0.001; }
DP
    if ! decomposePar -case "$d/$r" > "$d/$r/log.decomposePar" 2>&1; then
        ! grep -q 'dummy .*stub library' "$d/$r/log.decomposePar" ||
            echo "vsOpenFOAM.sh: this OpenFOAM has only a stub of the $decompose library: use -decompose simple" >&2
        die "decomposePar failed: see $d/$r/log.decomposePar"
    fi
    # shellcheck disable=SC2086
    measure "$c $r" "$d/$r" "$steps" mpirun $mpiflags -np 2 "$app" -parallel
    us=$(awk -v s="$cpu" -v p="$cells" -v k="$steps" 'BEGIN { printf "%.2f", 1e6 * s / (p * k) }')
    rows+=("${app}_mpi2_$decompose - $wall $cpu $us $first $rss")
    mpiwall=$wall
    for row in "${rows[@]}"; do
        read -r cfg np wall cpu us first rss <<< "$row"
        r1=- r2=- r3=-
        case $cfg in umppmFoam*)
            read -r r1 r2 r3 < <(awk -v c="$cpu" -v a="$pcg" -v g="$gamg" -v w="$wall" -v m="$mpiwall" \
                'function q(x, y) { return y > 0 ? sprintf("%.2f", x / y) : "-" } BEGIN { print q(c, a), q(c, g), q(w, m) }') ;;
        esac
        emit "$(printf "$fmt" "$c" "${cfg//_/ }" "$cells" "$np" "$steps" "$wall" "$cpu" "$us" "$first" "$rss" "$r1" "$r2" "$r3")"
    done
done
emit "# logs: WORK/CASE/<run>/log (run = umppm-ompT ico-PCG ico-GAMG ico-mpi2), WORK = $work"
