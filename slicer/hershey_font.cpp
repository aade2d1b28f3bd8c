// Hershey fonts through libhersheyfont: the library finds the .jhf files of
// hershey-fonts-data where Debian installs them and turns each glyph into polylines.
#include "slicer/hershey_font.h"

// hersheyfont.h is a C header without extern "C" guards.
extern "C" {
#include <hersheyfont.h>
}

#include <algorithm>
#include <memory>

#include "slicer/input_error.h"

namespace strand::slicer {

namespace {

struct FontDeleter {
  void operator()(hershey_font* f) const { hershey_font_free(f); }
};

// libhersheyfont gives x from the glyph's left edge and y up from the baseline.
Glyph glyph_of(const hershey_glyph& g) {
  Glyph out;
  out.advance = g.width;
  for (const hershey_path* p = g.paths; p != nullptr; p = p->next) {
    if (p->nverts < 2) continue;
    SubPath s;
    s.start = Vec2(p->verts[0].x, p->verts[0].y);
    for (int i = 1; i < p->nverts; ++i) {
      CurvePiece c;
      c.p[0] = Vec2(p->verts[i].x, p->verts[i].y);
      s.pieces.push_back(c);
    }
    s.closed = s.pieces.back().p[0] == s.start;
    out.paths.push_back(std::move(s));
  }
  return out;
}

std::string installed_list() {
  std::string list;
  for (const auto& n : hershey_font_names()) list += (list.empty() ? "" : ", ") + n;
  return list;
}

}  // namespace

const std::vector<std::string>& hershey_font_names() {
  static const std::vector<std::string> kNames = {
      "astrology", "cursive",  "cyrilc_1",  "cyrillic",  "futural",   "futuram",  "gothgbt",
      "gothgrt",   "gothiceng", "gothicger", "gothicita", "gothitt",   "greek",    "greekc",
      "greeks",    "japanese", "markers",   "mathlow",   "mathupp",   "meteorology", "music",
      "rowmand",   "rowmans",  "rowmant",   "scriptc",   "scripts",   "symbolic", "timesg",
      "timesi",    "timesib",  "timesr",    "timesrb"};
  return kNames;
}

Font load_hershey_font(const std::string& name) {
  const bool known = std::find(hershey_font_names().begin(), hershey_font_names().end(), name) !=
                     hershey_font_names().end();
  // only names from the list reach the library, so no path can be smuggled in
  std::unique_ptr<hershey_font, FontDeleter> f(known ? hershey_font_load(name.c_str()) : nullptr);
  if (!f) {
    throw InputError("font = hershey:" + name + ": not an installed Hershey font (hershey-fonts-data has " +
                     installed_list() + ")");
  }
  Font font;
  font.name = "hershey:" + name;
  font.single_stroke = true;
  font.units_per_em = kHersheyUnitsPerEm;
  // the 32-unit body: capitals 21 units tall, lower case 14, descenders 7 below the baseline
  font.underline_position = -4.0;
  font.underline_thickness = 1.0;
  font.strikeout_position = 7.0;
  font.overline_position = 24.0;
  for (int c = 32; c < 127; ++c) {
    const hershey_glyph* g = hershey_font_glyph(f.get(), static_cast<unsigned char>(c));
    if (g != nullptr && (g->width > 0 || g->npaths > 0)) font.glyphs[static_cast<char32_t>(c)] = glyph_of(*g);
  }
  return font;
}

}  // namespace strand::slicer
