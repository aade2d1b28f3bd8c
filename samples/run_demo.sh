#!/usr/bin/env bash
# The main demo: runs every job file in samples/ into OUT (G-code, JSON report, summary),
# draws previews of each job's G-code, and runs every sweep in samples/sweeps/ into
# OUT/<sweep name>/ (G-code per point, manifest, index.html contact sheet). Jobs on a curved
# substrate write what their machine takes (the job's "output" extension: a robot cell's pose
# CSV with its .java, .src, .dat and .extruder.gcode, or a rotary printer's 4-axis G-code),
# checked on their cylinder; a robot-held mesh's job (tetrachiral-sphere-cap-robot.json) also
# writes the record of its mesh beside the CSV, which its check and preview read.
# Usage: samples/run_demo.sh path/to/strand OUT
set -euo pipefail
strand="$(cd "$(dirname "$1")" && pwd)/$(basename "$1")"
samples="$(cd "$(dirname "$0")" && pwd)"
out="$2"
mkdir -p "$out"
cd "$out"
# Inputs are named relative to OUT so the file headers and reports carry no path of this
# machine (the same checkout anywhere gives byte-identical files).
samples="$(realpath --relative-to=. "$samples")"
for job in "$samples"/*.json; do
  name="$(basename "$job" .json)"
  machine="$(sed -n 's/.*"machine": *"\([^"]*\)".*/\1/p' "$job")"
  if grep -q '"substrate"' "$job"; then
    output="$(sed -n 's/.*"output": *"\([^"]*\)".*/\1/p' "$job")"
    ext="${output##*.}"
    "$strand" job "$job" -o "$name.$ext" --report "$name.json" | tee "$name-summary.txt"
    # Crossings in (u, v) around the cylinder (or on the mesh's map), poses against the nozzle,
    # contact points on the offset surfaces, reach and joints.
    "$strand" check "$name.$ext" --machine "$machine" > "$name-check.txt"
    tail -n 1 "$name-check.txt"
    # Drawn on the workpiece: the cylinder's axis along x, its u = 0 line on top (a mesh:
    # its outside up, translucent under the poses).
    for view in png html glb; do "$strand" preview "$name.$ext" -o "$name-preview.$view"; done
    continue
  fi
  "$strand" job "$job" -o "$name.gcode" --report "$name.json" | tee "$name-summary.txt"
  # Check the specimen against its machine (crossings, strands, volume) and draw layer 1 (the
  # one layer of a single-layer print test: layer 0).
  layer=1
  if [[ "$(grep -c '^;LAYER_CHANGE' "$name.gcode")" -lt 2 ]]; then layer=0; fi
  "$strand" check "$name.gcode" --machine "$machine" --svg-layer "$layer" "$name-layer$layer.svg" > "$name-check.txt"
  tail -n 1 "$name-check.txt"
  for ext in png svg html glb; do "$strand" preview "$name.gcode" -o "$name-preview.$ext"; done
done
"$strand" plot "$samples/plot/shapes.svg" --machine xy-plotter-servo --fit 380x260 -o plot-shapes.gcode --report plot-shapes.json | tee plot-shapes-summary.txt
"$strand" check plot-shapes.gcode --machine xy-plotter-servo | tail -n 1
for ext in png html; do "$strand" preview plot-shapes.gcode -o "plot-shapes-preview.$ext"; done
# Issue 14: lettering with filled shapes, a grey photo traced into two pen layers, a label.
"$strand" plot "$samples/plot/lettering.svg" --machine xy-plotter-servo --hatch-spacing 0.8 -o plot-lettering.gcode --report plot-lettering.json | tee plot-lettering-summary.txt
"$strand" plot "$samples/plot/photo.png" --trace --levels 2 --hatch-spacing 1.2 --fit 240x160 --machine xy-plotter-servo -o plot-photo.gcode --report plot-photo.json | tee plot-photo-summary.txt
"$strand" trace "$samples/plot/photo.png" --levels 2 -o photo-traced.svg
"$strand" text "scaffold d=0.84 gap=1.6\nplate 3" --size 6 -o label.svg
for plot in plot-lettering plot-photo; do
  "$strand" check "$plot.gcode" --machine xy-plotter-servo | tail -n 1
  for ext in png html; do "$strand" preview "$plot.gcode" -o "$plot-preview.$ext"; done
done
# Meshes (samples/meshes/): a bone plug filled with the scaffold and with the tetrachiral
# lattice, a torus and Keenan Crane's spot with the scaffold, and a scaffold specimen laid on a curved plate
# (3-axis, nozzle vertical); every file checked against its machine and drawn with its mesh
# under it (PNG, and HTML with a 3D orbit view).
slice() {  # name machine strand-slice-arguments...
  local name="$1" machine="$2"; shift 2
  "$strand" slice "$@" --machine "$machine" -o "$name.gcode" --report "$name.json" \
    --preview "$name-preview.png" --preview "$name-preview.html" | tee "$name-summary.txt"
  "$strand" check "$name.gcode" --machine "$machine" > "$name-check.txt"
  tail -n 1 "$name-check.txt"
}
slice bone-plug-scaffold deltawasp-2040-clay "$samples/meshes/bone-plug.stl" --pattern scaffold \
  --nozzle 0.6 --gap 1 --perimeters 1
slice bone-plug-tetrachiral deltawasp-2040-clay "$samples/meshes/bone-plug.stl" --pattern tetrachiral \
  --nozzle 0.4 --cell 5 --node-core 1
slice torus-scaffold deltawasp-2040-clay "$samples/meshes/torus.stl" --pattern scaffold --nozzle 0.84 --gap 1.6
# A real public mesh: Keenan Crane's spot (CC0), +Y up and 1.5 units long, scaled to 30 mm.
slice spot-scaffold deltawasp-2040-clay "$samples/meshes/spot.obj" --up y --scale-to-fit 30x30x30 \
  --pattern scaffold --nozzle 0.6 --gap 1 --perimeters 1
slice curved-plate-scaffold marlin-xyz-200 --onto "$samples/meshes/curved-plate.obj" --pattern scaffold \
  --nozzle 0.6 --gap 1 --size 40x24 --layers 2
for sweep in "$samples"/sweeps/*.json; do
  [ -e "$sweep" ] || continue
  "$strand" sweep "$sweep" -o "$(basename "$sweep" .json)"
done
echo "demo output in $(pwd); sweeps: $(pwd)/*/index.html"
