// G-code reader: any file (Strand's or another slicer's) into a MotionProgram, plus the
// problems found while reading (inch units, non-finite numbers, arcs).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "slicer/motion.h"

namespace strand::post {

// Arcs a reader can flatten: radii outside [kMinArcRadiusMm, kMaxArcRadiusMm] (a kilometre)
// are read as straight moves and reported; the chords of all arcs at the finest flattening
// tolerance (kMinFlattenToleranceMm) are bounded by kMaxArcChords, so no file makes checks
// or previews flatten without end.
inline constexpr double kMinArcRadiusMm = 1e-4;
inline constexpr double kMaxArcRadiusMm = 1e6;
inline constexpr double kMinFlattenToleranceMm = 1e-3;
inline constexpr double kMaxArcChords = 5e7;

struct ParseIssue {
  int line = 0;        // 1-based line number
  std::string what;    // "inch units (G20)", "non-finite number in 'X nan'"
};

struct ParsedGcode {
  slicer::MotionProgram program;
  std::vector<ParseIssue> issues;
  std::vector<int> arc_lines;      // lines holding G2/G3
  std::vector<int> move_lines;     // source line of each move in program.moves
  // Rotary-axis files (A words, degrees): the A position after each move, parallel to
  // program.moves; empty when the file has no A word.
  std::vector<double> a_deg;
  bool has_e = false;              // deposits are recognised by E when true, by G1 otherwise
  bool inches = false;
};

// Layers come from ;LAYER:/;LAYER_CHANGE comments when present, else from z changes of
// deposits. A deposit is a move with growing E (files with E words) or any G1/G2/G3 that
// moves in XY (files without E, as for valve and pen machines).
ParsedGcode parse_gcode(std::string_view text);

}  // namespace strand::post
