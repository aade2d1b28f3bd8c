// SVG text into shapes: each character's glyph placed at its position (x, y, dx, dy,
// text-anchor per text chunk, font-size) or along its <textPath>, through the text element's
// transform into mm.
// Hershey glyphs become stroked single lines; outline glyphs become filled contours.
#pragma once

#include <string>
#include <vector>

#include "slicer/svg_import.h"

namespace strand::slicer {

enum class TextMode {
  Hershey,  // single-stroke Hershey font for all text (plotters; the default)
  Outline,  // the font each text names, through fontconfig + FreeType, filled
  None,     // text is not drawn (listed as skipped)
};
// Throws InputError naming plot.text for an unknown name.
TextMode text_mode_from_string(const std::string& name);

struct TextOptions {
  TextMode mode = TextMode::Hershey;
  // "hershey:NAME" (Hershey mode; default futural), or an installed family that replaces
  // the drawing's families (Outline mode; empty = each text's own font-family).
  std::string font;
  // Hershey mode: each run of characters (a text chunk in one font-family, weight and style)
  // scaled horizontally so that its advance is that of the font the drawing names (the
  // family fontconfig finds for its font-family list, else fontconfig's sans-serif), measured
  // with FreeType: lines as long as a browser draws them. false: the Hershey advances.
  bool fit_width = false;
};

// Text along a <textPath> is placed on the path flattened within kTextPathToleranceMm; the
// flattened points of all text paths of a drawing together are kept below kMaxTextPathPoints
// (bounded from the control points before flattening) by coarsening that tolerance.
inline constexpr double kTextPathToleranceMm = 0.001;
inline constexpr double kMaxTextPathPoints = 1'000'000;

struct TextDrawing {
  std::vector<SvgShape> shapes;       // one per text element that draws something
  int elements = 0;                   // text elements drawn
  int glyphs = 0;                     // characters drawn with a glyph (spaces excluded)
  int missing = 0;                    // characters the font has no glyph for
  int off_path = 0;                   // characters on a textPath whose middle lies off it
  std::vector<std::string> fonts;     // fonts used, in order of first use
  std::string summary() const;        // "2 elements, 31 glyphs (hershey:futural)"
};

// Lays out every text of the drawing. Throws InputError for a font that is not installed.
TextDrawing layout_text(const std::vector<SvgText>& texts, const TextOptions& o);

// The Hershey font name in "hershey:NAME", or "" when `font` is not of that form.
std::string hershey_name(const std::string& font);

}  // namespace strand::slicer
