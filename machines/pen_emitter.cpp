// Writing plotter G-code: pen lift by servo, Z or drum, pen changes, kinematic axes.
#include "machines/pen_emitter.h"

#include <cmath>
#include <stdexcept>

#include "machines/gcode_format.h"
#include "machines/plotter_kinematics.h"

namespace strand::machines {

namespace {

std::string fmt_axis(double v) { return fmt_fixed(v, kPenAxisDecimals); }

class PenWriter {
 public:
  PenWriter(const MachineProfile& m) : m_(m), pen_(m.plotter.pen) {}

  void line(const std::string& s) { out_ += s + "\n"; }
  std::string take() { return std::move(out_); }

  void start(const slicer::Vec3& start_paper) {
    for (const auto& s : m_.start_gcode) line(s);
    line("G21 ; millimetres");
    line("G90 ; absolute positions");
    if (m_.plotter.setup.kind != PlotterKind::Xy) {
      const Vec2 a = to_axes(m_.plotter.setup, start_paper.head<2>());
      line("G92 X" + fmt_axis(a.x()) + " Y" + fmt_axis(a.y()) + " ; pen parked at the home mark");
    }
    if (pen_.lift == PenLift::Drum) {
      line("G92 Z0 ; drum at its start mark, no marker engaged");
    }
    lift(true);
  }

  void end() {
    for (const auto& s : m_.end_gcode) line(s);
  }

  void move(const slicer::Move& mv, bool draw) {
    const Vec2 a = to_axes(m_.plotter.setup, mv.end_mm.head<2>());
    std::string s = draw ? "G1" : "G0";
    s += " X" + fmt_axis(a.x()) + " Y" + fmt_axis(a.y());
    if (draw && mv.feed_mm_per_min != feed_) {
      feed_ = mv.feed_mm_per_min;
      s += " F" + fmt_feed(feed_);
    }
    if (!draw && m_.firmware != Firmware::Grbl) s += " F" + fmt_feed(mv.feed_mm_per_min);
    line(s);
  }

  void dwell(double s) {
    if (m_.firmware == Firmware::Grbl) {
      line("G4 P" + fmt_fixed(s, 3));  // GRBL: seconds
    } else {
      line("G4 P" + fmt_fixed(s * 1000.0, 0));  // Marlin/RepRap: milliseconds
    }
  }

  void select(int tool) {
    if (tool == tool_) return;
    const int k = tool + 1;
    if (pen_.lift == PenLift::Drum) {
      if (tool_ >= 0 && tool > tool_) {
        // forward only while a marker is engaged
      } else if (tool_ >= 0) {
        drum(360.0, "full turn: the drum cannot turn back with a marker engaged");
        line("G92 Z0");
      }
      drum(drum_engage_deg(pen_, k), "engage marker " + std::to_string(k));
      drum(drum_rest_deg(pen_, k), "marker " + std::to_string(k) + " at rest");
    } else if (!pen_.change_gcode.empty() && tool_ >= 0) {
      for (std::string s : pen_.change_gcode) {
        const auto at = s.find("{pen}");
        if (at != std::string::npos) s.replace(at, 5, std::to_string(k));
        line(s);
      }
    }
    line(";PEN:" + std::to_string(k));
    tool_ = tool;
  }

  void lift(bool up) {
    const PenSetup& p = pen_;
    switch (p.lift) {
      case PenLift::Servo:
      case PenLift::Z:
        line(pen_lift_command(m_, up));
        break;
      case PenLift::Drum:
        if (tool_ < 0) return;  // no marker engaged: nothing touches the wall
        drum(up ? drum_rest_deg(p, tool_ + 1) : drum_write_deg(p, tool_ + 1), up ? "pen up" : "pen down");
        break;
    }
  }

 private:
  void drum(double deg, const std::string& why) {
    line("G1 Z" + fmt_axis(deg) + " F" + fmt_feed(m_.limits.z_feed_mm_per_min) + " ; " + why);
    line("M400");
  }

  const MachineProfile& m_;
  const PenSetup& pen_;
  std::string out_;
  double feed_ = -1.0;
  int tool_ = -1;
};

}  // namespace

std::string pen_lift_command(const MachineProfile& m, bool up) {
  const PenSetup& p = m.plotter.pen;
  const std::string why = up ? " ; pen up" : " ; pen down";
  switch (p.lift) {
    case PenLift::Servo:
      if (m.firmware == Firmware::Grbl) return "M3 S" + fmt_fixed(up ? p.up_value : p.down_value, 0) + why;
      return "M280 P" + std::to_string(p.servo_index) + " S" + fmt_fixed(up ? p.up_value : p.down_value, 0) + why;
    case PenLift::Z:
      return std::string(up ? "G0" : "G1") + " Z" + fmt_axis(up ? p.z_up_mm : p.z_down_mm) +
             (up ? "" : " F" + fmt_feed(m.limits.z_feed_mm_per_min)) + why;
    case PenLift::Drum:
      break;
  }
  throw std::logic_error("pen_lift_command: " + m.name + " lifts its pens with a drum");
}

double drum_engage_deg(const PenSetup& pen, int k) { return (k + 1) * pen.drum.engage_step_deg; }
double drum_rest_deg(const PenSetup& pen, int k) {
  return drum_engage_deg(pen, k) - pen.drum.rest_offset_deg;
}
double drum_write_deg(const PenSetup& pen, int k) {
  return drum_rest_deg(pen, k) - pen.drum.write_offset_deg;
}

std::string emit_pen_gcode(const slicer::MotionProgram& program, const MachineProfile& machine,
                           const std::vector<std::string>& header) {
  if (!machine.plotter.enabled) throw std::logic_error("emit_pen_gcode: " + machine.name + " is not a plotter");
  PenWriter w(machine);
  for (const auto& h : header) w.line(h.empty() ? ";" : "; " + comment_text(h));
  w.start(program.start_mm);
  w.line(";LAYER_CHANGE");
  w.line(";Z:0");
  w.line(";HEIGHT:0");
  w.line(";LAYER:0");
  w.line(";TYPE:Perimeter");
  w.line(";FEATURE:pen");
  slicer::Vec3 at = program.start_mm;
  for (const auto& mv : program.moves) {
    const bool xy_same = (mv.end_mm.head<2>() - at.head<2>()).norm() == 0.0;
    switch (mv.kind) {
      case slicer::MoveKind::Travel:
        if (xy_same && mv.end_mm.z() != at.z()) {
          if (mv.end_mm.z() == kPenDownZ) w.select(mv.tool);
          w.lift(mv.end_mm.z() != kPenDownZ);
        } else if (!xy_same) {
          w.move(mv, false);
        }
        break;
      case slicer::MoveKind::Deposit: w.move(mv, true); break;
      case slicer::MoveKind::Dwell: w.dwell(slicer::dwell_seconds(program, mv)); break;
      case slicer::MoveKind::Raw: w.line(slicer::raw_text(program, mv)); break;
    }
    if (mv.kind == slicer::MoveKind::Travel || mv.kind == slicer::MoveKind::Deposit) at = mv.end_mm;
  }
  w.end();
  return w.take();
}

}  // namespace strand::machines
