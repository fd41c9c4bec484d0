#!/usr/bin/env bash
# Sets up (as scripts/setup.sh) and runs every test: unit, verification and command-line.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
ctest --test-dir build --output-on-failure -j2
