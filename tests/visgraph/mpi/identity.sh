#!/usr/bin/env bash
# `mpirun -np NP attenuvis vg ...` writes byte-identical files to one process
# (the same program started without a launcher): the shares of the pass are
# integer fixed-point sums, reduced exactly, whatever the process count; the
# space-syntax measures join every share's lines of sight and each node's
# values come from one process.
# usage: identity.sh ATTENUVIS MPIEXEC NP WORKDIR layouts|city
set -euo pipefail
attenuvis=$1 mpiexec=$2 np=$3 dir=$4 scenes=$5
rm -rf "$dir" && mkdir -p "$dir" && cd "$dir"
# CI runs as root, which OpenMPI refuses unless told.
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

compared=0
# same NAME ARGS...: the run on one process and on NP processes, every output compared byte for byte.
same() {
  local name=$1
  shift
  "$attenuvis" vg "$@" --quiet --out "$name.1.csv" --ply "$name.1.ply" --geojson "$name.1.geojson"
  "$mpiexec" --oversubscribe -np "$np" "$attenuvis" vg "$@" --quiet --out "$name.$np.csv" --ply "$name.$np.ply" \
    --geojson "$name.$np.geojson"
  for ext in csv ply geojson; do
    cmp "$name.1.$ext" "$name.$np.$ext"
  done
  [ "$(wc -l <"$name.1.csv")" -gt 100 ] || { echo "$name: too few nodes to test anything" >&2; exit 1; }
  compared=$((compared + 1))
}

case $scenes in
  layouts)
    # Culled all-to-all (leaf clusters shared by cost), every pair cast, a
    # pruned pass (rows dealt round-robin), a distance limit, to a target.
    same culled layout:2 --conditions clear,fog:advection,rain:8 --distances
    same cast layout:1 --conditions clear,sigma:0.01 --distances --no-culling
    same pruned layout:3 --conditions sigma:4 --prune-below 1e-3
    same limited layout:0 --conditions sigma:0.01 --max-distance 10 --distances
    same target layout:4 --conditions sigma:0.01,fog:advection --target-point 1,1,1.7 --distances
    # Space syntax: every measure on bit rows (the rows OR-ed) and on CSR
    # lists (the pairs gathered), with a radius and step depth.
    same syntax layout:2 --spacing 2 --conditions clear,fog:advection --measures all,step-depth \
      --contrast-threshold 0.5 --depth-from 10,10,1.7
    same syntax_csr layout:4 --spacing 2 --conditions clear,snow:dry:4 --measures all --contrast-threshold 0.5 \
      --graph csr --radius 3
    ;;
  city)
    "$attenuvis" scene city --rings 1 --out city.obj
    same city city.obj --spacing 4 --conditions clear,fog:advection,rain:8 --distances
    same city_syntax city.obj --spacing 6 --conditions clear,fog:advection \
      --measures connectivity,clustering,control,controllability,mean-depth,integration,entropy,through-vision,component
    ;;
  *)
    echo "unknown scene set '$scenes'" >&2
    exit 2
    ;;
esac
echo "$compared runs on $np processes identical to one process"
