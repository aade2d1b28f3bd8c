// SVG import: a document (pugixml DOM) into shapes made of exact curves in millimetres,
// with every transform, viewBox and unit baked in, plus what pens they may map to.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "slicer/curves.h"
#include "slicer/svg_text.h"

namespace strand::slicer {

struct SvgShape {
  std::string element;                   // "path", "rect", "circle", ...
  std::vector<SubPath> paths;            // mm, SVG orientation (y down), document origin
  bool stroked = false;                  // stroke is set and not none
  bool filled = false;                   // fill is set (default black) and not none
  bool evenodd = false;                  // fill-rule
  std::string stroke_color;              // normalised "#rrggbb" (or the lower-cased text)
  std::string fill_color;
  std::vector<std::string> group_ids;    // ids of enclosing elements, nearest first
  std::vector<std::string> layer_labels; // inkscape:label of enclosing layers, nearest first

  bool operator==(const SvgShape&) const = default;
};

struct SvgDrawing {
  std::vector<SvgShape> shapes;          // document order
  std::vector<SvgText> texts;            // <text> elements, document order (not yet drawn)
  std::vector<std::string> skipped;      // "image (1)": elements not drawn
  Vec2 page_mm = Vec2::Zero();           // the root viewport's size
};

// Parses an SVG document. Malformed XML, a non-svg root, unknown units and references to
// missing ids throw InputError naming `origin`; hidden elements (display:none,
// visibility:hidden) are left out; text is kept as characters in `texts` (text_layout draws
// it); images are listed in `skipped`.
SvgDrawing import_svg(std::string_view text, const std::string& origin);

// "#F00", "red", "rgb(255,0,0)" -> "#ff0000"; anything else lower-cased as is.
std::string normalise_color(std::string_view text);

}  // namespace strand::slicer
