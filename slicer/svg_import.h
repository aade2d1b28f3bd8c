// SVG import: a document (pugixml DOM) into shapes made of exact curves in millimetres,
// with every transform, viewBox and unit baked in, plus what pens they may map to.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "slicer/curves.h"
#include "slicer/svg_text.h"

namespace strand::slicer {

// Bounds on one drawing (docs/limits.md), each checked before the work it bounds; beyond
// one, import_svg throws InputError.
// Elements nested deeper than this, each <use> reference counting as a level.
inline constexpr int kMaxSvgDepth = 256;
// '<' and '=' characters in the document: an upper bound on the elements, text runs and
// attributes pugixml would hold in memory, counted before parsing.
inline constexpr std::size_t kMaxSvgMarkup = 4'000'000;
// Elements visited, every <use> copy counted again; a drawing without <use> has at most
// kMaxSvgMarkup of them anyway (a 300,000-line plot is a normal benchmark drawing).
inline constexpr std::size_t kMaxSvgElements = 4'000'000;
// Elements instantiated by <use> references (nested <use> grow exponentially: 39 levels each
// using the previous twice would be 5e11 copies).
inline constexpr std::size_t kMaxSvgUseCopies = 250'000;
// Bytes of attribute values read, every <use> copy counted again.
inline constexpr std::size_t kMaxSvgAttributeBytes = std::size_t{256} << 20;
// Curve pieces (lines, cubics, arcs) and sub-paths of all shapes together.
inline constexpr std::size_t kMaxSvgPieces = 2'000'000;
// Characters of all <text> elements together.
inline constexpr std::size_t kMaxSvgTextChars = 100'000;

struct SvgShape {
  std::string element;         // "path", "rect", "circle", ...
  std::string id;              // the element's own id, if any (for messages)
  std::vector<SubPath> paths;  // mm, SVG orientation (y down), document origin
  bool stroked = false;        // stroke is set and not none
  bool filled = false;         // fill is set (default black) and not none
  bool evenodd = false;        // fill-rule
  std::string stroke_color;    // normalised "#rrggbb" (or the lower-cased text)
  std::string fill_color;
  double stroke_width_mm = 0.0;           // stroke-width after transforms (their mean scale)
  std::vector<std::string> group_ids;     // ids of enclosing elements, nearest first
  std::vector<std::string> layer_labels;  // inkscape:label of enclosing layers, nearest first

  bool operator==(const SvgShape&) const = default;
};

struct SvgDrawing {
  std::vector<SvgShape> shapes;      // document order
  std::vector<SvgText> texts;        // <text> elements, document order (not yet drawn)
  std::vector<std::string> skipped;  // "image (1)": what was not drawn or not applied
  Vec2 page_mm = Vec2::Zero();       // the root viewport's size
};

// Parses an SVG document. Internal DTD entities are expanded first (svg_entities.h).
// Malformed XML, a non-svg root, unknown units, references to missing ids or in a cycle, any
// limit above and coordinates beyond kMaxCoordinateMm after transforms throw InputError
// naming `origin` (and the element); hidden elements (display:none, visibility:hidden) are
// left out; of a <switch> only the first child without requiredExtensions is drawn; text is
// kept as characters in `texts` (text_layout draws it), with the paths of its <textPath>
// elements (a text whose textPath has no usable reference is skipped with a note); images,
// foreign objects, external entities and ignored clip paths, masks and markers are counted
// in `skipped`.
SvgDrawing import_svg(std::string_view text, const std::string& origin);

}  // namespace strand::slicer
