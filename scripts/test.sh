#!/usr/bin/env bash
# The whole test suite from a fresh clone: install, build, run every CTest label
# (unit, verification, regression, cli). Exit code is CTest's.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/build.sh
BUILD_DIR=${BUILD_DIR:-build}
ctest --test-dir "$BUILD_DIR" --output-on-failure -j "$(nproc)" --timeout 900
