// Cutting a MotionProgram into drawable polylines.
#include "postprocess/preview/preview_scene.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "postprocess/plan/arc_segmentation.h"

namespace strand::post {

using slicer::MoveKind;
using slicer::Vec3;

namespace {

bool continues(const PreviewPath& p, const slicer::Move& mv, bool travel) {
  return p.travel == travel && p.layer == mv.layer &&
         (travel || (p.feature == mv.feature && p.tool == mv.tool));
}

void append_move(PreviewPath& path, const Vec3& from, const slicer::Move& mv, double tol) {
  if (!mv.is_arc) {
    path.points_mm.push_back(mv.end_mm);
    return;
  }
  const auto pts = segment_arc(from.head<2>(), mv.center_mm, mv.end_mm.head<2>(), mv.ccw, tol);
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const double f = static_cast<double>(i + 1) / static_cast<double>(pts.size());
    path.points_mm.push_back(Vec3(pts[i].x(), pts[i].y(), from.z() + f * (mv.end_mm.z() - from.z())));
  }
}

void grow(PreviewScene& s, const Vec3& p, bool& first) {
  if (first) {
    s.min_mm = s.max_mm = p;
    first = false;
  }
  s.min_mm = s.min_mm.cwiseMin(p);
  s.max_mm = s.max_mm.cwiseMax(p);
}

// Deposits on layers; else every deposit; else every path.
void compute_bounds(PreviewScene& s) {
  bool first = true;
  for (int pass = 0; pass < 3 && first; ++pass) {
    for (const auto& p : s.paths) {
      if ((pass < 2 && p.travel) || (pass == 0 && p.layer < 0)) continue;
      for (const auto& q : p.points_mm) grow(s, q, first);
    }
  }
}

}  // namespace

PreviewScene preview_scene(const slicer::MotionProgram& program, double arc_tolerance_mm,
                           std::vector<std::string> pen_colours) {
  PreviewScene s;
  s.pen_colours = std::move(pen_colours);
  for (const auto& l : program.layers) s.layer_z_mm.push_back(l.z_mm);
  Vec3 at = program.start_mm;
  bool open = false;  // the last path ends at `at`
  for (const auto& mv : program.moves) {
    if (mv.kind == MoveKind::Dwell || mv.kind == MoveKind::Raw) continue;
    const bool travel = mv.kind == MoveKind::Travel;
    if (!open || !continues(s.paths.back(), mv, travel)) {
      PreviewPath p;
      p.layer = mv.layer;
      p.feature = mv.feature;
      p.tool = mv.tool;
      p.travel = travel;
      p.points_mm.push_back(at);
      s.paths.push_back(std::move(p));
    }
    append_move(s.paths.back(), at, mv, arc_tolerance_mm);
    if (!travel) s.bead_width_mm = std::max(s.bead_width_mm, mv.width_mm);
    if (!travel && mv.feature != slicer::Feature::Pen && mv.tool != 0) s.by_tool = true;
    at = mv.end_mm;
    open = true;
  }
  compute_bounds(s);
  return s;
}

PreviewScene scene_from_paths(std::vector<PreviewPath> paths, std::vector<double> layer_offsets_mm,
                              slicer::TriangleMesh substrate, double bead_width_mm) {
  for (const auto& p : paths) {
    if (p.points_mm.size() < 2) {
      throw std::invalid_argument("scene_from_paths: a path needs two points");
    }
    for (const auto& q : p.points_mm) {
      if (!q.allFinite()) throw std::invalid_argument("scene_from_paths: non-finite point");
    }
  }
  PreviewScene s;
  s.paths = std::move(paths);
  s.layer_z_mm = std::move(layer_offsets_mm);
  s.substrate = std::move(substrate);
  s.bead_width_mm = bead_width_mm;
  s.layer_value = "offset";
  compute_bounds(s);
  return s;
}

bool is_3d(const PreviewScene& s) {
  if (!s.substrate.triangles.empty()) return true;
  for (const auto& p : s.paths) {
    if (p.travel || p.layer < 0 || p.layer >= static_cast<int>(s.layer_z_mm.size())) continue;
    const double z = s.layer_z_mm[static_cast<std::size_t>(p.layer)];
    for (const auto& q : p.points_mm) {
      if (std::abs(q.z() - z) > 1e-3) return true;
    }
  }
  return false;
}

Rgb feature_colour(slicer::Feature f) {
  switch (f) {
    case slicer::Feature::Infill: return {0.69, 0.19, 0.16};    // PrusaSlicer solid infill red
    case slicer::Feature::Wall: return {1.0, 0.55, 0.0};        // perimeter orange
    case slicer::Feature::Ligament: return {0.12, 0.47, 0.71};
    case slicer::Feature::Node: return {0.17, 0.63, 0.17};
    case slicer::Feature::Grip: return {0.58, 0.40, 0.74};
    case slicer::Feature::Frame: return {0.55, 0.34, 0.29};
    case slicer::Feature::Link: return {0.50, 0.50, 0.50};
    case slicer::Feature::Pen: return {0.10, 0.10, 0.10};
  }
  return {0, 0, 0};
}

Rgb layer_colour(int layer, int layer_count) {
  const double t = layer_count > 1 ? std::clamp(static_cast<double>(layer) / (layer_count - 1), 0.0, 1.0) : 0.0;
  return {0.15 + 0.8 * t, 0.3 + 0.3 * (1.0 - std::abs(2.0 * t - 1.0)), 0.95 - 0.8 * t};
}

std::string hex_colour(const Rgb& c) {
  char text[8];
  auto byte = [](double v) { return static_cast<int>(std::lround(std::clamp(v, 0.0, 1.0) * 255.0)); };
  std::snprintf(text, sizeof text, "#%02x%02x%02x", byte(c.r), byte(c.g), byte(c.b));
  return text;
}

std::optional<Rgb> parse_hex_colour(const std::string& text) {
  if (text.size() != 7 || text[0] != '#' ||
      text.find_first_not_of("0123456789abcdefABCDEF", 1) != std::string::npos)
    return std::nullopt;
  const auto byte = [&](std::size_t at) {
    return std::stoi(text.substr(at, 2), nullptr, 16) / 255.0;
  };
  return Rgb{byte(1), byte(3), byte(5)};
}

PreviewKey deposit_key(const PreviewScene& scene, const PreviewPath& path) {
  if (path.feature != slicer::Feature::Pen && scene.by_tool) {
    // Printheads: blue, orange, green, ... (Tableau 10), far apart on any background.
    static const Rgb kTools[] = {{0.12, 0.47, 0.71}, {1.00, 0.50, 0.05}, {0.17, 0.63, 0.17}, {0.84, 0.15, 0.16},
                                 {0.58, 0.40, 0.74}, {0.55, 0.34, 0.29}, {0.89, 0.47, 0.76}, {0.09, 0.75, 0.81}};
    const auto k = static_cast<std::size_t>(std::max(path.tool, 0));
    return {"tool " + std::to_string(k), kTools[k % std::size(kTools)]};
  }
  if (path.feature != slicer::Feature::Pen) {
    return {slicer::to_string(path.feature), feature_colour(path.feature)};
  }
  const int tool = std::max(path.tool, 0);
  const auto k = static_cast<std::size_t>(tool);
  if (k < scene.pen_colours.size()) {
    if (const auto c = parse_hex_colour(scene.pen_colours[k])) {
      return {"pen " + std::to_string(tool + 1) + " " + scene.pen_colours[k], *c};
    }
  }
  // pens without a colour: dark grey, then colours far apart (Tableau 10)
  static const Rgb kPens[] = {{0.10, 0.10, 0.10}, {0.12, 0.47, 0.71}, {0.84, 0.15, 0.16},
                              {0.17, 0.63, 0.17}, {1.00, 0.50, 0.05}, {0.58, 0.40, 0.74},
                              {0.55, 0.34, 0.29}, {0.89, 0.47, 0.76}, {0.09, 0.75, 0.81}};
  return {"pen " + std::to_string(tool + 1), kPens[k % std::size(kPens)]};
}

std::vector<PreviewKey> deposit_keys(const PreviewScene& scene,
                                     const std::function<bool(const PreviewPath&)>& keep) {
  std::vector<std::pair<slicer::Feature, int>> used;
  std::vector<const PreviewPath*> first;
  for (const auto& p : scene.paths) {
    if (p.travel || (keep && !keep(p))) continue;
    const bool by_tool = p.feature != slicer::Feature::Pen && scene.by_tool;
    const int tool = p.feature == slicer::Feature::Pen || by_tool ? p.tool : 0;
    const slicer::Feature feature = by_tool ? slicer::Feature::Infill : p.feature;
    if (std::find(used.begin(), used.end(), std::pair{feature, tool}) != used.end()) continue;
    used.emplace_back(feature, tool);
    first.push_back(&p);
  }
  std::vector<std::size_t> order(used.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return used[a] < used[b]; });
  std::vector<PreviewKey> out;
  for (std::size_t i : order) out.push_back(deposit_key(scene, *first[i]));
  return out;
}

}  // namespace strand::post
