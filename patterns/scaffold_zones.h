// Porosity per zone of a graded or scheduled log-pile (patterns/scaffold.h): zones along the
// grade's axis (or its layers for z), and the layer range of each schedule entry.
#pragma once

#include <nlohmann/json.hpp>
#include <vector>

#include "patterns/scaffold.h"
#include "slicer/geometry.h"

namespace strand::patterns {

// The straight lines one layer lays, c*n + s*u for c in offsets, and its bead section.
struct LaidLayer {
  slicer::Vec2 u, n;
  std::vector<double> offsets;
  double bead_area_mm2 = 0.0;
  double bead_width_mm = 0.0;
  double inside_volume_mm3 = 0.0;  // deposited inside the footprint
};

// "porosity_zones": for a grade along x or y, 1 - (bead volume inside the zone's slab of the
// footprint) / (slab volume) per zone, a bead cut by a slab's side split by its width (in 16
// strips; for lines across or along the axis the zones add up to the whole) (GapGrade::zone_count equal parts of the graded length,
// the last one to the footprint's edge); along z, the same over the layers whose bottom lies in
// the zone. Each with from_mm, to_mm, the gap at both ends and the porosity. Empty: no grade.
nlohmann::json grade_zones(const ScaffoldParams& p, const ScaffoldGeometry& g,
                           const std::vector<LaidLayer>& layers);
// "porosity_by_schedule": the porosity of each schedule entry's layers.
nlohmann::json schedule_zones(const ScaffoldParams& p, const ScaffoldGeometry& g,
                              const std::vector<LaidLayer>& layers);

}  // namespace strand::patterns
