// Region patterns from the generators' own tables: scaffold lines on a fixed grid, lattice
// layers generated once (big enough to cover the part) and flattened to polylines.
#include "patterns/region_pattern.h"

#include <algorithm>
#include <cmath>

#include "patterns/scaffold.h"
#include "slicer/input_error.h"
#include "slicer/tolerances.h"
#include "slicer/units.h"

namespace strand::patterns {

using slicer::Vec2;

namespace {

const char* const kExtentKeys[] = {"size", "rows", "cols", "height", "layers", "overhang", "grip"};
// Lattices are generated at most this many cells across (the tables' own bound is 500).
constexpr int kMaxLatticeCells = 400;

// Arc from `from` around `center` to `to` as chords within kDefaultArcToleranceMm.
void flatten_arc(const Vec2& from, const slicer::Segment& s, PatternLine& out) {
  const double r = (from - s.center_mm).norm();
  const double sweep = slicer::arc_sweep(s.center_mm, from, s.end_mm, s.ccw);
  const double tol = std::min(slicer::kDefaultArcToleranceMm, r / 2);
  const double step = r > 0 ? 2.0 * std::acos(1.0 - tol / r) : std::abs(sweep);
  const int n = std::max(1, static_cast<int>(std::ceil(std::abs(sweep) / std::max(step, 1e-6))));
  const double a0 = slicer::angle_of(s.center_mm, from);
  for (int k = 1; k < n; ++k) {
    out.points.push_back(slicer::on_circle(s.center_mm, r, a0 + sweep * k / n));
    out.features.push_back(s.feature);
  }
  out.points.push_back(s.end_mm);
  out.features.push_back(s.feature);
}

PatternLine flattened(const slicer::Stroke& s) {
  PatternLine line;
  line.points.push_back(s.start_mm);
  Vec2 at = s.start_mm;
  for (const auto& seg : s.segments) {
    if (seg.kind == slicer::SegmentKind::Arc) {
      flatten_arc(at, seg, line);
    } else {
      line.points.push_back(seg.end_mm);
      line.features.push_back(seg.feature);
    }
    at = seg.end_mm;
  }
  return line;
}

// Generates one layer of a lattice with `cells` rows and columns (even).
slicer::Toolpath lattice_layer(const GeneratorSpec& g, nlohmann::json values, int cols, int rows) {
  values.erase("height");
  values["layers"] = 1;
  values["rows"] = rows;
  values["cols"] = cols;
  if (g.table().defs.end() != std::find_if(g.table().defs.begin(), g.table().defs.end(),
                                           [](const auto& d) { return d.key == "grip"; })) {
    values["grip"] = 0.0;
  }
  return g.generate(slicer::resolve_params(g.table(), values));
}

int even_cells(double need_mm, double cell_mm) {
  const int n = static_cast<int>(std::ceil(need_mm / cell_mm)) + 2;
  return n + (n % 2);
}

// Lattice big enough for the part: a 4 x 4 probe gives the cell size, then the real one.
void build_lattice(const GeneratorSpec& g, const nlohmann::json& values, const Vec2& half,
                   RegionPattern& p) {
  const slicer::Toolpath probe = lattice_layer(g, values, 4, 4);
  p.layer_height_mm = probe.layers.front().height_mm;
  const auto [lo, hi] = slicer::bounds(probe);
  const Vec2 cell = (hi - lo) / 4.0;
  const int cols = even_cells(2 * half.x() + 2 * cell.x(), cell.x());
  const int rows = even_cells(2 * half.y() + 2 * cell.y(), cell.y());
  if (std::max(cols, rows) > kMaxLatticeCells) {
    throw InputError("slice: the part needs " + std::to_string(std::max(cols, rows)) + " " +
                     g.name + " cells across; at most " + std::to_string(kMaxLatticeCells) +
                     " (use a larger cell)");
  }
  const slicer::Toolpath t = lattice_layer(g, values, cols, rows);
  double central_length = 0.0;
  const auto [tlo, thi] = slicer::bounds(t);
  const Vec2 c = (tlo + thi) / 2.0, q = (thi - tlo) / 4.0;  // central half: [c - q, c + q]
  for (const auto& s : t.layers.front().strokes) {
    PatternLine line = flattened(s);
    for (std::size_t i = 0; i + 1 < line.points.size(); ++i) {
      const Vec2 m = (line.points[i] + line.points[i + 1]) / 2.0 - c;
      if (std::abs(m.x()) < q.x() && std::abs(m.y()) < q.y())
        central_length += (line.points[i + 1] - line.points[i]).norm();
    }
    p.lattice.push_back(std::move(line));
  }
  const double area = slicer::bead_area_mm2(p.nozzle_mm, p.layer_height_mm);
  p.porosity = 1.0 - central_length * area / (4.0 * q.x() * q.y() * p.layer_height_mm);
}

}  // namespace

bool is_extent_key(const std::string& key) {
  return std::find(std::begin(kExtentKeys), std::end(kExtentKeys), key) != std::end(kExtentKeys);
}

RegionPattern region_pattern(const GeneratorSpec& g, const nlohmann::json& given,
                             const Vec2& half) {
  std::vector<std::string> problems;
  for (const auto& [k, v] : given.items()) {
    if (is_extent_key(k)) {
      problems.push_back(g.name + "." + k + " = " + slicer::value_text(v) +
                         ": makes no sense for a sliced part (its shape sets the extent)");
    }
  }
  if (!problems.empty()) throw InputError(problems);
  RegionPattern p;
  p.name = g.name;
  nlohmann::json probe = given;
  probe["layers"] = 1;
  p.values = slicer::resolve_params(g.table(), probe);
  for (const char* k : kExtentKeys) p.values.erase(k);
  if (g.name == "scaffold") {
    probe["size"] = nlohmann::json::array({2 * half.x() + 1.0, 2 * half.y() + 1.0});
    const ScaffoldParams s = scaffold_params_from(slicer::resolve_params(g.table(), probe));
    if (s.grade.axis != GradeAxis::None || s.stagger) {
      throw InputError(std::string("scaffold.") + (s.stagger ? "stagger" : "grade") +
                       ": not for a sliced part's fill (use strand scaffold)");
    }
    p.nozzle_mm = s.nozzle_mm;
    p.layer_height_mm = s.layer_height_mm;
    p.speed_mm_per_min = s.speed_mm_per_min;
    p.pitch_mm = s.pitch_mm;
    p.angles_deg = s.angles_deg;
    p.min_piece_mm = s.nozzle_mm;
    p.porosity = 1.0 - slicer::bead_area_mm2(s.nozzle_mm, s.layer_height_mm) /
                           (s.pitch_mm * s.layer_height_mm);
    return p;
  }
  const nlohmann::json values = slicer::resolve_params(g.table(), probe);
  p.nozzle_mm = values.at("nozzle").get<double>();
  p.speed_mm_per_min = values.at("speed").get<double>();
  p.connector = slicer::Feature::Frame;
  p.min_piece_mm = 4.0 * p.nozzle_mm;
  build_lattice(g, given, half, p);
  return p;
}

std::vector<PatternLine> pattern_lines(const RegionPattern& p, int layer, const Vec2& half) {
  if (!p.lattice.empty()) return p.lattice;
  const double a =
      slicer::deg_to_rad(p.angles_deg[static_cast<std::size_t>(layer) % p.angles_deg.size()]);
  const Vec2 u(std::cos(a), std::sin(a)), n(-std::sin(a), std::cos(a));
  const double reach = half.norm() + p.pitch_mm;
  const int k = static_cast<int>(std::ceil(reach / p.pitch_mm));
  std::vector<PatternLine> out;
  for (int i = -k; i <= k; ++i) {
    const Vec2 c = (i * p.pitch_mm) * n;
    out.push_back({{c - reach * u, c + reach * u}, {slicer::Feature::Infill}, i + k});
  }
  return out;
}

}  // namespace strand::patterns
