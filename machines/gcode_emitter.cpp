// Writes a MotionProgram as G-code with viewer comments, flow words and valve commands.
#include "machines/gcode_emitter.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <ostream>

#include "machines/gcode_format.h"
#include "machines/deposit_pieces.h"
#include "slicer/units.h"

namespace strand::machines {

using slicer::Feature;
using slicer::Move;
using slicer::MoveKind;

namespace {

std::string expand(const std::string& line, const MachineProfile& m) {
  std::string s = replace_all(line, "{lead_s}", fmt_fixed(m.deposition.lead_s, 1));
  s = replace_all(s, "{lead_ms}", fmt_fixed(m.deposition.lead_s * 1000.0, 0));
  s = replace_all(s, "{message}", m.deposition.message);
  return s;
}

// Text is formatted into a buffer handed to the stream in blocks of about this size, bytes.
constexpr std::size_t kFlushBytes = 1 << 16;

// One number as written (fixed_chars), compared as text to drop repeated words.
struct Word {
  char text[kFixedCharsMax];
  std::size_t size = 0;
  std::string_view view() const { return {text, size}; }
  bool operator==(const Word& o) const { return view() == o.view(); }
};

// Emission state: what the firmware has been told so far. Text accumulates in `out`; with a
// sink, full blocks are written there as they fill (nothing of the file is kept).
class Writer {
 public:
  Writer(const MachineProfile& m, const EmitOptions& o, std::string& out, std::ostream* sink)
      : base_(m), m_(m), o_(o), out_(out), sink_(sink) {
    const auto model = m.deposition.model;
    e_words_ = model == DepositionModel::EVolumetric || o.viewer_e;
    relative_e_ = o.viewer_e || m.deposition.relative_e;
    for (const Tool& t : m.tools) {
      if (t.deposition.model != DepositionModel::EVolumetric) continue;
      any_e_ = true;
      relative_e_ = relative_e_ || t.deposition.relative_e;
    }
    any_e_ = any_e_ || e_words_;
  }

  void run(const slicer::MotionProgram& p) {
    head();
    add(p);
    finish();
  }

  // The file's first lines: the preview warning and the header comments.
  void head() {
    if (o_.viewer_e) {
      out_ += comment("PREVIEW ONLY - NOT FOR PRINTING: E words are computed ink volume (mm3, relative) for viewers");
    }
    for (const auto& h : o_.header) out_ += h.empty() ? comment("") : comment(h);
    if (!base_.tools.empty()) {
      // PrusaSlicer's key: its viewer and Strand's reader place each head's moves by it.
      std::string offsets;
      for (const Tool& t : base_.tools) {
        offsets += (offsets.empty() ? "" : ",") + fmt_xyz(t.offset_mm.x()) + "x" + fmt_xyz(t.offset_mm.y());
      }
      out_ += comment("extruder_offset = " + offsets);
    }
  }

  // The next piece of the program; the first also writes the start G-code and preamble.
  void add(const slicer::MotionProgram& p) {
    if (!begun_) {
      begun_ = true;
      for (const auto& line : m_.start_gcode) out_ += expand(line, m_) + "\n";
      preamble();
    }
    if (!at_set_ && !p.moves.empty()) {  // layers before the first move may be empty
      at_ = p.start_mm;
      at_set_ = true;
    }
    for (const auto& mv : p.moves) {
      write(mv, p);
      if (sink_ && out_.size() >= kFlushBytes) flush();
      if ((++written_ & 0xfffu) == 0) slicer::progress_step(o_.progress, written_);
    }
  }

  void finish() {
    if (!begun_) add(slicer::MotionProgram{});
    close_flow();
    out_ += ";TYPE:Custom\n";
    if (o_.viewer_e) out_ += comment("PREVIEW ONLY - NOT FOR PRINTING");
    for (const auto& line : m_.end_gcode) out_ += expand(line, m_) + "\n";
    if (sink_) flush();
  }

 private:
  void flush() {
    sink_->write(out_.data(), static_cast<std::streamsize>(out_.size()));
    out_.clear();
  }

  // "; text" or, on GRBL, "(text)" (GRBL comments may not nest parentheses).
  std::string comment(const std::string& text) const {
    if (m_.firmware != Firmware::Grbl) return text.empty() ? ";\n" : "; " + comment_text(text) + "\n";
    return "(" + comment_text(text, false) + ")\n";
  }

  std::string code(const std::string& words, const std::string& note) const {
    if (note.empty()) return words + "\n";
    return m_.firmware == Firmware::Grbl ? words + " (" + note + ")\n" : words + " ; " + note + "\n";
  }

  // Waits until queued moves finish (before commands that act at once, e.g. M42/M280/M106).
  std::string sync() const { return m_.firmware == Firmware::Grbl ? "G4 P0\n" : "M400\n"; }

  void preamble() {
    out_ += code("G21", "millimetres") + code("G90", "absolute XYZ");
    // Heated or cooled heads start reaching their set points; each change waits for its own.
    for (std::size_t k = 0; k < base_.tools.size(); ++k) {
      const Tool& t = base_.tools[k];
      if (t.temperature_c > 0) out_ += code("M104 T" + std::to_string(k) + " S" + fmt_fixed(t.temperature_c, 0), t.name);
    }
    if (!any_e_) return;
    // Marlin: G90 also resets the E mode, so the E mode must come after it.
    out_ += relative_e_ ? code("M83", "relative E") : code("M82", "absolute E");
    out_ += "G92 E0\n";
    if (m_.deposition.model != DepositionModel::EVolumetric || o_.viewer_e) return;
    allow_cold_extrusion();
    if (m_.deposition.prime_e > 0) {
      e_only(m_.deposition.prime_e, "prime");
      if (!relative_e_) e_ = 0.0;
      out_ += "G92 E0\n";
    }
  }

  // Paste is extruded cold: Marlin refuses E moves below EXTRUDE_MINTEMP without M302 S0,
  // RepRapFirmware without M302 P1 (Klipper: min_extrude_temp in its config).
  void allow_cold_extrusion() {
    for (const auto& l : m_.start_gcode) {
      if (l.starts_with("M302")) return;
    }
    if (m_.firmware == Firmware::Marlin) out_ += code("M302 S0", "cold paste: allow E without heat");
    if (m_.firmware == Firmware::RepRap) out_ += code("M302 P1", "cold paste: allow E without heat");
  }

  // E-only move, split so no single move exceeds EXTRUDE_MAXLENGTH.
  void e_only(double de, const std::string& note) {
    const double max = m_.deposition.extrude_max_length;
    const int n = std::max(1, static_cast<int>(std::ceil(std::abs(de) / max - 1e-9)));
    for (int i = 0; i < n; ++i) {
      out_ += "G1 E";
      e_step(de / n);
      out_ += code(" F200", note);
    }
    feed_ = "200";
  }

  void write(const Move& mv, const slicer::MotionProgram& p) {
    if (mv.layer >= 0 && mv.layer != layer_) layer_change(mv.layer, p);
    if (!base_.tools.empty() && mv.kind != MoveKind::Raw && mv.tool != tool_) change_tool(mv.tool);
    switch (mv.kind) {
      case MoveKind::Raw:
        out_ += slicer::raw_text(p, mv);
        out_ += '\n';
        break;
      case MoveKind::Dwell: dwell(slicer::dwell_seconds(p, mv)); break;
      case MoveKind::Travel: travel(mv); break;
      case MoveKind::Deposit: deposit(mv); break;
    }
  }

  // Another printhead (issue 33): the last one's flow closed, the change in the firmware's
  // words (or the profile's), then that tool's deposition; absolute E restarts from 0.
  void change_tool(int tool) {
    close_flow();
    const auto k = static_cast<std::size_t>(std::clamp(tool, 0, static_cast<int>(base_.tools.size()) - 1));
    const Tool& t = base_.tools[k];
    auto lines = [&](const std::vector<std::string>& templates, std::size_t index) {
      for (const auto& line : templates) {
        out_ += replace_all(replace_all(line, "{tool}", std::to_string(index)), "{name}", base_.tools[index].name) + "\n";
      }
    };
    if (tool_ >= 0) lines(base_.tools[static_cast<std::size_t>(tool_)].deselect_gcode, static_cast<std::size_t>(tool_));
    if (t.temperature_c > 0) out_ += code("M109 T" + std::to_string(k) + " S" + fmt_fixed(t.temperature_c, 0), "wait for " + t.name);
    lines(base_.tool_change_gcode.empty() ? std::vector<std::string>{"T{tool}"} : base_.tool_change_gcode, k);
    lines(t.select_gcode, k);
    m_.deposition = t.deposition;
    e_words_ = m_.deposition.model == DepositionModel::EVolumetric || o_.viewer_e;
    retracted_ = false;
    if (e_words_ && !relative_e_) {
      out_ += "G92 E0\n";
      e_ = 0.0;
    }
    tool_ = static_cast<int>(k);
  }

  void layer_change(int layer, const slicer::MotionProgram& p) {
    layer_ = layer;
    const auto& info = p.layers.at(static_cast<std::size_t>(layer));
    out_ += ";LAYER_CHANGE\n;Z:" + fmt_xyz(info.z_mm) + "\n;HEIGHT:" + fmt_xyz(info.height_mm) +
            "\n;LAYER:" + std::to_string(layer) + "\n";
    feature_written_ = false;
  }

  void dwell(double s) {
    if (m_.firmware == Firmware::Grbl) {
      out_ += "G4 P" + fmt_fixed(s, 3) + "\n";  // GRBL: seconds
    } else {
      out_ += "G4 P" + fmt_fixed(s * 1000.0, 0) + "\n";  // Marlin, RRF, Klipper: ms
    }
  }

  void travel(const Move& mv) {
    close_flow();
    out_ += "G0";
    axes(mv);
    feed(mv.feed_mm_per_min);
    out_ += '\n';
  }

  void deposit(const Move& whole) {
    if (whole.coast) {
      close_flow();
    } else {
      open_flow();
    }
    const PiecePlan plan = piece_plan(at_, whole, m_, e_words_ && !o_.viewer_e);
    if (plan.n == 1 && !plan.chords) {
      deposit_piece(whole);
      return;
    }
    for (const Move& mv : deposit_pieces(at_, whole, plan)) deposit_piece(mv);
  }

  void deposit_piece(Move mv) {
    // A piece shorter than the output's 0.001 mm steps would be a line without an axis word
    // ("G1 E0.00003"): its volume goes to the next deposit instead, so the E total is kept.
    if (!mv.is_arc && unmoved_at_output_precision(mv)) {
      pending_volume_mm3_ += mv.volume_mm3;
      at_ = mv.end_mm;
      return;
    }
    mv.volume_mm3 += pending_volume_mm3_;
    pending_volume_mm3_ = 0.0;
    if (!feature_written_ || mv.feature != feature_) {
      out_ += ";TYPE:" + viewer_role(mv.feature) + "\n;FEATURE:" + to_string(mv.feature) + "\n";
      feature_ = mv.feature;
      feature_written_ = true;
    }
    if (mv.width_mm > 0 && mv.width_mm != width_) {
      out_ += ";WIDTH:" + fmt_xyz(mv.width_mm) + "\n";
      width_ = mv.width_mm;
    }
    out_ += mv.is_arc ? (mv.ccw ? "G3" : "G2") : "G1";
    const Eigen::Vector2d start(at_.x(), at_.y());
    axes(mv);
    if (mv.is_arc) {
      number(" I", mv.center_mm.x() - start.x(), 3);
      number(" J", mv.center_mm.y() - start.y(), 3);
    }
    if (e_words_) {
      out_ += " E";
      e_word(mv.volume_mm3);
    }
    feed(mv.feed_mm_per_min);
    out_ += '\n';
  }

  // Appends `prefix` and the number with `decimals` digits.
  void number(const char* prefix, double v, int decimals) {
    char buf[kFixedCharsMax];
    out_ += prefix;
    out_.append(buf, fixed_chars(buf, v, decimals));
  }

  void e_word(double volume_mm3) {
    const double mm3_per_e = o_.viewer_e && m_.deposition.model != DepositionModel::EVolumetric
                                 ? 1.0
                                 : m_.deposition.mm3_per_e;
    e_step(volume_mm3 / mm3_per_e);
  }

  // Whether `mv` ends where the last written X, Y and Z words already put the nozzle.
  bool unmoved_at_output_precision(const Move& mv) const {
    for (int i = 0; i < 3; ++i) {
      if (last_[i].size == 0) return false;
      if (mv.end_mm[i] == last_value_[i]) continue;
      Word v;
      v.size = fixed_chars(v.text, mv.end_mm[i], 3);
      if (!(v == last_[i])) return false;
    }
    return true;
  }

  // Axis words that changed (X and Y always on arcs), 3 decimals. A value equal to the last
  // one needs no formatting to know its text is the same.
  void axes(const Move& mv) {
    static constexpr const char* kNames[3] = {" X", " Y", " Z"};
    for (int i = 0; i < 3; ++i) {
      if (mv.end_mm[i] == last_value_[i] && last_[i].size > 0) {
        if (mv.is_arc && i < 2) {
          out_ += kNames[i];
          out_ += last_[i].view();
        }
        continue;
      }
      last_value_[i] = mv.end_mm[i];
      Word v;
      v.size = fixed_chars(v.text, mv.end_mm[i], 3);
      if (!(v == last_[i]) || (mv.is_arc && i < 2)) {
        out_ += kNames[i];
        out_ += v.view();
      }
      if (!(v == last_[i])) std::memcpy(last_[i].text, v.text, (last_[i].size = v.size));
    }
    at_ = mv.end_mm;
  }

  // " F<feed>" when it differs from the last feed written.
  void feed(double f) {
    Word v;
    v.size = fixed_chars(v.text, f, 0);
    if (v.view() == feed_) return;
    feed_.assign(v.view());
    out_ += " F";
    out_ += feed_;
  }

  void open_flow() {
    if (flowing_) return;
    flowing_ = true;
    if (retracted_) {
      e_only(m_.deposition.retract_e, "undo suck-back");
      retracted_ = false;
    }
    if (m_.deposition.model != DepositionModel::Valve) return;
    out_ += sync();  // M42/M106/M280 act at once: wait for queued moves first
    for (const auto& l : m_.deposition.on_gcode) out_ += l + "\n";
    if (m_.deposition.lead_s > 0) dwell(m_.deposition.lead_s);
  }

  void close_flow() {
    if (!flowing_) return;
    flowing_ = false;
    if (m_.deposition.model == DepositionModel::EVolumetric && m_.deposition.retract_e > 0 &&
        !o_.viewer_e) {
      e_only(-m_.deposition.retract_e, "suck-back");
      retracted_ = true;
    }
    if (m_.deposition.model != DepositionModel::Valve) return;
    out_ += sync();
    for (const auto& l : m_.deposition.off_gcode) out_ += l + "\n";
  }

  // Appends the E value of a move of `de` units in the current E mode.
  void e_step(double de) {
    char buf[kFixedCharsMax];
    if (!relative_e_) e_ += de;
    out_.append(buf, fixed_chars(buf, relative_e_ ? de : e_, 5));
  }

  const MachineProfile& base_;
  MachineProfile m_;  // base_ with the current tool's deposition
  const EmitOptions& o_;
  std::string& out_;
  std::ostream* sink_;
  bool e_words_ = false;  // the current tool's moves carry E
  bool any_e_ = false;    // some tool does (the E mode is set at start)
  int tool_ = -1;         // the printhead selected, -1 before the first (tools only)
  bool relative_e_ = false;
  double e_ = 0.0;
  bool flowing_ = false;
  bool retracted_ = false;
  int layer_ = -1;
  Feature feature_ = Feature::Infill;
  bool feature_written_ = false;
  double width_ = -1.0;
  Word last_[3];
  double pending_volume_mm3_ = 0.0;  // of pieces too short to write, added to the next
  double last_value_[3] = {0.0, 0.0, 0.0};  // the value last_ was formatted from
  std::string feed_;
  slicer::Vec3 at_ = slicer::Vec3::Zero();
  bool begun_ = false;
  bool at_set_ = false;
  std::size_t written_ = 0;
};

}  // namespace

std::string emit_gcode(const slicer::MotionProgram& program, const MachineProfile& machine,
                       const EmitOptions& options) {
  std::string out;
  Writer(machine, options, out, nullptr).run(program);
  return out;
}

void emit_gcode(const slicer::MotionProgram& program, const MachineProfile& machine,
                const EmitOptions& options, std::ostream& out) {
  std::string buffer;
  buffer.reserve(kFlushBytes + 4096);
  Writer(machine, options, buffer, &out).run(program);
}

std::string gcode_head(const MachineProfile& machine, const EmitOptions& options) {
  std::string out;
  Writer(machine, options, out, nullptr).head();
  return out;
}

struct GcodeBodyWriter::Impl {
  Impl(const MachineProfile& m, const EmitOptions& o, std::ostream& out) : options(o), writer(m, options, buffer, &out) {
    options.header.clear();
    buffer.reserve(kFlushBytes + 4096);
  }
  EmitOptions options;
  std::string buffer;
  Writer writer;
};

GcodeBodyWriter::GcodeBodyWriter(const MachineProfile& machine, const EmitOptions& options, std::ostream& out)
    : impl_(std::make_unique<Impl>(machine, options, out)) {}
GcodeBodyWriter::~GcodeBodyWriter() = default;
void GcodeBodyWriter::add(const slicer::MotionProgram& piece) { impl_->writer.add(piece); }
void GcodeBodyWriter::finish() { impl_->writer.finish(); }

}  // namespace strand::machines
