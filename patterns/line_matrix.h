// Line-width matrix (ink development, issue 32): straight lines in a grid of speeds x flows,
// printed in one layer with square fiducial marks at the corners, so that a photo of the
// print can be rectified and every line's width measured (postprocess/measure/).
#pragma once

#include <memory>
#include <nlohmann/json.hpp>
#include <vector>

#include "slicer/layer_source.h"
#include "slicer/params.h"
#include "slicer/toolpath.h"

namespace strand::patterns {

struct LineMatrixParams {
  double nozzle_mm = 0.6;
  std::vector<double> speeds_mm_per_min = {200, 300, 450, 600};
  // Ink flow relative to the nozzle-wide bead: the planned bead section is flow x the section
  // of a nozzle-wide bead, so E-driven machines push flow x the usual volume.
  std::vector<double> flows = {0.8, 1.0, 1.25, 1.5};
  double length_mm = 20.0;      // each line
  double spacing_mm = 3.0;      // centre to centre, between rows and between columns' ends
  double fiducial_mm = 3.0;     // side of the square marks
  double layer_height_mm = 0.48;
  double speed_mm_per_min = 250.0;  // the marks' speed
  int layers = 1;
};

// One layer centred on (0, 0): columns of speeds along x, rows of flows along y, printed row
// by row, then the four marks. The record's derived keys: "lines" (index = print order,
// speed_mm_min, flow, start_mm, end_mm, width_mm), "fiducials" (x_mm, y_mm, size_mm, in the
// part frame: the photo is measured against these), "nozzle_mm" and, per stroke in print
// order, the planner's "stroke_speeds_mm_per_min", "stroke_flows" (a pneumatic machine sets
// its pressure where the flow changes) and "stroke_labels" (a G-code comment each).
std::unique_ptr<slicer::LayerSource> line_matrix_layers(const LineMatrixParams& p);

const slicer::ParamTable& line_matrix_table();
LineMatrixParams line_matrix_params_from(const nlohmann::json& values);

// Bead width whose section (slicer::bead_area_mm2) is `flow` x that of a `nozzle_mm` bead.
double width_for_flow(double nozzle_mm, double layer_height_mm, double flow);

}  // namespace strand::patterns
