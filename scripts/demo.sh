#!/usr/bin/env bash
# The main job on the bundled default scene: install, build, run, and say where the maps are.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/build.sh
OUT=${1:-results/demo}
./build/avalanche-hazard demo --out "$OUT" --overwrite
