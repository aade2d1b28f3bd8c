#!/usr/bin/env bash
# The main demo: runs every job file in samples/ into OUT (G-code, JSON report, summary).
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
  # Check the specimen against its machine (crossings, strands, volume) and draw layer 1.
  machine="$(sed -n 's/.*"machine": *"\([^"]*\)".*/\1/p' "$job")"
  "$strand" check "$name.gcode" --machine "$machine" --svg-layer 1 "$name-layer1.svg" > "$name-check.txt"
  tail -n 1 "$name-check.txt"
done
"$strand" plot "$samples/plot/shapes.svg" --machine xy-plotter-servo --fit 380x260 -o plot-shapes.gcode --report plot-shapes.json | tee plot-shapes-summary.txt
echo "demo output in $(pwd)"
