// SVG document traversal on pugixml: styles and their inheritance, viewports, transforms,
// basic shapes as curves, `use` references, hidden and skipped elements.
#include "slicer/svg_import.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <map>
#include <pugixml.hpp>

#include "slicer/input_error.h"
#include "slicer/svg_syntax.h"
#include "slicer/svg_text_reader.h"
#include "slicer/units.h"

namespace strand::slicer {

namespace {

constexpr double kMmPerPx = kMmPerInch / 96.0;
// `use` chains deeper than this are treated as a reference cycle.
constexpr int kMaxUseDepth = 32;

// Inherited presentation state (SVG 1.1 property inheritance).
struct Style {
  std::string fill = "#000000";
  std::string stroke = "none";
  bool evenodd = false;
  bool visible = true;
  TextStyle text;
};

struct Context {
  Affine to_mm;
  Style style;
  std::vector<std::string> group_ids;
  std::vector<std::string> layer_labels;
  int use_depth = 0;
};

struct Importer {
  std::string origin;
  std::map<std::string, pugi::xml_node> by_id;
  SvgDrawing out;
  std::map<std::string, int> skipped;

  void walk(const pugi::xml_node& n, const Context& parent);
  void walk_children(const pugi::xml_node& n, const Context& c) {
    for (const auto& child : n.children()) {
      if (child.type() == pugi::node_element) walk(child, c);
    }
  }
  void shape(const pugi::xml_node& n, const Context& c, std::vector<SubPath> paths);
  void text(const pugi::xml_node& n, const TextStyle& parent_text, const Context& c);
  double len(const pugi::xml_node& n, const char* attr, double fallback = 0.0) const {
    const auto a = n.attribute(attr);
    if (!a) return fallback;
    return parse_length_px(a.value(), origin + ": <" + std::string(n.name()) + "> " + attr);
  }
};

std::string trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return std::string(s);
}

// Presentation attributes first, then the style attribute (which wins).
std::map<std::string, std::string> properties(const pugi::xml_node& n) {
  std::map<std::string, std::string> p;
  for (const char* k : {"fill", "stroke", "fill-rule", "display", "visibility", "font-size", "font-family",
                        "font-weight", "font-style", "text-anchor", "xml:space"}) {
    if (const auto a = n.attribute(k)) p[k] = trim(a.value());
  }
  std::string_view style = n.attribute("style").value();
  while (!style.empty()) {
    const auto semi = style.find(';');
    const std::string_view decl = style.substr(0, semi);
    const auto colon = decl.find(':');
    if (colon != std::string_view::npos) p[trim(decl.substr(0, colon))] = trim(decl.substr(colon + 1));
    if (semi == std::string_view::npos) break;
    style.remove_prefix(semi + 1);
  }
  return p;
}

std::string local_name(const pugi::xml_node& n) {
  std::string name = n.name();
  const auto colon = name.find(':');
  return colon == std::string::npos ? name : name.substr(colon + 1);
}

// viewBox + preserveAspectRatio: user space of a viewport of size w x h (px) into its
// parent's user space.
Affine viewport_transform(const pugi::xml_node& n, double w, double h, const std::string& origin) {
  Affine m;
  const auto vb_attr = n.attribute("viewBox");
  if (!vb_attr) return m;
  const auto vb = parse_number_list(vb_attr.value());
  if (vb.size() != 4 || vb[2] <= 0 || vb[3] <= 0) {
    throw InputError(origin + ": viewBox = \"" + std::string(vb_attr.value()) + "\": must be 4 numbers with width and height > 0");
  }
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

// Rect with rounded corners: rx/ry default to each other and clamp to half the sides.
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

void Importer::shape(const pugi::xml_node& n, const Context& c, std::vector<SubPath> paths) {
  SvgShape s;
  s.element = local_name(n);
  s.stroked = c.style.stroke != "none" && !c.style.stroke.empty();
  s.filled = c.style.fill != "none" && !c.style.fill.empty();
  if (s.element == "line" || s.element == "polyline") s.filled = s.filled && s.element != "line";
  s.evenodd = c.style.evenodd;
  s.stroke_color = s.stroked ? normalise_color(c.style.stroke) : "";
  s.fill_color = s.filled ? normalise_color(c.style.fill) : "";
  s.group_ids = c.group_ids;
  s.layer_labels = c.layer_labels;
  for (auto& p : paths) {
    if (!p.pieces.empty()) s.paths.push_back(transformed(p, c.to_mm));
  }
  if (!s.paths.empty() && (s.stroked || s.filled)) out.shapes.push_back(std::move(s));
}

void Importer::text(const pugi::xml_node& n, const TextStyle& parent_text, const Context& c) {
  SvgText t;
  t.to_mm = c.to_mm;
  t.stroked = c.style.stroke != "none" && !c.style.stroke.empty();
  t.filled = c.style.fill != "none" && !c.style.fill.empty();
  t.stroke_color = t.stroked ? normalise_color(c.style.stroke) : "";
  t.fill_color = t.filled ? normalise_color(c.style.fill) : "";
  t.group_ids = c.group_ids;
  t.layer_labels = c.layer_labels;
  // the reader applies the element's own font properties (relative sizes must apply once)
  t.chars = read_text_chars(n, parent_text, &properties, origin);
  if (!t.chars.empty()) out.texts.push_back(std::move(t));
}

// Applies the element's style and transform to `c`; false when it is display:none.
bool inherit(const pugi::xml_node& n, Context& c, const std::string& origin) {
  const auto props = properties(n);
  if (props.count("display") && props.at("display") == "none") return false;
  if (props.count("fill")) c.style.fill = props.at("fill");
  if (props.count("stroke")) c.style.stroke = props.at("stroke");
  if (props.count("fill-rule")) c.style.evenodd = props.at("fill-rule") == "evenodd";
  if (props.count("visibility")) c.style.visible = props.at("visibility") == "visible";
  inherit_text_style(props, c.style.text, origin);
  if (const auto t = n.attribute("transform")) {
    try {
      c.to_mm = compose(c.to_mm, parse_transform(t.value()));
    } catch (const InputError& e) {
      throw InputError(origin + ": " + e.what());
    }
  }
  return true;
}

void Importer::walk(const pugi::xml_node& n, const Context& parent) {
  const std::string name = local_name(n);
  Context c = parent;
  if (!inherit(n, c, origin)) return;
  if (name == "g" || name == "a" || name == "switch") {
    if (const auto id = n.attribute("id")) c.group_ids.insert(c.group_ids.begin(), id.value());
    if (std::string(n.attribute("inkscape:groupmode").value()) == "layer") {
      c.layer_labels.insert(c.layer_labels.begin(), n.attribute("inkscape:label").value());
    }
    walk_children(n, c);
    return;
  }
  if (name == "svg") {  // nested viewport
    const double w = len(n, "width", 0), h = len(n, "height", 0);
    c.to_mm = compose(c.to_mm, Affine{Eigen::Matrix2d::Identity(), Vec2(len(n, "x"), len(n, "y"))});
    c.to_mm = compose(c.to_mm, viewport_transform(n, w, h, origin));
    walk_children(n, c);
    return;
  }
  if (name == "use") {
    std::string href = n.attribute("href").value();
    if (href.empty()) href = n.attribute("xlink:href").value();
    if (href.size() < 2 || href[0] != '#' || !by_id.count(href.substr(1))) {
      throw InputError(origin + ": <use href=\"" + href + "\">: no element with that id");
    }
    if (c.use_depth >= kMaxUseDepth) throw InputError(origin + ": <use href=\"" + href + "\">: references form a cycle");
    c.to_mm = compose(c.to_mm, Affine{Eigen::Matrix2d::Identity(), Vec2(len(n, "x"), len(n, "y"))});
    ++c.use_depth;
    const pugi::xml_node target = by_id.at(href.substr(1));
    if (local_name(target) == "symbol") {
      walk_children(target, c);
    } else {
      walk(target, c);
    }
    return;
  }
  if (name == "image" || name == "foreignObject") {
    ++skipped[name];
    return;
  }
  if (!c.style.visible) return;
  if (name == "text") {
    text(n, parent.style.text, c);
    return;
  }
  std::vector<SubPath> paths;
  if (name == "path") {
    std::string error;
    paths = parse_path_data(n.attribute("d").value(), &error);
    if (!error.empty()) ++skipped["path data after an error"];
  } else if (name == "rect") {
    const bool has_rx = n.attribute("rx"), has_ry = n.attribute("ry");
    double rx = len(n, "rx"), ry = len(n, "ry");
    if (has_rx && !has_ry) ry = rx;
    if (has_ry && !has_rx) rx = ry;
    const double w = len(n, "width"), h = len(n, "height");
    if (w > 0 && h > 0) paths.push_back(rect_path(len(n, "x"), len(n, "y"), w, h, rx, ry));
  } else if (name == "circle" || name == "ellipse") {
    const double rx = name == "circle" ? len(n, "r") : len(n, "rx");
    const double ry = name == "circle" ? rx : len(n, "ry");
    if (rx > 0 && ry > 0) paths.push_back(ellipse_path(Vec2(len(n, "cx"), len(n, "cy")), rx, ry));
  } else if (name == "line") {
    paths.push_back(polyline_path({len(n, "x1"), len(n, "y1"), len(n, "x2"), len(n, "y2")}, false));
  } else if (name == "polyline" || name == "polygon") {
    auto v = parse_number_list(n.attribute("points").value());
    if (v.size() % 2) v.pop_back();  // SVG: an odd coordinate is an error; draw what is whole
    paths.push_back(polyline_path(v, name == "polygon"));
  } else {
    return;  // defs, symbol, style, metadata, gradients, clip paths: not drawn directly
  }
  shape(n, c, std::move(paths));
}

void index_ids(const pugi::xml_node& n, std::map<std::string, pugi::xml_node>& by_id) {
  for (const auto& child : n.children()) {
    if (child.type() != pugi::node_element) continue;
    if (const auto id = child.attribute("id")) by_id.emplace(id.value(), child);
    index_ids(child, by_id);
  }
}

}  // namespace

std::string normalise_color(std::string_view text) {
  static const std::map<std::string, std::string> kNamed = {
      {"black", "#000000"}, {"white", "#ffffff"}, {"red", "#ff0000"}, {"green", "#008000"},
      {"lime", "#00ff00"},  {"blue", "#0000ff"},  {"yellow", "#ffff00"}, {"cyan", "#00ffff"},
      {"magenta", "#ff00ff"}, {"orange", "#ffa500"}, {"purple", "#800080"}, {"gray", "#808080"},
      {"grey", "#808080"}, {"brown", "#a52a2a"}, {"navy", "#000080"}, {"pink", "#ffc0cb"}};
  std::string s = trim(text);
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char ch) { return std::tolower(ch); });
  if (kNamed.count(s)) return kNamed.at(s);
  const auto hex = [](const std::string& h) {
    return std::all_of(h.begin(), h.end(), [](unsigned char ch) { return std::isxdigit(ch); });
  };
  if (s.size() == 4 && s[0] == '#' && hex(s.substr(1))) {
    return std::string("#") + s[1] + s[1] + s[2] + s[2] + s[3] + s[3];
  }
  if (s.rfind("rgb(", 0) == 0 && s.back() == ')') {
    const auto v = parse_number_list(s.substr(4, s.size() - 5));
    if (v.size() == 3) {
      char buf[8];
      const auto ch = [](double x) { return static_cast<int>(std::clamp(x, 0.0, 255.0)); };
      std::snprintf(buf, sizeof buf, "#%02x%02x%02x", ch(v[0]), ch(v[1]), ch(v[2]));
      return buf;
    }
  }
  return s;
}

SvgDrawing import_svg(std::string_view text, const std::string& origin) {
  pugi::xml_document doc;
  const auto parsed = doc.load_buffer(text.data(), text.size());
  if (!parsed) {
    throw InputError(origin + ": malformed XML at byte " + std::to_string(parsed.offset) + " (" +
                     parsed.description() + ")");
  }
  const pugi::xml_node root = doc.document_element();
  if (local_name(root) != "svg") throw InputError(origin + ": the root element is <" + std::string(root.name()) + ">, not <svg>");
  Importer im;
  im.origin = origin;
  index_ids(doc, im.by_id);
  // Root viewport: width/height in their units (percentages fall back to the viewBox).
  std::vector<double> vb;
  if (const auto a = root.attribute("viewBox")) vb = parse_number_list(a.value());
  const auto dim = [&](const char* attr, int vb_index) {
    const std::string v = root.attribute(attr).value();
    if (!v.empty() && v.back() != '%') return im.len(root, attr);
    if (vb.size() == 4) return vb[vb_index];
    throw InputError(origin + ": <svg> needs " + std::string(attr) + " or a viewBox to know its size");
  };
  const double w_px = dim("width", 2), h_px = dim("height", 3);
  Context c;
  c.to_mm = compose(Affine{kMmPerPx * Eigen::Matrix2d::Identity(), Vec2::Zero()},
                    viewport_transform(root, w_px, h_px, origin));
  im.out.page_mm = Vec2(w_px, h_px) * kMmPerPx;
  if (inherit(root, c, origin)) im.walk_children(root, c);
  for (const auto& [name, count] : im.skipped) {
    im.out.skipped.push_back(name + " (" + std::to_string(count) + ")");
  }
  return im.out;
}

}  // namespace strand::slicer
