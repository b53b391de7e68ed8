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

bench_top=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)

# bench_options "NAME VAR ..." ARGS...: for each "-NAME VALUE" pair of ARGS
# sets the variable VAR to VALUE; an option not in the list, or one
# without its value, exits 1 naming the options known
bench_options() {
    local -a spec
    read -r -a spec <<< "$1"
    shift
    local i known=""
    for ((i = 0; i < ${#spec[@]}; i += 2)); do known+=" -${spec[i]}"; done
    while [ $# -gt 0 ]; do
        [ $# -ge 2 ] || { echo "option $1 needs a value (options:$known)" >&2; exit 1; }
        for ((i = 0; i < ${#spec[@]}; i += 2)); do
            if [ "$1" = "-${spec[i]}" ]; then
                printf -v "${spec[i + 1]}" '%s' "$2"
                break
            fi
        done
        [ "$i" -lt ${#spec[@]} ] || { echo "unknown option $1 (options:$known)" >&2; exit 1; }
        shift 2
    done
}

# bench_prepare TAG: builds the project; sets bin (its bin/), umppm (the
# solver run: $UMPPMFOAM if set, e.g. another build to compare, else
# bin/umppmFoam) and work (created; a new umppm-TAG.XXXXXX under TMPDIR
# unless already set, by -work)
bench_prepare() {
    make -C "$bench_top" -s >/dev/null
    bin=$bench_top/bin
    umppm=${UMPPMFOAM:-$bin/umppmFoam}
    case $umppm in */*) ;; *) umppm=$(command -v "$umppm" || echo "$umppm") ;; esac
    [ -x "$umppm" ] || { echo "no solver $umppm" >&2; exit 1; }
    umppm=$(cd "$(dirname "$umppm")" && pwd)/$(basename "$umppm") # the scripts cd into cases
    work=${work:-$(mktemp -d "${TMPDIR:-/tmp}/umppm-$1.XXXXXX")}
    mkdir -p "$work"
}

cavity_tutorial=/usr/share/doc/openfoam-examples/examples/incompressible/icoFoam/cavity/cavity

# cavity_copy DIR: the cavity tutorial as it is (scale 0.1, nu 0.01, lid
# speed 1: Re 10) copied into DIR, replacing it, gzipped files unpacked
cavity_copy() {
    [ -d "$cavity_tutorial" ] ||
        { echo "no OpenFOAM cavity tutorial in $cavity_tutorial (package openfoam-examples)" >&2; return 1; }
    rm -rf "$1" && cp -r "$cavity_tutorial" "$1" && find "$1" -name '*.gz' -exec gzip -d {} +
}

# ghia_writes DIR T0 T1 [RE]: one line "time u_rms v_rms" per time
# directory of DIR with T0 <= t <= T1 (a step that does not divide the
# write interval writes at the step after, so the times are listed, not
# assumed), the RMS errors from Ghia et al. (1982) at Re RE (default 1000)
# by bin/ghiaCompare; needs bench_prepare's bin
ghia_writes() {
    local t
    for t in $(ls "$1" | grep -E '^[0-9.]+$' | awk -v a="$2" -v b="$3" '$1 >= a - 1e-6 && $1 <= b + 1e-6' | sort -g); do
        "$bin/ghiaCompare" -Re "${4:-1000}" "$1" "$t" | tail -1 | awk -v t="$t" '{ print t, $3, $5 }'
    done
}

# max_speed FILE [FORMAT]: max |U| of the internal field of the
# volVectorField FILE (printf FORMAT, default %.4g)
max_speed() {
    awk -v fmt="${2:-%.4g}" '/^internalField/ { f = 1; next }
         f && /^\(/ && NF == 3 { gsub(/[()]/, ""); s = sqrt($1 * $1 + $2 * $2); if (s > m) m = s }
         f && /^\)/ { exit } END { printf fmt, m }' "$1"
}

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

# cavity_triangles DIR GEO [H]: the mesh of the case in DIR replaced by the
# gmsh triangles of tools/GEO (with -setnumber h H if given), converted by
# gmshToFoam, the patches typed as GEO's "// foam-patch-type:" lines say
# (icoFoam's cavity: movingWall and fixedWalls walls, frontAndBack empty);
# logs in DIR. Returns 1, with a message, on a failure.
cavity_triangles() {
    local d=$1 geo=$2 pt ty
    local -a size=()
    [ $# -lt 3 ] || size=(-setnumber h "$3")
    rm -rf "$d/constant/polyMesh"
    cp "$bench_top/tools/$geo" "$d/cavity.geo" &&
        (cd "$d" && gmsh -3 -format msh2 "${size[@]}" cavity.geo -o cavity.msh > log.gmsh 2>&1 &&
            gmshToFoam cavity.msh > log.gmshToFoam 2>&1) ||
        { echo "$d: gmsh or gmshToFoam failed (log.gmsh, log.gmshToFoam)" >&2; return 1; }
    while read -r pt ty; do
        [ -n "$pt" ] || continue
        foamDictionary -entry "entry0/$pt/type" -set "$ty" "$d/constant/polyMesh/boundary" > /dev/null 2>&1 ||
            { echo "$d: cannot set the type of patch $pt" >&2; return 1; }
    done < <(geoPatchTypes "$d/cavity.geo") # tutorials/RunFunctions
}
