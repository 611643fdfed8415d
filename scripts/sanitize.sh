#!/usr/bin/env bash
# CI step: builds build-asan (RelWithDebInfo at -O1, -fsanitize=address,undefined, UBSan
# findings fatal) and runs every test label in it (unit with io and gis, verification,
# regression, cli), with leak detection on. Known leaks of the libraries we link (not
# ours) are suppressed, each with its reason, in scripts/sanitizers/lsan.supp. Prints the
# step's wall time.
set -euo pipefail
cd "$(dirname "$0")/.."
start=$(date +%s)
ASAN_DIR=${ASAN_BUILD_DIR:-build-asan}
cmake -S . -B "$ASAN_DIR" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g" "-DCMAKE_C_FLAGS_RELWITHDEBINFO=-O1 -g" \
    -DAVALANCHE_SANITIZE=address,undefined ${CMAKE_ARGS:-}
# The verification and regression labels add about four minutes on 2 cores (2026-12-06:
# 122 s and 101 s of tests); the regression tests are the ones that run the strips on
# two threads and the extreme-case matrix, and found an undefined memcmp that the other
# labels did not (docs/testing.md, "Sanitizers"). The random sweep of the regression
# label (1000 tests) adds about 430 s of test time here, 3.6 minutes on 2 cores.
cmake --build "$ASAN_DIR" -j "$(nproc)" --target avalanche-hazard test_unit test_io test_gis test_cli \
    test_verification test_regression
asan_options=detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1
export ASAN_OPTIONS=$asan_options
export LSAN_OPTIONS=suppressions=$PWD/scripts/sanitizers/lsan.supp:print_suppressions=0
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
ctest --test-dir "$ASAN_DIR" -E BatchMpi --output-on-failure -j "$(nproc)" \
    --timeout 900
# The batch under mpirun: Open MPI's libraries have no frame pointers, so their leaks
# are only recognisable (and suppressible) with the slow unwinder, and with the
# components kept loaded (no dlclose) so that their frames have names.
ASAN_OPTIONS=$asan_options:fast_unwind_on_malloc=0 OMPI_MCA_mca_base_component_disable_dlclose=1 \
    ctest --test-dir "$ASAN_DIR" -R BatchMpi --output-on-failure --timeout 900
echo "sanitize step: $(( $(date +%s) - start )) s"
