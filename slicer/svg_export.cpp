// SVG output: layers of shapes as <path> elements with exact lines and cubic Béziers.
#include "slicer/svg_export.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace strand::slicer {

namespace {

// Arcs (none come from fonts or potrace) are written as chords this close to the curve, mm.
constexpr double kArcChordMm = 1e-3;
// The page's bounds are taken from curves flattened this finely, mm.
constexpr double kBoundsToleranceMm = 1e-3;

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f", std::abs(v) < 5e-4 ? 0.0 : v);
  return buf;
}

std::string pt(const Vec2& p) { return num(p.x()) + " " + num(p.y()); }

std::string colour(const std::string& c) { return c.empty() ? "#000000" : c; }

std::string escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '&') out += "&amp;";
    else if (c == '<') out += "&lt;";
    else if (c == '"') out += "&quot;";
    else out += c;
  }
  return out;
}

}  // namespace

std::string path_data(const std::vector<SubPath>& paths) {
  std::string d;
  for (const auto& s : paths) {
    d += (d.empty() ? "M " : " M ") + pt(s.start);
    Vec2 at = s.start;
    for (const auto& c : s.pieces) {
      if (c.kind == CurveKind::Line) {
        d += " L " + pt(c.p[0]);
      } else if (c.kind == CurveKind::Cubic) {
        d += " C " + pt(c.p[0]) + " " + pt(c.p[1]) + " " + pt(c.p[2]);
      } else {
        const Polyline pl = flatten(SubPath{at, {c}, false}, kArcChordMm);
        for (std::size_t i = 1; i < pl.size(); ++i) d += " L " + pt(pl[i]);
      }
      at = c.end();
    }
    if (s.closed) d += " Z";
  }
  return d;
}

namespace {

std::string document(const std::vector<SvgLayer>& layers, const Vec2& lo, const Vec2& hi, double stroke_width_mm) {
  const Vec2 size = hi - lo;
  std::string out = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  out += "<svg xmlns=\"http://www.w3.org/2000/svg\" "
         "xmlns:inkscape=\"http://www.inkscape.org/namespaces/inkscape\" width=\"" + num(size.x()) +
         "mm\" height=\"" + num(size.y()) + "mm\" viewBox=\"" + pt(lo) + " " + pt(size) + "\">\n";
  for (const auto& l : layers) {
    out += "  <g id=\"" + escape(l.id) + "\" inkscape:groupmode=\"layer\" inkscape:label=\"" + escape(l.label) + "\">\n";
    for (const auto& s : l.shapes) {
      out += "    <path fill=\"" + (s.filled ? escape(colour(s.fill_color)) : std::string("none")) + "\"";
      if (s.filled && s.evenodd) out += " fill-rule=\"evenodd\"";
      out += " stroke=\"" + (s.stroked ? escape(colour(s.stroke_color)) : std::string("none")) + "\"";
      if (s.stroked) out += " stroke-width=\"" + num(stroke_width_mm) + "\" stroke-linecap=\"round\" stroke-linejoin=\"round\"";
      out += " d=\"" + path_data(s.paths) + "\"/>\n";
    }
    out += "  </g>\n";
  }
  return out + "</svg>\n";
}

}  // namespace

std::string write_svg_page(const std::vector<SvgLayer>& layers, const Vec2& page_mm, double stroke_width_mm) {
  return document(layers, Vec2::Zero(), page_mm, stroke_width_mm);
}

std::string write_svg(const std::vector<SvgLayer>& layers, double margin_mm, double stroke_width_mm) {
  Vec2 lo(INFINITY, INFINITY), hi(-INFINITY, -INFINITY);
  for (const auto& l : layers) {
    for (const auto& s : l.shapes) {
      for (const auto& p : s.paths) {
        for (const auto& q : flatten(p, kBoundsToleranceMm)) {
          lo = lo.cwiseMin(q);
          hi = hi.cwiseMax(q);
        }
      }
    }
  }
  if (!(lo.x() <= hi.x())) lo = hi = Vec2::Zero();
  const Vec2 margin(margin_mm, margin_mm);
  return document(layers, lo - margin, hi + margin, stroke_width_mm);
}

}  // namespace strand::slicer
