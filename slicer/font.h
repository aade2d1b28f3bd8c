// Fonts as plain data for drawing text: glyph outlines or single strokes in font units
// (y up, baseline at 0, pen at x = 0), and the advance to the next glyph.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "slicer/curves.h"

namespace strand::slicer {

struct Glyph {
  double advance = 0.0;          // font units
  std::vector<SubPath> paths;    // font units; open strokes or closed contours

  bool operator==(const Glyph&) const = default;
};

struct Font {
  std::string name;              // "hershey:futural", "DejaVu Sans Bold"
  bool single_stroke = true;     // strokes to draw as they are (Hershey); else contours to fill
  double units_per_em = 1.0;     // font units in one em (the CSS font-size)
  // Decoration lines in font units, y up from the baseline: the centre of each line and
  // the underline's thickness (FreeType's face and OS/2 metrics; Hershey: a fixed body).
  double underline_position = -0.1;
  double underline_thickness = 0.05;
  double strikeout_position = 0.25;
  double overline_position = 0.75;
  std::map<char32_t, Glyph> glyphs;  // the characters loaded; others are missing

  bool operator==(const Font&) const = default;
};

}  // namespace strand::slicer
