#!/usr/bin/env bash
# Side by side: `strand slice` and PrusaSlicer's CLI on the same 100k-triangle torus, 200
# layers of 0.3 mm, 0.4 mm nozzle, rectilinear infill at the scaffold's spacing (2 mm).
# Wall time, CPU time (user, all threads) and peak memory from /usr/bin/time; on a loaded
# machine compare the CPU times. PrusaSlicer is not a build dependency:
# install it for the comparison only (apt-get install prusa-slicer). Then the public mesh corpus
# side by side (slice_vs_prusaslicer.py: layers, strands per layer, deposit inside the part).
# Usage: tests/bench/slice_vs_prusaslicer.sh BUILD_DIR [WORK_DIR]
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
build="$(cd "$1" && pwd)"
work="${2:-$(mktemp -d)}"
mkdir -p "$work"
cd "$work"
"$build/tests/strand_make_sample_meshes" --torus-100k torus.stl
measure() {  # label, command...: prints wall and CPU seconds and peak MB
  local label="$1"; shift
  /usr/bin/time -f "%e %U %M" -o time.txt "$@" > "$label.log" 2>&1 || { echo "$label failed:"; tail -5 "$label.log"; return 1; }
  read -r secs user kb < time.txt
  printf "%-14s %8.2f s wall %8.2f s CPU %8.1f MB peak\n" "$label" "$secs" "$user" "$((kb / 1024))"
}
measure strand "$build/cli/strand" slice torus.stl --pattern scaffold --nozzle 0.4 --pitch 2 \
  --layer-height 0.3 --machine marlin-xyz-200 -o strand.gcode
if command -v prusa-slicer > /dev/null; then
  # Infill density 20 % with a 0.4 mm line width is about a 2 mm line spacing; no skins,
  # one perimeter, no supports: the closest PrusaSlicer comes to a single-pattern fill.
  measure prusa-slicer prusa-slicer --export-gcode torus.stl --layer-height 0.3 \
    --first-layer-height 0.3 --nozzle-diameter 0.4 --fill-pattern rectilinear --fill-density 20% \
    --perimeters 1 --top-solid-layers 0 --bottom-solid-layers 0 --skirts 0 \
    --bed-shape 0x0,200x0,200x200,0x200 --center 100,100 --output prusa.gcode
else
  echo "prusa-slicer     not installed (apt-get install prusa-slicer)"
fi
ls -l ./*.gcode | awk '{print $5, $9}'
python3 "$here/slice_vs_prusaslicer.py" "$build/cli/strand" --work "$work/corpus"
