// Internal to the SVG importer: the state of one import and the helpers its three parts
// share (svg_import.cpp: the document; svg_import_walk.cpp: the element tree and its styles;
// svg_import_draw.cpp: shapes and text). Not for use outside slicer/.
#pragma once

#include <cstddef>
#include <map>
#include <memory>
#include <pugixml.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "slicer/curves.h"
#include "slicer/svg_css.h"
#include "slicer/svg_import.h"
#include "slicer/svg_syntax.h"
#include "slicer/svg_text.h"

namespace strand::slicer::svg_detail {

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

// A length or property value that is not valid: the element is skipped (or the property
// left out) with a note, the rest of the drawing is drawn.
struct BadValue {
  std::string note;
};

std::string trim(std::string_view s);

// Text for a note: cut short, control and non-ASCII bytes replaced (notes reach G-code
// comments and the summary).
std::string printable(std::string_view v, std::size_t max = 24);

// The element's name without its namespace prefix.
std::string local_name(const pugi::xml_node& n);

// "<path id="leaf">" for messages (the id cut short).
std::string describe(const pugi::xml_node& n);

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

  [[noreturn]] void over(const std::string& what, std::size_t limit, const pugi::xml_node& n) const;
  void note(const std::string& what);
  std::map<std::string, std::string> properties(const pugi::xml_node& n) const;
  void read_sheets(const std::vector<pugi::xml_node>& styles, const pugi::xml_document& doc);
  bool enter(const pugi::xml_node& n, const Context& parent, Context& c);
  bool inherit(const pugi::xml_node& n, Context& c);
  void walk(const pugi::xml_node& n, const Context& parent);
  void draw(const pugi::xml_node& n, const std::string& name, const Context& parent, Context& c);
  void walk_children(const pugi::xml_node& n, const Context& c);
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
             double fallback = 0.0) const;
};

}  // namespace strand::slicer::svg_detail
