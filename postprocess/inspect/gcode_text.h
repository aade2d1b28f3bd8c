// Line-level pieces of the G-code reader: address words, trimming, comment roles, O-words
// and the test for lines that need the RS274NGC expression reader. No allocation per line
// except where an O-word or expression line needs its text.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "slicer/toolpath.h"

namespace strand::post::gcode {

// The address words of one line ("G1 X1.5 Y-2" -> G 1, X 1.5, Y -2), first 16 kept.
struct Words {
  char letter[16];
  double value[16];
  int count = 0;
  bool bad_number = false;
  std::optional<double> get(char c) const {
    for (int i = 0; i < count; ++i) {
      if (letter[i] == c) return value[i];
    }
    return std::nullopt;
  }
};

bool is_letter(char c);

// Splits "G1 X1.5 Y-2 E0.1" into letter/number words; stops at ';' or '('. A word whose
// number is nan/inf, or a G word followed by something that is not a number, sets
// bad_number; a bare letter ("G28 X Y") is a flag word and is skipped.
Words split_words(std::string_view code);

bool starts_with(std::string_view s, std::string_view p);
// Spaces and tabs off both ends, a carriage return off the end.
std::string_view trim(std::string_view s);

// Strand's ;FEATURE: name as a feature, or fallback for a name it does not write.
slicer::Feature feature_from_comment(std::string_view name, slicer::Feature fallback);
// Another slicer's ;TYPE: role (Cura "WALL-OUTER", "FILL"; PrusaSlicer "Perimeter",
// "Solid infill") as the nearest feature, so previews colour walls and fills apart. Every
// role that is not a wall (fills, gap fill, skirt, support, wipe tower) reads as infill:
// FDM rules let such moves cross. Strand's own files follow with ;FEATURE:, which wins.
slicer::Feature feature_from_role(std::string_view role);

// "o100 while [...]" / "o<name> call [1]": the O-word's name, keyword and where its
// arguments start.
struct OWord {
  std::string name;
  std::string keyword;  // lower-case; empty for a bare program number ("O1000")
  std::size_t args = 0;
};
// How the file writes the O-word: o100 or o<name>.
std::string o_text(const std::string& name);
// The line's O-word; nullopt when the line is no O-word.
std::optional<OWord> o_word(std::string_view s);

// Comments out: "(...)" anywhere and ';' to the end.
std::string strip_comments(std::string_view s);

// A line that needs the RS274NGC reader: parameters or expressions in its code, and not a
// vendor's extended command ("EXCLUDE_OBJECT_DEFINE ... POLYGON=[[..]]", "M117 [text]",
// RepRapFirmware's "G1 X{move.axes[0].max}", read as before: a malformed number).
bool is_ngc_line(std::string_view s);

}  // namespace strand::post::gcode
