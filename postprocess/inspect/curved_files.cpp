// Reading pose CSVs and rotary G-code back onto the workpiece.
#include "postprocess/inspect/curved_files.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <charconv>
#include <cmath>

#include "machines/pose_csv.h"
#include "slicer/input_error.h"
#include "slicer/units.h"

namespace strand::post {

using slicer::Vec3;

namespace {

std::optional<Vec3> vec3_after(std::string_view line, std::string_view key) {
  if (line.substr(0, key.size()) != key) return std::nullopt;
  Vec3 v;
  const char* p = line.data() + key.size();
  const char* end = line.data() + line.size();
  for (int i = 0; i < 3; ++i) {
    const auto r = std::from_chars(p, end, v[i]);
    if (r.ec != std::errc() || !std::isfinite(v[i])) return std::nullopt;
    p = r.ptr + (r.ptr < end && *r.ptr == ',' ? 1 : 0);
  }
  return v;
}

}  // namespace

bool is_rotary_gcode(std::string_view text) {
  return text.find(";ROTARY_AXIS:") != std::string_view::npos;
}

RotaryHeader read_rotary_header(std::string_view text, const std::string& file) {
  std::optional<Vec3> dir, point;
  std::optional<double> radius;
  double length = 0.0;
  for (std::size_t pos = 0; pos < text.size();) {
    std::size_t nl = text.find('\n', pos);
    if (nl == std::string_view::npos) nl = text.size();
    const std::string_view line = text.substr(pos, nl - pos);
    pos = nl + 1;
    if (line.empty() || line[0] != ';') continue;
    if (auto v = vec3_after(line, ";ROTARY_AXIS_DIR:")) dir = v;
    if (auto v = vec3_after(line, ";ROTARY_AXIS_POINT:")) point = v;
    const std::string_view key = ";SUBSTRATE:cylinder radius=";
    if (line.substr(0, key.size()) != key) continue;
    double r = 0.0, l = 0.0;
    const char* end = line.data() + line.size();
    if (std::from_chars(line.data() + key.size(), end, r).ec == std::errc() && r > 0) radius = r;
    const std::size_t at = line.find(" length=");
    if (at != std::string_view::npos &&
        std::from_chars(line.data() + at + 8, end, l).ec == std::errc() && l > 0) {
      length = l;
    }
  }
  if (!dir || !point || !radius || dir->norm() < 1e-9 || std::abs(dir->normalized().z()) > 1e-6) {
    throw InputError("input = " + file +
                     ": a rotary G-code needs ;ROTARY_AXIS_DIR:x,y,z (horizontal), "
                     ";ROTARY_AXIS_POINT:x,y,z and ;SUBSTRATE:cylinder radius=R header lines");
  }
  return {dir->normalized(), *point, *radius, length};
}

std::vector<CylinderSample> rotary_samples(const ParsedGcode& parsed, const RotaryHeader& h) {
  const Vec3 up = Vec3::UnitZ();
  Eigen::Matrix3d ref;  // workpiece axes in the machine frame at A = 0 (as the writer poses it)
  ref << up, h.axis_dir.cross(up), h.axis_dir;
  std::vector<CylinderSample> samples;
  for (std::size_t i = 0; i < parsed.program.moves.size(); ++i) {
    const auto& mv = parsed.program.moves[i];
    if (mv.kind != slicer::MoveKind::Deposit && mv.kind != slicer::MoveKind::Travel) continue;
    const double a = parsed.a_deg.empty() ? 0.0 : parsed.a_deg[i];
    const Vec3 rel = mv.end_mm - h.axis_point_mm;
    const Vec3 p = ref.transpose() * (Eigen::AngleAxisd(-slicer::deg_to_rad(a), h.axis_dir) * rel);
    samples.push_back({mv.layer, mv.kind == slicer::MoveKind::Deposit, p,
                       static_cast<std::size_t>(parsed.move_lines[i]), mv.feature});
  }
  return samples;
}

namespace {

// Per layer, the largest deposit radius (layers without deposits keep 0).
std::vector<double> layer_radii(const std::vector<CylinderSample>& samples) {
  std::vector<double> radii;
  for (const auto& s : samples) {
    if (s.layer < 0) continue;
    if (radii.size() <= static_cast<std::size_t>(s.layer)) radii.resize(s.layer + 1, 0.0);
    if (s.extrude) radii[s.layer] = std::max(radii[s.layer], s.p_mm.head<2>().norm());
  }
  return radii;
}

// A pose CSV's cylinder from its layers: r_k = radius + (k + 1) h.
void infer_cylinder(CurvedPart& part, const std::vector<double>& radii) {
  double v_lo = 1e300, v_hi = -1e300;
  for (const auto& s : part.samples) {
    if (s.extrude) v_lo = std::min(v_lo, s.p_mm.z()), v_hi = std::max(v_hi, s.p_mm.z());
  }
  if (radii.size() < 2 || !(radii[1] > radii[0]) || v_hi < v_lo) return;
  const double h = radii[1] - radii[0];
  part.radius_mm = std::max(radii[0] - h, 0.0);
  part.length_mm = v_lo + v_hi;  // the pattern is centred at mid-length
  part.bead_width_mm = h;
}

}  // namespace

CurvedPart read_curved_part(std::string_view text, const std::string& file) {
  CurvedPart part;
  if (text.substr(0, std::string_view(machines::kPoseCsvHeader).size()) ==
      machines::kPoseCsvHeader) {
    const auto rows = machines::read_pose_csv(text, file);
    for (std::size_t i = 0; i < rows.size(); ++i) {
      part.samples.push_back(
          {rows[i].layer, rows[i].extrude, rows[i].contact_mm, i, rows[i].feature});
    }
    infer_cylinder(part, layer_radii(part.samples));
  } else if (is_rotary_gcode(text)) {
    const RotaryHeader h = read_rotary_header(text, file);
    const ParsedGcode parsed = parse_gcode(text);
    part.samples = rotary_samples(parsed, h);
    part.radius_mm = h.radius_mm;
    part.length_mm = h.length_mm;
    for (const auto& mv : parsed.program.moves)
      part.bead_width_mm = std::max(part.bead_width_mm, mv.width_mm);
  } else {
    throw InputError("input = " + file + ": neither a pose CSV nor rotary G-code");
  }
  for (double r : layer_radii(part.samples))
    part.layer_offsets_mm.push_back(r > 0 ? r - part.radius_mm : 0.0);
  return part;
}

std::vector<CylinderSample> read_curved_samples(std::string_view text, const std::string& file) {
  return read_curved_part(text, file).samples;
}

}  // namespace strand::post
