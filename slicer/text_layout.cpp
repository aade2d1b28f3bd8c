// Placing glyphs: pen position from absolute x/y and relative dx/dy, advance by the glyph
// width times font-size / units-per-em, then each text chunk shifted for its anchor; on a
// text path the pen moves along the path and each glyph is turned to the path's tangent.
#include "slicer/text_layout.h"

#include <Eigen/SVD>
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

  // The outline font whose advances --text-width fit matches: the first installed family of
  // the style's list, else fontconfig's sans-serif (what a browser on it falls back to).
  const Font& measure_for(const TextStyle& s) {
    const std::string family = installed_family(s.font_family).value_or("sans-serif");
    const std::string key = "widths|" + family + "|" + s.font_weight + "|" + s.font_style;
    if (!fonts.count(key))
      fonts.emplace(key, load_outline_font(family, s.font_weight, s.font_style, all_chars));
    return fonts.at(key);
  }
};

void add_font_name(TextDrawing& out, const std::string& name) {
  if (std::find(out.fonts.begin(), out.fonts.end(), name) == out.fonts.end())
    out.fonts.push_back(name);
}

// A text path measured along its length (SVG 1.1, 10.13.3): flattened, with the distance
// from its start at every point; the jumps between sub-paths count for nothing. The tangent
// is blended along each chord between the directions on either side of its ends where the
// path is smooth (inside a curve, or a joint turning less than kSmoothTurn), so glyphs turn
// with the curve rather than with its chords.
class PathRuler {
 public:
  struct Point {
    Vec2 at;
    Vec2 tangent;  // unit
  };

  PathRuler(const std::vector<SubPath>& paths, double tolerance) {
    for (const SubPath& sp : paths) {
      push(sp.start, true, false);
      Vec2 from = sp.start;
      for (const CurvePiece& piece : sp.pieces) {
        const Polyline q = flatten(SubPath{from, {piece}, false}, tolerance);
        for (std::size_t i = 1; i < q.size(); ++i)
          push(q[i], false, piece.kind != CurveKind::Line && i + 1 < q.size());
        from = piece.end();
      }
    }
    for (std::size_t k = 1; k + 1 < p_.size(); ++k) {  // joints that hardly turn
      const Vec2 in = dir(k), out = dir(k + 1);
      if (!smooth_[k] && in != Vec2::Zero() && out != Vec2::Zero() &&
          in.dot(out) > std::cos(kSmoothTurn))
        smooth_[k] = 1;
    }
  }

  double length() const { return s_.empty() ? 0.0 : s_.back(); }
  // Where the path ends (the last point of its last sub-path).
  Vec2 end() const { return p_.empty() ? Vec2::Zero() : p_.back(); }

  // The point at distance d along the path and the tangent there; before the start and past
  // the end, on the tangent line through that end.
  Point at(double d) const {
    const double length = this->length();
    if (!(length > 0)) return {p_.empty() ? Vec2::Zero() : p_.front(), Vec2(1, 0)};
    if (d < 0 || d > length) {
      const Point e = at(d < 0 ? 0.0 : length);
      return {e.at + (d < 0 ? d : d - length) * e.tangent, e.tangent};
    }
    // the chord k-1 -> k holding d: s_[k - 1] <= d < s_[k] (at the very end, the last chord)
    auto it = std::upper_bound(s_.begin(), s_.end(), d);
    if (it == s_.end()) it = std::lower_bound(s_.begin(), s_.end(), length);
    const auto k = static_cast<std::size_t>(it - s_.begin());
    const double chord = s_[k] - s_[k - 1], u = (d - s_[k - 1]) / chord;
    const Vec2 along = (p_[k] - p_[k - 1]) / chord;
    const auto blend = [&along](bool smooth, const Vec2& other) {
      const Vec2 sum = along + other;
      return smooth && other != Vec2::Zero() && sum.norm() > 1e-9 ? Vec2(sum.normalized()) : along;
    };
    const Vec2 ta = blend(smooth_[k - 1], dir(k - 1));
    const Vec2 tb = blend(smooth_[k], k + 1 < p_.size() ? dir(k + 1) : Vec2::Zero());
    const Vec2 t = (1 - u) * ta + u * tb;
    return {p_[k - 1] + (d - s_[k - 1]) * along, t.norm() > 1e-9 ? Vec2(t.normalized()) : along};
  }

 private:
  // Joints turning less than this are taken as smooth (a curve drawn as short lines).
  static constexpr double kSmoothTurn = 0.1;  // radians

  std::vector<Vec2> p_;
  std::vector<double> s_;                // distance from the start at each point
  std::vector<unsigned char> smooth_;    // the path is smooth through the point
  std::vector<unsigned char> starts_;    // a sub-path starts at the point

  void push(const Vec2& v, bool start, bool smooth) {
    s_.push_back(p_.empty() ? 0.0 : s_.back() + (start ? 0.0 : (v - p_.back()).norm()));
    p_.push_back(v);
    smooth_.push_back(smooth);
    starts_.push_back(start);
  }
  // The unit direction of the chord that ends at point k; zero when there is none.
  Vec2 dir(std::size_t k) const {
    if (k == 0 || starts_[k] || !(s_[k] > s_[k - 1])) return Vec2::Zero();
    return (p_[k] - p_[k - 1]) / (s_[k] - s_[k - 1]);
  }
};

// Flattening tolerance of each text's paths in its user units: kTextPathToleranceMm through
// the largest stretch of its transform, coarsened for all texts together (16 times at a
// time) while their bound on the flattened points is above kMaxTextPathPoints and falls.
std::vector<double> path_tolerances(const std::vector<SvgText>& texts) {
  std::vector<double> tolerance(texts.size(), INFINITY);
  for (std::size_t i = 0; i < texts.size(); ++i) {
    if (texts[i].paths.empty()) continue;
    const double sigma =
        Eigen::JacobiSVD<Eigen::Matrix2d>(texts[i].to_mm.linear).singularValues()(0);
    if (sigma > 0 && std::isfinite(sigma)) tolerance[i] = kTextPathToleranceMm / sigma;
  }
  double factor = 1.0, last = INFINITY;
  for (int round = 0; round < 64; ++round) {
    double points = 0.0;
    for (std::size_t i = 0; i < texts.size(); ++i) {
      for (const auto& tp : texts[i].paths) {
        for (const auto& sp : tp.paths) points += flatten_point_bound(sp, tolerance[i] * factor);
      }
    }
    if (points <= kMaxTextPathPoints || !(points < last)) break;
    last = points;
    factor *= 16.0;
  }
  for (double& t : tolerance) t *= factor;
  return tolerance;
}

struct Placed {
  const Glyph* glyph = nullptr;
  const Font* font = nullptr;
  char32_t code = U' ';
  // Baseline origin of the glyph in its line, baseline-shift applied: user units, or on a
  // text path (distance along it, offset across it towards SVG's +y when it runs along +x).
  Vec2 at = Vec2::Zero();
  double scale = 1.0;      // user units per font unit
  double stretch = 1.0;    // horizontal factor of --text-width fit
  double width = 0.0;      // user units of the glyph's own advance
  double advance = 0.0;    // user units to the next character, spacing included
  unsigned decoration = 0;
  int path = -1;           // index in SvgText::paths, -1 for none
  bool on_path = true;     // false: on a text path, its middle off the path (not drawn)
  Affine frame;            // the glyph's baseline frame (origin, x along its baseline) ->
                           // the text's user space, SVG y down
};

// Horizontal factors of --text-width fit, one per character: each run (characters of one
// chunk in one font-family, weight and style) gets the ratio of its advance in the font the
// drawing names to its Hershey advance (characters in both fonts; spacing not included).
std::vector<double> fit_stretch(const SvgText& t, FontCache& cache, TextDrawing& out) {
  std::vector<double> stretch(t.chars.size(), 1.0);
  const auto starts_run = [&t](std::size_t i) {
    const TextChar &c = t.chars[i], &p = t.chars[i - 1];
    return c.path != p.path || (c.path >= 0 ? bool(c.x) : c.x || c.y) ||
           c.style.font_family != p.style.font_family ||
           c.style.font_weight != p.style.font_weight || c.style.font_style != p.style.font_style;
  };
  for (std::size_t b = 0; b < t.chars.size();) {
    std::size_t e = b + 1;
    while (e < t.chars.size() && !starts_run(e)) ++e;
    double natural = 0.0, named = 0.0;
    for (std::size_t i = b; i < e; ++i) {
      const TextChar& c = t.chars[i];
      const Font& h = cache.font_for(c.style);
      const Font& m = cache.measure_for(c.style);
      add_font_name(out, h.name);
      add_font_name(out, "widths of " + m.name);
      const auto gh = h.glyphs.find(c.code), gm = m.glyphs.find(c.code);
      if (gh == h.glyphs.end() || gm == m.glyphs.end()) continue;
      natural += gh->second.advance / h.units_per_em * c.style.font_size;
      named += gm->second.advance / m.units_per_em * c.style.font_size;
    }
    if (natural > 0 && named > 0) std::fill(stretch.begin() + b, stretch.begin() + e, named / natural);
    b = e;
  }
  return stretch;
}

// Where a text path's characters start: startOffset along it (a fraction of its length, or
// in the units of its pathLength).
double start_offset(const TextPathShape& tp, const PathRuler& r) {
  if (tp.start_offset_fraction) return tp.start_offset * r.length();
  return tp.path_length > 0 ? tp.start_offset * r.length() / tp.path_length : tp.start_offset;
}

// Positions of every character of one text element (before the transform to mm): pen
// positions, chunks anchored, then each glyph's frame (on a path: its origin at its distance
// along the path, turned to the tangent at its middle, SVG 1.1, 10.13.3).
std::vector<Placed> place(const SvgText& t, const std::vector<PathRuler>& rulers,
                          const std::vector<double>& stretch, FontCache& cache, TextDrawing& out) {
  std::vector<Placed> placed;
  Vec2 pen = Vec2::Zero();
  int path = -1;  // the current chunk's text path
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
    if (c.path != path) {  // a text path starts its own chunk; after it, text goes on from its end
      close_chunk(i);
      chunk_start = i;
      pen = c.path >= 0 ? Vec2(start_offset(t.paths[c.path], rulers[c.path]), 0.0)
                        : rulers[path].end();
      path = c.path;
    }
    if (c.path >= 0 ? bool(c.x) : c.x || c.y) {  // on a path, x is a distance along it
      close_chunk(i);
      chunk_start = i;
      if (c.x) pen.x() = *c.x;
      if (c.y && c.path < 0) pen.y() = *c.y;
    }
    pen += Vec2(c.dx, c.dy);
    const Font& font = cache.font_for(c.style);
    add_font_name(out, font.name);
    Placed p;
    p.font = &font;
    p.code = c.code;
    p.at = pen - Vec2(0.0, c.style.baseline_shift);  // a shift up is towards SVG's -y
    p.scale = c.style.font_size / font.units_per_em;
    p.stretch = stretch.empty() ? 1.0 : stretch[i];
    p.decoration = c.style.decoration;
    p.path = c.path;
    const auto g = font.glyphs.find(c.code);
    if (g != font.glyphs.end()) {
      p.glyph = &g->second;
      p.width = g->second.advance * p.scale * p.stretch;
    } else {
      ++out.missing;
      p.width = 0.5 * c.style.font_size;  // an en space keeps the words apart
    }
    // CSS: letter-spacing after every character, word-spacing after every space
    p.advance = p.width + c.style.letter_spacing + (c.code == U' ' ? c.style.word_spacing : 0.0);
    pen.x() += p.advance;
    placed.push_back(p);
  }
  close_chunk(t.chars.size());
  for (Placed& p : placed) {
    if (p.path < 0) {
      p.frame.offset = p.at;
      continue;
    }
    const PathRuler& r = rulers[p.path];
    const double middle = p.at.x() + p.width / 2;
    p.on_path = middle >= 0 && middle <= r.length();
    const Vec2 tangent = r.at(middle).tangent;
    p.frame.linear << tangent.x(), -tangent.y(), tangent.y(), tangent.x();
    p.frame.offset = r.at(p.at.x()).at + p.frame.linear * Vec2(0.0, p.at.y());
  }
  return placed;
}

// Underline, overline and line-through of runs of characters that share the decoration,
// font, size, line and baseline and follow each other: lines in user units at the font's
// metrics (open strokes for single-stroke fonts, closed bars of the underline thickness for
// outlines); on a text path through every glyph's frame, so the line bends with the glyphs.
std::vector<SubPath> decorations(const std::vector<Placed>& placed) {
  std::vector<SubPath> out;
  for (std::size_t b = 0; b < placed.size();) {
    const Placed& first = placed[b];
    std::size_t e = b + 1;
    while (e < placed.size() && placed[e].decoration == first.decoration &&
           placed[e].font == first.font && placed[e].scale == first.scale &&
           placed[e].path == first.path && placed[e].on_path == first.on_path &&
           placed[e].at.y() == first.at.y() &&
           std::abs(placed[e].at.x() - (placed[e - 1].at.x() + placed[e - 1].advance)) <
               1e-9 * (1 + std::abs(placed[e].at.x()))) {
      ++e;
    }
    const double x0 = first.at.x(), x1 = placed[e - 1].at.x() + placed[e - 1].advance;
    if (first.decoration != 0 && first.font != nullptr && first.on_path && x1 > x0) {
      const Font& f = *first.font;
      // the line at height y of the glyphs' frames: their origins, then the run's end
      const auto line = [&](double y) {
        std::vector<Vec2> v{first.frame.apply(Vec2(0.0, y))};
        if (first.path >= 0) {
          for (std::size_t k = b + 1; k < e; ++k) v.push_back(placed[k].frame.apply(Vec2(0.0, y)));
        }
        v.push_back(placed[e - 1].frame.apply(Vec2(placed[e - 1].advance, y)));
        return v;
      };
      for (const auto& [flag, height] :
           {std::pair{kUnderline, f.underline_position}, std::pair{kOverline, f.overline_position},
            std::pair{kLineThrough, f.strikeout_position}}) {
        if (!(first.decoration & flag)) continue;
        const double y = -height * first.scale;  // font y up, SVG y down
        std::vector<Vec2> v;
        if (f.single_stroke) {
          v = line(y);
        } else {
          const double h = f.underline_thickness * first.scale / 2;
          v = line(y - h);
          const std::vector<Vec2> lower = line(y + h);
          v.insert(v.end(), lower.rbegin(), lower.rend());
        }
        std::vector<double> xy;
        for (const Vec2& q : v) xy.insert(xy.end(), {q.x(), q.y()});
        out.push_back(polyline_path(xy, !f.single_stroke));
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
  if (off_path > 0) s += ", " + std::to_string(off_path) + " character(s) off their path";
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
  const std::vector<double> tolerance = path_tolerances(texts);
  for (std::size_t i = 0; i < texts.size(); ++i) {
    const SvgText& t = texts[i];
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
    std::vector<PathRuler> rulers;
    for (const auto& tp : t.paths) rulers.emplace_back(tp.paths, tolerance[i]);
    const std::vector<double> stretch =
        o.fit_width && o.mode == TextMode::Hershey ? fit_stretch(t, cache, out) : std::vector<double>{};
    const std::vector<Placed> placed = place(t, rulers, stretch, cache, out);
    for (const Placed& p : placed) {
      if (!p.on_path) {
        out.off_path += p.code != U' ';
        continue;
      }
      if (p.glyph == nullptr) continue;
      out.glyphs += p.code != U' ' && !p.glyph->paths.empty();
      Affine m;
      m.linear = t.to_mm.linear * p.frame.linear *
                 Eigen::DiagonalMatrix<double, 2>(p.scale * p.stretch,
                                                  -p.scale);  // font y up, SVG y down
      m.offset = t.to_mm.apply(p.frame.offset);
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
