// Outline fonts: fontconfig matches a family to a file, FreeType decomposes each glyph's
// contours in font units (no scaling, no hinting), conics raised to exact cubics.
#include "slicer/outline_font.h"

#include <fontconfig/fontconfig.h>
#include <ft2build.h>
#include FT_FREETYPE_H
#include FT_OUTLINE_H
#include FT_TRUETYPE_TABLES_H

#include <algorithm>
#include <cctype>
#include <memory>
#include <vector>

#include "slicer/input_error.h"

namespace strand::slicer {

namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

bool generic_family(const std::string& f) {
  static const char* kGeneric[] = {"serif", "sans-serif", "sans", "monospace", "cursive", "fantasy", "system-ui"};
  return std::find(std::begin(kGeneric), std::end(kGeneric), lower(f)) != std::end(kGeneric);
}

// "'DejaVu Sans', Arial,sans-serif" -> {"DejaVu Sans", "Arial", "sans-serif"}
std::vector<std::string> family_list(const std::string& text) {
  std::vector<std::string> out;
  std::string item;
  for (std::size_t i = 0; i <= text.size(); ++i) {
    if (i == text.size() || text[i] == ',') {
      auto b = item.find_first_not_of(" \t\"'"), e = item.find_last_not_of(" \t\"'");
      if (b != std::string::npos) out.push_back(item.substr(b, e - b + 1));
      item.clear();
    } else {
      item += text[i];
    }
  }
  return out;
}

struct PatternDeleter {
  void operator()(FcPattern* p) const { FcPatternDestroy(p); }
};
using Pattern = std::unique_ptr<FcPattern, PatternDeleter>;

int fc_weight(const std::string& w) {
  if (w == "bold" || w == "bolder") return FC_WEIGHT_BOLD;
  if (w == "lighter") return FC_WEIGHT_LIGHT;
  if (!w.empty() && std::all_of(w.begin(), w.end(), [](unsigned char c) { return std::isdigit(c); })) {
    return FcWeightFromOpenType(std::stoi(w));
  }
  return FC_WEIGHT_REGULAR;
}

// The font fontconfig picks for a family, or null when the family is not installed.
Pattern match(const std::string& family, const std::string& weight, const std::string& style) {
  if (!FcInit()) return nullptr;
  Pattern pat(FcPatternCreate());
  FcPatternAddString(pat.get(), FC_FAMILY, reinterpret_cast<const FcChar8*>(family.c_str()));
  FcPatternAddInteger(pat.get(), FC_WEIGHT, fc_weight(weight));
  FcPatternAddInteger(pat.get(), FC_SLANT, style == "italic" ? FC_SLANT_ITALIC : style == "oblique" ? FC_SLANT_OBLIQUE : FC_SLANT_ROMAN);
  FcPatternAddBool(pat.get(), FC_OUTLINE, FcTrue);
  FcConfigSubstitute(nullptr, pat.get(), FcMatchPattern);
  FcDefaultSubstitute(pat.get());
  FcResult result = FcResultNoMatch;
  Pattern found(FcFontMatch(nullptr, pat.get(), &result));
  if (!found || result != FcResultMatch) return nullptr;
  if (generic_family(family)) return found;
  FcChar8* name = nullptr;
  for (int i = 0; FcPatternGetString(found.get(), FC_FAMILY, i, &name) == FcResultMatch; ++i) {
    if (lower(reinterpret_cast<const char*>(name)) == lower(family)) return found;
  }
  return nullptr;  // fontconfig fell back to another family: the one asked for is missing
}

struct Decomposer {
  std::vector<SubPath> paths;
  Vec2 at = Vec2::Zero();

  static Vec2 v(const FT_Vector* p) { return Vec2(static_cast<double>(p->x), static_cast<double>(p->y)); }
  static Decomposer& self(void* user) { return *static_cast<Decomposer*>(user); }
  static int move_to(const FT_Vector* to, void* user) {
    auto& d = self(user);
    d.at = v(to);
    d.paths.push_back({d.at, {}, true});
    return 0;
  }
  static int line_to(const FT_Vector* to, void* user) {
    auto& d = self(user);
    CurvePiece c;
    c.p[0] = v(to);
    d.paths.back().pieces.push_back(c);
    d.at = c.p[0];
    return 0;
  }
  static int conic_to(const FT_Vector* control, const FT_Vector* to, void* user) {
    auto& d = self(user);
    const Vec2 q = v(control), e = v(to);  // quadratic -> the exact cubic
    CurvePiece c;
    c.kind = CurveKind::Cubic;
    c.p[0] = d.at + 2.0 / 3.0 * (q - d.at);
    c.p[1] = e + 2.0 / 3.0 * (q - e);
    c.p[2] = e;
    d.paths.back().pieces.push_back(c);
    d.at = e;
    return 0;
  }
  static int cubic_to(const FT_Vector* c1, const FT_Vector* c2, const FT_Vector* to, void* user) {
    auto& d = self(user);
    CurvePiece c;
    c.kind = CurveKind::Cubic;
    c.p[0] = v(c1);
    c.p[1] = v(c2);
    c.p[2] = v(to);
    d.paths.back().pieces.push_back(c);
    d.at = c.p[2];
    return 0;
  }
};

struct LibraryDeleter {
  void operator()(FT_Library l) const { FT_Done_FreeType(l); }
};
struct FaceDeleter {
  void operator()(FT_Face f) const { FT_Done_Face(f); }
};

Glyph load_glyph(FT_Face face, char32_t code) {
  Glyph g;
  const FT_UInt index = FT_Get_Char_Index(face, code);
  if (index == 0 || FT_Load_Glyph(face, index, FT_LOAD_NO_SCALE) != 0) return g;
  g.advance = static_cast<double>(face->glyph->advance.x);
  if (face->glyph->format != FT_GLYPH_FORMAT_OUTLINE) return g;
  FT_Outline_Funcs funcs{};
  funcs.move_to = &Decomposer::move_to;
  funcs.line_to = &Decomposer::line_to;
  funcs.conic_to = &Decomposer::conic_to;
  funcs.cubic_to = &Decomposer::cubic_to;
  Decomposer d;
  FT_Outline_Decompose(&face->glyph->outline, &funcs, &d);
  std::erase_if(d.paths, [](const SubPath& s) { return s.pieces.empty(); });
  g.paths = std::move(d.paths);
  return g;
}

}  // namespace

std::optional<std::string> installed_family(const std::string& font_family_list) {
  for (const auto& f : family_list(font_family_list)) {
    if (match(f, "normal", "normal")) return f;
  }
  return std::nullopt;
}

Font load_outline_font(const std::string& family, const std::string& weight, const std::string& style,
                       const std::u32string& chars) {
  const Pattern found = match(family, weight, style);
  FcChar8* file = nullptr;
  int index = 0;
  if (!found || FcPatternGetString(found.get(), FC_FILE, 0, &file) != FcResultMatch) {
    throw InputError("font = \"" + family + "\": not an installed font (fc-list shows the installed ones)");
  }
  FcPatternGetInteger(found.get(), FC_INDEX, 0, &index);
  FT_Library raw_lib = nullptr;
  if (FT_Init_FreeType(&raw_lib) != 0) throw InputError("font = \"" + family + "\": FreeType cannot start");
  std::unique_ptr<FT_LibraryRec_, LibraryDeleter> lib(raw_lib);
  FT_Face raw_face = nullptr;
  if (FT_New_Face(lib.get(), reinterpret_cast<const char*>(file), index, &raw_face) != 0) {
    throw InputError("font = \"" + family + "\": " + reinterpret_cast<const char*>(file) + " is not a font FreeType reads");
  }
  std::unique_ptr<FT_FaceRec_, FaceDeleter> face(raw_face);
  Font font;
  FcChar8* fam = nullptr;
  FcChar8* sty = nullptr;
  FcPatternGetString(found.get(), FC_FAMILY, 0, &fam);
  FcPatternGetString(found.get(), FC_STYLE, 0, &sty);
  font.name = std::string(fam ? reinterpret_cast<const char*>(fam) : family.c_str()) +
              (sty ? " " + std::string(reinterpret_cast<const char*>(sty)) : "");
  font.single_stroke = false;
  font.units_per_em = face->units_per_EM > 0 ? face->units_per_EM : 1000.0;
  const double em = font.units_per_em;
  font.underline_thickness = face->underline_thickness > 0 ? face->underline_thickness : 0.05 * em;
  font.underline_position = face->underline_position != 0 ? face->underline_position : -0.1 * em;
  font.overline_position = (face->ascender > 0 ? face->ascender : 0.8 * em) - font.underline_thickness / 2;
  font.strikeout_position = 0.25 * em;
  if (const auto* os2 = static_cast<const TT_OS2*>(FT_Get_Sfnt_Table(face.get(), FT_SFNT_OS2));
      os2 != nullptr && os2->version != 0xFFFF && os2->yStrikeoutSize > 0) {
    font.strikeout_position = os2->yStrikeoutPosition - os2->yStrikeoutSize / 2.0;  // top -> centre
  }
  for (char32_t c : chars) {
    if (font.glyphs.count(c)) continue;
    Glyph g = load_glyph(face.get(), c);
    if (g.advance > 0 || !g.paths.empty()) font.glyphs[c] = std::move(g);
  }
  return font;
}

}  // namespace strand::slicer
