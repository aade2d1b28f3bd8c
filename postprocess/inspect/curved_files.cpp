// Reading pose CSVs and rotary G-code back onto the workpiece.
#include "postprocess/inspect/curved_files.h"

#include <Eigen/Geometry>
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
  for (std::size_t pos = 0; pos < text.size();) {
    std::size_t nl = text.find('\n', pos);
    if (nl == std::string_view::npos) nl = text.size();
    const std::string_view line = text.substr(pos, nl - pos);
    pos = nl + 1;
    if (line.empty() || line[0] != ';') continue;
    if (auto v = vec3_after(line, ";ROTARY_AXIS_DIR:")) dir = v;
    if (auto v = vec3_after(line, ";ROTARY_AXIS_POINT:")) point = v;
    const std::string_view key = ";SUBSTRATE:cylinder radius=";
    double r = 0.0;
    if (line.substr(0, key.size()) == key &&
        std::from_chars(line.data() + key.size(), line.data() + line.size(), r).ec == std::errc() &&
        r > 0) {
      radius = r;
    }
  }
  if (!dir || !point || !radius || dir->norm() < 1e-9 || std::abs(dir->normalized().z()) > 1e-6) {
    throw InputError("input = " + file +
                     ": a rotary G-code needs ;ROTARY_AXIS_DIR:x,y,z (horizontal), "
                     ";ROTARY_AXIS_POINT:x,y,z and ;SUBSTRATE:cylinder radius=R header lines");
  }
  return {dir->normalized(), *point, *radius};
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

std::vector<CylinderSample> read_curved_samples(std::string_view text, const std::string& file) {
  if (text.substr(0, std::string_view(machines::kPoseCsvHeader).size()) ==
      machines::kPoseCsvHeader) {
    std::vector<CylinderSample> samples;
    const auto rows = machines::read_pose_csv(text, file);
    for (std::size_t i = 0; i < rows.size(); ++i) {
      samples.push_back({rows[i].layer, rows[i].extrude, rows[i].contact_mm, i, rows[i].feature});
    }
    return samples;
  }
  if (!is_rotary_gcode(text)) {
    throw InputError("input = " + file + ": neither a pose CSV nor rotary G-code");
  }
  return rotary_samples(parse_gcode(text), read_rotary_header(text, file));
}

slicer::MotionProgram workpiece_program(const std::vector<CylinderSample>& samples) {
  slicer::MotionProgram p;
  for (const auto& s : samples) {
    slicer::Move mv;
    mv.kind = s.extrude ? slicer::MoveKind::Deposit : slicer::MoveKind::Travel;
    mv.end_mm = Vec3(s.p_mm.z(), -s.p_mm.y(), s.p_mm.x());  // axis along x, u = 0 on top
    mv.layer = s.layer;
    mv.feature = s.feature;
    while (s.layer >= 0 && static_cast<int>(p.layers.size()) <= s.layer)
      p.layers.push_back({0.0, 0.0});
    if (s.extrude && s.layer >= 0)
      p.layers[s.layer].z_mm = std::max(p.layers[s.layer].z_mm, s.p_mm.head<2>().norm());
    p.moves.push_back(mv);
  }
  if (!p.moves.empty()) p.start_mm = p.moves.front().end_mm;
  return p;
}

}  // namespace strand::post
