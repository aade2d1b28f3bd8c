// A curved-substrate check's report as JSON (`strand check --json`) and as text.
#include <cmath>
#include <cstdio>
#include <string>

#include "machines/gcode_format.h"
#include "postprocess/inspect/pose_check.h"
#include "slicer/params.h"
#include "slicer/units.h"

namespace strand::post {

using machines::fmt_fixed;

namespace {

nlohmann::json findings_json(const PoseFindings& f) {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& x : f.listed) list.push_back({{"at", x.row}, {"what", x.what}});
  return {{"total", f.total}, {"listed", list}};
}

nlohmann::json joints_json(const machines::JointReport& j) {
  nlohmann::json ranges = nlohmann::json::array();
  for (int i = 0; i < j.axes; ++i) {
    ranges.push_back({{"joint", "A" + std::to_string(i + 1)},
                      {"min_deg", std::round(slicer::rad_to_deg(j.min_rad[i]) * 100) / 100},
                      {"max_deg", std::round(slicer::rad_to_deg(j.max_rad[i]) * 100) / 100}});
  }
  return {{"ranges", ranges},
          {"max_reach_mm", std::round(j.max_reach_mm * 10) / 10},
          {"unreachable", j.unreachable},
          {"first_unreachable", j.first_unreachable_what},
          {"outside_limits", j.outside_limits},
          {"first_outside", j.first_outside_what},
          {"unchecked", j.unchecked}};
}

constexpr std::size_t kTextListed = 20;

void list_text(const char* title, const char* at, const PoseFindings& f, std::string& out) {
  if (f.total == 0) return;
  out += std::string(title) + " (" + std::to_string(f.total) + "):\n";
  for (std::size_t i = 0; i < f.listed.size() && i < kTextListed; ++i) {
    out += std::string("  ") + at + " " + std::to_string(f.listed[i].row) + ": " +
           f.listed[i].what + "\n";
  }
  if (f.total > kTextListed)
    out += "  ... and " + std::to_string(f.total - kTextListed) + " more\n";
}

std::string joints_text(const machines::JointReport& j) {
  std::string out = "joints (" + std::to_string(j.poses) + " poses solved along the path): ";
  for (int i = 0; i < j.axes; ++i) {
    out += std::string(i ? ", " : "") + "A" + std::to_string(i + 1) + " " +
           fmt_fixed(slicer::rad_to_deg(j.min_rad[i]), 1) + ".." +
           fmt_fixed(slicer::rad_to_deg(j.max_rad[i]), 1);
  }
  out += " deg; wrist up to " + fmt_fixed(j.max_reach_mm, 1) + " mm from the shoulder\n";
  if (j.unreachable)
    out += "  unreachable poses: " + std::to_string(j.unreachable) + ", first row " +
           std::to_string(*j.first_unreachable) + ": " + j.first_unreachable_what + "\n";
  if (j.outside_limits)
    out += "  poses outside the joint limits: " + std::to_string(j.outside_limits) +
           ", first row " + std::to_string(*j.first_outside) + ": " + j.first_outside_what + "\n";
  if (j.unchecked)
    out += "  " + std::to_string(j.unchecked) + " poses not solved after that many problems\n";
  return out;
}

}  // namespace

nlohmann::json to_json(const PoseCheckReport& r) {
  nlohmann::json layers = nlohmann::json::array();
  for (const auto& l : r.layers) {
    nlohmann::json crossings = nlohmann::json::array();
    for (const auto& c : l.crossings)
      crossings.push_back(
          {{"u_mm", c.at_mm.x()}, {"v_mm", c.at_mm.y()}, {"a", c.move_a}, {"b", c.move_b}});
    layers.push_back({{"layer", l.layer},
                      {r.on_mesh ? "offset_mm" : "radius_mm", std::round(l.radius_mm * 1e4) / 1e4},
                      {"strands", l.strands},
                      {"crossings", crossings},
                      {"touches", l.touches.size()}});
  }
  nlohmann::json j = {{"ok", r.ok()},
                      {"kind", r.kind},
                      {"machine", r.machine},
                      {"rows", r.rows},
                      {"layers", layers},
                      {"crossings", r.crossing_count()},
                      {"off_tip", findings_json(r.off_tip)},
                      {"normals", findings_json(r.normals)},
                      {"off_surface", findings_json(r.off_surface)},
                      {"speed", findings_json(r.speed)},
                      {"outside", findings_json(r.outside)},
                      {"numbering", findings_json(r.numbering)},
                      {"quaternions", findings_json(r.quaternions)},
                      {"extrusion", findings_json(r.extrusion)},
                      {"parse_issues", findings_json(r.parse)}};
  if (r.joints_checked) j["joints"] = joints_json(r.joints);
  if (r.transit_checked) j["transit"] = machines::transit_json(r.transit);
  if (!r.program_speeds.empty()) j["contact_speed"] = program_speeds_json(r.program_speeds);
  if (r.on_mesh) j["substrate"] = r.substrate_note;
  return j;
}

std::string to_text(const PoseCheckReport& r) {
  const bool csv = r.kind.rfind("pose CSV", 0) == 0;
  const char* at = csv ? "row" : "line";
  std::string out = r.kind + ": " + std::to_string(r.layers.size()) + " layers, " +
                    std::to_string(r.rows) + (csv ? " poses" : " moves") +
                    (r.machine.empty() ? "" : ", machine " + r.machine) + "\n";
  if (!r.substrate_note.empty()) out += r.substrate_note + "\n";
  out += r.on_mesh ? "layer  offset_mm  strands  crossings  touches   (crossings judged in the "
                     "mesh's (u, v))\n"
                   : "layer  radius_mm  strands  crossings  touches   (crossings judged in (u, v) "
                     "around the cylinder)\n";
  for (const auto& l : r.layers) {
    char row[160];
    std::snprintf(row, sizeof row, "%-6d %9s  %7d  %9zu  %7zu\n", l.layer,
                  fmt_fixed(l.radius_mm, 3).c_str(), l.strands, l.crossings.size(),
                  l.touches.size());
    out += row;
  }
  for (const auto& l : r.layers) {
    for (std::size_t i = 0; i < l.crossings.size() && i < kTextListed; ++i) {
      const auto& c = l.crossings[i];
      out += "  crossing in layer " + std::to_string(l.layer) + " at u " +
             fmt_fixed(c.at_mm.x(), 3) + ", v " + fmt_fixed(c.at_mm.y(), 3) + " mm: " + at + "s " +
             std::to_string(c.move_a) + " and " + std::to_string(c.move_b) + "\n";
    }
  }
  list_text("poses off the nozzle tip", at, r.off_tip, out);
  list_text("normals not facing the nozzle", at, r.normals, out);
  list_text("deposits off their layer's offset surface", at, r.off_surface, out);
  list_text("speed deviations", at, r.speed, out);
  list_text("moves outside the machine's envelope", at, r.outside, out);
  list_text("numbering (indices, layers, laps and their turn direction)", at, r.numbering, out);
  list_text("quaternions that are not unit", at, r.quaternions, out);
  list_text("deposits the file contradicts (extrude flag, feature, ink per mm)", at, r.extrusion,
            out);
  list_text("problems in the file", at, r.parse, out);
  if (r.joints_checked) out += joints_text(r.joints);
  if (r.transit_checked) out += "outside laps: " + machines::transit_text(r.transit) + "\n";
  out += program_speeds_text(r.program_speeds);
  out += r.ok() ? "check: OK\n" : "check: FAILED\n";
  return out;
}

}  // namespace strand::post
