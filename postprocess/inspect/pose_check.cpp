// Checks shared by pose CSVs and rotary G-code, the pose CSV reader's checks, and the report.
#include "postprocess/inspect/pose_check.h"

#include <algorithm>
#include <cmath>

#include "machines/gcode_format.h"
#include "machines/pose_csv.h"
#include "machines/workpiece_pose.h"
#include "postprocess/inspect/cylinder_contacts.h"
#include "slicer/input_error.h"
#include "slicer/tolerances.h"
#include "slicer/units.h"

namespace strand::post {

using machines::fmt_fixed;
using slicer::Vec3;

void PoseFindings::add(std::size_t row, std::string what) {
  if (listed.size() < kMaxListed) listed.push_back({row, std::move(what)});
  ++total;
}

bool PoseCheckReport::ok() const {
  const bool joints_ok = !joints_checked || joints.ok();
  return crossing_count() == 0 && off_tip.total == 0 && normals.total == 0 &&
         off_surface.total == 0 && speed.total == 0 && outside.total == 0 && parse.total == 0 &&
         joints_ok;
}

std::size_t PoseCheckReport::crossing_count() const {
  std::size_t n = 0;
  for (const auto& l : layers) n += l.crossings.size();
  return n;
}

namespace {

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

// Unwraps angle `a` next to the previous unwrapped angle.
double unwrap(double a, double previous) {
  return a + slicer::kTwoPi * std::round((previous - a) / slicer::kTwoPi);
}

}  // namespace

void check_on_cylinder(const std::vector<CylinderSample>& s, double touch_mm, PoseCheckReport& r) {
  std::vector<CylinderLayer> layers;
  for (std::size_t b = 0; b < s.size();) {
    std::size_t e = b;
    while (e + 1 < s.size() && s[e + 1].layer == s[b].layer) ++e;
    std::vector<double> radii;
    for (std::size_t i = b; i <= e; ++i) {
      if (s[i].extrude) radii.push_back(s[i].p_mm.head<2>().norm());
    }
    PoseLayerCheck lc{s[b].layer, median(radii)};
    CylinderLayer cl{s[b].layer, slicer::kTwoPi * lc.radius_mm, {}};
    double angle = 0.0;
    for (std::size_t i = std::max<std::size_t>(b, 1); i <= e; ++i) {
      if (!s[i].extrude) continue;
      const double rad = s[i].p_mm.head<2>().norm();
      if (std::abs(rad - lc.radius_mm) > slicer::kOffSurfaceMm) {
        r.off_surface.add(s[i].source, "radius " + fmt_fixed(rad, 4) + " mm, layer's " +
                                           fmt_fixed(lc.radius_mm, 4) + " mm");
      }
      const CylinderSample& from = s[i - 1];
      // A strand starts where the deposit starts (a file may start depositing at its very
      // first sample: then no strand is open yet).
      if (cl.strands.empty() || i == b || !from.extrude) {
        angle = std::atan2(from.p_mm.y(), from.p_mm.x());
        cl.strands.push_back({{slicer::Vec2(angle * lc.radius_mm, from.p_mm.z()), from.source}});
        ++lc.strands;
      }
      angle = unwrap(std::atan2(s[i].p_mm.y(), s[i].p_mm.x()), angle);
      cl.strands.back().push_back({slicer::Vec2(angle * lc.radius_mm, s[i].p_mm.z()), s[i].source});
    }
    r.layers.push_back(lc);
    layers.push_back(std::move(cl));
    b = e + 1;
  }
  const ContactReport contacts = find_cylinder_contacts(layers, touch_mm);
  for (auto& l : r.layers) {
    for (const auto& c : contacts.crossings)
      if (c.layer == l.layer) l.crossings.push_back(c);
    for (const auto& c : contacts.touches)
      if (c.layer == l.layer) l.touches.push_back(c);
  }
}

namespace {

// Nozzle tip and axis, speeds against plan and profile.
void check_rows(const std::vector<slicer::PosePoint>& rows, const machines::RobotCell& cell,
                PoseCheckReport& r) {
  const Vec3 up = -cell.nozzle_axis;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const auto& p = rows[i];
    const Eigen::Matrix3d rot = machines::rotation_of(p.workpiece_wxyz);
    const double off = (rot * p.contact_mm + p.workpiece_origin_mm - cell.nozzle_tip_mm).norm();
    if (off > slicer::kPoseTipMm)
      r.off_tip.add(i, "contact " + fmt_fixed(off, 4) + " mm from the nozzle tip");
    const double cosine = std::clamp((rot * p.normal.normalized()).dot(up), -1.0, 1.0);
    const double angle = slicer::rad_to_deg(std::acos(cosine));
    if (angle > slicer::kPoseNormalDeg)
      r.normals.add(i, "normal " + fmt_fixed(angle, 3) + " deg off the nozzle axis");
    if (i == 0) continue;
    const double len = (p.contact_mm - rows[i - 1].contact_mm).norm(), dt = p.t_s - rows[i - 1].t_s;
    if (len > 0 && dt <= 0) {
      r.speed.add(i, "time does not advance (" + fmt_fixed(dt, 6) + " s) over " +
                         fmt_fixed(len, 4) + " mm");
    } else if (len >= slicer::kSpeedCheckMinMm &&
               std::abs(len / dt - p.speed_mm_per_s) > slicer::kSpeedDeviation * p.speed_mm_per_s) {
      r.speed.add(i, "moves at " + fmt_fixed(len / dt, 3) + " mm/s, planned " +
                         fmt_fixed(p.speed_mm_per_s, 3) + " mm/s");
    }
    if (p.extrude && std::abs(p.speed_mm_per_s - cell.v_cart_mm_per_s) >
                         slicer::kSpeedDeviation * cell.v_cart_mm_per_s) {
      r.speed.add(i, "deposits at " + fmt_fixed(p.speed_mm_per_s, 3) +
                         " mm/s, the cell's v_cart is " + fmt_fixed(cell.v_cart_mm_per_s, 3) +
                         " mm/s");
    }
  }
}

}  // namespace

PoseCheckReport check_pose_csv(std::string_view text, const std::string& file,
                               const machines::MachineProfile& m) {
  if (!m.robot.enabled) {
    throw InputError("machine = " + m.name +
                     ": a pose CSV is checked against a robot-holds-substrate machine (e.g. "
                     "kuka-iiwa14-wasp-cylinder)");
  }
  std::vector<slicer::PosePoint> rows = machines::read_pose_csv(text, file);
  PoseCheckReport r;
  r.kind = "pose CSV";
  r.machine = m.name;
  r.rows = rows.size();
  check_rows(rows, m.robot, r);
  std::vector<CylinderSample> samples;
  double turn = 0.0;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    auto& p = rows[i];
    turn = i == 0 ? std::atan2(p.contact_mm.y(), p.contact_mm.x())
                  : unwrap(std::atan2(p.contact_mm.y(), p.contact_mm.x()), turn);
    p.turn_rad = turn;
    samples.push_back({p.layer, p.extrude, p.contact_mm, i});
  }
  check_on_cylinder(samples, slicer::kGcodeResolutionMm, r);
  r.joints = machines::analyse_joints(machines::lbr_iiwa_14_r820(m.robot), m.robot, rows);
  r.joints_checked = true;
  return r;
}

namespace {

nlohmann::json findings_json(const PoseFindings& f) {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& x : f.listed) list.push_back({{"at", x.row}, {"what", x.what}});
  return {{"total", f.total}, {"listed", list}};
}

nlohmann::json joints_json(const machines::JointReport& j) {
  nlohmann::json ranges = nlohmann::json::array();
  for (int i = 0; i < 7; ++i) {
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
  for (int i = 0; i < 7; ++i) {
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
                      {"radius_mm", std::round(l.radius_mm * 1e4) / 1e4},
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
                      {"parse_issues", findings_json(r.parse)}};
  if (r.joints_checked) j["joints"] = joints_json(r.joints);
  return j;
}

std::string to_text(const PoseCheckReport& r) {
  const bool csv = r.kind == "pose CSV";
  const char* at = csv ? "row" : "line";
  std::string out = r.kind + ": " + std::to_string(r.layers.size()) + " layers, " +
                    std::to_string(r.rows) + (csv ? " poses" : " moves") +
                    (r.machine.empty() ? "" : ", machine " + r.machine) + "\n";
  out +=
      "layer  radius_mm  strands  crossings  touches   (crossings judged in (u, v) around the "
      "cylinder)\n";
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
  list_text("problems in the file", at, r.parse, out);
  if (r.joints_checked) out += joints_text(r.joints);
  out += r.ok() ? "check: OK\n" : "check: FAILED\n";
  return out;
}

}  // namespace strand::post
