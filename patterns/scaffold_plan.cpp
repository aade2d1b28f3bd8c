// Per-layer plans of a log-pile scaffold.
#include "patterns/scaffold_plan.h"

#include <cmath>
#include <map>

#include "slicer/units.h"

namespace strand::patterns {

namespace {

// A direction as a key: the angle mod 180 in micro-degrees.
long long direction_key(double angle_deg) {
  const double a = std::fmod(std::fmod(angle_deg, 180.0) + 180.0, 180.0);
  const long long key = std::llround(a * 1e6);
  return key == 180'000'000 ? 0 : key;
}

const ScheduleEntry* entry_for(const ScaffoldParams& p, int layer) {
  for (const auto& e : p.schedule) {
    if (layer >= e.first && layer <= e.last) return &e;
  }
  return nullptr;
}

}  // namespace

double flow_width_mm(double nozzle_mm, double layer_height_mm, double flow) {
  if (flow == 1.0) return nozzle_mm;
  const double h = layer_height_mm;
  return flow * slicer::bead_area_mm2(nozzle_mm, h) / h + h - slicer::kPi * h / 4;
}

std::vector<LayerPlan> scaffold_layer_plans(const ScaffoldParams& p) {
  std::vector<LayerPlan> plans;
  std::map<long long, int> laid;  // layers so far per direction
  const int layers = std::max(p.layers, 0);
  for (int k = 0; k < layers; ++k) {
    LayerPlan l;
    l.angle_deg = p.angles_deg[static_cast<std::size_t>(k) % p.angles_deg.size()];
    l.pitch_mm = p.pitch_mm;
    if (p.grade.axis == GradeAxis::Z) l.pitch_mm = p.nozzle_mm + p.grade.at(static_cast<double>(k) / layers);
    l.speed_mm_per_min = p.speed_mm_per_min;
    if (const ScheduleEntry* e = entry_for(p, k)) {
      l.angle_deg = e->angle_deg.value_or(l.angle_deg);
      if (e->gap_mm) l.pitch_mm = p.nozzle_mm + *e->gap_mm;
      l.speed_mm_per_min = e->speed_mm_per_min.value_or(l.speed_mm_per_min);
      l.flow = e->flow.value_or(l.flow);
    }
    l.width_mm = flow_width_mm(p.nozzle_mm, p.layer_height_mm, l.flow);
    l.staggered = p.stagger && laid[direction_key(l.angle_deg)]++ % 2 == 1;
    plans.push_back(l);
  }
  return plans;
}

}  // namespace strand::patterns
