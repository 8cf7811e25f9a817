#!/usr/bin/env bash
# Every test: set up, build Release (the documentation with it) and run all
# tests, the documentation's examples among them; then build a second
# tree with clang, AddressSanitizer + UBSan and the libFuzzer targets (without
# the validation library: the report is checked in the Release tree), and run
# the tests not tagged [slow] plus a short fuzzing pass over every text reader.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
ctest --test-dir build --output-on-failure --parallel "$(nproc)"

ATTENUVIS_BUILD_DIR=build-asan \
ATTENUVIS_EXTRA_PACKAGES="clang libclang-rt-14-dev" \
ATTENUVIS_CMAKE_ARGS="-DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo -DATTENUVIS_SANITIZE=ON -DATTENUVIS_FUZZ=ON -DATTENUVIS_BUILD_BENCHMARKS=OFF -DATTENUVIS_TEST_SPEC=~[slow] -DATTENUVIS_PYTHON_PACKAGE=OFF -DATTENUVIS_MPI=OFF -DATTENUVIS_DOCS=OFF -DATTENUVIS_VALIDATION=OFF" \
  bash scripts/setup.sh
ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
  ctest --test-dir build-asan --output-on-failure --parallel "$(nproc)"
