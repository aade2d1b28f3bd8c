// Rotary G-code mapped back onto its cylinder through the header's axis and substrate lines.
#include <charconv>
#include <cmath>
#include <optional>

#include "machines/gcode_format.h"
#include "machines/kinematics.h"
#include "postprocess/inspect/pose_check.h"
#include "slicer/input_error.h"
#include "slicer/tolerances.h"
#include "slicer/units.h"

namespace strand::post {

using slicer::Vec3;

namespace {

struct RotaryHeader {
  std::optional<Vec3> dir, point;
  std::optional<double> radius_mm;
};

std::optional<Vec3> vec3_after(std::string_view line, std::string_view key) {
  if (line.substr(0, key.size()) != key) return std::nullopt;
  Vec3 v;
  const char* p = line.data() + key.size();
  const char* end = line.data() + line.size();
  for (int i = 0; i < 3; ++i) {
    const auto r = std::from_chars(p, end, v[i]);
    if (r.ec != std::errc()) return std::nullopt;
    p = r.ptr + (r.ptr < end && *r.ptr == ',' ? 1 : 0);
  }
  return v;
}

RotaryHeader read_header(std::string_view text) {
  RotaryHeader h;
  for (std::size_t pos = 0; pos < text.size();) {
    std::size_t nl = text.find('\n', pos);
    if (nl == std::string_view::npos) nl = text.size();
    const std::string_view line = text.substr(pos, nl - pos);
    pos = nl + 1;
    if (line.empty() || line[0] != ';') continue;
    if (auto v = vec3_after(line, ";ROTARY_AXIS_DIR:")) h.dir = v;
    if (auto v = vec3_after(line, ";ROTARY_AXIS_POINT:")) h.point = v;
    const std::string_view key = ";SUBSTRATE:cylinder radius=";
    if (line.substr(0, key.size()) == key) {
      double r = 0.0;
      if (std::from_chars(line.data() + key.size(), line.data() + line.size(), r).ec == std::errc())
        h.radius_mm = r;
    }
  }
  return h;
}

}  // namespace

bool is_rotary_gcode(std::string_view text) {
  return text.find(";ROTARY_AXIS:") != std::string_view::npos;
}

PoseCheckReport check_rotary_gcode(std::string_view text, const std::string& file,
                                   const machines::MachineProfile* machine) {
  const RotaryHeader h = read_header(text);
  if (!h.dir || !h.point || !h.radius_mm || h.dir->norm() < 1e-9 || std::abs(h.dir->z()) > 1e-6) {
    throw InputError("input = " + file +
                     ": a rotary G-code needs ;ROTARY_AXIS_DIR:x,y,z (horizontal), "
                     ";ROTARY_AXIS_POINT:x,y,z and ;SUBSTRATE:cylinder radius=R header lines");
  }
  const ParsedGcode parsed = parse_gcode(text);
  PoseCheckReport r;
  r.kind = "rotary G-code";
  r.machine = machine ? machine->name : "";
  r.rows = parsed.program.moves.size();
  for (const auto& issue : parsed.issues)
    r.parse.add(static_cast<std::size_t>(issue.line), issue.what);
  const Vec3 axis = h.dir->normalized(), up = Vec3::UnitZ();
  Eigen::Matrix3d ref;  // workpiece axes in the machine frame at A = 0 (as the writer poses it)
  ref << up, axis.cross(up), axis;
  std::vector<CylinderSample> samples;
  for (std::size_t i = 0; i < parsed.program.moves.size(); ++i) {
    const auto& mv = parsed.program.moves[i];
    if (mv.kind != slicer::MoveKind::Deposit && mv.kind != slicer::MoveKind::Travel) continue;
    const double a = parsed.a_deg.empty() ? 0.0 : parsed.a_deg[i];
    const Vec3 rel = mv.end_mm - *h.point;
    const Vec3 p = ref.transpose() * (Eigen::AngleAxisd(-slicer::deg_to_rad(a), axis) * rel);
    const std::size_t line = static_cast<std::size_t>(parsed.move_lines[i]);
    if (mv.kind == slicer::MoveKind::Deposit) {
      const Vec3 radial = rel - rel.dot(axis) * axis;
      const double angle =
          slicer::rad_to_deg(std::acos(std::clamp(radial.normalized().dot(up), -1.0, 1.0)));
      if (angle > slicer::kPoseNormalDeg)
        r.normals.add(line, "the nozzle is " + machines::fmt_fixed(angle, 3) +
                                " deg off the top of the cylinder");
    }
    if (machine) {
      if (auto why = machines::outside_reason(machine->volume, mv.end_mm))
        r.outside.add(line, *why);
    }
    samples.push_back({mv.layer, mv.kind == slicer::MoveKind::Deposit, p, line});
  }
  check_on_cylinder(samples, slicer::kGcodeResolutionMm, r);
  return r;
}

}  // namespace strand::post
