// Filament fusion test (ink development, issue 32; Ribeiro et al., Biofabrication 2017): one
// meander whose filaments come closer step by step, with square fiducial marks at the
// corners, so that a photo of the print shows at which spacing neighbouring filaments fuse.
#pragma once

#include <memory>
#include <nlohmann/json.hpp>

#include "slicer/layer_source.h"
#include "slicer/params.h"

namespace strand::patterns {

struct FusionTestParams {
  double nozzle_mm = 0.6;
  double spacing_start_mm = 2.4;  // centre to centre, first pair
  double spacing_end_mm = 0.6;    // last pair (at least the nozzle)
  double spacing_step_mm = 0.3;
  double length_mm = 20.0;        // each filament
  double fiducial_mm = 3.0;
  double layer_height_mm = 0.48;
  double speed_mm_per_min = 250.0;
  int layers = 1;                 // the marks in the first
};

// Layers centred on (0, 0), each one strand: filaments along y, spacings shrinking along +x,
// U-turns alternately at the top and bottom. The record's derived keys: "test" = "fusion",
// "spacings" (index, spacing_mm, filaments_x_mm [left, right], and the measured zone along
// the mid-line between them, start_mm [x, y] to end_mm [x, y], clear of the U-turns),
// "fiducials", "nozzle_mm", "layer_height_mm".
std::unique_ptr<slicer::LayerSource> fusion_test_layers(const FusionTestParams& p);

const slicer::ParamTable& fusion_test_table();
FusionTestParams fusion_test_params_from(const nlohmann::json& values);

}  // namespace strand::patterns
