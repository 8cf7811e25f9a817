#!/bin/sh
# Builds the Mie core of an earlier commit as a shared library for the speed
# comparison of mie_error_vs_time (--baseline LIB):
#   validation/bench/baseline/build_mie_baseline.sh [COMMIT] [OUTDIR]
# COMMIT defaults to 78ee94c (the core before the speed work), OUTDIR to
# build/mie_baseline_COMMIT.  The sources come from `git archive` (no checkout
# is touched); they are compiled with the flags of a Release build (-O3
# -DNDEBUG, C++17, GCC), the TLS model of a static link (the current core is
# linked statically into the benchmark) and hidden symbols except the shim's C
# entry point.  Prints the library's path.
set -eu
commit=${1:-78ee94c}
root=$(git -C "$(dirname "$0")" rev-parse --show-toplevel)
out=${2:-$root/build/mie_baseline_$commit}
mkdir -p "$out/src"
git -C "$root" archive "$commit" mie | tar -x -C "$out/src"
${CXX:-g++} -std=c++17 -O3 -DNDEBUG -fPIC -shared -fvisibility=hidden -fvisibility-inlines-hidden \
  -ftls-model=initial-exec -I"$out/src/mie/include" \
  "$out/src/mie/src/sphere_double.cpp" "$root/validation/bench/baseline/mie_baseline_shim.cpp" \
  -o "$out/libmie_baseline.so"
echo "$out/libmie_baseline.so"
