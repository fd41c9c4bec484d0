#!/usr/bin/env bash
# Two builds' speed on the same benches, run alternately (old, new, old, new …) so that this
# VM's drift over minutes falls on both alike: the 10⁵-element chains (bench/targets.sh's main
# row), the 70 × 70-bay lattice, a 10⁴-element chain rolled into a circle in one step, and the
# beam pressed along its length onto another (examples/, many contacts; whole command, one
# thread). Prints every run and each build's median.
# Usage: bash bench/alternate.sh OLD_BUILD_DIR NEW_BUILD_DIR [RUNS]    (RUNS default 5)
set -euo pipefail
cd "$(dirname "$0")/.."
old=$1 new=$2 runs=${3:-5}
for b in "$old" "$new"; do
  for f in bench/tsmframe_scaling bench/tsmframe_lattice tsmframe; do
    [ -x "$b/$f" ] || [ -x "$b/$(basename "$f")" ] || { echo "no $f in $b" >&2; exit 2; }
  done
done
# A build dir's binary, or the file beside the others where the binaries were copied flat.
bin() { [ -x "$1/$2" ] && echo "$1/$2" || echo "$1/$(basename "$2")"; }

# One bench: its label, the column of the figure (ns/element/iteration: 5; whole run s: 6), the
# command's arguments after the binary's name.
bench() {
  local label=$1 column=$2 program=$3; shift 3
  local o="" n=""
  for _ in $(seq "$runs"); do
    o+="$("$(bin "$old" "$program")" "$@" | awk -v c="$column" '{print $c}') "
    n+="$("$(bin "$new" "$program")" "$@" | awk -v c="$column" '{print $c}') "
  done
  median() { tr ' ' '\n' | grep -v '^$' | sort -g | awk '{v[NR] = $1} END {print (NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2)}'; }
  printf '%-44s old %-40s median %s\n' "$label" "$o" "$(echo "$o" | median)"
  printf '%-44s new %-40s median %s\n' "" "$n" "$(echo "$n" | median)"
}

# The whole command on an example, one thread, wall clock in seconds.
command_seconds() {
  local start end
  start=$(date +%s.%N)
  "$1" run "$2" --out "$(mktemp -d)" -q --threads 1 >/dev/null 2>&1 || true
  end=$(date +%s.%N)
  awk -v a="$start" -v b="$end" 'BEGIN {printf "%.3f\n", b - a}'
}
example() {
  local label=$1 model=$2 o="" n=""
  for _ in $(seq "$runs"); do
    o+="$(command_seconds "$(bin "$old" tsmframe)" "$model") "
    n+="$(command_seconds "$(bin "$new" tsmframe)" "$model") "
  done
  median() { tr ' ' '\n' | grep -v '^$' | sort -g | awk '{v[NR] = $1} END {print (NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2)}'; }
  printf '%-44s old %-40s median %s\n' "$label" "$o" "$(echo "$o" | median)"
  printf '%-44s new %-40s median %s\n' "" "$n" "$(echo "$n" | median)"
}

echo "bench (figure)                               build runs                                     median"
bench "10^5 chains (ns/element/iteration)" 5 bench/tsmframe_scaling 100 1000
bench "10^5 chains, whole run (s)" 6 bench/tsmframe_scaling 100 1000
bench "lattice 70x70x10 (ns/element/iteration)" 5 bench/tsmframe_lattice 70 10 1e6
bench "10^4 chain to a circle, one step (s)" 6 bench/tsmframe_scaling 1 10000 1.0 1
example "beam pressed onto a beam, one thread (s)" examples/beam-pressed-onto-beam.json
