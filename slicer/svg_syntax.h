// The micro-grammars inside SVG attributes: path data, transform lists, number lists,
// lengths with units and colours. Recursive-descent parsers that follow the SVG 1.1 BNF;
// each throws InputError naming the attribute and the offending text.
#pragma once

#include <cstddef>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "slicer/curves.h"

namespace strand::slicer {

// Path data ("M 10 10 l 5 0 a 5 5 0 0 1 5 5 z") into sub-paths in user units. Handles every
// command (M L H V C S Q T A Z), absolute and relative, implicit repeats, compact numbers
// ("1.5.5", "-1-2", "1e-3") and packed arc flags ("a1 1 0 00 10 10"). Quadratics become
// exact cubics; arcs keep their centre form. A syntax error keeps the pieces read so far
// (SVG's error rule) and is reported through `error` when non-null. More than `max_pieces`
// pieces and sub-paths together throw InputError before the next one is stored.
std::vector<SubPath> parse_path_data(
    std::string_view d, std::string* error = nullptr,
    std::size_t max_pieces = std::numeric_limits<std::size_t>::max());

// transform="matrix(...) translate(...) scale(...) rotate(a cx cy) skewX(...) skewY(...)".
Affine parse_transform(std::string_view text);

// "10,20 30 40" -> {10, 20, 30, 40}. More than `max_count` numbers throw InputError.
std::vector<double> parse_number_list(
    std::string_view text, std::size_t max_count = std::numeric_limits<std::size_t>::max());

// A length in user units (px); mm, cm, in, pt, pc, px and none are accepted at 96 px/in.
// Percentages and other units throw InputError naming `what`.
double parse_length_px(std::string_view text, const std::string& what);

// What a percentage length refers to (SVG 1.1, 7.10): the viewport's width, its height, or
// its normalised diagonal sqrt((w^2 + h^2) / 2) for lengths in no direction (r, stroke-width).
enum class LengthAxis { X, Y, Other };

// What relative lengths are relative to: em = font_size_px, ex = font_size_px / 2 (the CSS
// fallback without font metrics), % of the viewport (user units) along `axis`.
struct LengthBasis {
  double font_size_px = 16.0;
  Vec2 viewport = Vec2::Zero();
};

// A length in user units with every SVG unit: the absolute ones of parse_length_px, em, ex
// and %. Throws InputError naming `what` for malformed text and other units.
double resolve_length_px(std::string_view text, LengthAxis axis, const LengthBasis& basis,
                         const std::string& what);

// Elliptical arc from `from` to `to` (SVG endpoint form) as a centre-form piece; radii that
// are too small are scaled up as the SVG spec prescribes. Zero radii give a line.
CurvePiece arc_piece(const Vec2& from, double rx, double ry, double x_axis_rotation_deg,
                     bool large_arc, bool sweep, const Vec2& to);

// "#F00", "red", "rgb(255,0,0)" -> "#ff0000"; anything else lower-cased as is.
std::string normalise_color(std::string_view text);

}  // namespace strand::slicer
