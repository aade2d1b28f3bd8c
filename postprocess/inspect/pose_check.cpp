// Checks shared by pose CSVs and rotary G-code and the pose CSV reader's checks (the report's
// JSON and text: pose_report_text.cpp).
#include "postprocess/inspect/pose_check.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <optional>

#include "machines/gcode_format.h"
#include "machines/pose_csv.h"
#include "machines/workpiece_pose.h"
#include "postprocess/inspect/cylinder_contacts.h"
#include "postprocess/plan/laps.h"
#include "slicer/input_error.h"
#include "slicer/params.h"
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
         numbering.total == 0 && quaternions.total == 0 && extrusion.total == 0 && joints_ok &&
         (!transit_checked || transit.ok) &&
         std::all_of(program_speeds.begin(), program_speeds.end(),
                     [](const ProgramSpeed& s) { return s.ok(); });
}

std::size_t PoseCheckReport::crossing_count() const {
  std::size_t n = 0;
  for (const auto& l : layers) n += l.crossings.size();
  return n;
}

namespace {

// The planner's lap slack (laps.cpp): a reversal smaller than this does not start a lap, rad.
constexpr double kLapSlackRad = 0.017453292519943295;
// Lap checking passes over a layer once per lap: at most this many row visits.
constexpr double kMaxLapWork = 2e8;

// A workpiece orientation is a unit quaternion to this (the file writes 9 decimals).
constexpr double kQuaternionUnit = 1e-6;

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
      const double from_rad = from.p_mm.head<2>().norm();
      if ((!from.extrude || from.layer != s[i].layer) &&
          std::abs(from_rad - lc.radius_mm) > slicer::kOffSurfaceMm) {
        r.off_surface.add(s[i].source, "deposit starts at radius " + fmt_fixed(from_rad, 4) +
                                           " mm, off the layer's " + fmt_fixed(lc.radius_mm, 4) +
                                           " mm (a travel marked as depositing?)");
      }
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

// A row's time may differ from distance / speed by the file's rounding: 4 decimals of
// position (a chord up to 2e-4 mm off) and 6 of time, plus kSpeedDeviation.
bool time_fits(double len_mm, double dt_s, double speed_mm_per_s) {
  const double expected = len_mm / speed_mm_per_s;
  return std::abs(dt_s - expected) <=
         slicer::kSpeedDeviation * expected + 2e-6 + 2e-4 / speed_mm_per_s;
}

// Nozzle tip and axis, unit quaternions, times against distance / speed, speeds against the
// cell (deposits at v_cart, travels at its travel speed).
void check_rows(const std::vector<slicer::PosePoint>& rows, const machines::RobotCell& cell,
                PoseCheckReport& r) {
  const Vec3 up = -cell.nozzle_axis;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const auto& p = rows[i];
    const double q_norm = p.workpiece_wxyz.norm();
    if (std::abs(q_norm - 1.0) > kQuaternionUnit) {
      r.quaternions.add(i, "quaternion of norm " + fmt_fixed(q_norm, 9) +
                               ", not a unit quaternion (within 1e-6)");
    }
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
    if (!(p.speed_mm_per_s > 0)) {
      r.speed.add(i, "speed " + fmt_fixed(p.speed_mm_per_s, 4) + " mm/s: a move needs a speed > 0");
      continue;
    }
    if (len > 0 && dt <= 0) {
      r.speed.add(i, "time does not advance (" + fmt_fixed(dt, 6) + " s) over " +
                         fmt_fixed(len, 4) + " mm");
    } else if (!time_fits(len, dt, p.speed_mm_per_s)) {
      r.speed.add(i, "takes " + fmt_fixed(dt, 6) + " s for " + fmt_fixed(len, 4) + " mm at " +
                         fmt_fixed(p.speed_mm_per_s, 3) + " mm/s (" +
                         fmt_fixed(len / p.speed_mm_per_s, 6) + " s)");
    }
    const double planned = p.extrude ? cell.v_cart_mm_per_s : cell.travel_speed_mm_per_s;
    if (std::abs(p.speed_mm_per_s - planned) > slicer::kSpeedDeviation * planned) {
      r.speed.add(i, std::string(p.extrude ? "deposits" : "travels") + " at " +
                         fmt_fixed(p.speed_mm_per_s, 3) + " mm/s, the cell's " +
                         (p.extrude ? "v_cart" : "travel speed") + " is " + fmt_fixed(planned, 3) +
                         " mm/s");
    }
  }
}

// The cells the reader does not keep or reads loosely: index, extrude, layer, lap, feature.
struct RawRow {
  std::string_view index, extrude, layer, lap, feature;
};

std::vector<RawRow> raw_rows(std::string_view text) {
  std::vector<RawRow> out;
  std::size_t pos = text.find('\n');
  while (pos != std::string_view::npos && pos < text.size()) {
    ++pos;
    std::size_t nl = text.find('\n', pos);
    std::string_view line = text.substr(pos, nl == std::string_view::npos ? nl : nl - pos);
    pos = nl;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (line.empty()) continue;
    std::string_view cells[14];
    std::size_t start = 0;
    for (int c = 0; c < 14; ++c) {
      const std::size_t comma = line.find(',', start);
      cells[c] = line.substr(start, comma == std::string_view::npos ? comma : comma - start);
      start = comma == std::string_view::npos ? line.size() : comma + 1;
    }
    out.push_back({cells[0], cells[10], cells[11], cells[12], cells[13]});
  }
  return out;
}

// A whole number written as one ("12", not "12.0" or "1e1"), or nullopt.
std::optional<long long> whole(std::string_view cell) {
  long long v = 0;
  const auto r = std::from_chars(cell.data(), cell.data() + cell.size(), v);
  if (r.ec != std::errc() || r.ptr != cell.data() + cell.size()) return std::nullopt;
  return v;
}

// Indices 0, 1, 2, ...; layers from 0 up by one; laps from 0 up by one, a new one at every
// layer; every lap turning one way as the planner splits them (laps.h); extrude 1 exactly on
// rows with a deposit feature. One finding where a sequence breaks, not on every later row.
void check_numbering(const std::vector<RawRow>& raw, const std::vector<slicer::PosePoint>& rows,
                     PoseCheckReport& r, bool laps_by_turn = true) {
  long long prev_index = -1;
  for (std::size_t i = 0; i < raw.size() && i < rows.size(); ++i) {
    const auto index = whole(raw[i].index);
    if (!index) {
      r.numbering.add(i, "index '" + std::string(raw[i].index) + "' is not a whole number");
    } else {
      if (*index != prev_index + 1) {
        r.numbering.add(i, "index " + std::to_string(*index) + " after " +
                               std::to_string(prev_index) +
                               ": rows are numbered 0, 1, 2, ... (a row deleted, duplicated or "
                               "moved)");
      }
      prev_index = *index;
    }
    for (const auto& [name, cell] :
         {std::pair{"layer", raw[i].layer}, std::pair{"lap", raw[i].lap}}) {
      const auto v = whole(cell);
      if (!v || *v < 0 || *v > std::numeric_limits<int>::max()) {
        r.numbering.add(
            i, std::string(name) + " '" + std::string(cell) + "' is not a whole number >= 0");
      }
    }
    const bool travel = raw[i].feature == "travel";
    if (rows[i].extrude == travel) {
      r.extrusion.add(i, std::string("extrude ") + (rows[i].extrude ? "1" : "0") +
                             " on a row whose feature is " + std::string(raw[i].feature));
    }
    if (i == 0) {
      if (rows[0].layer != 0 || rows[0].lap != 0)
        r.numbering.add(0, "the first row is in layer " + std::to_string(rows[0].layer) + ", lap " +
                               std::to_string(rows[0].lap) + ": both start at 0");
      if (rows[0].extrude) r.extrusion.add(0, "the first row deposits, from nowhere");
      continue;
    }
    const auto& a = rows[i - 1];
    const auto& b = rows[i];
    if (b.layer != a.layer && b.layer != a.layer + 1) {
      r.numbering.add(i, "layer " + std::to_string(b.layer) + " after layer " +
                             std::to_string(a.layer) + ": layers go up by one");
    }
    if (b.lap != a.lap && b.lap != a.lap + 1) {
      r.numbering.add(i, "lap " + std::to_string(b.lap) + " after lap " + std::to_string(a.lap) +
                             ": laps go up by one");
    } else if (b.layer != a.layer && b.lap == a.lap) {
      r.numbering.add(i, "layer " + std::to_string(b.layer) + " starts inside lap " +
                             std::to_string(b.lap) + ": every layer starts a lap");
    }
  }
  // Laps as the planner splits them from the turns: each turns the workpiece one way.
  if (r.numbering.total != 0 || !laps_by_turn) return;  // the split needs layers in order
  // The split costs a pass over a layer per lap: bound it by the turn's reversals first.
  double work = 0.0;
  std::size_t reversals = 0;
  for (std::size_t b = 0; b < rows.size();) {
    std::size_t e = b;
    while (e + 1 < rows.size() && rows[e + 1].layer == rows[b].layer) ++e;
    double hi = rows[b].turn_rad, lo = hi;
    int dir = 0;
    std::size_t n = 0;
    for (std::size_t i = b; i <= e; ++i) {
      const double t = rows[i].turn_rad;
      if (dir >= 0) {
        hi = std::max(hi, t);
        if (hi - t > kLapSlackRad) ++n, dir = -1, lo = t;
      } else {
        lo = std::min(lo, t);
        if (t - lo > kLapSlackRad) ++n, dir = 1, hi = t;
      }
    }
    reversals += n;
    work += static_cast<double>(n + 2) * static_cast<double>(e - b + 1);
    b = e + 1;
  }
  if (work > kMaxLapWork) {
    r.numbering.add(0, "the turn reverses " + std::to_string(reversals) +
                           " times: laps are not checked past " +
                           slicer::short_number(kMaxLapWork) + " steps of work");
    return;
  }
  slicer::PoseProgram program;
  program.points = rows;
  assign_laps(program);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const int expected = program.points[i].lap;
    if (rows[i].lap == expected) continue;
    if (i > 0 && rows[i - 1].lap != program.points[i - 1].lap) continue;  // same run
    const auto& lap = program.laps[static_cast<std::size_t>(expected)];
    r.numbering.add(i, "lap " + std::to_string(rows[i].lap) + ", but the turns make this row lap " +
                           std::to_string(expected) + " (turning " +
                           (lap.direction > 0 ? "forward" : "back") + " from row " +
                           std::to_string(lap.first) + " to " + std::to_string(lap.last) + ")");
  }
}

}  // namespace

void check_pose_rows(const std::vector<slicer::PosePoint>& rows, const machines::RobotCell& cell,
                     PoseCheckReport& report) {
  check_rows(rows, cell, report);
}

void check_pose_numbering(std::string_view text, const std::vector<slicer::PosePoint>& rows,
                          bool laps_by_turn, PoseCheckReport& report) {
  check_numbering(raw_rows(text), rows, report, laps_by_turn);
}

void check_pose_transit(const std::vector<slicer::PosePoint>& rows, const machines::RobotCell& cell,
                        const machines::TransitWorkpiece& workpiece, PoseCheckReport& report) {
  std::optional<machines::Joints> last;
  if (report.joints_checked && report.joints.ok() && !report.joints.solutions.empty())
    last = report.joints.solutions.back();
  report.transit = machines::plan_transit(cell, rows, workpiece, last);
  report.transit_checked = true;
}

PoseCheckReport check_pose_csv(std::string_view text, const std::string& file,
                               const machines::MachineProfile& m) {
  if (!m.robot.enabled) {
    throw InputError("machine = " + m.name +
                     ": a pose CSV is checked against a robot-holds-substrate machine (e.g. "
                     "kuka-iiwa14-wasp-cylinder)");
  }
  std::vector<slicer::PosePoint> rows = machines::read_pose_csv(text, file);
  if (rows.empty()) {
    throw InputError("input = " + file +
                     ": no poses (a pose CSV has one row per pose after its header)");
  }
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
  check_numbering(raw_rows(text), rows, r);
  check_on_cylinder(samples, slicer::kGcodeResolutionMm, r);
  r.joints = machines::analyse_joints(machines::arm_model(m.robot), m.robot, rows, true);
  r.joints_checked = true;
  if (r.joints.ok()) {
    // The cylinder the rows lie on (radius from the layers; without one, the deposits' own
    // radius: a larger cylinder, on the safe side), its length from the pattern.
    const CurvedPart part = read_curved_part(text, file);
    std::vector<double> radii;
    double z_lo = 0.0, z_hi = 0.0;
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const auto& c = rows[i].contact_mm;
      radii.push_back(std::hypot(c.x(), c.y()));
      z_lo = i ? std::min(z_lo, c.z()) : c.z();
      z_hi = i ? std::max(z_hi, c.z()) : c.z();
    }
    const double radius = part.radius_mm > 0.0 ? part.radius_mm : median(radii);
    const double length = part.length_mm > 0.0 ? part.length_mm : std::max(z_hi, z_lo + z_hi);
    const double printed = part.layer_offsets_mm.empty() ? 0.0 : part.layer_offsets_mm.back();
    check_pose_transit(rows, m.robot, machines::cylinder_workpiece(radius, length, printed), r);
  }
  r.program_speeds = check_program_speeds(rows, file, m);
  return r;
}

}  // namespace strand::post
