// Toolpath helpers: names, lengths, bounds, reversal, JSON dump.
#include "slicer/toolpath.h"

#include <array>
#include <cmath>
#include <limits>

#include "slicer/input_error.h"
#include "slicer/units.h"

namespace strand::slicer {

namespace {

struct FeatureName {
  Feature feature;
  const char* name;
};
constexpr std::array<FeatureName, 8> kFeatureNames = {{
    {Feature::Infill, "infill"},
    {Feature::Wall, "wall"},
    {Feature::Ligament, "ligament"},
    {Feature::Node, "node"},
    {Feature::Grip, "grip"},
    {Feature::Frame, "frame"},
    {Feature::Link, "link"},
    {Feature::Pen, "pen"},
}};

void grow(std::pair<Vec2, Vec2>& box, const Vec2& p) {
  box.first = box.first.cwiseMin(p);
  box.second = box.second.cwiseMax(p);
}

// Adds the arc's end points and every axis extreme its sweep passes.
void grow_arc(std::pair<Vec2, Vec2>& box, const Vec2& from, const Segment& s) {
  grow(box, s.end_mm);
  const double r = (from - s.center_mm).norm();
  const double a0 = angle_of(s.center_mm, from);
  const double sweep = arc_sweep(s.center_mm, from, s.end_mm, s.ccw);
  for (int k = -4; k <= 4; ++k) {
    const double a = k * kPi / 2.0;
    const double rel = wrap_period(s.ccw ? a - a0 : a0 - a, kTwoPi);
    if (rel <= std::abs(sweep)) grow(box, on_circle(s.center_mm, r, a));
  }
}

}  // namespace

std::string to_string(Feature f) {
  for (const auto& fn : kFeatureNames) {
    if (fn.feature == f) return fn.name;
  }
  return "unknown";
}

Feature feature_from_string(const std::string& name) {
  for (const auto& fn : kFeatureNames) {
    if (name == fn.name) return fn.feature;
  }
  throw InputError("feature = " + name +
                   ": must be one of infill, wall, ligament, node, grip, frame, link, pen");
}

Segment line_to(const Vec2& end_mm, Feature feature) {
  return Segment{SegmentKind::Line, end_mm, Vec2::Zero(), true, feature};
}

Segment arc_to(const Vec2& end_mm, const Vec2& center_mm, bool ccw, Feature feature) {
  return Segment{SegmentKind::Arc, end_mm, center_mm, ccw, feature};
}

double segment_length(const Vec2& from, const Segment& s) {
  if (s.kind == SegmentKind::Line) return (s.end_mm - from).norm();
  const double r = (from - s.center_mm).norm();
  return r * std::abs(arc_sweep(s.center_mm, from, s.end_mm, s.ccw));
}

double stroke_length(const Stroke& s) {
  double total = 0.0;
  Vec2 at = s.start_mm;
  for (const auto& seg : s.segments) {
    total += segment_length(at, seg);
    at = seg.end_mm;
  }
  return total;
}

std::pair<Vec2, Vec2> bounds(const Toolpath& t) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  std::pair<Vec2, Vec2> box{Vec2(kInf, kInf), Vec2(-kInf, -kInf)};
  for (const auto& layer : t.layers) {
    for (const auto& stroke : layer.strokes) {
      grow(box, stroke.start_mm);
      Vec2 at = stroke.start_mm;
      for (const auto& seg : stroke.segments) {
        if (seg.kind == SegmentKind::Arc) {
          grow_arc(box, at, seg);
        } else {
          grow(box, seg.end_mm);
        }
        at = seg.end_mm;
      }
    }
  }
  return box;
}

Stroke reversed(const Stroke& s) {
  Stroke r = s;
  r.segments.clear();
  r.start_mm = s.end_mm();
  for (std::size_t i = s.segments.size(); i-- > 0;) {
    const Segment& seg = s.segments[i];
    const Vec2 start = i == 0 ? s.start_mm : s.segments[i - 1].end_mm;
    Segment back = seg;
    back.end_mm = start;
    back.ccw = !seg.ccw;
    r.segments.push_back(back);
  }
  return r;
}

std::vector<Stroke> nearest_first(std::vector<Stroke> strokes, Vec2& at) {
  std::vector<Stroke> out;
  while (!strokes.empty()) {
    std::size_t best = 0;
    bool flip = false;
    double best_d = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < strokes.size(); ++i) {
      const double ds = (strokes[i].start_mm - at).norm(), de = (strokes[i].end_mm() - at).norm();
      if (ds < best_d - 1e-9) best_d = ds, best = i, flip = false;
      if (de < best_d - 1e-9) best_d = de, best = i, flip = true;
    }
    out.push_back(flip ? reversed(strokes[best]) : strokes[best]);
    at = out.back().end_mm();
    strokes.erase(strokes.begin() + static_cast<std::ptrdiff_t>(best));
  }
  return out;
}

nlohmann::json to_json(const Toolpath& t) {
  nlohmann::json layers = nlohmann::json::array();
  for (const auto& layer : t.layers) {
    nlohmann::json strokes = nlohmann::json::array();
    for (const auto& s : layer.strokes) {
      nlohmann::json segs = nlohmann::json::array();
      for (const auto& seg : s.segments) {
        nlohmann::json j = {{"end", {seg.end_mm.x(), seg.end_mm.y()}},
                            {"feature", to_string(seg.feature)}};
        if (seg.kind == SegmentKind::Arc) {
          j["center"] = {seg.center_mm.x(), seg.center_mm.y()};
          j["ccw"] = seg.ccw;
        }
        segs.push_back(j);
      }
      strokes.push_back({{"start", {s.start_mm.x(), s.start_mm.y()}},
                         {"width_mm", s.width_mm},
                         {"segments", segs}});
    }
    layers.push_back({{"z_mm", layer.z_mm}, {"strokes", strokes}});
  }
  return {{"generator", t.generator},
          {"parameters", t.parameters},
          {"derived", t.derived},
          {"layers", layers}};
}

}  // namespace strand::slicer

namespace strand::slicer {

double bead_area_mm2(double w, double h) {
  if (h <= w) return (w - h) * h + kPi * h * h / 4.0;
  return kPi * w * h / 4.0;
}

}  // namespace strand::slicer
