// SVG top view of a layer: one <path> per run of same-feature deposits or travels, then
// the contact markers and a scale bar. Numbers use the G-code formatter (3 decimals).
#include "postprocess/preview/svg_layer.h"

#include <algorithm>
#include <cmath>

#include "machines/gcode_format.h"
#include "postprocess/plan/arc_segmentation.h"

namespace strand::post {

using slicer::Feature;
using slicer::MoveKind;
using slicer::Vec2;

namespace {

std::string num(double v) { return machines::fmt_xyz(v); }

// Feature colours (colour-blind safe Okabe-Ito palette where possible).
const char* colour(Feature f) {
  switch (f) {
    case Feature::Infill:
      return "#0072b2";
    case Feature::Wall:
      return "#009e73";
    case Feature::Ligament:
      return "#56b4e9";
    case Feature::Node:
      return "#cc79a7";
    case Feature::Grip:
      return "#e69f00";
    case Feature::Frame:
      return "#999933";
    case Feature::Link:
      return "#888888";
    case Feature::Pen:
      return "#000000";
  }
  return "#000000";
}

struct Run {
  bool deposit = false;
  Feature feature = Feature::Infill;
  double width_mm = 0.0;
  std::vector<Vec2> points;  // y already flipped for SVG
};

struct Bounds {
  Vec2 lo = Vec2::Constant(INFINITY), hi = Vec2::Constant(-INFINITY);
  void add(const Vec2& p) { lo = lo.cwiseMin(p), hi = hi.cwiseMax(p); }
};

Vec2 flip(const Vec2& p) { return {p.x(), -p.y()}; }

// Runs of consecutive moves of the layer with the same kind, feature and width.
std::vector<Run> collect_runs(const slicer::MotionProgram& p, int layer, double tol) {
  std::vector<Run> runs;
  slicer::Vec3 at = p.start_mm;
  for (const auto& mv : p.moves) {
    if (mv.kind == MoveKind::Raw || mv.kind == MoveKind::Dwell) continue;
    const Vec2 from = at.head<2>(), to = mv.end_mm.head<2>();
    at = mv.end_mm;
    if (mv.layer != layer || ((to - from).norm() == 0.0 && !mv.is_arc)) continue;
    const bool dep = mv.kind == MoveKind::Deposit;
    const bool joins = !runs.empty() && runs.back().deposit == dep &&
                       runs.back().feature == mv.feature && runs.back().width_mm == mv.width_mm &&
                       (runs.back().points.back() - flip(from)).norm() == 0.0;
    if (!joins) runs.push_back({dep, mv.feature, mv.width_mm, {flip(from)}});
    if (mv.is_arc) {
      for (const Vec2& q : segment_arc(from, mv.center_mm, to, mv.ccw, tol))
        runs.back().points.push_back(flip(q));
    } else {
      runs.back().points.push_back(flip(to));
    }
  }
  return runs;
}

// The drawing's extent: deposits and marks; travels only when the layer has no deposit
// (a travel from the machine's home would otherwise shrink the part to a dot).
Bounds bounds_of(const std::vector<Run>& runs, const LayerMarks& marks) {
  Bounds b;
  for (const Run& r : runs) {
    for (const Vec2& p : r.points) {
      if (r.deposit) b.add(flip(p));
    }
  }
  for (const auto& c : marks.crossings) b.add(c.at_mm);
  for (const auto& c : marks.touches) b.add(c.at_mm);
  if (!std::isfinite(b.lo.x())) {
    for (const Run& r : runs) {
      for (const Vec2& p : r.points) b.add(flip(p));
    }
  }
  if (!std::isfinite(b.lo.x())) b.add(Vec2::Zero()), b.add(Vec2(1, 1));
  return b;
}

std::string path_d(const std::vector<Vec2>& pts) {
  std::string d = "M" + num(pts[0].x()) + " " + num(pts[0].y());
  for (std::size_t i = 1; i < pts.size(); ++i) d += " L" + num(pts[i].x()) + " " + num(pts[i].y());
  return d;
}

std::string run_svg(const Run& r, double default_width_mm) {
  if (!r.deposit) {
    return "<path d=\"" + path_d(r.points) + "\" fill=\"none\" stroke=\"#777777\" stroke-width=\"" +
           num(default_width_mm / 4) + "\" stroke-dasharray=\"" + num(default_width_mm) + " " +
           num(default_width_mm) + "\"/>\n";
  }
  const double w = r.width_mm > 0 ? r.width_mm : default_width_mm;
  return "<path class=\"" + slicer::to_string(r.feature) + "\" d=\"" + path_d(r.points) +
         "\" fill=\"none\" stroke=\"" + colour(r.feature) +
         "\" stroke-opacity=\"0.7\" stroke-width=\"" + num(w) +
         "\" stroke-linecap=\"round\" stroke-linejoin=\"round\"/>\n";
}

std::string markers(const std::vector<Contact>& cs, const char* stroke, double radius_mm) {
  std::string out;
  for (const auto& c : cs) {
    out += "<circle cx=\"" + num(c.at_mm.x()) + "\" cy=\"" + num(-c.at_mm.y()) + "\" r=\"" +
           num(radius_mm) + "\" fill=\"none\" stroke=\"" + stroke + "\" stroke-width=\"" +
           num(radius_mm / 4) + "\"/>\n";
  }
  return out;
}

// A bar of a round length (1, 2 or 5 x 10^k mm), about a fifth of the drawing's larger
// side but at most half its width, bottom left.
std::string scale_bar(const Vec2& lo, const Vec2& hi, double margin) {
  const double size = std::max(hi.x() - lo.x(), hi.y() - lo.y());
  const double target = std::min(size / 5, (hi.x() - lo.x() + 2 * margin) / 2);
  const double p10 = std::pow(10.0, std::floor(std::log10(std::max(target, 1e-3))));
  const double len = target >= 5 * p10 ? 5 * p10 : (target >= 2 * p10 ? 2 * p10 : p10);
  const double x = lo.x(), y = hi.y() + margin * 0.6, t = margin * 0.15;
  return "<g class=\"scale\"><rect x=\"" + num(x) + "\" y=\"" + num(y - t / 2) + "\" width=\"" +
         num(len) + "\" height=\"" + num(t) + "\" fill=\"#000000\"/><text x=\"" + num(x + len + t) +
         "\" y=\"" + num(y + t) + "\" font-size=\"" + num(margin * 0.4) +
         "\" font-family=\"sans-serif\">" + machines::fmt_fixed(len, len < 1 ? 3 : 0) +
         " mm</text></g>\n";
}

// One swatch and name per feature drawn, in enum order, along the top margin.
std::string legend(const std::vector<Run>& runs, const Vec2& lo, double margin) {
  std::vector<bool> present(static_cast<std::size_t>(Feature::Pen) + 1, false);
  for (const Run& r : runs) {
    if (r.deposit) present[static_cast<std::size_t>(r.feature)] = true;
  }
  std::string out = "<g class=\"legend\">";
  double x = lo.x();
  const double y = lo.y() - margin * 0.5, t = margin * 0.15;
  for (std::size_t f = 0; f < present.size(); ++f) {
    if (!present[f]) continue;
    const std::string name = slicer::to_string(static_cast<Feature>(f));
    out += "<rect x=\"" + num(x) + "\" y=\"" + num(y - t) + "\" width=\"" + num(margin * 0.6) +
           "\" height=\"" + num(2 * t) + "\" fill=\"" + colour(static_cast<Feature>(f)) +
           "\"/><text x=\"" + num(x + margin * 0.7) + "\" y=\"" + num(y + t) + "\" font-size=\"" +
           num(margin * 0.4) + "\" font-family=\"sans-serif\">" + name + "</text>";
    x += margin * (1.0 + 0.25 * static_cast<double>(name.size()));
  }
  return out + "</g>\n";
}

}  // namespace

std::string layer_svg(const slicer::MotionProgram& p, int layer, const LayerMarks& marks,
                      double tol) {
  const std::vector<Run> runs = collect_runs(p, layer, tol);
  const Bounds b = bounds_of(runs, marks);
  const Vec2 lo = flip(Vec2(b.lo.x(), b.hi.y())), hi = flip(Vec2(b.hi.x(), b.lo.y()));
  const double size = std::max({hi.x() - lo.x(), hi.y() - lo.y(), 1.0});
  const double margin = size * 0.08, width = std::clamp(size / 200, 0.05, 0.4);
  std::string out = "<svg xmlns=\"http://www.w3.org/2000/svg\" viewBox=\"" + num(lo.x() - margin) +
                    " " + num(lo.y() - margin) + " " + num(hi.x() - lo.x() + 2 * margin) + " " +
                    num(hi.y() - lo.y() + 2 * margin) + "\" width=\"" +
                    num(hi.x() - lo.x() + 2 * margin) + "mm\" height=\"" +
                    num(hi.y() - lo.y() + 2 * margin) + "mm\">\n";
  out += "<title>layer " + std::to_string(layer) + " (top view, mm)</title>\n";
  out += "<rect x=\"" + num(lo.x() - margin) + "\" y=\"" + num(lo.y() - margin) + "\" width=\"" +
         num(hi.x() - lo.x() + 2 * margin) + "\" height=\"" + num(hi.y() - lo.y() + 2 * margin) +
         "\" fill=\"#ffffff\"/>\n";
  for (const Run& r : runs) out += run_svg(r, width);
  const double mark_r = std::max(size / 60, 0.3);
  out += markers(marks.touches, "#ff8c00", mark_r);
  out += markers(marks.crossings, "#e00000", mark_r);
  out += scale_bar(lo, hi, margin);
  out += legend(runs, lo, margin);
  return out + "</svg>\n";
}

}  // namespace strand::post
