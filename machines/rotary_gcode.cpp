// Rotary G-code text: one G0/G1 per pose, A in degrees, feeds from the planned times.
#include "machines/rotary_gcode.h"

#include <cmath>

#include "machines/gcode_emitter.h"
#include "machines/gcode_format.h"
#include "slicer/units.h"

namespace strand::machines {

namespace {

std::string vec_text(const Vec3& v) {
  return fmt_xyz(v.x()) + "," + fmt_xyz(v.y()) + "," + fmt_xyz(v.z());
}

class Writer {
 public:
  Writer(const slicer::PoseProgram& p, const MachineProfile& m, const RotaryGcodeInfo& info)
      : p_(p), m_(m), info_(info), letter_(std::string(1, m.rotary.letter)) {}

  std::string run() {
    header();
    const auto& pts = p_.points;
    if (pts.empty()) return std::move(out_);
    int layer = pts.front().layer;
    layer_change(layer, pts.front());
    out_ += "G0 X" + x_ + " Y" + y_ + " Z" + z_ + " " + letter_ + a_ + " F" +
            fmt_feed(m_.limits.travel_feed_mm_per_min) + " ; backed off above the first point\n";
    slicer::Feature feature = slicer::Feature::Link;
    for (std::size_t i = 1; i < pts.size(); ++i) {
      if (pts[i].layer != layer) layer = pts[i].layer, layer_change(layer, pts[i]);
      if (pts[i].extrude && pts[i].feature != feature) {
        feature = pts[i].feature;
        out_ += ";TYPE:" + viewer_role(feature) + "\n;FEATURE:" + slicer::to_string(feature) + "\n";
      }
      move(pts[i - 1], pts[i]);
    }
    for (const auto& l : m_.end_gcode) out_ += l + "\n";
    return std::move(out_);
  }

 private:
  void header() {
    for (const auto& h : info_.header) out_ += (h.empty() ? ";" : "; " + comment_text(h)) + "\n";
    const RotaryAxis& r = m_.rotary;
    out_ += ";ROTARY_AXIS:" + letter_ + "\n;ROTARY_AXIS_DIR:" + vec_text(r.axis_dir) + "\n";
    out_ += ";ROTARY_AXIS_POINT:" + vec_text(r.axis_point_mm) + "\n";
    out_ += ";SUBSTRATE:cylinder radius=" + fmt_fixed(p_.substrate.value("radius_mm", 0.0), 4) +
            " length=" + fmt_fixed(p_.substrate.value("length_mm", 0.0), 4) + "\n";
    out_ += "G21 ; mm\nG90 ; absolute XYZ and " + letter_ + " (degrees)\n";
    out_ += m_.deposition.relative_e ? "M83 ; relative E\n" : "M82 ; absolute E\n";
    if (r.inverse_time) out_ += "G93 ; inverse time: F = 1 / minutes per move\n";
    for (const auto& l : m_.start_gcode) out_ += l + "\n";
    if (!p_.points.empty()) remember(p_.points.front());
  }

  void layer_change(int layer, const slicer::PosePoint& p) {
    const double h = p_.layers[static_cast<std::size_t>(layer)].height_mm;
    out_ +=
        ";LAYER_CHANGE\n;Z:" +
        fmt_xyz(m_.rotary.axis_point_mm.z() + p_.substrate.value("radius_mm", 0.0) + p.offset_mm) +
        "\n;HEIGHT:" + fmt_xyz(h) + "\n;LAYER:" + std::to_string(layer) + "\n";
    if (static_cast<std::size_t>(layer) < info_.bead_width_mm.size()) {
      out_ += ";WIDTH:" + fmt_xyz(info_.bead_width_mm[layer]) + "\n";
    }
  }

  void move(const slicer::PosePoint& a, const slicer::PosePoint& b) {
    const std::string x0 = x_, y0 = y_, z0 = z_, a0 = a_;
    const Vec3 from = tip_;
    const double a_from = a_deg_;
    remember(b);
    const double dt_min = (b.t_s - a.t_s) / 60.0;
    if (dt_min <= 0 || (x_ == x0 && y_ == y0 && z_ == z0 && a_ == a0)) return;
    std::string line = b.extrude || m_.rotary.inverse_time ? "G1" : "G0";
    if (x_ != x0) line += " X" + x_;
    if (y_ != y0) line += " Y" + y_;
    if (z_ != z0) line += " Z" + z_;
    if (a_ != a0) line += " " + letter_ + a_;
    if (b.extrude) line += " E" + e_words(a, b);
    line += " F" + fmt_fixed(feed(from, tip_, a_deg_ - a_from, dt_min), 3);
    out_ += line + "\n";
  }

  // The feed that makes the move last its planned time (see the header comment).
  double feed(const Vec3& from, const Vec3& to, double da_deg, double dt_min) const {
    if (m_.rotary.inverse_time) return 1.0 / dt_min;
    const double xyz = (to - from).norm();
    return (xyz > 0 ? xyz : std::abs(da_deg)) / dt_min;
  }

  std::string e_words(const slicer::PosePoint& a, const slicer::PosePoint& b) {
    const std::size_t layer = static_cast<std::size_t>(b.layer);
    const double area = layer < info_.bead_area_mm2.size() ? info_.bead_area_mm2[layer] : 0.0;
    const double e = area * (b.contact_mm - a.contact_mm).norm() / m_.deposition.mm3_per_e;
    e_total_ += e;
    return fmt_e(m_.deposition.relative_e ? e : e_total_);
  }

  // The position as written (rounded to the file's 0.001), so feeds match what the firmware reads.
  void remember(const slicer::PosePoint& p) {
    const auto round3 = [](double v) { return std::round(v * 1000.0) / 1000.0; };
    tip_ = p.tip_mm.unaryExpr(round3);
    a_deg_ = round3(rotary_a_deg(p.turn_rad));
    x_ = fmt_xyz(tip_.x()), y_ = fmt_xyz(tip_.y()), z_ = fmt_xyz(tip_.z()), a_ = fmt_xyz(a_deg_);
  }

  const slicer::PoseProgram& p_;
  const MachineProfile& m_;
  const RotaryGcodeInfo& info_;
  const std::string letter_;
  std::string out_, x_, y_, z_, a_;
  Vec3 tip_ = Vec3::Zero();
  double a_deg_ = 0.0;
  double e_total_ = 0.0;
};

}  // namespace

double rotary_a_deg(double turn_rad) { return -slicer::rad_to_deg(turn_rad); }

std::string write_rotary_gcode(const slicer::PoseProgram& program, const MachineProfile& m,
                               const RotaryGcodeInfo& info) {
  return Writer(program, m, info).run();
}

}  // namespace strand::machines
