#!/bin/sh
# Builds the user's checkout of scattnlay (github.com/ovidiopr/scattnlay;
# O. Peña & U. Pal, Comput. Phys. Commun. 180:2348, 2009), double precision,
# as a shared library for mie_layered_speed --scattnlay LIB:
#   validation/bench/scattnlay/build_scattnlay.sh /path/to/scattnlay
# scattnlay is not part of attenuvis and is not fetched.  Its src/nmie.cc is
# compiled with scattnlay_shim.cpp (one C entry point around nmie::nMie) by
# g++ -std=c++20 -O3 -march=native (its own Release flags, tuned for this
# CPU: the peer at its best; without Google Highway, which scattnlay treats as
# optional).  The library goes to build/scattnlay/libscattnlay_shim.so
# (OUT=DIR to change the folder); prints its path.
set -eu
if [ $# -ne 1 ] || [ ! -r "$1/src/nmie.cc" ]; then
  echo "usage: $0 SCATTNLAY_CHECKOUT (the folder holding src/nmie.cc)" >&2
  exit 2
fi
here=$(cd "$(dirname "$0")" && pwd)
root=$(git -C "$here" rev-parse --show-toplevel)
out=${OUT:-$root/build/scattnlay}
mkdir -p "$out"
${CXX:-g++} -std=c++20 -O3 -march=native -fPIC -shared -I "$1/src" "$1/src/nmie.cc" "$here/scattnlay_shim.cpp" \
  -o "$out/libscattnlay_shim.so.tmp"
mv "$out/libscattnlay_shim.so.tmp" "$out/libscattnlay_shim.so"
echo "$out/libscattnlay_shim.so"
