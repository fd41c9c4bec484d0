#!/usr/bin/env bash
# Builds the libFuzzer targets (fuzz/README.md) with clang in build-fuzz/ and runs each for
# SECONDS (default 120) on one worker, niced, starting from the seed corpora (examples/,
# studies/) and the corpus earlier runs grew in build-fuzz/corpus/. Exits 1 on any finding —
# a crash, a sanitizer report, an input slower than 30 s, more than 2 GB — after both targets
# ran; the input is then in build-fuzz/findings/ and the report in build-fuzz/fuzz-TARGET.log.
#
#     bash scripts/fuzz.sh [SECONDS] [model|study …]
#     FUZZ_RUNS=10000000 bash scripts/fuzz.sh 0 model     # by executions instead of by time
#     FUZZ_OPT=-O0 bash scripts/fuzz.sh 30                # in build-fuzz-O0/
#     FUZZ_TIMEOUT=120 …                                  # an input's limit in s (default 30; the campaign's 120)
#
# FUZZ_OPT (default -O1) sets the optimisation: -O0 builds in two thirds of the time and runs each
# input several times slower (the model target's slowest seed 27 s, near the 30-s limit).
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-120}
shift || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(model study)
opt=${FUZZ_OPT:--O1}
build=build-fuzz
[ "$opt" = -O1 ] || build="build-fuzz$opt"

if ! command -v clang++ >/dev/null; then
  echo "fuzz: clang++ is missing (bash scripts/setup.sh installs it)" >&2
  exit 2
fi
# -O1 with line tables only (AddressSanitizer's advice): a finding's stack still names file and
# line, and the targets compile in much less time than at -O2 with full debug information.
if [ -f "$build/CMakeCache.txt" ] && ! grep -q "^CMAKE_GENERATOR:INTERNAL=Ninja$" "$build/CMakeCache.txt"; then
  rm -rf "$build/CMakeCache.txt" "$build/CMakeFiles"  # made with Makefiles by an earlier version of this script
fi
CXX=clang++ cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="$opt -gline-tables-only -DNDEBUG" -DTSMFRAME_FUZZ=ON -DTSMFRAME_TESTS=OFF -DTSMFRAME_BENCH=OFF -DTSMFRAME_PYTHON=OFF >/dev/null
nice cmake --build "$build" -j"$(nproc)" --target "${targets[@]/#/tsmframe_fuzz_}" >/dev/null

limits=(-max_len=16384 -timeout="${FUZZ_TIMEOUT:-30}" -rss_limit_mb=2048 -print_final_stats=1)
if [ -n "${FUZZ_RUNS:-}" ]; then limits+=(-runs="$FUZZ_RUNS"); else limits+=(-max_total_time="$seconds"); fi
found=0
for target in "${targets[@]}"; do
  corpus="$build/corpus/$target"
  log="$build/fuzz-$target.log"
  mkdir -p "$corpus" "$build/findings"
  start=$(date +%s)
  rc=0
  nice "$build/fuzz/tsmframe_fuzz_$target" "$corpus" "$build/fuzz/corpus/$target" "${limits[@]}" \
    -artifact_prefix="$build/findings/$target-" >"$log" 2>&1 || rc=$?
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
  if [ "$rc" = 0 ]; then
    echo "fuzz: $target: ${runs:-?} executions in $(( $(date +%s) - start )) s, no finding"
  elif [ "$rc" = 72 ]; then  # libFuzzer's exit code when stopped by SIGINT: no finding
    echo "fuzz: $target: stopped after ${runs:-?} executions in $(( $(date +%s) - start )) s, no finding"
  else
    found=1
    echo "fuzz: $target: FINDING after $(( $(date +%s) - start )) s (report: $log)" >&2
    grep -E -A12 "ERROR:|runtime error:|terminate called|Test unit written" "$log" | head -40 >&2 || tail -40 "$log" >&2
  fi
done
exit $found
