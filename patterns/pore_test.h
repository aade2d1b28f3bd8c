// Pore test (ink development, issue 32): an N x N grid of square pores, a log-pile of 0/90
// layers, with square fiducial marks at the corners, so that a photo of the print gives each
// pore's Pr = L^2 / (16 A) (Ouyang et al. 2016: 1 for a square pore, pi/4 for a round one).
#pragma once

#include <memory>
#include <nlohmann/json.hpp>

#include "slicer/layer_source.h"
#include "slicer/params.h"

namespace strand::patterns {

struct PoreTestParams {
  double nozzle_mm = 0.6;
  int pores = 4;                 // per side
  double pore_size_mm = 1.8;     // open side of a pore, between nozzle-wide filaments
  double fiducial_mm = 3.0;      // side of the square marks
  double layer_height_mm = 0.48;
  double speed_mm_per_min = 250.0;
  int layers = 2;                // 0/90 alternately; the marks in the first
};

// Layers centred on (0, 0), each one serpentine strand: filaments along x in even layers,
// along y in odd ones, turning half a pitch outside the grid. The record's derived keys:
// "test" = "pore", "pores" (index row by row from -y, -x; centre_mm [x, y], side_mm
// intended), "fiducials" (x_mm, y_mm, size_mm), "pitch_mm", "nozzle_mm", "layer_height_mm".
std::unique_ptr<slicer::LayerSource> pore_test_layers(const PoreTestParams& p);

const slicer::ParamTable& pore_test_table();
PoreTestParams pore_test_params_from(const nlohmann::json& values);

}  // namespace strand::patterns
