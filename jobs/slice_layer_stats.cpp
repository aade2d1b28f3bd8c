// Strands per region and layers with material but no deposit (jobs/slice_layer_stats.h).
#include "jobs/slice_layer_stats.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "patterns/region_strands.h"

namespace strand::jobs {

namespace {

double rounded_mm(double v) { return std::round(v * 1000.0) / 1000.0; }

std::string mm_text(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.3f", v);
  return buf;
}

}  // namespace

bool has_material(const slicer::Region& region, double nozzle_mm) {
  return !slicer::offset_region(region, -nozzle_mm / 4.0).empty();
}

void SliceLayerStats::add(std::size_t k, const slicer::Region& region, const slicer::Layer& layer) {
  nlohmann::json parts = nlohmann::json::array();
  const slicer::Region parts_seen = patterns::bead_parts(region, nozzle_mm_);
  for (const patterns::RegionStrands& r : patterns::strands_per_region(parts_seen, layer.strokes)) {
    parts.push_back({{"strands", r.strands}, {"holes", r.holes}});
  }
  per_region_.push_back(std::move(parts));
  const bool deposits = std::any_of(layer.strokes.begin(), layer.strokes.end(),
                                    [](const slicer::Stroke& s) { return !s.segments.empty(); });
  if (!deposits && has_material(region, nozzle_mm_)) {
    empty_.push_back({{"layer", k}, {"z_mm", rounded_mm(layer.z_mm)}});
  }
}

void SliceLayerStats::write(nlohmann::json& derived) const {
  derived["empty_material_layers"] = empty_;
  derived["strands_per_region"] = per_region_;
}

std::vector<std::string> layer_summary_lines(const nlohmann::json& derived) {
  std::vector<std::string> out;
  if (derived.contains("empty_material_layers")) {
    const auto& empty = derived.at("empty_material_layers");
    std::string line = "  empty layers   " + std::to_string(empty.size());
    if (!empty.empty()) {
      line += " with material but no deposit: z ";
      constexpr std::size_t kNamed = 5;
      for (std::size_t i = 0; i < std::min(kNamed, empty.size()); ++i) {
        line += (i ? ", " : "") + mm_text(empty[i].at("z_mm").get<double>());
      }
      line += " mm";
      if (empty.size() > kNamed) line += " and " + std::to_string(empty.size() - kNamed) + " more";
    }
    out.push_back(line);
  }
  if (derived.contains("strands_per_region")) {
    int most = 0;
    std::vector<std::size_t> exceeded;  // layer numbers, as the G-code's ;LAYER: comments
    const auto& layers = derived.at("strands_per_region");
    for (std::size_t k = 0; k < layers.size(); ++k) {
      bool over = false;
      for (const auto& r : layers[k]) {
        const int strands = r.at("strands").get<int>();
        most = std::max(most, strands);
        over = over || strands > 1 + r.at("holes").get<int>();
      }
      if (over) exceeded.push_back(k);
    }
    std::string line = "  strands        at most " + std::to_string(most) +
                       " per region (bound: 1 + 1 per hole, exceeded in " + std::to_string(exceeded.size()) +
                       " layers";
    constexpr std::size_t kNamed = 5;
    for (std::size_t i = 0; i < std::min(kNamed, exceeded.size()); ++i) {
      line += (i ? ", " : ": ") + std::to_string(exceeded[i]);
    }
    if (exceeded.size() > kNamed) line += " and " + std::to_string(exceeded.size() - kNamed) + " more";
    out.push_back(line + ")");
  }
  return out;
}

}  // namespace strand::jobs
