#!/usr/bin/env bash
# `make run`'s demo (samples/run_demo.sh) into a fresh folder: it must finish, every sample job
# must leave a summary and a check ending "check: OK", and every flat job a layer drawing (a
# single-layer print test once stopped the demo: --svg-layer 1 of a one-layer file).
# Usage: tests/run_demo_test.sh STRAND OUT
set -euo pipefail
strand="$1"
out="$2"
src="$(cd "$(dirname "$0")/.." && pwd)"
rm -rf "$out"
"$src/samples/run_demo.sh" "$strand" "$out" > "$out.log" 2>&1 || { tail -n 20 "$out.log"; exit 1; }
failed=0
for job in "$src"/samples/*.json; do
  name="$(basename "$job" .json)"
  for f in "$name-summary.txt" "$name-check.txt"; do
    [[ -s "$out/$f" ]] || { echo "$name: no $f"; failed=1; }
  done
  [[ "$(tail -n 1 "$out/$name-check.txt" 2>/dev/null)" == "check: OK" ]] || { echo "$name: check not OK"; failed=1; }
  if ! grep -q '"substrate"' "$job" && ! compgen -G "$out/$name-layer[01].svg" > /dev/null; then
    echo "$name: no layer drawing"; failed=1
  fi
done
exit $failed
