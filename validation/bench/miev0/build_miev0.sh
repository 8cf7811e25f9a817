#!/bin/sh
# Builds W. J. Wiscombe's MIEV0 from the user's own copy of its Fortran
# source as a shared library for mie_error_vs_time --miev0 LIB:
#   validation/bench/miev0/build_miev0.sh MIEV0.f ErrPack.f [more.f ...]
# MIEV0 is not part of attenuvis and is not fetched: pass the files of the
# public distribution (MIEV0.f and the ErrPack.f it calls).  They are compiled
# as in the timings the README quotes: gfortran -O2 with default REAL and
# COMPLEX promoted to double (-fdefault-real-8).  The library goes to
# build/miev0/libmiev0.so (OUT=DIR to change the folder); prints its path.
set -eu
if [ $# -lt 1 ]; then
  echo "usage: $0 MIEV0.f ErrPack.f [more.f ...]" >&2
  exit 2
fi
for f in "$@"; do
  [ -r "$f" ] || { echo "build_miev0.sh: cannot read $f" >&2; exit 2; }
done
root=$(git -C "$(dirname "$0")" rev-parse --show-toplevel)
out=${OUT:-$root/build/miev0}
mkdir -p "$out"
${FC:-gfortran} -O2 -fdefault-real-8 -fPIC -shared -ffixed-line-length-none "$@" -o "$out/libmiev0.so.tmp"
mv "$out/libmiev0.so.tmp" "$out/libmiev0.so"
echo "$out/libmiev0.so"
