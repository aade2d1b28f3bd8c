// E-only G-code: runs of deposits become E moves at constant E feed, runs of travels dwells.
#include "machines/extruder_gcode.h"

#include <algorithm>
#include <cmath>

#include "machines/gcode_format.h"
#include "slicer/units.h"

namespace strand::machines {

namespace {

// Deposits whose E feeds differ from the run's first by less than this fraction share one
// move (a paste extruder does not follow feed changes of a corner's few tenths of a second).
constexpr double kSameFeedFraction = 0.01;

class Writer {
 public:
  Writer(const slicer::PoseProgram& p, const MachineProfile& m, const ExtruderGcodeInfo& info)
      : p_(p), m_(m), info_(info) {}

  ExtruderProgram run() {
    out_.lap_e.assign(std::max<std::size_t>(p_.laps.size(), 1), 0.0);
    prologue();
    const auto& pts = p_.points;
    int lap = -1, layer = -1;
    for (std::size_t i = 1; i < pts.size(); ++i) {
      if (pts[i].layer != layer)
        flush(), layer = pts[i].layer, text_ += ";LAYER:" + std::to_string(layer) + "\n";
      if (pts[i].lap != lap) flush(), lap = pts[i].lap, lap_start(lap);
      lap_ = static_cast<std::size_t>(std::clamp(lap, 0, static_cast<int>(out_.lap_e.size()) - 1));
      segment(i);
    }
    flush();
    handshake_end();
    for (const auto& l : m_.end_gcode) text_ += l + "\n";
    out_.gcode = std::move(text_);
    return std::move(out_);
  }

 private:
  void prologue() {
    for (const auto& h : info_.header) text_ += (h.empty() ? ";" : "; " + comment_text(h)) + "\n";
    text_ += "M83 ; relative E\n";
    for (const auto& l : m_.start_gcode) text_ += l + "\n";
    const Vec3& park = m_.robot.extruder.park_mm;
    text_ += "G1 X" + fmt_xyz(park.x()) + " Y" + fmt_xyz(park.y()) + " Z" + fmt_xyz(park.z()) +
            " F" + fmt_feed(m_.robot.extruder.park_feed_mm_per_min) +
            " ; park the nozzle where it touches the cylinder\n";
    text_ += "M400 ; wait until parked\n";
  }

  void lap_start(int lap) {
    const auto& l = p_.laps[static_cast<std::size_t>(lap)];
    text_ += ";LAP:" + std::to_string(lap) + " layer " + std::to_string(l.layer) +
            (l.direction > 0 ? " forward" : " return") + ", turn " +
            fmt_fixed(slicer::rad_to_deg(l.turn_min_rad), 1) + " to " +
            fmt_fixed(slicer::rad_to_deg(l.turn_max_rad), 1) + " deg\n";
    const auto& x = m_.robot.extruder;
    const int level = lap_signal_level(m_.robot, lap);
    if (!reset_) handshake_reset(), reset_ = true;
    if (x.ready_pin >= 0) {
      // Two-way handshake: the previous lap's moves done, tell the robot this lap may start.
      text_ += "M400 ; finish the previous lap\n";
      text_ += "M42 P" + std::to_string(x.ready_pin) + " S" + (level == 1 ? "255" : "0") +
              " ; ready for lap " + std::to_string(lap) + "\n";
    }
    if (x.handshake_pin >= 0) {
      text_ += "M226 P" + std::to_string(x.handshake_pin) + " S" + std::to_string(level) +
              " ; wait for the robot's lap signal\n";
    }
  }

  // Before lap 0: the ready output to the level before lap 0, then wait until the robot has
  // reset its lap output too (levels an earlier run left are never taken for lap 0).
  void handshake_reset() {
    const auto& x = m_.robot.extruder;
    if (x.ready_pin < 0 && x.handshake_pin < 0) return;
    const int idle = handshake_idle_level(m_.robot);
    text_ += "; handshake reset: both lines to the level before lap 0\n";
    if (x.ready_pin >= 0) {
      text_ += "M42 P" + std::to_string(x.ready_pin) + " S" + (idle == 1 ? "255" : "0") +
               " ; reset: ready for no lap yet\n";
    }
    if (x.handshake_pin >= 0) {
      text_ += "M226 P" + std::to_string(x.handshake_pin) + " S" + std::to_string(idle) +
               " ; reset: wait for the robot's reset\n";
    }
  }

  // After the last lap: its moves done, the ready output back to the level before lap 0 (the
  // robot waits for it before it resets its lap output): a finished run leaves both there.
  void handshake_end() {
    const auto& x = m_.robot.extruder;
    if (x.ready_pin < 0) return;
    text_ += "M400 ; finish the last lap\n";
    text_ += "M42 P" + std::to_string(x.ready_pin) + " S" +
             (handshake_idle_level(m_.robot) == 1 ? "255" : "0") +
             " ; handshake reset after the last lap: ready for no lap\n";
  }

  double time_at(std::size_t i) const {
    return info_.t_s.size() == p_.points.size() ? info_.t_s[i] : p_.points[i].t_s;
  }

  void segment(std::size_t i) {
    const slicer::PosePoint& a = p_.points[i - 1];
    const slicer::PosePoint& b = p_.points[i];
    const double dt = time_at(i) - time_at(i - 1);
    if (dt <= 0) return;
    if (!b.extrude) {
      if (run_e_ > 0) flush();
      dwell_s_ += dt;
      return;
    }
    if (dwell_s_ > 0) flush();
    const double len = (b.contact_mm - a.contact_mm).norm();
    const double area = static_cast<std::size_t>(b.layer) < info_.bead_area_mm2.size()
                            ? info_.bead_area_mm2[b.layer]
                            : 0.0;
    const double e = deposit_e(m_, len, dt, area);
    const double feed = e / dt * 60.0;
    if (run_e_ > 0 && std::abs(feed - run_first_feed_) > kSameFeedFraction * run_first_feed_)
      flush();
    if (run_e_ <= 0) run_first_feed_ = feed;
    run_e_ += e;
    run_s_ += dt;
    out_.lap_e[lap_] += e;
    out_.e_total += e;
  }

  // Writes the pending dwell or E run; E runs in pieces of at most extrude_max_length.
  void flush() {
    if (dwell_s_ > 0) {
      const double ms = dwell_s_ * 1000.0 + carry_ms_;
      const long whole = std::lround(std::floor(ms));
      carry_ms_ = ms - static_cast<double>(whole);  // keeps the time line within 1 ms
      if (whole > 0) text_ += "G4 P" + std::to_string(whole) + " ; robot travels\n";
      dwell_s_ = 0;
    }
    if (run_e_ > 0) {
      const double max_e = m_.deposition.extrude_max_length;
      const int pieces = std::max(1, static_cast<int>(std::ceil(run_e_ / max_e - 1e-12)));
      const double feed = run_e_ / run_s_ * 60.0;
      for (int k = 0; k < pieces; ++k)
        text_ += "G1 E" + fmt_e(run_e_ / pieces) + " F" + fmt_fixed(feed, 3) + "\n";
      run_e_ = 0, run_s_ = 0;
    }
  }

  const slicer::PoseProgram& p_;
  const MachineProfile& m_;
  const ExtruderGcodeInfo& info_;
  std::string text_;
  ExtruderProgram out_;
  std::size_t lap_ = 0;
  bool reset_ = false;
  double run_e_ = 0.0, run_s_ = 0.0, run_first_feed_ = 0.0, dwell_s_ = 0.0, carry_ms_ = 0.0;
};

}  // namespace

double e_per_mm(const MachineProfile& m, double speed_mm_per_s, double bead_area_mm2) {
  if (m.robot.extruder.time_based) {
    return m.robot.extruder.v_ext_mm_per_min / slicer::mm_per_s_to_mm_per_min(speed_mm_per_s);
  }
  return bead_area_mm2 / m.deposition.mm3_per_e;
}

int lap_signal_level(const RobotCell& cell, int lap) {
  return (cell.extruder.handshake_state + lap) % 2;
}

int handshake_idle_level(const RobotCell& cell) { return 1 - lap_signal_level(cell, 0); }

double deposit_e(const MachineProfile& m, double length_mm, double duration_s,
                 double bead_area_mm2) {
  if (m.robot.extruder.time_based) return m.robot.extruder.v_ext_mm_per_min / 60.0 * duration_s;
  return length_mm * bead_area_mm2 / m.deposition.mm3_per_e;
}

ExtruderProgram extruder_program(const slicer::PoseProgram& program, const MachineProfile& m,
                                 const ExtruderGcodeInfo& info) {
  return Writer(program, m, info).run();
}

std::string write_extruder_gcode(const slicer::PoseProgram& program, const MachineProfile& m,
                                 const ExtruderGcodeInfo& info) {
  return extruder_program(program, m, info).gcode;
}

}  // namespace strand::machines
