// Lengths and times from the pose program, grouped by layer and lap.
#include "postprocess/plan/pose_report.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "machines/contact_speed.h"
#include "machines/gcode_format.h"
#include "postprocess/plan/cylinder_placement.h"
#include "postprocess/plan/report.h"
#include "slicer/input_error.h"
#include "slicer/units.h"

namespace strand::post {

namespace {

struct Sums {
  double deposit_mm = 0.0, travel_mm = 0.0, time_s = 0.0, volume_mm3 = 0.0;
};

// Sums of the motions ending at points (first, last].
Sums sums(const slicer::PoseProgram& p, std::size_t first, std::size_t last,
          const std::vector<double>& areas) {
  Sums s;
  for (std::size_t i = first + 1; i <= last && i < p.points.size(); ++i) {
    const auto& a = p.points[i - 1];
    const auto& b = p.points[i];
    const double len = (b.contact_mm - a.contact_mm).norm();
    (b.extrude ? s.deposit_mm : s.travel_mm) += len;
    if (b.extrude && static_cast<std::size_t>(b.layer) < areas.size())
      s.volume_mm3 += len * areas[b.layer];
    s.time_s += b.t_s - a.t_s;
  }
  return s;
}

nlohmann::json lap_json(const slicer::PoseProgram& p, std::size_t k,
                        const std::vector<double>& areas) {
  const auto& lap = p.laps[k];
  const Sums s = sums(p, lap.first, lap.last, areas);
  return {{"lap", k},
          {"layer", lap.layer},
          {"direction", lap.direction > 0 ? "forward" : "return"},
          {"turn_min_deg", round_to(slicer::rad_to_deg(lap.turn_min_rad), 2)},
          {"turn_max_deg", round_to(slicer::rad_to_deg(lap.turn_max_rad), 2)},
          {"turn_range_deg", round_to(slicer::rad_to_deg(lap.turn_max_rad - lap.turn_min_rad), 2)},
          {"deposit_length_mm", round_to(s.deposit_mm, 3)},
          {"time_s", round_to(s.time_s, 2)}};
}

nlohmann::json layers_json(const slicer::PoseProgram& p, const std::vector<double>& areas) {
  nlohmann::json out = nlohmann::json::array();
  for (std::size_t k = 0; k < p.layers.size(); ++k) {
    std::size_t laps = 0, first = p.points.size(), last = 0;
    for (const auto& lap : p.laps) {
      if (lap.layer != static_cast<int>(k)) continue;
      ++laps, first = std::min(first, lap.first), last = std::max(last, lap.last);
    }
    const Sums s = laps ? sums(p, first, last, areas) : Sums{};
    out.push_back({{"layer", k},
                   {"offset_mm", round_to(p.layers[k].offset_mm, 4)},
                   {"u_stretch", round_to(p.layers[k].u_stretch, 5)},
                   {"laps", laps},
                   {"deposit_length_mm", round_to(s.deposit_mm, 3)},
                   {"time_s", round_to(s.time_s, 2)}});
  }
  return out;
}

// "6 in 3 layers, 2 per layer (forward and return alternate), turning at most 290.7 deg per
// lap"; differing counts read "2/1/2/1 per layer".
std::string laps_text(const nlohmann::json& r) {
  std::vector<std::string> counts;
  for (const auto& l : r.at("layers")) counts.push_back(std::to_string(l.at("laps").get<int>()));
  std::string per_layer = counts.empty() ? "0" : counts.front();
  if (std::any_of(counts.begin(), counts.end(),
                  [&](const std::string& c) { return c != counts.front(); })) {
    per_layer.clear();
    for (const auto& c : counts) per_layer += (per_layer.empty() ? "" : "/") + c;
  }
  double widest = 0.0;
  for (const auto& lap : r.at("laps"))
    widest = std::max(widest, lap.at("turn_range_deg").get<double>());
  const auto& tot = r.at("totals");
  return std::to_string(tot.at("laps").get<int>()) + " in " +
         std::to_string(tot.at("layers").get<int>()) + " layers, " + per_layer +
         " per layer (forward and return alternate), turning at most " +
         machines::fmt_fixed(widest, 1) + " deg per lap";
}

}  // namespace

std::vector<double> bead_areas_mm2(const slicer::Toolpath& t) {
  std::vector<double> out;
  for (const auto& l : t.layers) {
    double a = 0.0;
    for (const auto& s : l.strokes) a = std::max(a, slicer::bead_area_mm2(s.width_mm, s.height_mm));
    out.push_back(a);
  }
  return out;
}

std::vector<double> bead_widths_mm(const slicer::Toolpath& t) {
  std::vector<double> out;
  for (const auto& l : t.layers) {
    double w = 0.0;
    for (const auto& s : l.strokes) w = std::max(w, s.width_mm);
    out.push_back(w);
  }
  return out;
}

nlohmann::json pose_report(const slicer::Toolpath& t, const slicer::SubstrateSpec& s,
                           const machines::MachineProfile& m, const slicer::PoseProgram& p) {
  const auto areas = bead_areas_mm2(t);
  const Sums all = sums(p, 0, p.points.size() - 1, areas);
  nlohmann::json laps = nlohmann::json::array();
  for (std::size_t k = 0; k < p.laps.size(); ++k) laps.push_back(lap_json(p, k, areas));
  nlohmann::json substrate = p.substrate;
  substrate["wrap"] = slicer::to_string(s.wrap);
  substrate["placement"] = placement_text(s);
  return {{"generator", t.generator},
          {"parameters", t.parameters},
          {"derived", t.derived},
          {"machine", {{"name", m.name}, {"kinematics", machines::to_string(m.volume.kind)}}},
          {"substrate", substrate},
          {"totals",
           {{"layers", p.layers.size()},
            {"laps", p.laps.size()},
            {"poses", p.points.size()},
            {"deposit_length_mm", round_to(all.deposit_mm, 3)},
            {"travel_length_mm", round_to(all.travel_mm, 3)},
            {"bead_volume_ml", round_to(slicer::mm3_to_ml(all.volume_mm3), 4)},
            {"time_s", round_to(all.time_s, 1)}}},
          {"layers", layers_json(p, areas)},
          {"laps", laps}};
}

std::string pose_summary(const nlohmann::json& r) {
  using machines::fmt_fixed;
  std::ostringstream o;
  const auto& tot = r.at("totals");
  const auto& sub = r.at("substrate");
  o << r.at("generator").get<std::string>() << " on a cylinder -> "
    << r.at("outputs").at("main").get<std::string>() << " ("
    << r.at("machine").at("name").get<std::string>() << ")\n";
  o << "  substrate      cylinder r " << fmt_fixed(sub.at("radius_mm").get<double>(), 3)
    << " mm, length " << fmt_fixed(sub.at("length_mm").get<double>(), 3) << " mm, wrap "
    << sub.at("wrap").get<std::string>() << ", arc length at "
    << sub.at("arc_length_at").get<std::string>() << "\n";
  const auto& d = r.at("derived");
  if (d.is_object() && d.contains("cells_around") && d.contains("cell_around_mm")) {
    o << "  wrap           " << d.at("cells_around").get<int>() << " cells of "
      << fmt_fixed(d.at("cell_around_mm").get<double>(), 3) << " mm around";
    if (d.contains("cell_around_requested_mm")) {
      o << " (asked " << fmt_fixed(d.at("cell_around_requested_mm").get<double>(), 3) << " mm)";
    }
    o << "\n";
  }
  o << "  u stretch      ";
  for (const auto& l : r.at("layers")) o << fmt_fixed(l.at("u_stretch").get<double>(), 4) << " ";
  o << "(layer length per mm of pattern x)\n";
  o << "  laps           " << laps_text(r) << "\n";
  o << "  deposited      " << fmt_fixed(tot.at("deposit_length_mm").get<double>() / 1000.0, 3)
    << " m on the surface, " << tot.at("poses").get<int>() << " poses\n";
  o << "  time           " << clock_text(tot.at("time_s").get<double>()) << "\n";
  if (r.contains("lap_timing"))
    o << "  lap timing     " << r.at("lap_timing").at("text").get<std::string>() << "\n";
  if (r.contains("ink"))
    o << "  ink            " << r.at("ink").at("text").get<std::string>() << "\n";
  if (r.contains("programs"))
    o << "  programs       " << r.at("programs").at("text").get<std::string>() << "\n";
  if (r.contains("robot"))
    o << "  joints         " << r.at("robot").at("text").get<std::string>() << "\n";
  o << contact_speed_summary(r);
  if (r.contains("warnings"))
    for (const auto& w : r.at("warnings")) o << "  warning        " << w.get<std::string>() << "\n";
  return o.str();
}

namespace {

nlohmann::json figures_json(const machines::ContactSpeedFigures& f) {
  return {{"worst_ratio", round_to(f.worst_ratio, 4)},
          {"worst_ratio_row", f.worst_ratio_row},
          {"worst_lap_time_difference_pct", round_to(100.0 * f.worst_lap_difference, 2)},
          {"worst_lap", f.worst_lap},
          {"deposit_moves", f.deposit_moves}};
}

std::string signed_pct(double fraction) {
  const std::string t = machines::fmt_fixed(100.0 * fraction, 1);
  return (t[0] == '-' ? "" : "+") + t + " %";
}

}  // namespace

void add_contact_speed(nlohmann::json& report, const slicer::PoseProgram& p,
                       const machines::MachineProfile& m) {
  nlohmann::json programs = nlohmann::json::array();
  std::string text;
  for (const machines::VendorProgram& v : machines::vendor_programs(m.robot)) {
    const auto written = machines::contact_speed_figures(p, machines::timed_motions(p, v.frame));
    // The same frame moved at each row's own speed: what the program did before it scaled.
    std::vector<machines::ProgrammedMotion> at_row_speed = machines::timed_motions(p, v.frame);
    for (std::size_t i = 1; i < at_row_speed.size(); ++i)
      at_row_speed[i].speed_mm_per_s = p.points[i].speed_mm_per_s;
    const auto unscaled = machines::contact_speed_figures(p, at_row_speed);
    nlohmann::json j = figures_json(written);
    j["program"] = v.name;
    j["moves"] = v.frame == machines::MovedFrame::Contact
                     ? "the contact point"
                     : "a workpiece frame, speeds scaled by its chord / the contact chord";
    j["at_row_speed"] = figures_json(unscaled);
    programs.push_back(j);
    text += (text.empty() ? "" : ", ") + v.name + " " +
            machines::fmt_fixed(written.worst_ratio, 3) + " / " +
            signed_pct(written.worst_lap_difference);
    const bool off = std::abs(written.worst_ratio - 1.0) > kContactSpeedTolerance ||
                     std::abs(written.worst_lap_difference) > kContactSpeedTolerance;
    if (off) {
      throw InputError("robot program " + v.name + ": the contact point would move at " +
                       machines::fmt_fixed(written.worst_ratio, 3) + "x the planned speed (row " +
                       std::to_string(written.worst_ratio_row) + ") and lap " +
                       std::to_string(written.worst_lap) + " take " +
                       signed_pct(written.worst_lap_difference) +
                       " against the extruder's time line (more than " +
                       machines::fmt_fixed(100.0 * kContactSpeedTolerance, 0) + " %)");
    }
  }
  report["contact_speed"] = {
      {"programs", programs},
      {"text", text + " (worst contact / planned speed, worst lap against the extruder)"}};
}

std::string contact_speed_summary(const nlohmann::json& r) {
  if (!r.contains("contact_speed")) return "";
  return "  contact speed  " + r.at("contact_speed").at("text").get<std::string>() + "\n";
}

}  // namespace strand::post
