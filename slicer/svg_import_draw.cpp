// SVG import, the drawn elements: basic shapes and paths as curves in millimetres with their
// pen colours, and <text> with its characters and text paths, each bounded by the drawing's
// limits (pieces, characters, coordinates).
#include <algorithm>
#include <cmath>
#include <pugixml.hpp>
#include <utility>

#include "slicer/input_error.h"
#include "slicer/params.h"
#include "slicer/svg_importer.h"
#include "slicer/svg_shapes.h"
#include "slicer/svg_syntax.h"
#include "slicer/svg_text.h"
#include "slicer/svg_text_reader.h"

namespace strand::slicer::svg_detail {

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
  const std::string what = describe(text) + " <textPath href=\"" + printable(href, 40) + "\">: ";
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
    const auto found = href.size() < 2 || href[0] != '#' ? by_id.end() : by_id.find(href.substr(1));
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
  if (std::string(tp.attribute("side").value()) == "right")
    ++skipped["textPath side=right (drawn on the left)"];
  return out;
}

}  // namespace strand::slicer::svg_detail
