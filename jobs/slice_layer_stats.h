// What the slice job measures on each filled layer, in layer order: the strands in each
// connected region of the section against the bound a region allows (one, plus one per hole),
// and layers where the part has material but nothing is deposited.
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "slicer/region.h"
#include "slicer/toolpath.h"

namespace strand::jobs {

// Whether a layer has material a bead is meant for: some part of the region at least half a
// bead wide (narrower slivers are left out, as the thin-feature rule says).
bool has_material(const slicer::Region& region, double nozzle_mm);

// The sums over the layers, fed in order; derived keys and summary lines at the end.
class SliceLayerStats {
 public:
  explicit SliceLayerStats(double nozzle_mm) : nozzle_mm_(nozzle_mm) {}
  void add(std::size_t k, const slicer::Region& region, const slicer::Layer& layer);
  // derived.empty_material_layers [{"layer", "z_mm"}], derived.strands_per_region
  // [[{"strands", "holes"}, ...] per layer].
  void write(nlohmann::json& derived) const;

 private:
  double nozzle_mm_;
  nlohmann::json empty_ = nlohmann::json::array();
  nlohmann::json per_region_ = nlohmann::json::array();
};

// The summary lines of a sliced part's derived keys: "  empty layers   0" or "  empty layers
// 2 with material but no deposit: z 3.120, 7.440 mm" (five named, then "and N more"), and
// "  strands        at most N per region (bound: 1 + 1 per hole, exceeded in K layers)".
std::vector<std::string> layer_summary_lines(const nlohmann::json& derived);

}  // namespace strand::jobs
