// Pose CSV text: fixed digits, one row per pose.
#include "machines/pose_csv.h"

#include <charconv>
#include <cmath>

#include "machines/gcode_format.h"
#include "slicer/input_error.h"

namespace strand::machines {

namespace {

constexpr int kColumns = 20;
// Digits: positions to 0.1 um and quaternions/normals to 1e-9 keep R p + x within 0.01 mm
// of the tip and R n within 0.1 deg of the nozzle axis after a round trip through text.
constexpr int kMmDigits = 4;
constexpr int kUnitDigits = 9;

std::string feature_name(const slicer::PosePoint& p) {
  return p.extrude ? slicer::to_string(p.feature) : "travel";
}

void append_row(std::string& out, std::size_t index, const slicer::PosePoint& p) {
  const auto mm = [](double v) { return fmt_fixed(v, kMmDigits); };
  const auto unit = [](double v) { return fmt_fixed(v, kUnitDigits); };
  out += std::to_string(index) + ',' + fmt_fixed(p.t_s, 6) + ',';
  out += mm(p.workpiece_origin_mm.x()) + ',' + mm(p.workpiece_origin_mm.y()) + ',' +
         mm(p.workpiece_origin_mm.z()) + ',';
  out += unit(p.workpiece_wxyz[0]) + ',' + unit(p.workpiece_wxyz[1]) + ',' +
         unit(p.workpiece_wxyz[2]) + ',' + unit(p.workpiece_wxyz[3]) + ',';
  out += fmt_fixed(p.speed_mm_per_s, 4) + ',' + (p.extrude ? "1" : "0") + ',' +
         std::to_string(p.layer) + ',' + std::to_string(p.lap) + ',' + feature_name(p) + ',';
  out += mm(p.contact_mm.x()) + ',' + mm(p.contact_mm.y()) + ',' + mm(p.contact_mm.z()) + ',';
  out += unit(p.normal.x()) + ',' + unit(p.normal.y()) + ',' + unit(p.normal.z()) + '\n';
}

std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> cells;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    cells.push_back(line.substr(
        start, comma == std::string_view::npos ? std::string_view::npos : comma - start));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return cells;
}

double number(std::string_view cell, bool& ok) {
  double v = 0.0;
  const auto r = std::from_chars(cell.data(), cell.data() + cell.size(), v);
  ok = ok && r.ec == std::errc() && r.ptr == cell.data() + cell.size() && std::isfinite(v);
  return v;
}

slicer::PosePoint parse_row(const std::vector<std::string_view>& c, bool& ok) {
  slicer::PosePoint p;
  auto n = [&](int i) { return number(c[i], ok); };
  p.t_s = n(1);
  p.workpiece_origin_mm = slicer::Vec3(n(2), n(3), n(4));
  p.workpiece_wxyz = slicer::Quat4(n(5), n(6), n(7), n(8));
  p.speed_mm_per_s = n(9);
  ok = ok && (c[10] == "0" || c[10] == "1");
  p.extrude = c[10] == "1";
  p.layer = static_cast<int>(n(11));
  p.lap = static_cast<int>(n(12));
  if (c[13] != "travel") {
    try {
      p.feature = slicer::feature_from_string(std::string(c[13]));
    } catch (const InputError&) {
      ok = false;
    }
  }
  p.contact_mm = slicer::Vec3(n(14), n(15), n(16));
  p.normal = slicer::Vec3(n(17), n(18), n(19));
  return p;
}

}  // namespace

std::string write_pose_csv(const slicer::PoseProgram& program) {
  std::string out = std::string(kPoseCsvHeader) + '\n';
  out.reserve(program.points.size() * 200);
  for (std::size_t i = 0; i < program.points.size(); ++i) append_row(out, i, program.points[i]);
  return out;
}

std::vector<slicer::PosePoint> read_pose_csv(std::string_view text, const std::string& file) {
  std::vector<slicer::PosePoint> rows;
  std::size_t pos = 0;
  int line_no = 0;
  while (pos < text.size()) {
    std::size_t nl = text.find('\n', pos);
    if (nl == std::string_view::npos) nl = text.size();
    std::string_view line = text.substr(pos, nl - pos);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    pos = nl + 1;
    ++line_no;
    if (line_no == 1) {
      if (line != kPoseCsvHeader) {
        throw InputError("input = " + file + ": line 1 must be the pose CSV header " +
                         kPoseCsvHeader);
      }
      continue;
    }
    if (line.empty()) continue;
    const auto cells = split(line);
    bool ok = cells.size() == kColumns;
    if (ok) rows.push_back(parse_row(cells, ok));
    if (!ok) {
      throw InputError(
          "input = " + file + ": line " + std::to_string(line_no) +
          ": must have 20 numbers and names as in the header (finite, extrude 0 or 1)");
    }
  }
  if (line_no == 0)
    throw InputError("input = " + file + ": empty (a pose CSV starts with its header)");
  return rows;
}

}  // namespace strand::machines
