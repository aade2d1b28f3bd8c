// What `strand slice` prints after the part's size, shared by every front end.
#include <algorithm>
#include <cstdio>

#include "jobs/slice_job.h"
#include "jobs/slice_layer_stats.h"

namespace strand::jobs {

std::string slice_summary_text(const SliceResult& r, const SliceSettings& s) {
  std::string out = r.produced.summary;
  const auto& d = r.toolpath.derived;
  if (d.contains("pattern_strands_per_layer")) {
    int most = 0;
    for (const auto& n : d.at("pattern_strands_per_layer")) most = std::max(most, n.get<int>());
    out += "  pattern        " + s.pattern + ": at most " + std::to_string(most) + " pattern strand(s) per layer, " +
           std::to_string(s.perimeters) + " perimeter(s)\n";
  }
  if (d.contains("objects")) {  // a slice by objects: each object's printhead
    std::string list;
    for (const auto& o : d.at("objects"))
      list += (list.empty() ? "" : ", ") + o.at("name").get<std::string>() + " in T" + std::to_string(o.at("tool").get<int>());
    out += "  objects        " + list + "\n";
  }
  if (d.contains("thin_beads") && d.at("thin_beads").at("count").get<int>() > 0) {
    char line[96];
    std::snprintf(line, sizeof line, "%d centre line(s), %.3f mm", d.at("thin_beads").at("count").get<int>(),
                  d.at("thin_beads").at("length_mm").get<double>());
    out += std::string("  thin beads     ") + line + "\n";
  }
  for (const std::string& line : layer_summary_lines(d)) out += line + "\n";
  if (d.contains("substrate")) {
    const auto& sub = d.at("substrate");
    char line[256];
    std::snprintf(line, sizeof line, "%s, 3D/uv area ratio %.3f to %.3f, conformal stretch up to %.3f",
                  sub.at("uv_source").get<std::string>().c_str(), sub.at("area_ratio_3d_to_uv")[0].get<double>(),
                  sub.at("area_ratio_3d_to_uv")[1].get<double>(), sub.at("conformal_stretch_max").get<double>());
    out += "  substrate      " + s.onto + ": " + line + "\n";
  }
  for (const auto& c : r.part.changes) out += "  repaired       " + c + "\n";
  if (r.scale != 1.0) {
    char line[64];
    std::snprintf(line, sizeof line, "%.6g", r.scale);
    out += std::string("  scale          ") + line + "\n";
  }
  for (const auto& n : r.notes) {
    const bool skip = n.rfind("skipped", 0) == 0;
    out += (skip ? "  skipped        " + n.substr(8) : "  note           " + n) + "\n";
  }
  return out;
}

}  // namespace strand::jobs
