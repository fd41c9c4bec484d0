#!/usr/bin/env bash
# Sets up (as scripts/setup.sh) and runs every test: unit, verification and command-line; then
# builds the fuzz targets with clang (at -O0: half the build time, and a short run needs no more)
# and runs each for FUZZ_SECONDS (default 30; fuzz/README.md).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
ctest --test-dir build --output-on-failure -j2
FUZZ_OPT=-O0 bash scripts/fuzz.sh "${FUZZ_SECONDS:-30}"
