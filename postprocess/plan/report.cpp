// Report assembly from the toolpath record, the machine and the estimates.
#include "postprocess/plan/report.h"

#include <cmath>
#include <sstream>

#include "machines/gcode_format.h"
#include "slicer/params.h"
#include "slicer/units.h"

namespace strand::post {

double round_to(double v, int decimals) {
  const double s = std::pow(10.0, decimals);
  return std::round(v * s) / s;
}

std::string clock_text(double s) {
  const long total = std::lround(s);
  std::ostringstream o;
  o << total / 3600 << "h " << (total / 60) % 60 << "m " << total % 60 << "s";
  return o.str();
}

nlohmann::json make_report(const slicer::Toolpath& t, const machines::MachineProfile& m,
                           const Estimate& e, const std::string& gcode_path) {
  nlohmann::json layers = nlohmann::json::array();
  nlohmann::json strands = nlohmann::json::array();
  for (const auto& l : e.layers) {
    layers.push_back({{"layer", l.layer},
                      {"z_mm", round_to(l.z_mm, 4)},
                      {"strands", l.strands},
                      {"deposit_length_mm", round_to(l.deposit_length_mm, 3)},
                      {"volume_mm3", round_to(l.volume_mm3, 3)},
                      {"volume_ml", round_to(slicer::mm3_to_ml(l.volume_mm3), 5)},
                      {"syringe_fills", round_to(slicer::mm3_to_ml(l.volume_mm3) / m.deposition.reservoir_ml, 5)},
                      {"time_naive_s", round_to(l.time_naive_s, 2)},
                      {"time_trapezoid_s", round_to(l.time_trapezoid_s, 2)}});
    strands.push_back(l.strands);
  }
  nlohmann::json report = {
      {"generator", t.generator},
      {"parameters", t.parameters},
      {"derived", t.derived},
      {"machine", {{"name", m.name},
                   {"firmware", machines::to_string(m.firmware)},
                   {"deposition", machines::to_string(m.deposition.model)},
                   {"arcs", m.arcs}}},
      {"output", gcode_path},
      {"totals", {{"layers", e.layers.size()},
                  {"deposit_length_mm", round_to(e.deposit_length_mm, 3)},
                  {"travel_length_mm", round_to(e.travel_length_mm, 3)},
                  {"ink_volume_mm3", round_to(e.volume_mm3, 3)},
                  {"ink_volume_ml", round_to(slicer::mm3_to_ml(e.volume_mm3), 4)},
                  {"reservoir_ml", m.deposition.reservoir_ml},
                  {"syringe_fills", round_to(slicer::mm3_to_ml(e.volume_mm3) / m.deposition.reservoir_ml, 3)},
                  {"syringe_loads", static_cast<int>(std::ceil(slicer::mm3_to_ml(e.volume_mm3) / m.deposition.reservoir_ml - 1e-9))},
                  {"time_naive_s", round_to(e.time_naive_s, 1)},
                  {"time_trapezoid_s", round_to(e.time_trapezoid_s, 1)}}},
      {"strands_per_layer", std::move(strands)},  // moved: a tall job has thousands of layers
      {"layers", std::move(layers)},
  };
  // Several printheads (issue 33): each one's ink and length, and the changes.
  if (!m.tools.empty() || e.tools.size() > 1) {
    nlohmann::json tools = nlohmann::json::array();
    for (const auto& te : e.tools) {
      const auto k = static_cast<std::size_t>(te.tool);
      tools.push_back({{"tool", te.tool},
                       {"name", k < m.tools.size() ? m.tools[k].name : "tool " + std::to_string(te.tool)},
                       {"strands", te.strands},
                       {"deposit_length_mm", round_to(te.deposit_length_mm, 3)},
                       {"ink_volume_mm3", round_to(te.volume_mm3, 3)},
                       {"ink_volume_ml", round_to(slicer::mm3_to_ml(te.volume_mm3), 4)},
                       {"time_deposit_s", round_to(te.time_naive_s, 1)}});
    }
    report["totals"]["tools"] = std::move(tools);
    report["totals"]["tool_changes"] = e.tool_changes;
  }
  return report;
}

std::string summary_text(const nlohmann::json& r) {
  std::ostringstream o;
  const auto& d = r.at("derived");
  const auto& tot = r.at("totals");
  o << r.at("generator").get<std::string>() << " -> " << r.at("output").get<std::string>() << " ("
    << r.at("machine").at("name").get<std::string>() << ")\n";
  if (d.contains("footprint_mm")) {
    o << "  footprint      " << machines::fmt_xyz(d["footprint_mm"][0].get<double>()) << " x "
      << machines::fmt_xyz(d["footprint_mm"][1].get<double>()) << " mm, height "
      << machines::fmt_xyz(d.value("height_mm", 0.0)) << " mm\n";
  }
  if (d.contains("size_mm")) {
    o << "  size           " << machines::fmt_xyz(d["size_mm"][0].get<double>()) << " x "
      << machines::fmt_xyz(d["size_mm"][1].get<double>()) << " x " << machines::fmt_xyz(d["size_mm"][2].get<double>())
      << " mm\n";
  }
  if (d.contains("node_radius_mm")) {
    o << "  nodes          r " << machines::fmt_xyz(d["node_radius_mm"].get<double>()) << " mm, ring "
      << machines::fmt_xyz(d["node_ring_thickness_mm"].get<double>()) << " mm vs ligament "
      << machines::fmt_xyz(d["ligament_thickness_mm"].get<double>()) << " mm\n";
  }
  if (d.contains("filaments_per_layer")) o << "  filaments      " << d["filaments_per_layer"].dump() << " per layer (cycle)\n";
  std::size_t max_strands = 0;
  for (const auto& s : r.at("strands_per_layer")) max_strands = std::max(max_strands, s.get<std::size_t>());
  o << "  layers         " << tot.at("layers").get<int>() << ", at most " << max_strands << " strand(s) per layer\n";
  if (d.contains("porosity")) {
    o << "  porosity       " << machines::fmt_fixed(100.0 * d["porosity"].get<double>(), 1) << " %";
    if (d.contains("porosity_thesis")) o << " (thesis formula " << machines::fmt_fixed(100.0 * d["porosity_thesis"].get<double>(), 1) << " %)";
    o << "\n";
  }
  // Graded or scheduled scaffolds: porosity per zone, "x 0-7.5 mm 61.2 %" or "layers 0-4 58.0 %".
  for (const char* key : {"porosity_zones", "porosity_by_schedule"}) {
    if (!d.contains(key)) continue;
    o << (std::string(key) == "porosity_zones" ? "  zones         " : "  scheduled     ");
    for (const auto& z : d[key]) {
      if (z.contains("axis")) {
        o << " " << z["axis"].get<std::string>() << " " << slicer::short_number(std::round(z["from_mm"].get<double>() * 100) / 100)
          << "-" << slicer::short_number(std::round(z["to_mm"].get<double>() * 100) / 100) << " mm";
      } else {
        o << " layers " << z["layers"].get<std::string>();
      }
      o << " " << machines::fmt_fixed(100.0 * z["porosity"].get<double>(), 1) << " %" << (&z == &d[key].back() ? "" : ",");
    }
    o << "\n";
  }
  o << "  deposited      " << machines::fmt_fixed(tot.at("deposit_length_mm").get<double>() / 1000.0, 3) << " m, ink "
    << machines::fmt_fixed(tot.at("ink_volume_ml").get<double>(), 2) << " mL ("
    << machines::fmt_fixed(tot.at("syringe_fills").get<double>(), 2) << " fills of the "
    << slicer::short_number(tot.at("reservoir_ml").get<double>()) << " mL reservoir)\n";
  if (tot.contains("tools")) {
    o << "  tools         ";
    for (const auto& t : tot.at("tools")) {
      o << " " << t.at("tool").get<int>() << " (" << t.at("name").get<std::string>() << ") "
        << machines::fmt_fixed(t.at("deposit_length_mm").get<double>() / 1000.0, 3) << " m "
        << machines::fmt_fixed(t.at("ink_volume_ml").get<double>(), 2) << " mL;";
    }
    o << " " << tot.at("tool_changes").get<int>() << " change(s)\n";
  }
  o << "  time           " << clock_text(tot.at("time_trapezoid_s").get<double>())
    << " (acceleration + junction limits), " << clock_text(tot.at("time_naive_s").get<double>())
    << " (distance / feed)\n";
  return o.str();
}

}  // namespace strand::post
