#!/usr/bin/env bash
# Builds burst if needed and runs the test suite (everything but the bench and long labels), 2 at a time.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
cd build
ctest -LE "bench|long" -j 2 --output-on-failure --timeout 900 "$@"
