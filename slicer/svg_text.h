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

// Text decorations (CSS text-decoration-line), a set of flags.
enum TextDecoration : unsigned { kUnderline = 1, kOverline = 2, kLineThrough = 4 };

// Font properties, inherited down the document like fill and stroke. Lengths in user units
// (px) of the element's coordinate system, computed where they are given (em and % resolved).
struct TextStyle {
  double font_size = 16.0;
  std::string font_family = "sans-serif";  // as written: "'DejaVu Sans', sans-serif"
  std::string font_weight = "normal";
  std::string font_style = "normal";
  TextAnchor anchor = TextAnchor::Start;
  bool preserve_space = false;  // xml:space="preserve"
  double letter_spacing = 0.0;  // added after every character
  double word_spacing = 0.0;    // added after every space
  // Not inherited but applying to the content of the element that sets them (CSS 2.1):
  unsigned decoration = 0;      // TextDecoration flags of this element and its ancestors
  double baseline_shift = 0.0;  // up (against SVG's y), summed over nested tspans

  bool operator==(const TextStyle&) const = default;
};

// Applies the text properties among `props` to `style`: the inherited ones (font-size,
// font-family, font-weight, font-style, text-anchor, xml:space, letter-spacing,
// word-spacing; "inherit" keeps the parent's value) and, for text content elements
// (`text_content`), text-decoration and baseline-shift (sub, super, lengths, % of the
// font-size; `tspan` is false for <text> itself, where baseline-shift does not apply).
// Lengths in px, em, ex, % and absolute units; `viewport` for percentages of spacing. A value
// that is not valid is left out and described in `notes` ("font-size = \"1q\"").
void inherit_text_style(const std::map<std::string, std::string>& props, TextStyle& style,
                        const Vec2& viewport, std::vector<std::string>& notes,
                        bool text_content = false, bool tspan = false);

// One addressable character of a <text> element after white-space handling.
struct TextChar {
  char32_t code = U' ';
  // Absolute position and shift from the x, y, dx, dy lists of the innermost element that
  // gives one for this character (user units); an absolute x or y starts a new text chunk.
  std::optional<double> x, y;
  double dx = 0.0, dy = 0.0;
  TextStyle style;
  // The <textPath> it lies on (an index into SvgText::paths), -1 for none. On a path, x is
  // a distance along it, y is not used (the x and y lists of elements outside the textPath
  // do not reach it), dx moves along the path and dy across it.
  int path = -1;

  bool operator==(const TextChar&) const = default;
};

// The path a <textPath> sets its characters along (SVG 1.1, 10.13): the referenced path or
// basic shape, or the textPath's own `path` data, with the referenced element's transform, in
// the user space of the text element.
struct TextPathShape {
  std::vector<SubPath> paths;  // followed one after the other (the jumps between them not counted)
  double start_offset = 0.0;   // where the text starts: user units along the path, or a fraction
  bool start_offset_fraction = false;  // of the path's length (startOffset="25%")
  double path_length = 0.0;    // the path's pathLength (0: none): startOffset lengths are in
                               // its units (scaled by the computed length / pathLength)

  bool operator==(const TextPathShape&) const = default;
};

// A <text> element: characters in document order, placed in the text's user space.
struct SvgText {
  std::vector<TextChar> chars;
  std::vector<TextPathShape> paths;  // its <textPath> elements, in document order
  Affine to_mm;  // the element's user space -> mm (SVG y down)
  bool stroked = false, filled = false;
  std::string stroke_color, fill_color;
  std::vector<std::string> group_ids;  // as SvgShape, for pen assignment
  std::vector<std::string> layer_labels;

  bool operator==(const SvgText&) const = default;
};

// UTF-8 <-> code points (fontconfig's converters); malformed bytes become U+FFFD.
std::u32string utf8_to_u32(const std::string& text);
std::string u32_to_utf8(const std::u32string& text);

}  // namespace strand::slicer
