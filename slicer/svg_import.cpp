// SVG document traversal on pugixml: styles and their inheritance, viewports, transforms,
// basic shapes as curves, `use` references and symbols, hidden and skipped elements, and the
// drawing's limits (depth, elements, attribute bytes, pieces, text, coordinates).
#include "slicer/svg_import.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <map>
#include <memory>
#include <pugixml.hpp>
#include <utility>

#include "slicer/input_error.h"
#include "slicer/params.h"
#include "slicer/svg_css.h"
#include "slicer/svg_entities.h"
#include "slicer/svg_shapes.h"
#include "slicer/svg_syntax.h"
#include "slicer/svg_text_reader.h"
#include "slicer/units.h"

namespace strand::slicer {

namespace {

constexpr double kMmPerPx = kMmPerInch / 96.0;

// Inherited presentation state (SVG 1.1 property inheritance).
struct Style {
  std::string fill = "#000000";
  std::string stroke = "none";
  bool evenodd = false;
  bool visible = true;
  double stroke_width = 1.0;  // user units of the element that set it
  TextStyle text;
};

struct Context {
  Affine to_mm;
  Style style;
  // Shared, never changed once made: a context is copied for every element (and every <use>
  // copy), the lists only when a group adds to them.
  std::shared_ptr<const std::vector<std::string>> group_ids =
      std::make_shared<std::vector<std::string>>();
  std::shared_ptr<const std::vector<std::string>> layer_labels = group_ids;
  Vec2 viewport = Vec2::Zero();  // the nearest viewport's size in user units (for percentages)
  int depth = 0;                 // elements and <use> references above this one
};

std::shared_ptr<const std::vector<std::string>> prepended(const std::vector<std::string>& v,
                                                          const char* first) {
  auto out = std::make_shared<std::vector<std::string>>();
  out->reserve(v.size() + 1);
  out->push_back(first);
  out->insert(out->end(), v.begin(), v.end());
  return out;
}

std::string trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return std::string(s);
}

// Properties an SVG element may give as attributes (presentation attributes).
constexpr const char* kPresentation[] = {"fill",           "stroke",         "fill-rule",
                                         "display",        "visibility",     "font-size",
                                         "font-family",    "font-weight",    "font-style",
                                         "text-anchor",    "xml:space",      "clip-path",
                                         "mask",           "marker-start",   "marker-mid",
                                         "marker-end",     "stroke-width",   "text-decoration",
                                         "baseline-shift", "letter-spacing", "word-spacing"};

// A length or property value that is not valid: the element is skipped (or the property
// left out) with a note, the rest of the drawing is drawn.
struct BadValue {
  std::string note;
};

// Text for a note: cut short, control and non-ASCII bytes replaced (notes reach G-code
// comments and the summary).
std::string printable(std::string_view v, std::size_t max = 24) {
  std::string out(v.substr(0, max));
  for (char& ch : out) {
    if (static_cast<unsigned char>(ch) < 0x20 || static_cast<unsigned char>(ch) > 0x7e) ch = '?';
  }
  return out + (v.size() > max ? "..." : "");
}

// Distinct notes kept in the summary; more are counted under one line.
constexpr std::size_t kMaxNotes = 20;

std::string local_name(const pugi::xml_node& n) {
  std::string name = n.name();
  const auto colon = name.find(':');
  return colon == std::string::npos ? name : name.substr(colon + 1);
}

// "<path id="leaf">" for messages (the id cut short).
std::string describe(const pugi::xml_node& n) {
  std::string d = "<" + printable(local_name(n), 40);
  if (const auto id = n.attribute("id")) d += " id=\"" + printable(id.value(), 40) + "\"";
  return d + ">";
}

Affine translation(const Vec2& v) { return {Eigen::Matrix2d::Identity(), v}; }

struct Importer {
  std::string origin;
  std::map<std::string, pugi::xml_node> by_id;
  SvgDrawing out;
  std::map<std::string, int> skipped;
  std::size_t notes = 0;
  StyleSheet sheet;
  std::unique_ptr<CssCascade> cascade;
  std::vector<pugi::xml_node> uses;  // <use> targets being drawn, outermost first
  std::size_t elements = 0, use_copies = 0, attribute_bytes = 0, pieces = 0, text_chars = 0;

  [[noreturn]] void over(const std::string& what, std::size_t limit,
                         const pugi::xml_node& n) const {
    throw InputError(origin + ": " + describe(n) + ": the drawing has more than " +
                     std::to_string(limit) + " " + what + " (the limit for one drawing)");
  }
  void note(const std::string& what) {
    if (skipped.count(what) || ++notes <= kMaxNotes) {
      ++skipped[what];
    } else {
      ++skipped["more values in error"];
    }
  }
  std::map<std::string, std::string> properties(const pugi::xml_node& n) const;
  void read_sheets(const std::vector<pugi::xml_node>& styles, const pugi::xml_document& doc);
  bool enter(const pugi::xml_node& n, const Context& parent, Context& c);
  bool inherit(const pugi::xml_node& n, Context& c);
  void walk(const pugi::xml_node& n, const Context& parent);
  void draw(const pugi::xml_node& n, const std::string& name, const Context& parent, Context& c);
  void walk_children(const pugi::xml_node& n, const Context& c) {
    for (const auto& child : n.children()) {
      if (child.type() == pugi::node_element) walk(child, c);
    }
  }
  void walk_switch(const pugi::xml_node& n, const Context& c);
  void use(const pugi::xml_node& n, Context c);
  void viewport(const pugi::xml_node& n, Context c, const Vec2& size);
  bool geometry(const pugi::xml_node& n, const std::string& name, const Context& c,
                std::vector<SubPath>& paths);
  void shape(const pugi::xml_node& n, const Context& c, std::vector<SubPath> paths);
  void text(const pugi::xml_node& n, const TextStyle& parent_text, const Context& c);
  TextPathShape text_path(const pugi::xml_node& text, const pugi::xml_node& tp, const Context& c);
  // A length attribute in user units: em and ex of the element's font-size, % of the
  // viewport along `axis`. A value in error throws BadValue (the element is skipped).
  double len(const pugi::xml_node& n, const char* attr, LengthAxis axis, const Context& c,
             double fallback = 0.0) const {
    const auto a = n.attribute(attr);
    if (!a) return fallback;
    try {
      return resolve_length_px(trim(a.value()), axis,
                               LengthBasis{c.style.text.font_size, c.viewport}, attr);
    } catch (const InputError&) {
      throw BadValue{describe(n) + " " + attr + " = \"" + printable(a.value()) +
                     "\": not a length (element skipped)"};
    }
  }
};

// Counts the element against the drawing's limits, then applies its style and transform;
// false when it is display:none.
bool Importer::enter(const pugi::xml_node& n, const Context& parent, Context& c) {
  c = parent;
  c.depth = parent.depth + 1;
  if (c.depth > kMaxSvgDepth) {
    throw InputError(origin + ": " + describe(n) + ": elements nest deeper than " +
                     std::to_string(kMaxSvgDepth) + " levels (each <use> counts as one)");
  }
  if (++elements > kMaxSvgElements) over("elements (each <use> copy counted)", kMaxSvgElements, n);
  if (!uses.empty() && ++use_copies > kMaxSvgUseCopies)
    over("elements copied by <use>", kMaxSvgUseCopies, n);
  for (const auto& a : n.attributes()) attribute_bytes += std::strlen(a.value());
  if (attribute_bytes > kMaxSvgAttributeBytes)
    over("bytes of attributes (each <use> copy counted)", kMaxSvgAttributeBytes, n);
  return inherit(n, c);
}

// The cascade of one element: presentation attributes, sheet rules by specificity and
// order, the style attribute, !important sheet rules, !important style declarations.
std::map<std::string, std::string> Importer::properties(const pugi::xml_node& n) const {
  std::map<std::string, std::string> p;
  for (const char* k : kPresentation) {
    if (const auto a = n.attribute(k)) p[k] = trim(a.value());
  }
  CssMatch m;
  try {
    if (cascade) m = cascade->matching(n);
  } catch (const InputError& e) {
    throw InputError(origin + ": " + e.what());
  }
  for (const CssDeclaration* d : m.normal) p[d->property] = d->value;
  const char* style = n.attribute("style").value();
  const std::vector<CssDeclaration> own =
      *style ? parse_css_declarations(style) : std::vector<CssDeclaration>{};
  for (const auto& d : own) {
    if (!d.important) p[d.property] = d.value;
  }
  for (const CssDeclaration* d : m.important) p[d->property] = d->value;
  for (const auto& d : own) {
    if (d.important) p[d.property] = d.value;
  }
  return p;
}

bool Importer::inherit(const pugi::xml_node& n, Context& c) {
  const auto props = properties(n);
  // "inherit" keeps the parent's value: every property read here is inherited in SVG or,
  // for display, hides the element's whole subtree when none
  const auto get = [&](const char* key) -> const std::string* {
    const auto p = props.find(key);
    return p == props.end() || p->second == "inherit" ? nullptr : &p->second;
  };
  if (const auto* v = get("display"); v && *v == "none") return false;
  if (const auto* v = get("fill")) c.style.fill = *v;
  if (const auto* v = get("stroke")) c.style.stroke = *v;
  if (const auto* v = get("fill-rule")) c.style.evenodd = *v == "evenodd";
  if (const auto* v = get("visibility")) c.style.visible = *v == "visible";
  std::vector<std::string> bad;
  inherit_text_style(props, c.style.text, c.viewport, bad, local_name(n) == "text");
  if (const auto* v = get("stroke-width")) {
    try {
      c.style.stroke_width = resolve_length_px(
          *v, LengthAxis::Other, LengthBasis{c.style.text.font_size, c.viewport}, "stroke-width");
    } catch (const InputError&) {
      bad.push_back("stroke-width = \"" + printable(*v) + "\"");
    }
  }
  for (const auto& b : bad) note(describe(n) + " " + b + ": not valid (left out)");
  for (const char* ignored : {"clip-path", "mask", "marker-start", "marker-mid", "marker-end"}) {
    const auto p = props.find(ignored);
    if (p != props.end() && p->second != "none")
      ++skipped[std::string(ignored).substr(0, 6) == "marker" ? "marker" : ignored];
  }
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
  Context c;
  if (!enter(n, parent, c)) return;
  const std::string name = local_name(n);
  try {
    draw(n, name, parent, c);
  } catch (const BadValue& bad) {
    note(bad.note);
  }
}

void Importer::draw(const pugi::xml_node& n, const std::string& name, const Context& parent,
                    Context& c) {
  if (name == "g" || name == "a") {
    if (const auto id = n.attribute("id")) c.group_ids = prepended(*c.group_ids, id.value());
    if (std::string(n.attribute("inkscape:groupmode").value()) == "layer") {
      c.layer_labels = prepended(*c.layer_labels, n.attribute("inkscape:label").value());
    }
    walk_children(n, c);
  } else if (name == "switch") {
    walk_switch(n, c);
  } else if (name == "svg") {  // nested viewport: width and height default to 100%
    viewport(n, c,
             Vec2(len(n, "width", LengthAxis::X, c, c.viewport.x()),
                  len(n, "height", LengthAxis::Y, c, c.viewport.y())));
  } else if (name == "use") {
    use(n, c);
  } else if (name == "image" || name == "foreignObject") {
    ++skipped[name];
  } else if (c.style.visible && name == "text") {
    text(n, parent.style.text, c);
  } else if (std::vector<SubPath> paths; c.style.visible && geometry(n, name, c, paths)) {
    shape(n, c, std::move(paths));
  }
}

// A switch draws its first child whose conditions hold; Strand supports no extensions, so
// a child with requiredExtensions (Illustrator's private data) never does.
void Importer::walk_switch(const pugi::xml_node& n, const Context& c) {
  for (const auto& child : n.children()) {
    if (child.type() != pugi::node_element) continue;
    if (!trim(child.attribute("requiredExtensions").value()).empty()) continue;
    walk(child, c);
    return;
  }
}

// <use>: the referenced element drawn at x, y; a symbol or svg gets the use's width and
// height as its viewport (SVG 1.1, 5.6), its viewBox scaled into it.
void Importer::use(const pugi::xml_node& n, Context c) {
  std::string href = n.attribute("href").value();
  if (href.empty()) href = n.attribute("xlink:href").value();
  const auto found = href.size() < 2 || href[0] != '#' ? by_id.end() : by_id.find(href.substr(1));
  const std::string what = origin + ": <use href=\"" + href.substr(0, 40) + "\">";
  if (found == by_id.end()) throw InputError(what + ": no element with that id");
  const pugi::xml_node target = found->second;
  if (std::find(uses.begin(), uses.end(), target) != uses.end())
    throw InputError(what + ": references form a cycle");
  c.to_mm = compose(
      c.to_mm, translation(Vec2(len(n, "x", LengthAxis::X, c), len(n, "y", LengthAxis::Y, c))));
  const std::string kind = local_name(target);
  // the use's own width and height (a value in error skips the use before it is entered)
  const auto size = [&](const char* attr, LengthAxis axis) {
    return n.attribute(attr) ? std::optional<double>(len(n, attr, axis, c)) : std::nullopt;
  };
  const std::optional<double> use_w = size("width", LengthAxis::X);
  const std::optional<double> use_h = size("height", LengthAxis::Y);
  uses.push_back(target);
  struct Pop {
    std::vector<pugi::xml_node>& v;
    ~Pop() { v.pop_back(); }
  } pop{uses};
  if (kind == "symbol" || kind == "svg") {
    Context t;
    if (enter(target, c, t)) {
      viewport(target, t,
               Vec2(use_w ? *use_w : len(target, "width", LengthAxis::X, t, c.viewport.x()),
                    use_h ? *use_h : len(target, "height", LengthAxis::Y, t, c.viewport.y())));
    }
  } else {
    walk(target, c);
  }
}

// A nested svg or an instantiated symbol: a new viewport of `size` (parent user units).
void Importer::viewport(const pugi::xml_node& n, Context c, const Vec2& size) {
  if (!(size.x() > 0) || !(size.y() > 0)) return;  // SVG: a zero-sized viewport draws nothing
  if (local_name(n) == "svg") {
    c.to_mm = compose(
        c.to_mm, translation(Vec2(len(n, "x", LengthAxis::X, c), len(n, "y", LengthAxis::Y, c))));
  }
  c.to_mm = compose(c.to_mm, viewport_transform(n, size.x(), size.y(), origin));
  c.viewport = view_box_size(n, origin).value_or(size);
  walk_children(n, c);
}

// The element's outline as sub-paths in user units; false for elements that are not basic
// shapes (defs, symbol, style, metadata, gradients, clip paths: not drawn directly).
bool Importer::geometry(const pugi::xml_node& n, const std::string& name, const Context& c,
                        std::vector<SubPath>& paths) {
  constexpr LengthAxis X = LengthAxis::X, Y = LengthAxis::Y;
  const std::size_t room = kMaxSvgPieces - std::min(pieces, kMaxSvgPieces);
  if (name == "path") {
    std::string error;
    try {
      paths = parse_path_data(n.attribute("d").value(), &error, room);
    } catch (const InputError&) {
      over("curve pieces", kMaxSvgPieces, n);
    }
    if (!error.empty()) ++skipped["path data after an error"];
  } else if (name == "rect") {
    const bool has_rx = n.attribute("rx"), has_ry = n.attribute("ry");
    double rx = len(n, "rx", X, c), ry = len(n, "ry", Y, c);
    if (has_rx && !has_ry) ry = rx;
    if (has_ry && !has_rx) rx = ry;
    const double w = len(n, "width", X, c), h = len(n, "height", Y, c);
    if (w > 0 && h > 0)
      paths.push_back(rect_path(len(n, "x", X, c), len(n, "y", Y, c), w, h, rx, ry));
  } else if (name == "circle" || name == "ellipse") {
    const double rx = name == "circle" ? len(n, "r", LengthAxis::Other, c) : len(n, "rx", X, c);
    const double ry = name == "circle" ? rx : len(n, "ry", Y, c);
    if (rx > 0 && ry > 0)
      paths.push_back(ellipse_path(Vec2(len(n, "cx", X, c), len(n, "cy", Y, c)), rx, ry));
  } else if (name == "line") {
    paths.push_back(polyline_path(
        {len(n, "x1", X, c), len(n, "y1", Y, c), len(n, "x2", X, c), len(n, "y2", Y, c)}, false));
  } else if (name == "polyline" || name == "polygon") {
    std::vector<double> v;
    try {
      v = parse_number_list(n.attribute("points").value(), 2 * room + 2);
    } catch (const InputError& e) {
      if (std::string(e.what()).find("more than") == std::string::npos)
        throw InputError(origin + ": " + describe(n) + " " + e.what());
      over("curve pieces", kMaxSvgPieces, n);
    }
    if (v.size() % 2) v.pop_back();  // SVG: an odd coordinate is an error; draw what is whole
    paths.push_back(polyline_path(v, name == "polygon"));
  } else {
    return false;
  }
  return true;
}

void Importer::shape(const pugi::xml_node& n, const Context& c, std::vector<SubPath> paths) {
  SvgShape s;
  s.element = local_name(n);
  s.id = n.attribute("id").value();
  s.stroked = c.style.stroke != "none" && !c.style.stroke.empty();
  s.filled = c.style.fill != "none" && !c.style.fill.empty() && s.element != "line";
  s.evenodd = c.style.evenodd;
  s.stroke_color = s.stroked ? normalise_color(c.style.stroke) : "";
  s.fill_color = s.filled ? normalise_color(c.style.fill) : "";
  const Eigen::Matrix2d& l = c.to_mm.linear;  // mean scale: the root of the area ratio
  s.stroke_width_mm =
      c.style.stroke_width * std::sqrt(std::abs(l(0, 0) * l(1, 1) - l(0, 1) * l(1, 0)));
  s.group_ids = *c.group_ids;
  s.layer_labels = *c.layer_labels;
  if (!s.stroked && !s.filled) return;
  for (const auto& p : paths) pieces += p.pieces.size() + 1;
  if (pieces > kMaxSvgPieces) over("curve pieces", kMaxSvgPieces, n);
  for (auto& p : paths) {
    if (p.pieces.empty()) continue;
    SubPath t = transformed(p, c.to_mm);
    const double m = max_abs_coordinate(t);
    if (!(m <= kMaxCoordinateMm)) {
      throw InputError(origin + ": " + describe(n) + ": a coordinate is " +
                       (std::isfinite(m) ? short_number(m) + " mm" : std::string("not finite")) +
                       " after transforms (at most " + short_number(kMaxCoordinateMm) +
                       " mm from the origin)");
    }
    s.paths.push_back(std::move(t));
  }
  if (!s.paths.empty()) out.shapes.push_back(std::move(s));
}

void Importer::text(const pugi::xml_node& n, const TextStyle& parent_text, const Context& c) {
  SvgText t;
  t.to_mm = c.to_mm;
  t.stroked = c.style.stroke != "none" && !c.style.stroke.empty();
  t.filled = c.style.fill != "none" && !c.style.fill.empty();
  t.stroke_color = t.stroked ? normalise_color(c.style.stroke) : "";
  t.fill_color = t.filled ? normalise_color(c.style.fill) : "";
  t.group_ids = *c.group_ids;
  t.layer_labels = *c.layer_labels;
  // the reader applies the element's own font properties (relative sizes must apply once)
  std::vector<std::string> bad;
  std::vector<pugi::xml_node> text_paths;
  try {
    t.chars = read_text_chars(
        n, parent_text, [this](const pugi::xml_node& e) { return properties(e); }, c.viewport, bad,
        origin, kMaxSvgTextChars - text_chars, text_paths);
  } catch (const InputError& e) {
    if (std::string(e.what()).find("more than") != std::string::npos) throw;  // a limit
    // "<text> dy = ...", "<tspan> dy = ..." after the file name
    std::string what = e.what();
    if (what.rfind(origin + ": ", 0) == 0) what = what.substr(origin.size() + 2);
    const std::string msg = printable(what, 60);
    const bool own = msg.rfind("<text> ", 0) == 0;
    throw BadValue{describe(n) + (own ? msg.substr(6) : " " + msg) + " (element skipped)"};
  }
  for (const auto& tp : text_paths) t.paths.push_back(text_path(n, tp, c));
  for (const auto& b : bad) note("<tspan> in " + describe(n) + " " + b + ": not valid (left out)");
  text_chars += t.chars.size();
  if (!t.chars.empty()) out.texts.push_back(std::move(t));
}

// A <textPath> of `text`: its own `path` data (SVG 2), else the path or basic shape its href
// names in this document, with that element's transform, in the text's user space (SVG 1.1,
// 10.13.1). A missing or unusable reference, or a startOffset that is not a length, skips the
// whole text with a note; the pieces count against the drawing's limit like a drawn shape's.
TextPathShape Importer::text_path(const pugi::xml_node& text, const pugi::xml_node& tp,
                                  const Context& c) {
  std::string href = tp.attribute("href").value();
  if (href.empty()) href = tp.attribute("xlink:href").value();
  const std::string what =
      describe(text) + " <textPath href=\"" + printable(href, 40) + "\">: ";
  TextPathShape out;
  Affine to_text;  // the referenced element's user space -> the text's
  if (const auto d = tp.attribute("path")) {
    std::string error;
    const std::size_t room = kMaxSvgPieces - std::min(pieces, kMaxSvgPieces);
    try {
      out.paths = parse_path_data(d.value(), &error, room);
    } catch (const InputError&) {
      over("curve pieces", kMaxSvgPieces, tp);
    }
    if (!error.empty()) ++skipped["path data after an error"];
  } else {
    if (href.empty()) throw BadValue{what + "no href or path (text skipped)"};
    const auto found =
        href.size() < 2 || href[0] != '#' ? by_id.end() : by_id.find(href.substr(1));
    if (found == by_id.end()) throw BadValue{what + "no element with that id (text skipped)"};
    const pugi::xml_node target = found->second;
    if (!geometry(target, local_name(target), c, out.paths))
      throw BadValue{what + "not a path or basic shape (text skipped)"};
    if (const auto tr = target.attribute("transform")) {
      try {
        to_text = parse_transform(tr.value());
      } catch (const InputError&) {
        throw BadValue{what + "its transform is not valid (text skipped)"};
      }
    }
    if (const auto pl = target.attribute("pathLength")) {
      try {
        out.path_length = parse_length_px(trim(pl.value()), "pathLength");
      } catch (const InputError&) {
        out.path_length = 0.0;  // not a number: ignored, as browsers do
      }
      if (!(out.path_length > 0) || !std::isfinite(out.path_length)) out.path_length = 0.0;
    }
  }
  for (const auto& p : out.paths) pieces += p.pieces.size() + 1;
  if (pieces > kMaxSvgPieces) over("curve pieces", kMaxSvgPieces, tp);
  const Affine to_mm = compose(c.to_mm, to_text);
  for (auto& p : out.paths) {
    p = transformed(p, to_text);
    if (!(max_abs_coordinate(transformed(p, to_mm)) <= kMaxCoordinateMm))
      throw BadValue{what + "a coordinate is beyond " + short_number(kMaxCoordinateMm) +
                     " mm after transforms (text skipped)"};
  }
  if (const auto so = tp.attribute("startOffset")) {
    const std::string v = trim(so.value());
    try {
      out.start_offset_fraction = !v.empty() && v.back() == '%';
      // a percentage of a unit viewport is the fraction itself
      out.start_offset = resolve_length_px(
          v, LengthAxis::X,
          LengthBasis{c.style.text.font_size, out.start_offset_fraction ? Vec2(1, 1) : c.viewport},
          "startOffset");
    } catch (const InputError&) {
      throw BadValue{what + "startOffset = \"" + printable(v) + "\": not a length (text skipped)"};
    }
  }
  if (std::string(tp.attribute("side").value()) == "right") ++skipped["textPath side=right (drawn on the left)"];
  return out;
}

// The text of an element (a <style> sheet): its character data, CDATA sections included.
std::string sheet_text(const pugi::xml_node& n) {
  std::string out;
  for (const auto& child : n.children()) {
    if (child.type() == pugi::node_pcdata || child.type() == pugi::node_cdata) out += child.value();
  }
  return out;
}

// A pseudo-attribute of a processing instruction: href="#s" in <?xml-stylesheet ...?>.
std::string pseudo_attribute(std::string_view pi, std::string_view name) {
  for (std::size_t at = pi.find(name); at != std::string_view::npos; at = pi.find(name, at + 1)) {
    if (at > 0 && !std::isspace(static_cast<unsigned char>(pi[at - 1]))) continue;
    std::size_t k = at + name.size();
    while (k < pi.size() && std::isspace(static_cast<unsigned char>(pi[k]))) ++k;
    if (k >= pi.size() || pi[k] != '=') continue;
    ++k;
    while (k < pi.size() && std::isspace(static_cast<unsigned char>(pi[k]))) ++k;
    if (k >= pi.size() || (pi[k] != '"' && pi[k] != '\'')) continue;
    const auto end = pi.find(pi[k], k + 1);
    if (end == std::string_view::npos) return "";
    return std::string(pi.substr(k + 1, end - k - 1));
  }
  return "";
}

// Ids of every element, without recursion (pugixml's traversal is iterative), refusing a
// document nested deeper than kMaxSvgDepth before anything recurses over it.
struct IdIndex : pugi::xml_tree_walker {
  std::map<std::string, pugi::xml_node>* by_id = nullptr;
  std::vector<pugi::xml_node> styles;  // <style> elements in document order
  pugi::xml_node too_deep;
  bool for_each(pugi::xml_node& n) override {
    if (n.type() != pugi::node_element) return true;
    if (depth() > kMaxSvgDepth) {
      too_deep = n;
      return false;
    }
    if (const auto id = n.attribute("id")) by_id->emplace(id.value(), n);
    if (local_name(n) == "style") styles.push_back(n);
    return true;
  }
};

pugi::xml_document parse(std::string_view text, const std::string& origin) {
  const std::size_t markup = static_cast<std::size_t>(std::count(text.begin(), text.end(), '<')) +
                             static_cast<std::size_t>(std::count(text.begin(), text.end(), '='));
  if (markup > kMaxSvgMarkup) {
    throw InputError(origin + ": the document has " + std::to_string(markup) +
                     " '<' and '=' (elements and attributes; at most " +
                     std::to_string(kMaxSvgMarkup) + ")");
  }
  pugi::xml_document doc;
  // processing instructions kept: <?xml-stylesheet?> may point at a sheet inside the file
  const auto parsed =
      doc.load_buffer(text.data(), text.size(), pugi::parse_default | pugi::parse_pi);
  if (!parsed) {
    throw InputError(origin + ": malformed XML at byte " + std::to_string(parsed.offset) + " (" +
                     parsed.description() + ")");
  }
  return doc;
}

}  // namespace

// Sheets in document order: <?xml-stylesheet?> instructions before the root (only those
// pointing inside the file: an external sheet is never loaded), then <style> elements.
void Importer::read_sheets(const std::vector<pugi::xml_node>& styles,
                           const pugi::xml_document& doc) {
  std::vector<pugi::xml_node> read;
  for (const auto& pi : doc.children()) {
    if (pi.type() != pugi::node_pi || std::string_view(pi.name()) != "xml-stylesheet") continue;
    const std::string type = pseudo_attribute(pi.value(), "type");
    const std::string href = pseudo_attribute(pi.value(), "href");
    if (!type.empty() && type != "text/css") {
      ++skipped["style sheet of type " + printable(type)];
    } else if (href.size() < 2 || href[0] != '#' || !by_id.count(href.substr(1))) {
      ++skipped["external style sheet (never loaded)"];
    } else if (pseudo_attribute(pi.value(), "alternate") != "yes") {
      const pugi::xml_node target = by_id.at(href.substr(1));
      parse_css(sheet_text(target), sheet);
      read.push_back(target);
    }
  }
  for (const auto& n : styles) {
    const std::string type = trim(n.attribute("type").value());
    if (!type.empty() && type != "text/css") {
      ++skipped["style sheet of type " + printable(type)];
    } else if (std::find(read.begin(), read.end(), n) == read.end()) {
      parse_css(sheet_text(n), sheet);
    }
  }
  for (const auto& [what, count] : sheet.skipped) skipped[what] += count;
  if (!sheet.rules.empty()) cascade = std::make_unique<CssCascade>(sheet);
}

SvgDrawing import_svg(std::string_view text, const std::string& origin) {
  const std::optional<ExpandedEntities> expanded = expand_entities(text, origin);
  pugi::xml_document doc = parse(expanded ? std::string_view(expanded->text) : text, origin);
  const pugi::xml_node root = doc.document_element();
  if (local_name(root) != "svg")
    throw InputError(origin + ": the root element is <" + std::string(root.name()).substr(0, 40) +
                     ">, not <svg>");
  Importer im;
  im.origin = origin;
  IdIndex index;
  index.by_id = &im.by_id;
  doc.traverse(index);
  if (index.too_deep) {
    throw InputError(origin + ": " + describe(index.too_deep) + ": elements nest deeper than " +
                     std::to_string(kMaxSvgDepth) + " levels");
  }
  im.read_sheets(index.styles, doc);
  // Root viewport: width/height in their units (percentages fall back to the viewBox).
  const std::optional<Vec2> vb = view_box_size(root, origin);
  const auto dim = [&](const char* attr, int axis) {
    const std::string v = root.attribute(attr).value();
    if (!v.empty() && v.back() != '%')
      return resolve_length_px(v, LengthAxis::X, LengthBasis{}, origin + ": <svg> " + attr);
    if (vb) return (*vb)[axis];
    throw InputError(origin + ": <svg> needs " + std::string(attr) +
                     " or a viewBox to know its size");
  };
  const Vec2 size_px(dim("width", 0), dim("height", 1));
  Context c;
  c.to_mm = compose(Affine{kMmPerPx * Eigen::Matrix2d::Identity(), Vec2::Zero()},
                    viewport_transform(root, size_px.x(), size_px.y(), origin));
  c.viewport = vb.value_or(size_px);
  im.out.page_mm = size_px * kMmPerPx;
  if (im.inherit(root, c)) im.walk_children(root, c);
  if (expanded && expanded->external > 0) im.skipped["external entity"] += expanded->external;
  for (const auto& [name, count] : im.skipped) {
    im.out.skipped.push_back(name + " (" + std::to_string(count) + ")");
  }
  im.by_id.clear();
  doc.reset();  // the parsed document goes before the caller lays the drawing out
  return std::move(im.out);
}

}  // namespace strand::slicer
