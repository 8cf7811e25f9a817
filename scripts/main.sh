#!/usr/bin/env bash
# The main job: set up, build, and reproduce the seed paper and the published
# charts into out/report.html.  Extra arguments go to `attenuvis reproduce`.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
./build/apps/attenuvis reproduce --out out "$@"
