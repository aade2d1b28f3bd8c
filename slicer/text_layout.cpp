// Placing glyphs: pen position from absolute x/y and relative dx/dy, advance by the glyph
// width times font-size / units-per-em, then each text chunk shifted for its anchor.
#include "slicer/text_layout.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>

#include "slicer/hershey_font.h"
#include "slicer/input_error.h"
#include "slicer/outline_font.h"
#include "slicer/params.h"
#include "slicer/svg_shapes.h"

namespace strand::slicer {

namespace {

constexpr const char* kDefaultHershey = "futural";

// Fonts loaded once per layout, by the key that selects them.
struct FontCache {
  TextOptions options;
  std::u32string all_chars;
  std::map<std::string, Font> fonts;

  const Font& font_for(const TextStyle& s) {
    if (options.mode == TextMode::Hershey) {
      std::string name = hershey_name(options.font);
      if (name.empty()) name = options.font.empty() ? kDefaultHershey : options.font;
      if (!fonts.count(name)) fonts.emplace(name, load_hershey_font(name));
      return fonts.at(name);
    }
    std::string family = options.font;
    if (family.empty()) {
      const auto found = installed_family(s.font_family);
      if (!found)
        throw InputError("text font-family = " + s.font_family +
                         ": no installed font carries it (fc-list shows the installed fonts; "
                         "--font NAME picks one)");
      family = *found;
    }
    const std::string key = family + "|" + s.font_weight + "|" + s.font_style;
    if (!fonts.count(key))
      fonts.emplace(key, load_outline_font(family, s.font_weight, s.font_style, all_chars));
    return fonts.at(key);
  }
};

struct Placed {
  const Glyph* glyph = nullptr;
  const Font* font = nullptr;
  Vec2 at = Vec2::Zero();  // user units, baseline origin of the glyph (baseline-shift applied)
  double scale = 1.0;      // user units per font unit
  double advance = 0.0;    // user units to the next character, spacing included
  unsigned decoration = 0;
};

// Positions of every character of one text element (before the transform to mm).
std::vector<Placed> place(const SvgText& t, FontCache& cache, TextDrawing& out) {
  std::vector<Placed> placed;
  Vec2 pen = Vec2::Zero();
  std::size_t chunk_start = 0;
  const auto close_chunk = [&](std::size_t end) {
    if (chunk_start >= end) return;
    const double width = pen.x() - placed[chunk_start].at.x();
    const TextAnchor a = t.chars[chunk_start].style.anchor;
    const double shift = a == TextAnchor::Middle ? -width / 2 : a == TextAnchor::End ? -width : 0.0;
    for (std::size_t k = chunk_start; k < end; ++k) placed[k].at.x() += shift;
  };
  for (std::size_t i = 0; i < t.chars.size(); ++i) {
    const TextChar& c = t.chars[i];
    if (c.x || c.y) {
      close_chunk(i);
      chunk_start = i;
      if (c.x) pen.x() = *c.x;
      if (c.y) pen.y() = *c.y;
    }
    pen += Vec2(c.dx, c.dy);
    const Font& font = cache.font_for(c.style);
    if (std::find(out.fonts.begin(), out.fonts.end(), font.name) == out.fonts.end())
      out.fonts.push_back(font.name);
    Placed p;
    p.font = &font;
    p.at = pen - Vec2(0.0, c.style.baseline_shift);  // a shift up is towards SVG's -y
    p.scale = c.style.font_size / font.units_per_em;
    p.decoration = c.style.decoration;
    const auto g = font.glyphs.find(c.code);
    if (g != font.glyphs.end()) {
      p.glyph = &g->second;
      p.advance = g->second.advance * p.scale;
      out.glyphs += c.code != U' ' && !g->second.paths.empty();
    } else {
      ++out.missing;
      p.advance = 0.5 * c.style.font_size;  // an en space keeps the words apart
    }
    // CSS: letter-spacing after every character, word-spacing after every space
    p.advance += c.style.letter_spacing + (c.code == U' ' ? c.style.word_spacing : 0.0);
    pen.x() += p.advance;
    placed.push_back(p);
  }
  close_chunk(t.chars.size());
  return placed;
}

// Underline, overline and line-through of runs of characters that share the decoration,
// font, size and baseline and follow each other: lines in user units at the font's metrics
// (open strokes for single-stroke fonts, closed bars of the underline thickness for outlines).
std::vector<SubPath> decorations(const std::vector<Placed>& placed) {
  std::vector<SubPath> out;
  for (std::size_t b = 0; b < placed.size();) {
    const Placed& first = placed[b];
    std::size_t e = b + 1;
    while (e < placed.size() && placed[e].decoration == first.decoration &&
           placed[e].font == first.font && placed[e].scale == first.scale &&
           placed[e].at.y() == first.at.y() &&
           std::abs(placed[e].at.x() - (placed[e - 1].at.x() + placed[e - 1].advance)) <
               1e-9 * (1 + std::abs(placed[e].at.x()))) {
      ++e;
    }
    const double x0 = first.at.x(), x1 = placed[e - 1].at.x() + placed[e - 1].advance;
    if (first.decoration != 0 && first.font != nullptr && x1 > x0) {
      const Font& f = *first.font;
      for (const auto& [flag, height] :
           {std::pair{kUnderline, f.underline_position}, std::pair{kOverline, f.overline_position},
            std::pair{kLineThrough, f.strikeout_position}}) {
        if (!(first.decoration & flag)) continue;
        const double y = first.at.y() - height * first.scale;  // font y up, SVG y down
        if (f.single_stroke) {
          out.push_back(polyline_path({x0, y, x1, y}, false));
        } else {
          const double h = f.underline_thickness * first.scale / 2;
          out.push_back(polyline_path({x0, y - h, x1, y - h, x1, y + h, x0, y + h}, true));
        }
      }
    }
    b = e;
  }
  return out;
}

// Spacing and shifts add up along a line: a glyph placed beyond the coordinate bound is
// refused like any other coordinate of the drawing.
SubPath checked(SubPath p) {
  const double m = max_abs_coordinate(p);
  if (!(m <= kMaxCoordinateMm)) {
    throw InputError("text: a glyph lies at " +
                     (std::isfinite(m) ? short_number(m) + " mm"
                                       : std::string("a coordinate that is not finite")) +
                     " (at most " + short_number(kMaxCoordinateMm) + " mm from the origin)");
  }
  return p;
}

}  // namespace

TextMode text_mode_from_string(const std::string& name) {
  if (name == "hershey") return TextMode::Hershey;
  if (name == "outline") return TextMode::Outline;
  if (name == "none") return TextMode::None;
  throw InputError("plot.text = " + name + ": must be one of hershey, outline, none");
}

std::string hershey_name(const std::string& font) {
  const std::string prefix = "hershey:";
  return font.rfind(prefix, 0) == 0 ? font.substr(prefix.size()) : "";
}

std::string TextDrawing::summary() const {
  std::string s = std::to_string(elements) + " element(s), " + std::to_string(glyphs) + " glyphs";
  if (missing > 0) s += ", " + std::to_string(missing) + " character(s) without a glyph";
  std::string list;
  for (const auto& f : fonts) list += (list.empty() ? "" : ", ") + f;
  return s + (list.empty() ? "" : " (" + list + ")");
}

TextDrawing layout_text(const std::vector<SvgText>& texts, const TextOptions& o) {
  TextDrawing out;
  if (o.mode == TextMode::None) return out;
  FontCache cache{o, {}, {}};
  for (const auto& t : texts) {
    for (const auto& c : t.chars) cache.all_chars.push_back(c.code);
  }
  for (const auto& t : texts) {
    SvgShape shape;
    shape.element = "text";
    shape.group_ids = t.group_ids;
    shape.layer_labels = t.layer_labels;
    const bool strokes = o.mode == TextMode::Hershey;
    // single strokes are drawn whether the text is filled or stroked; outlines follow the style
    shape.stroked = strokes ? (t.stroked || t.filled) : t.stroked;
    shape.filled = strokes ? false : t.filled;
    shape.stroke_color = t.stroked ? t.stroke_color : strokes ? t.fill_color : "";
    shape.fill_color = t.fill_color;
    if (!shape.stroked && !shape.filled) continue;
    const std::vector<Placed> placed = place(t, cache, out);
    for (const Placed& p : placed) {
      if (p.glyph == nullptr) continue;
      Affine m;
      m.linear = t.to_mm.linear *
                 Eigen::DiagonalMatrix<double, 2>(p.scale, -p.scale);  // font y up, SVG y down
      m.offset = t.to_mm.apply(p.at);
      for (const auto& path : p.glyph->paths) shape.paths.push_back(checked(transformed(path, m)));
    }
    for (const SubPath& line : decorations(placed))
      shape.paths.push_back(checked(transformed(line, t.to_mm)));
    if (shape.paths.empty()) continue;
    ++out.elements;
    out.shapes.push_back(std::move(shape));
  }
  return out;
}

}  // namespace strand::slicer
