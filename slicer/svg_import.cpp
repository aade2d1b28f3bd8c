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

// Presentation attributes first, then the style attribute (which wins).
std::map<std::string, std::string> properties(const pugi::xml_node& n) {
  std::map<std::string, std::string> p;
  for (const char* k : {"fill", "stroke", "fill-rule", "display", "visibility", "font-size",
                        "font-family", "font-weight", "font-style", "text-anchor", "xml:space",
                        "clip-path", "mask", "marker-start", "marker-mid", "marker-end"}) {
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

// "<path id="leaf">" for messages (the id cut short).
std::string describe(const pugi::xml_node& n) {
  std::string d = "<" + local_name(n);
  if (const auto id = n.attribute("id"))
    d += " id=\"" + std::string(id.value()).substr(0, 40) + "\"";
  return d + ">";
}

Affine translation(const Vec2& v) { return {Eigen::Matrix2d::Identity(), v}; }

struct Importer {
  std::string origin;
  std::map<std::string, pugi::xml_node> by_id;
  SvgDrawing out;
  std::map<std::string, int> skipped;
  std::vector<pugi::xml_node> uses;  // <use> targets being drawn, outermost first
  std::size_t elements = 0, use_copies = 0, attribute_bytes = 0, pieces = 0, text_chars = 0;

  [[noreturn]] void over(const std::string& what, std::size_t limit,
                         const pugi::xml_node& n) const {
    throw InputError(origin + ": " + describe(n) + ": the drawing has more than " +
                     std::to_string(limit) + " " + what +
                     " (the limit for one drawing)");
  }
  bool enter(const pugi::xml_node& n, const Context& parent, Context& c);
  bool inherit(const pugi::xml_node& n, Context& c);
  void walk(const pugi::xml_node& n, const Context& parent);
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
  // A length in user units; "P%" is P percent of `percent_of`.
  double len(const pugi::xml_node& n, const char* attr, double percent_of,
             double fallback = 0.0) const {
    const auto a = n.attribute(attr);
    if (!a) return fallback;
    const std::string v = trim(a.value());
    const std::string what = origin + ": " + describe(n) + " " + attr;
    if (!v.empty() && v.back() == '%')
      return parse_length_px(v.substr(0, v.size() - 1), what) * percent_of / 100.0;
    return parse_length_px(v, what);
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

bool Importer::inherit(const pugi::xml_node& n, Context& c) {
  const auto props = properties(n);
  if (props.count("display") && props.at("display") == "none") return false;
  if (props.count("fill")) c.style.fill = props.at("fill");
  if (props.count("stroke")) c.style.stroke = props.at("stroke");
  if (props.count("fill-rule")) c.style.evenodd = props.at("fill-rule") == "evenodd";
  if (props.count("visibility")) c.style.visible = props.at("visibility") == "visible";
  inherit_text_style(props, c.style.text, origin);
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
             Vec2(len(n, "width", c.viewport.x(), c.viewport.x()),
                  len(n, "height", c.viewport.y(), c.viewport.y())));
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
  c.to_mm =
      compose(c.to_mm, translation(Vec2(len(n, "x", c.viewport.x()), len(n, "y", c.viewport.y()))));
  uses.push_back(target);
  const std::string kind = local_name(target);
  if (kind == "symbol" || kind == "svg") {
    const auto size = [&](const char* attr, double full) {
      return n.attribute(attr) ? len(n, attr, full) : len(target, attr, full, full);
    };
    Context t;
    if (enter(target, c, t))
      viewport(target, t, Vec2(size("width", c.viewport.x()), size("height", c.viewport.y())));
  } else {
    walk(target, c);
  }
  uses.pop_back();
}

// A nested svg or an instantiated symbol: a new viewport of `size` (parent user units).
void Importer::viewport(const pugi::xml_node& n, Context c, const Vec2& size) {
  if (!(size.x() > 0) || !(size.y() > 0)) return;  // SVG: a zero-sized viewport draws nothing
  if (local_name(n) == "svg") {
    c.to_mm = compose(c.to_mm,
                      translation(Vec2(len(n, "x", c.viewport.x()), len(n, "y", c.viewport.y()))));
  }
  c.to_mm = compose(c.to_mm, viewport_transform(n, size.x(), size.y(), origin));
  c.viewport = view_box_size(n, origin).value_or(size);
  walk_children(n, c);
}

// The element's outline as sub-paths in user units; false for elements that are not basic
// shapes (defs, symbol, style, metadata, gradients, clip paths: not drawn directly).
bool Importer::geometry(const pugi::xml_node& n, const std::string& name, const Context& c,
                        std::vector<SubPath>& paths) {
  const Vec2 vp = c.viewport;
  const double diagonal = vp.norm() / std::sqrt(2.0);  // what percentages of radii refer to
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
    double rx = len(n, "rx", vp.x()), ry = len(n, "ry", vp.y());
    if (has_rx && !has_ry) ry = rx;
    if (has_ry && !has_rx) rx = ry;
    const double w = len(n, "width", vp.x()), h = len(n, "height", vp.y());
    if (w > 0 && h > 0)
      paths.push_back(rect_path(len(n, "x", vp.x()), len(n, "y", vp.y()), w, h, rx, ry));
  } else if (name == "circle" || name == "ellipse") {
    const double rx = name == "circle" ? len(n, "r", diagonal) : len(n, "rx", vp.x());
    const double ry = name == "circle" ? rx : len(n, "ry", vp.y());
    if (rx > 0 && ry > 0)
      paths.push_back(ellipse_path(Vec2(len(n, "cx", vp.x()), len(n, "cy", vp.y())), rx, ry));
  } else if (name == "line") {
    paths.push_back(polyline_path(
        {len(n, "x1", vp.x()), len(n, "y1", vp.y()), len(n, "x2", vp.x()), len(n, "y2", vp.y())},
        false));
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
  t.chars = read_text_chars(n, parent_text, &properties, origin, kMaxSvgTextChars - text_chars);
  text_chars += t.chars.size();
  if (!t.chars.empty()) out.texts.push_back(std::move(t));
}

// Ids of every element, without recursion (pugixml's traversal is iterative), refusing a
// document nested deeper than kMaxSvgDepth before anything recurses over it.
struct IdIndex : pugi::xml_tree_walker {
  std::map<std::string, pugi::xml_node>* by_id = nullptr;
  pugi::xml_node too_deep;
  bool for_each(pugi::xml_node& n) override {
    if (n.type() != pugi::node_element) return true;
    if (depth() > kMaxSvgDepth) {
      too_deep = n;
      return false;
    }
    if (const auto id = n.attribute("id")) by_id->emplace(id.value(), n);
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
  const auto parsed = doc.load_buffer(text.data(), text.size());
  if (!parsed) {
    throw InputError(origin + ": malformed XML at byte " + std::to_string(parsed.offset) + " (" +
                     parsed.description() + ")");
  }
  return doc;
}

}  // namespace

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
  // Root viewport: width/height in their units (percentages fall back to the viewBox).
  const std::optional<Vec2> vb = view_box_size(root, origin);
  const auto dim = [&](const char* attr, int axis) {
    const std::string v = root.attribute(attr).value();
    if (!v.empty() && v.back() != '%') return im.len(root, attr, 0.0);
    if (vb) return (*vb)[axis];
    throw InputError(origin + ": <svg> needs " + std::string(attr) + " or a viewBox to know its size");
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
