// SVG text as the importer reads it: characters with their positions (x, y, dx, dy lists),
// font properties and anchor, before any font is chosen (slicer/text_layout turns them into
// shapes with Hershey or outline fonts).
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "slicer/curves.h"

namespace strand::slicer {

enum class TextAnchor { Start, Middle, End };

// Font properties, inherited down the document like fill and stroke.
struct TextStyle {
  double font_size = 16.0;           // user units (px) of the element's coordinate system
  std::string font_family = "sans-serif";  // as written: "'DejaVu Sans', sans-serif"
  std::string font_weight = "normal";
  std::string font_style = "normal";
  TextAnchor anchor = TextAnchor::Start;
  bool preserve_space = false;       // xml:space="preserve"

  bool operator==(const TextStyle&) const = default;
};

// Applies the text properties among `props` (font-size, font-family, font-weight,
// font-style, text-anchor, xml:space) to `style`; font-size in %, em, keywords or lengths.
// Throws InputError naming `origin` for a font-size that is no length.
void inherit_text_style(const std::map<std::string, std::string>& props, TextStyle& style,
                        const std::string& origin);

// One addressable character of a <text> element after white-space handling.
struct TextChar {
  char32_t code = U' ';
  // Absolute position and shift from the x, y, dx, dy lists of the innermost element that
  // gives one for this character (user units); an absolute x or y starts a new text chunk.
  std::optional<double> x, y;
  double dx = 0.0, dy = 0.0;
  TextStyle style;

  bool operator==(const TextChar&) const = default;
};

// A <text> element: characters in document order, placed in the text's user space.
struct SvgText {
  std::vector<TextChar> chars;
  Affine to_mm;                      // the element's user space -> mm (SVG y down)
  bool stroked = false, filled = false;
  std::string stroke_color, fill_color;
  std::vector<std::string> group_ids;     // as SvgShape, for pen assignment
  std::vector<std::string> layer_labels;

  bool operator==(const SvgText&) const = default;
};

// UTF-8 <-> code points (fontconfig's converters); malformed bytes become U+FFFD.
std::u32string utf8_to_u32(const std::string& text);
std::string u32_to_utf8(const std::u32string& text);

}  // namespace strand::slicer
