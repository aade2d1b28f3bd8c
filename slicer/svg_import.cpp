// SVG import: the document parsed with pugixml (markup bounded first), its ids and style
// sheets, the root viewport, and the drawing's notes; the helpers every part of the import
// shares. The tree walk is in svg_import_walk.cpp, shapes and text in svg_import_draw.cpp.
#include "slicer/svg_import.h"

#include <algorithm>
#include <cctype>
#include <map>
#include <memory>
#include <pugixml.hpp>
#include <utility>

#include "slicer/input_error.h"
#include "slicer/params.h"
#include "slicer/svg_css.h"
#include "slicer/svg_entities.h"
#include "slicer/svg_importer.h"
#include "slicer/svg_shapes.h"
#include "slicer/svg_syntax.h"
#include "slicer/units.h"

namespace strand::slicer {

namespace svg_detail {

std::string trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return std::string(s);
}

std::string printable(std::string_view v, std::size_t max) {
  std::string out(v.substr(0, max));
  for (char& ch : out) {
    if (static_cast<unsigned char>(ch) < 0x20 || static_cast<unsigned char>(ch) > 0x7e) ch = '?';
  }
  return out + (v.size() > max ? "..." : "");
}

std::string local_name(const pugi::xml_node& n) {
  std::string name = n.name();
  const auto colon = name.find(':');
  return colon == std::string::npos ? name : name.substr(colon + 1);
}

std::string describe(const pugi::xml_node& n) {
  std::string d = "<" + printable(local_name(n), 40);
  if (const auto id = n.attribute("id")) d += " id=\"" + printable(id.value(), 40) + "\"";
  return d + ">";
}

namespace {

// Distinct notes kept in the summary; more are counted under one line.
constexpr std::size_t kMaxNotes = 20;

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

[[noreturn]] void Importer::over(const std::string& what, std::size_t limit,
                                 const pugi::xml_node& n) const {
  throw InputError(origin + ": " + describe(n) + ": the drawing has more than " +
                   std::to_string(limit) + " " + what + " (the limit for one drawing)");
}

void Importer::note(const std::string& what) {
  if (skipped.count(what) || ++notes <= kMaxNotes) {
    ++skipped[what];
  } else {
    ++skipped["more values in error"];
  }
}

double Importer::len(const pugi::xml_node& n, const char* attr, LengthAxis axis, const Context& c,
                     double fallback) const {
  const auto a = n.attribute(attr);
  if (!a) return fallback;
  try {
    return resolve_length_px(trim(a.value()), axis, LengthBasis{c.style.text.font_size, c.viewport},
                             attr);
  } catch (const InputError&) {
    throw BadValue{describe(n) + " " + attr + " = \"" + printable(a.value()) +
                   "\": not a length (element skipped)"};
  }
}

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

}  // namespace svg_detail

namespace {

constexpr double kMmPerPx = kMmPerInch / 96.0;

}  // namespace

SvgDrawing import_svg(std::string_view text, const std::string& origin) {
  using svg_detail::Context, svg_detail::IdIndex, svg_detail::Importer, svg_detail::describe,
      svg_detail::local_name, svg_detail::parse;
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