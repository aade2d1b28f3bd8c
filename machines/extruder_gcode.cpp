// E-only G-code: runs of deposits become E moves at constant E feed, runs of travels dwells.
#include "machines/extruder_gcode.h"

#include <algorithm>
#include <cmath>

#include "machines/gcode_format.h"
#include "slicer/units.h"

namespace strand::machines {

namespace {

// Deposits whose E feeds differ by less than this share one move, E units/min.
constexpr double kSameFeed = 1e-6;

class Writer {
 public:
  Writer(const slicer::PoseProgram& p, const MachineProfile& m, const ExtruderGcodeInfo& info)
      : p_(p), m_(m), info_(info) {}

  std::string run() {
    prologue();
    const auto& pts = p_.points;
    int lap = -1, layer = -1;
    for (std::size_t i = 1; i < pts.size(); ++i) {
      if (pts[i].layer != layer)
        flush(), layer = pts[i].layer, out_ += ";LAYER:" + std::to_string(layer) + "\n";
      if (pts[i].lap != lap) flush(), lap = pts[i].lap, lap_start(lap);
      segment(pts[i - 1], pts[i]);
    }
    flush();
    for (const auto& l : m_.end_gcode) out_ += l + "\n";
    return std::move(out_);
  }

 private:
  void prologue() {
    for (const auto& h : info_.header) out_ += (h.empty() ? ";" : "; " + comment_text(h)) + "\n";
    out_ += "M83 ; relative E\n";
    for (const auto& l : m_.start_gcode) out_ += l + "\n";
    const Vec3& park = m_.robot.extruder.park_mm;
    out_ += "G1 X" + fmt_xyz(park.x()) + " Y" + fmt_xyz(park.y()) + " Z" + fmt_xyz(park.z()) +
            " F" + fmt_feed(m_.robot.extruder.park_feed_mm_per_min) +
            " ; park the nozzle where it touches the cylinder\n";
    out_ += "M400 ; wait until parked\n";
  }

  void lap_start(int lap) {
    const auto& l = p_.laps[static_cast<std::size_t>(lap)];
    out_ += ";LAP:" + std::to_string(lap) + " layer " + std::to_string(l.layer) +
            (l.direction > 0 ? " forward" : " return") + ", turn " +
            fmt_fixed(slicer::rad_to_deg(l.turn_min_rad), 1) + " to " +
            fmt_fixed(slicer::rad_to_deg(l.turn_max_rad), 1) + " deg\n";
    const auto& x = m_.robot.extruder;
    const int level = lap_signal_level(m_.robot, lap);
    if (x.ready_pin >= 0) {
      // Two-way handshake: the previous lap's moves done, tell the robot this lap may start.
      out_ += "M400 ; finish the previous lap\n";
      out_ += "M42 P" + std::to_string(x.ready_pin) + " S" + (level == 1 ? "255" : "0") +
              " ; ready for lap " + std::to_string(lap) + "\n";
    }
    if (x.handshake_pin >= 0) {
      out_ += "M226 P" + std::to_string(x.handshake_pin) + " S" + std::to_string(level) +
              " ; wait for the robot's lap signal\n";
    }
  }

  void segment(const slicer::PosePoint& a, const slicer::PosePoint& b) {
    const double dt = b.t_s - a.t_s;
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
    const double e = len * e_per_mm(m_, b.speed_mm_per_s, area);
    const double feed = e / dt * 60.0;
    if (run_e_ > 0 && std::abs(feed - run_feed_) > kSameFeed) flush();
    run_feed_ = feed;
    run_e_ += e;
  }

  // Writes the pending dwell or E run; E runs in pieces of at most extrude_max_length.
  void flush() {
    if (dwell_s_ > 0) {
      const double ms = dwell_s_ * 1000.0 + carry_ms_;
      const long whole = std::lround(std::floor(ms));
      carry_ms_ = ms - static_cast<double>(whole);  // keeps the time line within 1 ms
      if (whole > 0) out_ += "G4 P" + std::to_string(whole) + " ; robot travels\n";
      dwell_s_ = 0;
    }
    if (run_e_ > 0) {
      const double max_e = m_.deposition.extrude_max_length;
      const int pieces = std::max(1, static_cast<int>(std::ceil(run_e_ / max_e - 1e-12)));
      for (int k = 0; k < pieces; ++k)
        out_ += "G1 E" + fmt_e(run_e_ / pieces) + " F" + fmt_fixed(run_feed_, 3) + "\n";
      run_e_ = 0;
    }
  }

  const slicer::PoseProgram& p_;
  const MachineProfile& m_;
  const ExtruderGcodeInfo& info_;
  std::string out_;
  double run_e_ = 0.0, run_feed_ = 0.0, dwell_s_ = 0.0, carry_ms_ = 0.0;
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

std::string write_extruder_gcode(const slicer::PoseProgram& program, const MachineProfile& m,
                                 const ExtruderGcodeInfo& info) {
  return Writer(program, m, info).run();
}

}  // namespace strand::machines
