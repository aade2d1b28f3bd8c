// The G-code reader's state machine, shared by its two halves: gcode_parser.cpp (lines,
// comments, moves, arcs) and gcode_ngc_program.cpp (RS274NGC parameters, O-word blocks, calls).
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "postprocess/inspect/gcode_parser.h"
#include "postprocess/inspect/gcode_text.h"
#include "postprocess/inspect/ngc_expression.h"

namespace strand::post::gcode {

using slicer::Feature;
using slicer::Move;
using slicer::MoveKind;
using slicer::Vec3;

// G and M numbers are small; a huge one ("G1e12") names no command and would not fit int.
constexpr double kMaxCommandNumber = 1e6;

// An issue quotes at most this much of its line: a file of one huge line keeps a short report.
constexpr std::size_t kQuotedLineBytes = 200;

// A milling program: the spindle turns faster than any pen servo or laser value (S > this,
// rpm) and a cutting move goes below the work surface (z < -kPlungeMm).
constexpr double kSpindleMinRpm = 1000.0;
constexpr double kPlungeMm = 0.05;

// O-word programs may repeat lines (loops, calls) this many times beyond the file's own
// lines, and read this many bytes beyond its size: then the loop is called unbounded.
constexpr std::size_t kMaxRepeatedLines = 1'000'000;
constexpr std::size_t kMaxRepeatedBytes = 64u << 20;
constexpr int kMaxCallDepth = 64;
constexpr std::size_t kMaxNamedParameters = 10'000;

// One reading of one file: run() once, or feed() every line then finish().
class Reader {
 public:
  Reader(std::string_view text, const PenReading& pen);
  // A reading fed line by line (no O-word program): `scan` is what the text would tell.
  Reader(const GcodeScan& scan, const PenReading& pen);
  // The moves go to `sink` a layer at a time (parse_gcode_layers); not owned.
  void set_sink(const PieceSink* sink) { sink_ = sink; }
  ParsedGcode run();
  void feed(std::string_view raw_line);
  ParsedGcode finish();

  // Per line, as has_o_words and scan_has_e read a whole text.
  static bool line_has_o_word(std::string_view raw_line);
  static bool line_has_e(std::string_view raw_line);

 private:
  static bool has_o_words(std::string_view t);
  void run_streaming();
  // Hands the moves read so far to the sink and drops them.
  void flush();

  // O-word programs: lines by index, blocks matched first, then run with a program counter.
  ParsedGcode run_indexed();
  [[noreturn]] void bad(std::size_t index, const std::string& what) const;

  // Pairs every O-word block: sub/endsub, if/elseif/else/endif, while/endwhile,
  // do/while, repeat/endrepeat; break and continue point at their loop.
  void match_blocks();
  double condition(std::size_t index);

  // Runs one O-word line; returns the next line index.
  std::size_t o_step(std::size_t pc, const OWord& o);

  struct CallFrame {
    std::size_t return_to = 0;
    std::unordered_map<int, double> numbered;
    std::map<std::string, double> named;
  };
  std::size_t call(std::size_t pc, const OWord& o);
  std::size_t return_from(std::size_t pc, const OWord& o);
  void unsupported(int n, const std::string& what);

  // Parameters and positions for expressions (positions in the file's units).
  class Scope : public NgcScope {
   public:
    explicit Scope(const Reader& r) : r_(r) {}
    double numbered(int i) const override {
      if (i >= 5420 && i <= 5423) return i == 5423 ? r_.a_ : r_.pos_[i - 5420] / r_.scale_;
      const auto it = r_.numbered_.find(i);
      if (it != r_.numbered_.end()) return it->second;
      if (i >= 5000) throw NgcUnsupported("system parameter #" + std::to_string(i));
      return 0.0;
    }
    std::optional<double> named(const std::string& n) const override {
      if (n == "_x" || n == "_y" || n == "_z") return r_.pos_[n[1] - 'x'] / r_.scale_;
      if (n == "_a") return r_.a_;
      if (n == "_metric") return r_.scale_ == 1.0 ? 1.0 : 0.0;
      if (n == "_imperial") return r_.scale_ == 1.0 ? 0.0 : 1.0;
      const auto it = r_.named_.find(n);
      if (it != r_.named_.end()) return it->second;
      return std::nullopt;
    }

   private:
    const Reader& r_;
  };

  // A line with parameters or expressions: words evaluated, then the assignments made (all
  // reads on a line see the values from before it, as RS274NGC says).
  void ngc_line(std::string_view s, int n);
  void words(const Words& w, std::string_view s, int n);

  // Files whose moves carry E words (other than E0 everywhere) use E to tell deposits.
  static bool scan_has_e(std::string_view t);
  void line(std::string_view s, int n);
  void comment(std::string_view c, int);

  // "pen 2 colour: #d40000", a header line of Strand's pen G-code: pen 2 draws in that colour.
  void pen_colour(std::string_view c);
  void new_layer(std::optional<double> z);
  void m_code(int code, const Words& w, int n);

  // Without E a G1/G2/G3 in XY draws, unless the file lifts its pen: by command, or by z
  // above the pen-down height when the reading gives one.
  bool draws(int code, const Vec3& target) const;
  void g_code(int code, const Words& w, int n);
  void dwell(const Words& w, int n);
  void motion(int code, const Words& w, int n);

  // Reads an A word (rotary axis, degrees); true when there is one. Moves before the first
  // A word were at the old A.
  bool rotary(const Words& w);
  void arc(Move& mv, int code, const Words& w, int n);

  // Keeps every later flattening finite: absurd radii become straight moves, and the chord
  // count of all arcs at the finest tolerance stays within kMaxArcChords.
  void bound_arc(Move& mv, int n);

  std::string_view text_;
  const PenReading& pen_;
  ParsedGcode out_;
  const PieceSink* sink_ = nullptr;
  std::size_t moves_read_ = 0;  // moves of the whole reading, those handed over included
  std::size_t first_move_ = 0;  // index of out_.program.moves[0] in the whole reading
  int fed_lines_ = 0;
  Vec3 pos_ = Vec3::Zero();
  double e_ = 0.0;
  double a_ = 0.0;      // rotary axis position, degrees
  bool has_a_ = false;  // an A word was read: a_deg is kept parallel to the moves
  double feed_ = 0.0;
  double scale_ = 1.0;
  double width_ = 0.0;
  double arc_chords_ = 0.0;
  bool relative_ = false;
  bool relative_e_ = false;
  bool has_markers_ = false;
  bool has_e_ = false;
  bool marker_pending_ = false;
  bool layer_z_known_ = false;  // the current layer's z came from ;Z: or a deposit
  int layer_ = -1;
  std::optional<bool> pen_down_;  // unset until the file's first pen command
  bool valve_open_ = false;       // valve outputs read (pen_.valve_on_m): the output is on
  int spindle_line_ = 0, spindle_m_ = 0, plunge_line_ = 0;  // milling: M3/M4 S, cut below z 0
  double spindle_s_ = 0.0, plunge_z_ = 0.0;
  // RS274NGC: parameters, O-word blocks (by line index), calls and repeat counters.
  std::unordered_map<int, double> numbered_;
  std::map<std::string, double> named_;
  Scope scope_{*this};
  std::vector<std::string_view> lines_;
  std::unordered_map<std::size_t, OWord> o_words_;
  std::unordered_map<std::size_t, std::size_t> end_, partner_;
  std::unordered_map<std::size_t, std::vector<std::size_t>> branches_;
  std::map<std::string, std::size_t> subs_;
  std::unordered_map<std::size_t, long long> repeats_;
  std::vector<CallFrame> calls_;
  std::size_t loop_line_ = 0;  // the loop or call that repeated lines last (1-based)
  bool stopped_ = false;       // an unsupported construct: the rest is not read
  Feature feature_ = Feature::Infill;
  std::int16_t tool_ = 0;  // pen (;PEN:k) or printhead (T<n>) from here on, 0-based
  // Printheads' nozzle offsets from the carriage ("; extruder_offset = 0x0,35x0", as
  // PrusaSlicer writes them): moves are read where each nozzle lays its bead.
  std::vector<slicer::Vec2> tool_offsets_;
  void tool_offsets(std::string_view c);
};

}  // namespace strand::post::gcode
