#!/usr/bin/env bash
# The main demo: runs every job file in samples/ into OUT (G-code, JSON report, summary),
# draws previews of each job's G-code, and runs every sweep in samples/sweeps/ into
# OUT/<sweep name>/ (G-code per point, manifest, index.html contact sheet).
# Usage: samples/run_demo.sh path/to/strand OUT
set -euo pipefail
strand="$(cd "$(dirname "$1")" && pwd)/$(basename "$1")"
samples="$(cd "$(dirname "$0")" && pwd)"
out="$2"
mkdir -p "$out"
cd "$out"
for job in "$samples"/*.json; do
  name="$(basename "$job" .json)"
  "$strand" job "$job" -o "$name.gcode" --report "$name.json" | tee "$name-summary.txt"
  for ext in png svg html glb; do "$strand" preview "$name.gcode" -o "$name-preview.$ext"; done
done
for sweep in "$samples"/sweeps/*.json; do
  [ -e "$sweep" ] || continue
  "$strand" sweep "$sweep" -o "$(basename "$sweep" .json)"
done
echo "demo output in $(pwd); sweeps: $(pwd)/*/index.html"
