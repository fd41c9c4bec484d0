#!/usr/bin/env bash
# The whole test suite built with AddressSanitizer and UndefinedBehaviorSanitizer (g++; CXX=clang++
# for clang) in build-sanitize/, Eigen's own index checks on (no NDEBUG): any report — a bad
# access, a leak, undefined behaviour — aborts the program and fails its test. Without the
# Python module (an instrumented module would need the sanitizer runtime preloaded into python).
#
#     bash scripts/sanitize.sh [CTEST ARGUMENTS…]        e.g. -R Study
set -euo pipefail
cd "$(dirname "$0")/.."
build=build-sanitize
sanitizers="-fsanitize=address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer"
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" \
  -DCMAKE_CXX_FLAGS="$sanitizers" -DCMAKE_EXE_LINKER_FLAGS="$sanitizers" -DCMAKE_SHARED_LINKER_FLAGS="$sanitizers" \
  -DTSMFRAME_PYTHON=OFF -DTSMFRAME_BENCH=OFF -DTSMFRAME_TEST_TIME_SCALE=10 >/dev/null
nice cmake --build "$build" -j"$(nproc)"
export ASAN_OPTIONS="abort_on_error=1:detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1"
export UBSAN_OPTIONS="print_stacktrace=1:abort_on_error=1"
ctest --test-dir "$build" --output-on-failure -j"$(nproc)" "$@"
