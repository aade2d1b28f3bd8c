// Chiral auxetic tensile specimens (thesis appendix "TETRA AUX" / "esachirale"): the
// parameters and generator shared by `strand tetrachiral` and `strand hexachiral`.
#pragma once

#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "patterns/wrap_fit.h"
#include "slicer/layer_source.h"
#include "slicer/params.h"
#include "slicer/toolpath.h"

namespace strand::patterns {

enum class ChiralKind { Tetra, Hexa };

struct ChiralParams {
  double nozzle_mm = 0.5;  // filament diameter d
  double cell_mm = 10.0;   // node spacing l
  int rows = 6;            // cells along y (specimen length)
  int cols = 2;            // cells along x (specimen width)
  int layers = 5;
  double layer_height_mm = 0.4;  // h, 0.8 d by default
  double core_mm = 1.87;         // hole inside the innermost pass
  int passes = 3;                // concentric passes per node visit (odd)
  double grip_mm = 0.0;          // grip tab length at each end, 0 = none
  double speed_mm_per_min = 250.0;
};

// Parameter table shared by both lattices; `default_core_mm` differs.
slicer::ParamTable chiral_table(const std::string& name, double default_core_mm, int rows,
                                int cols);
// Checked conversion from resolved values; throws InputError naming every violated rule
// (layer height, odd passes, grip, cell too small for the node).
ChiralParams chiral_params_from(ChiralKind kind, const std::string& name,
                                const nlohmann::json& values);
// Smallest cell for these parameters (mm): ligaments clear foreign nodes and each other by
// one nozzle diameter.
double chiral_min_cell_mm(ChiralKind kind, const ChiralParams& p);
// Layers centred on (0, 0), layer k at z = (k + 1) h; derived sizes and porosity.
std::unique_ptr<slicer::LayerSource> chiral_layers(ChiralKind kind, const ChiralParams& p);
slicer::Toolpath generate_chiral(ChiralKind kind, const ChiralParams& p);

// `--wrap full`: what a ring of this lattice allows round a circumference (the smallest
// valid cell; tetrachiral needs an even count, so each end row pairs into frame edges).
WrapRule chiral_wrap_rule(ChiralKind kind, const ChiralParams& p);
// The lattice as a ring periodic in x with the period of `fit` (fit.cells nodes round it at
// fit.cell_mm in both directions, p.cols ignored), `p.rows` cells along y, frame and grips
// only at the two ends; one strand per layer that runs on past the seam.
slicer::Toolpath generate_chiral_ring(ChiralKind kind, ChiralParams p, const WrapFit& fit);

}  // namespace strand::patterns
