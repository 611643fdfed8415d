#!/usr/bin/env bash
# Installs the Debian packages (setup.sh) and builds avalanche-hazard in build/ (Release).
set -euo pipefail
cd "$(dirname "$0")/.."
./setup.sh
BUILD_DIR=${BUILD_DIR:-build}
cmake -S . -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE=Release ${CMAKE_ARGS:-}
cmake --build "$BUILD_DIR" -j "$(nproc)"
