// Writes a MotionProgram as G-code with viewer comments, flow words and valve commands.
#include "machines/gcode_emitter.h"

#include <cmath>

#include "machines/gcode_format.h"
#include "slicer/units.h"

namespace strand::machines {

using slicer::Feature;
using slicer::Move;
using slicer::MoveKind;

namespace {

std::string replace_all(std::string s, const std::string& from, const std::string& to) {
  for (std::size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size())) {
    s.replace(at, from.size(), to);
  }
  return s;
}

std::string expand(const std::string& line, const MachineProfile& m) {
  std::string s = replace_all(line, "{lead_s}", fmt_fixed(m.deposition.lead_s, 1));
  s = replace_all(s, "{lead_ms}", fmt_fixed(m.deposition.lead_s * 1000.0, 0));
  s = replace_all(s, "{message}", m.deposition.message);
  return s;
}

// Emission state: what the firmware has been told so far.
class Writer {
 public:
  Writer(const MachineProfile& m, const EmitOptions& o) : m_(m), o_(o) {
    const auto model = m.deposition.model;
    e_words_ = model == DepositionModel::EVolumetric || o.viewer_e;
    relative_e_ = o.viewer_e || m.deposition.relative_e;
  }

  std::string run(const slicer::MotionProgram& p) {
    for (const auto& h : o_.header) out_ += h.empty() ? ";\n" : "; " + h + "\n";
    for (const auto& line : m_.start_gcode) out_ += expand(line, m_) + "\n";
    preamble();
    at_ = p.start_mm;
    for (const auto& mv : p.moves) write(mv, p);
    close_flow();
    out_ += ";TYPE:Custom\n";
    for (const auto& line : m_.end_gcode) out_ += expand(line, m_) + "\n";
    return out_;
  }

 private:
  void preamble() {
    out_ += "G21 ; millimetres\nG90 ; absolute XYZ\n";
    if (!e_words_) return;
    // Marlin: G90 also resets the E mode, so the E mode must come after it.
    out_ += relative_e_ ? "M83 ; relative E\n" : "M82 ; absolute E\n";
    out_ += "G92 E0\n";
    if (m_.deposition.model == DepositionModel::EVolumetric && m_.deposition.prime_e > 0 &&
        !o_.viewer_e) {
      out_ += "G1 E" + fmt_e(m_.deposition.prime_e) + " F200 ; prime\nG92 E0\n";
    }
  }

  void write(const Move& mv, const slicer::MotionProgram& p) {
    if (mv.layer >= 0 && mv.layer != layer_) layer_change(mv.layer, p);
    switch (mv.kind) {
      case MoveKind::Raw: out_ += mv.text + "\n"; break;
      case MoveKind::Dwell: dwell(mv.dwell_s); break;
      case MoveKind::Travel: travel(mv); break;
      case MoveKind::Deposit: deposit(mv); break;
    }
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
    out_ += "G0" + axes(mv) + feed(mv.feed_mm_per_min) + "\n";
  }

  void deposit(const Move& mv) {
    open_flow();
    if (!feature_written_ || mv.feature != feature_) {
      out_ += ";TYPE:" + viewer_role(mv.feature) + "\n;FEATURE:" + to_string(mv.feature) + "\n";
      feature_ = mv.feature;
      feature_written_ = true;
    }
    if (mv.width_mm > 0 && mv.width_mm != width_) {
      out_ += ";WIDTH:" + fmt_xyz(mv.width_mm) + "\n";
      width_ = mv.width_mm;
    }
    std::string line = mv.is_arc ? (mv.ccw ? "G3" : "G2") : "G1";
    const Eigen::Vector2d start(at_.x(), at_.y());
    line += axes(mv);
    if (mv.is_arc) {
      line += " I" + fmt_xyz(mv.center_mm.x() - start.x()) + " J" + fmt_xyz(mv.center_mm.y() - start.y());
    }
    if (e_words_) line += " E" + e_word(mv.volume_mm3);
    line += feed(mv.feed_mm_per_min);
    out_ += line + "\n";
  }

  std::string e_word(double volume_mm3) {
    const double mm3_per_e = o_.viewer_e && m_.deposition.model != DepositionModel::EVolumetric
                                 ? 1.0
                                 : m_.deposition.mm3_per_e;
    return e_step(volume_mm3 / mm3_per_e);
  }

  std::string axes(const Move& mv) {
    std::string s;
    const char* names[3] = {" X", " Y", " Z"};
    for (int i = 0; i < 3; ++i) {
      const std::string v = fmt_xyz(mv.end_mm[i]);
      if (v != last_[i] || (mv.is_arc && i < 2)) s += names[i] + v;
      last_[i] = v;
    }
    at_ = mv.end_mm;
    return s;
  }

  std::string feed(double f) {
    const std::string v = fmt_feed(f);
    if (v == feed_) return "";
    feed_ = v;
    return " F" + v;
  }

  void open_flow() {
    if (flowing_) return;
    flowing_ = true;
    if (retracted_) {
      out_ += "G1 E" + e_step(m_.deposition.retract_e) + " ; undo suck-back\n";
      retracted_ = false;
    }
    if (m_.deposition.model != DepositionModel::Valve) return;
    out_ += "M400\n";  // M42/M106/M280 act at once: wait for queued moves first
    for (const auto& l : m_.deposition.on_gcode) out_ += l + "\n";
    if (m_.deposition.lead_s > 0) dwell(m_.deposition.lead_s);
  }

  void close_flow() {
    if (!flowing_) return;
    flowing_ = false;
    if (m_.deposition.model == DepositionModel::EVolumetric && m_.deposition.retract_e > 0 &&
        !o_.viewer_e) {
      out_ += "G1 E" + e_step(-m_.deposition.retract_e) + " ; suck-back\n";
      retracted_ = true;
    }
    if (m_.deposition.model != DepositionModel::Valve) return;
    out_ += "M400\n";
    for (const auto& l : m_.deposition.off_gcode) out_ += l + "\n";
  }

  // An E-only move of `de` units in the current E mode.
  std::string e_step(double de) {
    if (relative_e_) return fmt_e(de);
    e_ += de;
    return fmt_e(e_);
  }

  const MachineProfile& m_;
  const EmitOptions& o_;
  std::string out_;
  bool e_words_ = false;
  bool relative_e_ = false;
  double e_ = 0.0;
  bool flowing_ = false;
  bool retracted_ = false;
  int layer_ = -1;
  Feature feature_ = Feature::Infill;
  bool feature_written_ = false;
  double width_ = -1.0;
  std::string last_[3];
  std::string feed_;
  slicer::Vec3 at_ = slicer::Vec3::Zero();
};

}  // namespace

std::string viewer_role(Feature f) {
  switch (f) {
    case Feature::Infill: return "Solid infill";
    case Feature::Wall: return "Perimeter";
    case Feature::Ligament: return "Internal infill";
    case Feature::Node: return "External perimeter";
    case Feature::Grip: return "Top solid infill";
    case Feature::Frame: return "Overhang perimeter";
    case Feature::Link: return "Skirt/Brim";
    case Feature::Pen: return "Perimeter";
  }
  return "Custom";
}

std::string emit_gcode(const slicer::MotionProgram& program, const MachineProfile& machine,
                       const EmitOptions& options) {
  return Writer(machine, options).run(program);
}

}  // namespace strand::machines
