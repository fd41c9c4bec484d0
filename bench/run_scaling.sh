#!/usr/bin/env bash
# Cost per Newton iteration against model size: C chains of 1,000 elements, one process per size
# (so each peak memory is its own). Usage: bash bench/run_scaling.sh [chains...] (default 1 10 100 1000)
set -euo pipefail
cd "$(dirname "$0")/.."
[ -x build/bench/tsmframe_scaling ] || bash scripts/setup.sh >/dev/null
chains=("$@")
[ ${#chains[@]} -gt 0 ] || chains=(1 10 100 1000)
printf '%9s %5s %6s %10s %9s %8s %8s\n' elements steps iters "ms/iter" "ns/el/it" "total_s" "peak_MB"
for c in "${chains[@]}"; do build/bench/tsmframe_scaling "$c" 1000; done
