// Log-pile scaffold geometry. Each layer: parallel lines clipped to the footprint grown by
// the overhang, joined into one serpentine by connectors that run along that grown
// rectangle, so every U-turn lies outside the footprint and nothing crosses. Layers after
// the first begin with a link that runs further out, from the previous layer's end to the
// nearest possible start of the new serpentine.
#include "patterns/scaffold.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "patterns/scaffold_grade.h"
#include "patterns/scaffold_plan.h"
#include "patterns/scaffold_zones.h"
#include "slicer/tolerances.h"
#include "slicer/units.h"

namespace strand::patterns {

using slicer::Feature;
using slicer::Segment;
using slicer::Stroke;
using slicer::Vec2;

namespace {

// Axis-aligned rectangle centred on the origin, walked counter-clockwise from (hx, -hy).
struct Rect {
  double hx = 0.0;
  double hy = 0.0;
  double perimeter() const { return 4.0 * (hx + hy); }
  std::array<Vec2, 4> corners() const {  // at t = 2hy, 2hy+2hx, 4hy+2hx, 0 (= perimeter)
    return {Vec2(hx, hy), Vec2(-hx, hy), Vec2(-hx, -hy), Vec2(hx, -hy)};
  }
  std::array<double, 4> corner_params() const {
    return {2 * hy, 2 * hy + 2 * hx, 4 * hy + 2 * hx, perimeter()};
  }
};

// Perimeter parameter of a point on the rectangle's boundary.
double param_of(const Rect& r, const Vec2& p) {
  const double dx_right = std::abs(p.x() - r.hx), dy_top = std::abs(p.y() - r.hy);
  const double dx_left = std::abs(p.x() + r.hx), dy_bottom = std::abs(p.y() + r.hy);
  const double m = std::min({dx_right, dy_top, dx_left, dy_bottom});
  if (m == dx_right) return p.y() + r.hy;
  if (m == dy_top) return 2 * r.hy + (r.hx - p.x());
  if (m == dx_left) return 2 * r.hy + 2 * r.hx + (r.hy - p.y());
  return 4 * r.hy + 2 * r.hx + (p.x() + r.hx);
}

Vec2 outward_normal(const Rect& r, const Vec2& p) {
  const double t = param_of(r, p);
  const auto c = r.corner_params();
  if (t < c[0]) return Vec2(1, 0);
  if (t < c[1]) return Vec2(0, 1);
  if (t < c[2]) return Vec2(-1, 0);
  return Vec2(0, -1);
}

// Corners passed when walking the boundary from `from` to `to`, then `to` itself.
std::vector<Vec2> walk(const Rect& r, const Vec2& from, const Vec2& to, bool ccw) {
  const double per = r.perimeter();
  const double t0 = param_of(r, from);
  const double dist = ccw ? slicer::wrap_period(param_of(r, to) - t0, per) : slicer::wrap_period(t0 - param_of(r, to), per);
  const auto corners = r.corners();
  const auto cp = r.corner_params();
  std::vector<std::pair<double, Vec2>> passed;
  for (int i = 0; i < 4; ++i) {
    const double along = ccw ? slicer::wrap_period(cp[i] - t0, per) : slicer::wrap_period(t0 - cp[i], per);
    if (along > 1e-9 && along < dist - 1e-9) passed.emplace_back(along, corners[i]);
  }
  std::sort(passed.begin(), passed.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<Vec2> out;
  for (const auto& p : passed) out.push_back(p.second);
  out.push_back(to);
  return out;
}

// Is `t` strictly inside the ccw (or cw) walk from t0 to t1?
bool on_walk(double per, double t0, double t1, double t, bool ccw) {
  const double dist = ccw ? slicer::wrap_period(t1 - t0, per) : slicer::wrap_period(t0 - t1, per);
  const double along = ccw ? slicer::wrap_period(t - t0, per) : slicer::wrap_period(t0 - t, per);
  return along > 1e-9 && along < dist - 1e-9;
}

// Parameter range [s0, s1] of the line c*n + s*u inside the rectangle; empty if s0 > s1.
std::pair<double, double> clip(const Rect& r, const Vec2& n, const Vec2& u, double c) {
  double s0 = -std::numeric_limits<double>::infinity(), s1 = -s0;
  const Vec2 base = c * n;
  const double half[2] = {r.hx, r.hy};
  for (int k = 0; k < 2; ++k) {
    if (std::abs(u[k]) < 1e-12) {
      if (std::abs(base[k]) > half[k] + 1e-9) return {1, 0};
      continue;
    }
    double a = (-half[k] - base[k]) / u[k], b = (half[k] - base[k]) / u[k];
    if (a > b) std::swap(a, b);
    s0 = std::max(s0, a);
    s1 = std::min(s1, b);
  }
  return {s0, s1};
}

struct LayerLines {
  Vec2 u, n;
  std::vector<double> offsets;              // c of each line c*n + s*u, ascending
  std::vector<std::pair<Vec2, Vec2>> ends;  // (u- end, u+ end) on the grown rectangle
  double inside_length_mm = 0.0;            // filament length inside the footprint
};

// Offsets of a layer's lines along its normal: spread over the extent at the layer's pitch
// and centred, or where a grade along x or y puts them (a layer parallel to the grade's axis
// keeps the pitch of the mean gap).
std::vector<double> line_offsets(const ScaffoldParams& p, const ScaffoldGeometry& g, const Vec2& n,
                                 double extent, double pitch_mm) {
  const GradeAxis axis = p.grade.axis;
  const double n_axis = axis == GradeAxis::X ? n.x() : axis == GradeAxis::Y ? n.y() : 0.0;
  if (std::abs(n_axis) > 1e-9) {
    const bool x = axis == GradeAxis::X;
    return graded_offsets_mm(p.grade, p.nozzle_mm, n_axis, x ? g.width_mm : g.depth_mm,
                             x ? p.width_mm : p.depth_mm, (extent - p.nozzle_mm) / 2);
  }
  const int count = static_cast<int>(std::floor((extent - p.nozzle_mm) / pitch_mm + 1e-9)) + 1;
  std::vector<double> out;
  for (int i = 0; i < count; ++i) out.push_back((i - (count - 1) / 2.0) * pitch_mm);
  return out;
}

LayerLines layer_lines(const ScaffoldParams& p, const ScaffoldGeometry& g, const LayerPlan& plan) {
  LayerLines L;
  const double a = slicer::deg_to_rad(plan.angle_deg);
  L.u = Vec2(std::cos(a), std::sin(a));
  L.n = Vec2(-std::sin(a), std::cos(a));
  const Rect foot{g.width_mm / 2, g.depth_mm / 2};
  const Rect grown{foot.hx + p.overhang_mm, foot.hy + p.overhang_mm};
  const double extent = g.width_mm * std::abs(L.n.x()) + g.depth_mm * std::abs(L.n.y());
  L.offsets = line_offsets(p, g, L.n, extent, plan.pitch_mm);
  if (plan.staggered && L.offsets.size() > 1) {  // half a pitch over: between the lines
    for (std::size_t i = 0; i + 1 < L.offsets.size(); ++i) L.offsets[i] = (L.offsets[i] + L.offsets[i + 1]) / 2;
    L.offsets.pop_back();
  }
  for (const double c : L.offsets) {
    const auto [s0, s1] = clip(grown, L.n, L.u, c);
    const auto [f0, f1] = clip(foot, L.n, L.u, c);
    L.ends.emplace_back(c * L.n + s0 * L.u, c * L.n + s1 * L.u);
    L.inside_length_mm += std::max(0.0, f1 - f0);
  }
  return L;
}

// One serpentine over the lines; `reverse_order` starts from the last line, `flip` starts
// the first line at its u+ end.
Stroke serpentine(const LayerLines& L, const Rect& grown, bool reverse_order, bool flip) {
  const int n = static_cast<int>(L.ends.size());
  auto line = [&](int k) { return L.ends[static_cast<std::size_t>(reverse_order ? n - 1 - k : k)]; };
  Stroke s;
  const double per = grown.perimeter();
  for (int k = 0; k < n; ++k) {
    const auto [lo, hi] = line(k);
    const bool forward = (k % 2 == 0) != flip;
    const Vec2 from = forward ? lo : hi;
    const Vec2 to = forward ? hi : lo;
    if (k == 0) {
      s.start_mm = from;
    } else {
      const Vec2 at = s.end_mm();
      const auto [plo, phi] = line(k - 1);
      const Vec2 far_prev = forward ? phi : plo;  // the other ends must stay off the walk
      const Vec2 far_next = to;
      const double t0 = param_of(grown, at), t1 = param_of(grown, from);
      const bool ccw = !on_walk(per, t0, t1, param_of(grown, far_prev), true) &&
                       !on_walk(per, t0, t1, param_of(grown, far_next), true);
      for (const Vec2& q : walk(grown, at, from, ccw)) s.segments.push_back(slicer::line_to(q, Feature::Infill));
    }
    s.segments.push_back(slicer::line_to(to, Feature::Infill));
  }
  return s;
}

// Where serpentine(L, grown, reverse_order, flip) starts, without building it.
Vec2 serpentine_start(const LayerLines& L, bool reverse_order, bool flip) {
  if (L.ends.empty()) return Vec2::Zero();
  const auto& [lo, hi] = reverse_order ? L.ends.back() : L.ends.front();
  return flip ? hi : lo;
}

// Link from `from` (end of the previous layer) to `to` (start of this one), outside.
std::vector<Segment> link(const Rect& grown, double clearance, const Vec2& from, const Vec2& to) {
  std::vector<Segment> out;
  if ((from - to).norm() < slicer::kSamePointMm) return out;
  const Rect outer{grown.hx + clearance, grown.hy + clearance};
  const Vec2 a = from + clearance * outward_normal(grown, from);
  const Vec2 b = to + clearance * outward_normal(grown, to);
  const double per = outer.perimeter();
  const bool ccw = slicer::wrap_period(param_of(outer, b) - param_of(outer, a), per) <= per / 2;
  out.push_back(slicer::line_to(a, Feature::Link));
  for (const Vec2& q : walk(outer, a, b, ccw)) out.push_back(slicer::line_to(q, Feature::Link));
  out.push_back(slicer::line_to(to, Feature::Link));
  return out;
}

double bead_area(const ScaffoldParams& p) { return slicer::bead_area_mm2(p.nozzle_mm, p.layer_height_mm); }

}  // namespace

ScaffoldGeometry scaffold_geometry(const ScaffoldParams& p) {
  ScaffoldGeometry g;
  auto count = [&](double side) {
    return std::max(2, static_cast<int>(std::lround((side - p.nozzle_mm) / p.pitch_mm)) + 1);
  };
  g.filaments_x = count(p.width_mm);
  g.filaments_y = count(p.depth_mm);
  g.width_mm = (g.filaments_x - 1) * p.pitch_mm + p.nozzle_mm;
  g.depth_mm = (g.filaments_y - 1) * p.pitch_mm + p.nozzle_mm;
  if (p.grade.axis == GradeAxis::X || p.grade.axis == GradeAxis::Y) {
    const bool x = p.grade.axis == GradeAxis::X;
    const auto centres = graded_centres_mm(p.grade, p.nozzle_mm, x ? p.width_mm : p.depth_mm);
    (x ? g.filaments_x : g.filaments_y) = static_cast<int>(centres.size());
    (x ? g.width_mm : g.depth_mm) = centres.back() + p.nozzle_mm / 2;
  }
  g.height_mm = p.layers * p.layer_height_mm;
  g.link_clearance_mm = p.pitch_mm;
  return g;
}

namespace {

// Layer k is the serpentine of its plan (angle, spacing, stagger) that starts nearest where
// layer k - 1 ended, joined to it by a link outside: each layer needs only the previous one's
// end. The lines are made again per layer (cheap), so memory does not grow with the stack.
class ScaffoldLayers final : public slicer::LayerSource {
 public:
  explicit ScaffoldLayers(const ScaffoldParams& p)
      : p_(p), g_(scaffold_geometry(p)), grown_{g_.width_mm / 2 + p.overhang_mm, g_.depth_mm / 2 + p.overhang_mm},
        plans_(scaffold_layer_plans(p)) {
    const bool zones = p.grade.axis != GradeAxis::None || !p.schedule.empty();
    // A cycle of plans repeats unless a z grade or a schedule changes layers one by one.
    const bool by_layer = p.grade.axis == GradeAxis::Z || !p.schedule.empty();
    const std::size_t cycle = by_layer ? plans_.size() : p.angles_deg.size() * (p.stagger ? 2 : 1);
    double inside_length = 0.0;  // in nozzle-wide beads: each layer's length times its flow
    nlohmann::json per_layer = nlohmann::json::array();
    std::vector<LaidLayer> laid;
    for (std::size_t k = 0; k < plans_.size(); ++k) {
      const LayerLines lines = layer_lines(p, g_, plans_[k]);
      inside_length += lines.inside_length_mm * plans_[k].flow;
      if (k < cycle) per_layer.push_back(lines.ends.size());
      if (zones) {
        const double area = plans_[k].flow * bead_area(p);
        laid.push_back({lines.u, lines.n, lines.offsets, area, plans_[k].width_mm, area * lines.inside_length_mm});
      }
    }
    record.generator = "scaffold";
    record.derived = scaffold_report(p, g_, g_.width_mm, per_layer, inside_length);
    record.derived["link_clearance_mm"] = g_.link_clearance_mm;
    if (p.stagger) record.derived["stagger_mm"] = p.pitch_mm / 2;
    if (p.grade.axis != GradeAxis::None) record.derived["porosity_zones"] = grade_zones(p, g_, laid);
    if (!p.schedule.empty()) {
      record.derived["porosity_by_schedule"] = schedule_zones(p, g_, laid);
      nlohmann::json speeds = nlohmann::json::array();
      for (const auto& plan : plans_) speeds.push_back(plan.speed_mm_per_min);
      record.derived["stroke_speeds_mm_per_min"] = speeds;  // one strand per layer
    }
  }

  std::size_t layer_count() const override { return plans_.size(); }

  slicer::Layer layer(std::size_t k) override {
    const LayerLines lines = layer_lines(p_, g_, plans_[k]);
    // The variant starting nearest the previous layer's end; only that one is built.
    int best = 0;
    double best_gap = std::numeric_limits<double>::infinity();
    for (int variant = 0; variant < (k == 0 || lines.ends.empty() ? 1 : 4); ++variant) {
      const double gap = (serpentine_start(lines, variant & 1, variant & 2) - prev_end_).norm();
      if (gap < best_gap - 1e-9) best_gap = gap, best = variant;
    }
    Stroke stroke = serpentine(lines, grown_, best & 1, best & 2);
    if (k > 0) {
      std::vector<Segment> segs = link(grown_, g_.link_clearance_mm, prev_end_, stroke.start_mm);
      segs.insert(segs.end(), stroke.segments.begin(), stroke.segments.end());
      stroke.start_mm = prev_end_;
      stroke.segments = std::move(segs);
    }
    stroke.width_mm = plans_[k].width_mm;
    stroke.height_mm = p_.layer_height_mm;
    prev_end_ = stroke.end_mm();
    const int layer_number = static_cast<int>(k) + 1;
    return {layer_number * p_.layer_height_mm, p_.layer_height_mm, {std::move(stroke)}};
  }

 private:
  ScaffoldParams p_;
  ScaffoldGeometry g_;
  Rect grown_;
  std::vector<LayerPlan> plans_;
  Vec2 prev_end_ = Vec2::Zero();
};

}  // namespace

std::unique_ptr<slicer::LayerSource> scaffold_layers(const ScaffoldParams& p) {
  return std::make_unique<ScaffoldLayers>(p);
}

slicer::Toolpath generate_scaffold(const ScaffoldParams& p) { return slicer::collect(*scaffold_layers(p)); }

nlohmann::json scaffold_report(const ScaffoldParams& p, const ScaffoldGeometry& g, double width_mm,
                               const nlohmann::json& filaments_per_layer, double inside_length_mm) {
  const double box = width_mm * g.depth_mm * g.height_mm;
  return {
      {"footprint_mm", {width_mm, g.depth_mm}},
      {"filaments_per_layer", filaments_per_layer},
      {"layers", p.layers},
      {"height_mm", g.height_mm},
      {"layer_height_mm", p.layer_height_mm},
      {"pitch_mm", p.pitch_mm},
      {"gap_mm", p.pitch_mm - p.nozzle_mm},
      {"overhang_mm", p.overhang_mm},
      {"bead_area_mm2", bead_area(p)},
      {"porosity", 1.0 - inside_length_mm * bead_area(p) / box},
      {"porosity_formula",
       "1 - (filament length inside the footprint * bead area) / (width * depth * height)"},
  };
}

}  // namespace strand::patterns
