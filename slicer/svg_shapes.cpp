// Basic SVG shapes as curves and viewport mappings (SVG 1.1, 9.2-9.5 and 7.7-7.8).
#include "slicer/svg_shapes.h"

#include <algorithm>
#include <cctype>
#include <pugixml.hpp>

#include "slicer/input_error.h"
#include "slicer/svg_syntax.h"
#include "slicer/units.h"

namespace strand::slicer {

namespace {

std::string trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return std::string(s);
}

std::vector<double> view_box(const pugi::xml_node& n, const std::string& origin) {
  const auto attr = n.attribute("viewBox");
  if (!attr) return {};
  std::vector<double> vb;
  try {
    vb = parse_number_list(attr.value(), 5);
  } catch (const InputError&) {
    vb.clear();  // not numbers, or too many: the message below says what is wanted
  }
  if (vb.size() != 4 || !(vb[2] > 0) || !(vb[3] > 0)) {
    throw InputError(origin + ": viewBox = \"" + std::string(attr.value()).substr(0, 80) +
                     "\": must be 4 numbers with width and height > 0");
  }
  return vb;
}

}  // namespace

SubPath polyline_path(const std::vector<double>& v, bool closed) {
  SubPath s;
  if (v.size() < 4) return s;
  s.start = Vec2(v[0], v[1]);
  for (std::size_t i = 2; i + 1 < v.size(); i += 2) {
    CurvePiece c;
    c.p[0] = Vec2(v[i], v[i + 1]);
    s.pieces.push_back(c);
  }
  if (closed) {
    CurvePiece c;
    c.p[0] = s.start;
    s.pieces.push_back(c);
    s.closed = true;
  }
  return s;
}

SubPath ellipse_path(const Vec2& c, double rx, double ry) {
  CurvePiece arc;
  arc.kind = CurveKind::Arc;
  arc.center = c;
  arc.axes << rx, 0, 0, ry;
  arc.t0_rad = 0.0;
  arc.sweep_rad = kTwoPi;
  return {c + Vec2(rx, 0), {arc}, true};
}

SubPath rect_path(double x, double y, double w, double h, double rx, double ry) {
  rx = std::min(rx, w / 2);
  ry = std::min(ry, h / 2);
  if (rx <= 0 || ry <= 0) return polyline_path({x, y, x + w, y, x + w, y + h, x, y + h}, true);
  SubPath s{Vec2(x + rx, y), {}, true};
  const auto line = [&](double px, double py) {
    CurvePiece c;
    c.p[0] = Vec2(px, py);
    s.pieces.push_back(c);
  };
  const auto corner = [&](double cx, double cy, double t0) {
    CurvePiece a;
    a.kind = CurveKind::Arc;
    a.center = Vec2(cx, cy);
    a.axes << rx, 0, 0, ry;
    a.t0_rad = t0;
    a.sweep_rad = kPi / 2;
    s.pieces.push_back(a);
  };
  line(x + w - rx, y);
  corner(x + w - rx, y + ry, -kPi / 2);
  line(x + w, y + h - ry);
  corner(x + w - rx, y + h - ry, 0.0);
  line(x + rx, y + h);
  corner(x + rx, y + h - ry, kPi / 2);
  line(x, y + ry);
  corner(x + rx, y + ry, kPi);
  return s;
}

std::optional<Vec2> view_box_size(const pugi::xml_node& n, const std::string& origin) {
  const auto vb = view_box(n, origin);
  if (vb.empty()) return std::nullopt;
  return Vec2(vb[2], vb[3]);
}

Affine viewport_transform(const pugi::xml_node& n, double w, double h, const std::string& origin) {
  Affine m;
  const auto vb = view_box(n, origin);
  if (vb.empty()) return m;
  double sx = w / vb[2], sy = h / vb[3];
  std::string par = trim(n.attribute("preserveAspectRatio").value());
  if (par.empty()) par = "xMidYMid meet";
  double ax = 0.5, ay = 0.5;
  if (par.rfind("none", 0) != 0) {
    const bool slice = par.find("slice") != std::string::npos;
    sx = sy = slice ? std::max(sx, sy) : std::min(sx, sy);
    if (par.find("xMin") != std::string::npos) ax = 0.0;
    if (par.find("xMax") != std::string::npos) ax = 1.0;
    if (par.find("YMin") != std::string::npos) ay = 0.0;
    if (par.find("YMax") != std::string::npos) ay = 1.0;
  }
  m.linear << sx, 0, 0, sy;
  m.offset = Vec2(-vb[0] * sx + ax * (w - vb[2] * sx), -vb[1] * sy + ay * (h - vb[3] * sy));
  return m;
}

}  // namespace strand::slicer
