#!/usr/bin/env bash
# Installs what attenuvis needs from Debian 12 (only what is missing), then
# configures and builds the Release tree in build/.  Idempotent: run it as
# often as you like.  Used by scripts/main.sh and scripts/test.sh.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  build-essential cmake ninja-build
  libboost-dev libboost-math-dev       # Boost.Math quadrature/special functions, Boost.Multiprecision
  libeigen3-dev libembree-dev libtinyobjloader-dev libtbb-dev libnanoflann-dev
  libcli11-dev nlohmann-json3-dev catch2 libbenchmark-dev libtinygltf-dev
  python3 python3-matplotlib python3-numpy
  libnetcdf-dev                             # netCDF-4 tables
  libcgal-dev                               # the ground inferred under buildings-only city models (Delaunay)
  libgdal-dev gdal-bin python3-gdal         # DEMs, footprint layers, GeoPackage out; gdal-bin and python3-gdal for their tests and docs
  pybind11-dev python3-dev python3-pytest  # the Python package (python/) and its tests
  python3-xarray python3-netcdf4           # optional there; its tests and examples use them
  python3-networkx                         # the space-syntax measures' independent reference (tests, benchmark)
  libopenmpi-dev openmpi-bin               # optional: `mpirun -np N attenuvis vg` (ATTENUVIS_MPI)
  python3-sphinx python3-myst-parser python3-breathe doxygen  # the documentation (docs/): HTML and attenuvis(1)
  man-db                                   # `man attenuvis` (the installed page)
)
# Callers add what only they need (scripts/test.sh: clang and its libFuzzer runtime).
read -r -a extra <<<"${ATTENUVIS_EXTRA_PACKAGES:-}"
packages+=("${extra[@]}")
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  if [ "$(id -u)" -eq 0 ]; then sudo=""; else sudo="sudo"; fi
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

set -f  # ATTENUVIS_CMAKE_ARGS may hold a Catch2 spec like ~[slow]; never glob it
build_dir=${ATTENUVIS_BUILD_DIR:-build}
cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release ${ATTENUVIS_CMAKE_ARGS:-} >/dev/null
cmake --build "$build_dir" --parallel "$(nproc)"
# The Release tree is installed (the program to /usr/local/bin, its data to
# /usr/local/share/attenuvis, the Python package to Debian's
# /usr/local/lib/python3.X/dist-packages), so `attenuvis` and
# `import attenuvis` work from any directory.  Other trees are not installed.
if [ "$build_dir" = build ]; then
  if [ "$(id -u)" -eq 0 ]; then sudo=""; else sudo="sudo"; fi
  $sudo cmake --install "$build_dir" >/dev/null
fi
