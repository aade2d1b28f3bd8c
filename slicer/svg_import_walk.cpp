// SVG import, the element tree: each element counted against the drawing's limits, its
// properties cascaded (attributes, sheets, style) and inherited, groups, switches, <use>
// references and nested viewports walked in document order.
#include <algorithm>
#include <cstring>
#include <map>
#include <memory>
#include <optional>
#include <pugixml.hpp>
#include <utility>

#include "slicer/input_error.h"
#include "slicer/svg_css.h"
#include "slicer/svg_importer.h"
#include "slicer/svg_shapes.h"
#include "slicer/svg_syntax.h"
#include "slicer/svg_text.h"

namespace strand::slicer::svg_detail {

namespace {

// Properties an SVG element may give as attributes (presentation attributes).
constexpr const char* kPresentation[] = {"fill",           "stroke",         "fill-rule",
                                         "display",        "visibility",     "font-size",
                                         "font-family",    "font-weight",    "font-style",
                                         "text-anchor",    "xml:space",      "clip-path",
                                         "mask",           "marker-start",   "marker-mid",
                                         "marker-end",     "stroke-width",   "text-decoration",
                                         "baseline-shift", "letter-spacing", "word-spacing"};

std::shared_ptr<const std::vector<std::string>> prepended(const std::vector<std::string>& v,
                                                          const char* first) {
  auto out = std::make_shared<std::vector<std::string>>();
  out->reserve(v.size() + 1);
  out->push_back(first);
  out->insert(out->end(), v.begin(), v.end());
  return out;
}

Affine translation(const Vec2& v) { return {Eigen::Matrix2d::Identity(), v}; }

}  // namespace

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

void Importer::walk_children(const pugi::xml_node& n, const Context& c) {
  for (const auto& child : n.children()) {
    if (child.type() == pugi::node_element) walk(child, c);
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

}  // namespace strand::slicer::svg_detail
