#!/usr/bin/env bash
# The main job: set up, build, and reproduce the seed paper and the published
# charts into out/report.html.  Extra arguments go to `attenuvis reproduce`.
#
# The report also times the Mie core against its earlier self (commit 78ee94c),
# built from the git history into build/mie_baseline_78ee94c/ (once; again when
# the build script or its shim change).  Without the history (a source archive,
# a shallow clone) the report is made without that table and says how to add it.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh

baseline_dir=build/mie_baseline_78ee94c
baseline_lib=$baseline_dir/libmie_baseline.so
baseline_args=()
if [ -f "$baseline_lib" ] && [ "$baseline_lib" -nt validation/bench/baseline/build_mie_baseline.sh ] &&
  [ "$baseline_lib" -nt validation/bench/baseline/mie_baseline_shim.cpp ]; then
  baseline_args=(--mie-baseline "$baseline_lib")
else
  echo "main: building the Mie core of commit 78ee94c for the speed comparison"
  mkdir -p build
  if bash validation/bench/baseline/build_mie_baseline.sh 78ee94c "$PWD/$baseline_dir" >build/mie_baseline.log 2>&1; then
    baseline_args=(--mie-baseline "$baseline_lib")
  else
    rm -f "$baseline_lib"
    echo "main: note: could not build the Mie core of commit 78ee94c (it needs the git history; see" \
      "build/mie_baseline.log); the report is made without the speed-up against it"
  fi
fi
./build/apps/attenuvis reproduce --out out "${baseline_args[@]}" "$@"
