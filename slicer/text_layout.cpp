// Placing glyphs: pen position from absolute x/y and relative dx/dy, advance by the glyph
// width times font-size / units-per-em, then each text chunk shifted for its anchor.
#include "slicer/text_layout.h"

#include <map>
#include <optional>

#include "slicer/hershey_font.h"
#include "slicer/input_error.h"
#include "slicer/outline_font.h"

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
      if (!found) throw InputError("text font-family = " + s.font_family + ": no installed font carries it (fc-list shows the installed fonts; --font NAME picks one)");
      family = *found;
    }
    const std::string key = family + "|" + s.font_weight + "|" + s.font_style;
    if (!fonts.count(key)) fonts.emplace(key, load_outline_font(family, s.font_weight, s.font_style, all_chars));
    return fonts.at(key);
  }
};

struct Placed {
  const Glyph* glyph = nullptr;
  Vec2 at = Vec2::Zero();  // user units, baseline origin of the glyph
  double scale = 1.0;      // user units per font unit
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
    if (std::find(out.fonts.begin(), out.fonts.end(), font.name) == out.fonts.end()) out.fonts.push_back(font.name);
    Placed p;
    p.at = pen;
    p.scale = c.style.font_size / font.units_per_em;
    const auto g = font.glyphs.find(c.code);
    if (g != font.glyphs.end()) {
      p.glyph = &g->second;
      pen.x() += g->second.advance * p.scale;
      out.glyphs += c.code != U' ' && !g->second.paths.empty();
    } else {
      ++out.missing;
      pen.x() += 0.5 * c.style.font_size;  // an en space keeps the words apart
    }
    placed.push_back(p);
  }
  close_chunk(t.chars.size());
  return placed;
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
    for (const Placed& p : place(t, cache, out)) {
      if (p.glyph == nullptr) continue;
      Affine m;
      m.linear = t.to_mm.linear * Eigen::DiagonalMatrix<double, 2>(p.scale, -p.scale);  // font y up, SVG y down
      m.offset = t.to_mm.apply(p.at);
      for (const auto& path : p.glyph->paths) shape.paths.push_back(transformed(path, m));
    }
    if (shape.paths.empty()) continue;
    ++out.elements;
    out.shapes.push_back(std::move(shape));
  }
  return out;
}

}  // namespace strand::slicer
