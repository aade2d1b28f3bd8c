// Re-entrant (bow-tie) honeycomb in the part plane: cells with vertical side ribs and
// inclined top and bottom ribs that point into the cell at the re-entrant angle. Printed as
// one open strand per layer: the lattice is cut into vertical bands between neighbouring
// rib lines, each band is a wavy path (vertical rib, inclined rib, vertical rib, ...), and
// neighbouring bands meet at the free tips of the top and bottom rows, so they join into a
// serpentine. Interior vertical ribs are laid twice, side by side by one nozzle width (one
// pass per band), so nothing crosses; they come out about 2 d wide.
#pragma once

#include <memory>
#include <nlohmann/json.hpp>

#include "slicer/layer_source.h"
#include "slicer/params.h"
#include "slicer/toolpath.h"

namespace strand::patterns {

struct ReentrantParams {
  double nozzle_mm = 0.84;          // filament diameter d
  double cell_width_mm = 8.0;       // W: distance between a cell's vertical ribs
  double cell_height_mm = 8.0;      // H: vertical rib length (a cell's side height)
  double angle_deg = 20.0;          // theta: inclined ribs dip this far below horizontal
  int rows = 4;                     // rows of cells, even (so the bands join)
  int cols = 4;                     // full cells per odd row; even rows end in half cells
  int layers = 4;
  double layer_height_mm = 0.672;   // 0.8 d by default
  double speed_mm_per_min = 250.0;
};

// Sizes derived from the parameters, computed in one place. Rib lines (vertical) sit at
// x_j = j * W / 2, j = 0..2 cols; row r has vertical ribs on lines with j + r odd, row pitch
// H - delta where delta = (W / 2) tan(theta) is the depth of the re-entrant tip.
struct ReentrantGeometry {
  double tip_depth_mm = 0.0;        // delta
  double row_pitch_mm = 0.0;        // H - delta
  int bands = 0;                    // 2 cols
  double width_mm = 0.0;            // outer size: cols * W + d
  // Row 0's vertical ribs all sit on interior lines, so their lower ends are clipped and
  // rise by (d / 2) tan(theta); the top row reaches its nominal height on the outer lines.
  double bottom_lift_mm = 0.0;
  double depth_mm = 0.0;            // (rows - 1) * row pitch + H - bottom lift + d
  double height_mm = 0.0;
  double inclined_rib_mm = 0.0;     // nominal inclined rib, line to line: (W / 2) / cos(theta)
  // Centre-line clearances that must stay >= d: between the tips inside a cell (vertical)
  // and between a band's vertical ribs in consecutive rows (horizontal), mm.
  double tip_gap_mm = 0.0;
  double band_gap_mm = 0.0;
};

ReentrantGeometry reentrant_geometry(const ReentrantParams& p);
// Layers centred on (0, 0); layer k at z = (k + 1) * layer height. Odd layers run the
// serpentine backwards, so each layer starts where the previous one ended.
std::unique_ptr<slicer::LayerSource> reentrant_layers(const ReentrantParams& p);
slicer::Toolpath generate_reentrant(const ReentrantParams& p);
// `--wrap full` round a circumference `period_mm` (x, periodic): a whole number of cells
// round it (at least 2; the cell width adjusted to fit between 4 nozzles and the width at
// which the tips would close, cell height and angle kept), cols ignored. Every rib line is
// interior, so every vertical rib is laid twice side by side; one closed strand per layer,
// odd layers reversed.
slicer::Toolpath generate_reentrant_wrapped(const ReentrantParams& p, double period_mm);

const slicer::ParamTable& reentrant_table();
ReentrantParams reentrant_params_from(const nlohmann::json& values);

}  // namespace strand::patterns
