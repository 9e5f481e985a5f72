#!/usr/bin/env bash
# Builds burst if needed and runs the test suite (everything but the benchmark label), 2 at a time.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
cd build
ctest -LE bench -j 2 --output-on-failure --timeout 900 "$@"
