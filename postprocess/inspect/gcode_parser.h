// G-code reader: any file (Strand's or another slicer's) into a MotionProgram, plus the
// problems found while reading (inch units, non-finite numbers, arcs).
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "postprocess/inspect/pen_reading.h"
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
  int line = 0;      // 1-based line number
  std::string what;  // "inch units (G20)", "non-finite number in 'X nan'"
};

struct ParsedGcode {
  slicer::MotionProgram program;
  std::vector<ParseIssue> issues;  // problems: the file is not read faithfully
  // How the file was read where it could be read more than one way (inch units converted,
  // which pen convention): reported, never a failure.
  std::vector<ParseIssue> notes;
  std::vector<int> arc_lines;   // lines holding G2/G3
  std::vector<int> move_lines;  // source line of each move in program.moves
  // Rotary-axis files (A words, degrees): the A position after each move, parallel to
  // program.moves; empty when the file has no A word.
  std::vector<double> a_deg;
  // E advanced by each move (relative or absolute E read as a step), parallel to a_deg; in
  // the pieces of a reading layer by layer (parse_gcode_layers) always, parallel to the moves.
  std::vector<double> e_step;
  bool has_e = false;  // deposits are recognised by E when true, by G1 otherwise
  bool inches = false;
  int pen_commands = 0;  // M300/M280/M3/M4/M5 read as pen up or down
  // Some were M300 S or M280 S: a pen servo. M3/M5 alone may drive a pen, a laser or a
  // GRBL machine's dispenser, so only a servo makes the file a drawing by default.
  bool pen_servo = false;
  // Colours of pens 1, 2, ... ("#rrggbb", empty when not given) from Strand's pen G-code
  // header ("; pen 2 colour: #d40000"); each move's pen is its tool, from ";PEN:k".
  std::vector<std::string> pen_colours;
};

// Pens a file may name (;PEN:k, "pen k colour:"); higher numbers are not read.
inline constexpr int kMaxPens = 64;

// Layers come from ;LAYER:/;LAYER_CHANGE comments when present, else from z changes of
// deposits. RS274NGC dialects (LinuxCNC, Planet CNC) are read: parameters (#1, #<name>,
// #<_x>/#<_y>/#<_z> the current position), [expressions] (ngc_expression.h), O-word
// subroutines, if/while/do/repeat blocks, run with a bound on repeated lines. Throws
// InputError naming the line for an expression error (division by zero, an unset
// parameter), unmatched O-word blocks and a loop past the bound; a construct the reader
// cannot follow (a call of a subroutine in another file, a probe result) is one issue
// "unsupported: ... at line N" and the rest of the file is not read. A milling program
// (spindle above 1000 rpm, cutting below z 0) is named in the issues. A deposit is a move with
// growing E (files with E words) or any G1/G2/G3 that moves in XY (files without E, as for valve
// and pen machines) while the pen, if the file lifts one (M300 S, M280 S, M3/M5 read through `pen`,
// or z above pen.z_down_max_mm), is down.
ParsedGcode parse_gcode(std::string_view text, const PenReading& pen = {});

// What a reading must know of the whole file before its first line (a first pass over a file
// read line by line): whether layers are marked, whether E tells deposits, whether it is an
// RS274NGC program with O-words (read from its whole text), and its first kHeadBytes.
struct GcodeScan {
  bool has_markers = false;  // ";LAYER" anywhere
  bool has_e = false;        // as parse_gcode decides it
  bool has_o_words = false;
  bool rotary = false;  // ";ROTARY_AXIS:" anywhere (curved_files.h)
  std::string head;
  static constexpr std::size_t kHeadBytes = 4096;
  void add_line(std::string_view raw_line);  // each line in order, without its '\n'
};
GcodeScan scan_gcode(std::string_view text);

// A reading handed over layer by layer. `piece` holds the moves read since the last call
// (program.moves with move_lines, dwells, texts, a_deg, e_step, arc_lines), all layers so
// far in program.layers (each final but the last, which the next call or the end closes),
// and the issues and notes so far; `first_move` is the index of piece.program.moves[0] in
// the whole reading. The reader calls it when a layer begins and at the end, then drops the
// moves.
using PieceSink = std::function<void(const ParsedGcode& piece, std::size_t first_move)>;
// Lines of one file in order, each without its '\n', the text after the last '\n' too.
using LineSource = std::function<void(const std::function<void(std::string_view)>& each)>;

// parse_gcode, but the moves go to `sink` a layer at a time: memory holds one layer. The
// result is parse_gcode's with no moves left in it. The text's form reads RS274NGC
// programs too; the lines' form needs `scan` of the same lines and no O-words.
ParsedGcode parse_gcode_layers(std::string_view text, const PenReading& pen,
                               const PieceSink& sink);
ParsedGcode parse_gcode_layers(const LineSource& lines, const GcodeScan& scan,
                               const PenReading& pen, const PieceSink& sink);

// parse_drawing's second reading: after a first reading `first` whose drawing (deposit)
// moves span [low_z_mm, high_z_mm], the pen reading by Z and the note that says so, when the
// file lifts its pen by neither command nor the profile's z; nullopt to keep the first.
struct PenByZ {
  PenReading pen;
  ParseIssue note;
};
std::optional<PenByZ> pen_by_z(const ParsedGcode& first, const PenReading& pen, double low_z_mm,
                               double high_z_mm);

// A pen drawing: as parse_gcode, and when the file lifts its pen by neither command nor the
// profile's z, drawing moves more than kPenLiftMinMm above the lowest one are read as pen-up
// travels (Z-lift plotters), with a note saying so.
ParsedGcode parse_drawing(std::string_view text, const PenReading& pen);

}  // namespace strand::post
