// Filament collapse test (ink development, issue 32; Ribeiro et al., Biofabrication 2017):
// solid pillars printed layer by layer with growing gaps between them, and one filament laid
// across their tops in the last layer, so that a photo shows how far the filament sags in each
// gap. Square fiducial marks at the corners of the first layer.
#pragma once

#include <memory>
#include <nlohmann/json.hpp>
#include <vector>

#include "slicer/layer_source.h"
#include "slicer/params.h"

namespace strand::patterns {

struct CollapseTestParams {
  double nozzle_mm = 0.6;
  std::vector<double> gaps_mm = {1, 2, 4, 8, 16};  // between neighbouring pillars, along x
  double pillar_mm = 3.0;         // side of each square pillar
  double fiducial_mm = 3.0;
  double layer_height_mm = 0.48;
  double speed_mm_per_min = 250.0;
  int layers = 6;                 // all but the last are pillars; the last is the filament
};

// Layers centred on (0, 0): per pillar layer one serpentine stroke per pillar (0/90
// alternately), then the filament along y = 0 over every pillar. The record's derived keys:
// "test" = "collapse", "gaps" (index, gap_mm, the span start_mm [x, 0] to end_mm [x, 0]
// between the pillars' faces), "pillar_mm" (their side), "filament_z_mm", "pillar_height_mm",
// "fiducials", "nozzle_mm", "layer_height_mm".
std::unique_ptr<slicer::LayerSource> collapse_test_layers(const CollapseTestParams& p);

const slicer::ParamTable& collapse_test_table();
CollapseTestParams collapse_test_params_from(const nlohmann::json& values);

}  // namespace strand::patterns
