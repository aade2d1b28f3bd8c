// Fixed-digit number formatting for G-code: 3 decimals for XYZ/IJ, 5 for E, 0 for F.
// One formatter so output is byte-identical for identical input.
#pragma once

#include <cstddef>
#include <string>

#include "slicer/toolpath.h"

namespace strand::machines {

// Room fixed_chars needs: sign, 15 integer digits, point, 9 decimals, or the long form of
// huge and non-finite values.
inline constexpr std::size_t kFixedCharsMax = 352;

// Writes fixed-point text with `decimals` digits into `out` (at least kFixedCharsMax chars),
// returns the length; never writes "-0.000". No allocation: the emitters' hot path.
std::size_t fixed_chars(char* out, double v, int decimals);
// The same text as a string.
std::string fmt_fixed(double v, int decimals);
inline std::string fmt_xyz(double mm) { return fmt_fixed(mm, 3); }
inline std::string fmt_e(double e) { return fmt_fixed(e, 5); }
inline std::string fmt_feed(double mm_per_min) { return fmt_fixed(mm_per_min, 0); }

// Text made safe inside one G-code comment: control characters (a newline would start a
// new, uncommented line: G-code injection) become spaces; with `parentheses` false (GRBL's
// "( ... )" comments cannot nest) ( and ) become [ and ].
std::string comment_text(std::string text, bool parentheses = true);

// PrusaSlicer's viewer knows only its own role names in ;TYPE:; this maps ours onto them.
std::string viewer_role(slicer::Feature f);

// `s` with every `from` replaced by `to` (the profiles' {placeholders} in templates).
std::string replace_all(std::string s, const std::string& from, const std::string& to);

}  // namespace strand::machines
