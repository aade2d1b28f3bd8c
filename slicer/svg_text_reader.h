// Internal to the SVG importer: the characters of one <text> element read from the pugixml
// tree (white space, tspan nesting, x/y/dx/dy lists). Not for use outside slicer/.
#pragma once

#include <cstddef>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "slicer/svg_text.h"

namespace pugi {
class xml_node;
}

namespace strand::slicer {

// An element's properties after the cascade (attributes, sheets, style attribute).
using PropertyReader = std::function<std::map<std::string, std::string>(const pugi::xml_node&)>;

// Characters of `text` (a <text> element) with their positions and styles; hidden tspans
// (display:none) are left out; `viewport` (user units) is what percentages refer to. Property
// values in error are left out and described in `notes`. Throws InputError naming `origin`
// for malformed x/y/dx/dy lengths and for more than `max_chars` characters (checked as they
// are read). The <textPath> elements with characters are added to `text_paths` in document
// order; a character on one has its index there as TextChar::path (a textPath inside another
// is read as a tspan of the outer one).
std::vector<TextChar> read_text_chars(const pugi::xml_node& text, const TextStyle& inherited,
                                      const PropertyReader& properties, const Vec2& viewport,
                                      std::vector<std::string>& notes, const std::string& origin,
                                      std::size_t max_chars,
                                      std::vector<pugi::xml_node>& text_paths);

}  // namespace strand::slicer
