#!/usr/bin/env bash
# The main job: set up, then run every model in examples/ into out/<name>/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh

mkdir -p out
status=0
: > out/summary.txt
for model in examples/*.json; do
  name=$(basename "$model" .json)
  set +e
  build/tsmframe run "$model" --out "out/$name" 2>"out/$name.log"
  code=$?
  set -e
  printf '%-28s exit %d  %s\n' "$name" "$code" "$(tail -n 1 "out/$name.log")" | tee -a out/summary.txt
  [ $code -eq 0 ] || status=1
done
echo "results: out/<example>/results.json and steps.csv; progress logs: out/<example>.log; this table: out/summary.txt"
exit $status
