#!/usr/bin/env bash
# CI step: builds the libFuzzer harnesses (fuzz/) with clang in build-fuzz and runs each
# for FUZZ_SECONDS (default 30) from its seed corpus; fails on any crash, sanitizer
# report or abort (the crashing input is left in build-fuzz/artifacts/). docs/testing.md.
set -euo pipefail
cd "$(dirname "$0")/.."
start=$(date +%s)
FUZZ_DIR=${FUZZ_BUILD_DIR:-build-fuzz}
SECONDS_PER_HARNESS=${FUZZ_SECONDS:-30}
CC=clang CXX=clang++ cmake -S . -B "$FUZZ_DIR" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g" "-DCMAKE_C_FLAGS_RELWITHDEBINFO=-O1 -g" \
    -DAVALANCHE_BUILD_FUZZERS=ON -DAVALANCHE_BUILD_TESTS=OFF -DAVALANCHE_WITH_MPI=OFF \
    ${CMAKE_ARGS:-}
cmake --build "$FUZZ_DIR" -j "$(nproc)" --target fuzz_scenario fuzz_points
mkdir -p "$FUZZ_DIR/artifacts"
export ASAN_OPTIONS=detect_leaks=1
export LSAN_OPTIONS=suppressions=$PWD/scripts/sanitizers/lsan.supp:print_suppressions=0
for harness in scenario points; do
    # New inputs go to a scratch corpus; the committed seeds stay as they are.
    work="$FUZZ_DIR/corpus-$harness"
    mkdir -p "$work"
    dict=()
    [ -f "fuzz/$harness.dict" ] && dict=("-dict=fuzz/$harness.dict")
    "$FUZZ_DIR/fuzz/fuzz_$harness" "$work" "fuzz/corpus/$harness" "${dict[@]}" \
        -max_total_time="$SECONDS_PER_HARNESS" -max_len=4096 -timeout=10 -rss_limit_mb=2048 \
        -print_final_stats=1 -artifact_prefix="$FUZZ_DIR/artifacts/$harness-"
done
echo "fuzz step: $(( $(date +%s) - start )) s"
