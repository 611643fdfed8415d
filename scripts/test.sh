#!/usr/bin/env bash
# The whole test suite from a fresh clone: install, build, run every CTest label
# (unit, verification, regression, cli); then the unit, io, gis and cli tests again under
# AddressSanitizer + UndefinedBehaviorSanitizer (scripts/sanitize.sh) and each libFuzzer
# harness for a bounded time (scripts/fuzz.sh). docs/testing.md explains the steps.
# AVALANCHE_SANITIZE_STEP=0 or AVALANCHE_FUZZ_STEP=0 skips a step (local runs).
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/build.sh
BUILD_DIR=${BUILD_DIR:-build}
ctest --test-dir "$BUILD_DIR" --output-on-failure -j "$(nproc)" --timeout 900
if [ "${AVALANCHE_SANITIZE_STEP:-1}" != 0 ]; then ./scripts/sanitize.sh; fi
if [ "${AVALANCHE_FUZZ_STEP:-1}" != 0 ]; then ./scripts/fuzz.sh; fi
