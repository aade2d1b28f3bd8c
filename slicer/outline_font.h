// Outline fonts installed on the system: fontconfig finds the file for a family, FreeType
// reads the glyph contours (lines, conics and cubics, kept exact as cubics).
#pragma once

#include <optional>
#include <string>

#include "slicer/font.h"

namespace strand::slicer {

// Loads the glyphs of `chars` from the font fontconfig matches for one family name
// ("DejaVu Sans"; generic names such as "sans-serif" take the system's default), weight
// ("normal", "bold", "100".."900") and style ("normal", "italic", "oblique"). Throws
// InputError naming the family when no installed font carries it.
Font load_outline_font(const std::string& family, const std::string& weight,
                       const std::string& style, const std::u32string& chars);

// The first family of a CSS font-family list ("'Foo', Bar, sans-serif") that is installed,
// or std::nullopt; generic families always count as installed.
std::optional<std::string> installed_family(const std::string& font_family_list);

}  // namespace strand::slicer
