// KRL text: one DEF per lap piece, inline LIN frames, speeds in m/s.
#include "machines/krl_writer.h"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "machines/extruder_gcode.h"
#include "machines/gcode_format.h"
#include "machines/workpiece_pose.h"
#include "slicer/units.h"

namespace strand::machines {

namespace {

constexpr std::size_t kMaxKrlName = 24;  // KRL identifiers

std::string frame_text(const Vec3& p, const Vec3& abc) {
  return "{X " + fmt_fixed(p.x(), 4) + ", Y " + fmt_fixed(p.y(), 4) + ", Z " + fmt_fixed(p.z(), 4) +
         ", A " + fmt_fixed(abc.x(), 4) + ", B " + fmt_fixed(abc.y(), 4) + ", C " +
         fmt_fixed(abc.z(), 4) + "}";
}

// A sub-program: LIN to points [first, last], all of lap `lap`.
struct Piece {
  std::string name;
  std::size_t first, last;
  int lap;
  bool starts_lap;
};

// Laps own the points whose motion they execute (point 0 is the start, reached by PTP);
// laps longer than `per_module` points are cut into several sub-programs.
std::vector<Piece> pieces(const slicer::PoseProgram& p, const std::string& module, int per_module) {
  std::vector<Piece> out;
  const auto& pts = p.points;
  for (std::size_t i = 1; i < pts.size();) {
    std::size_t j = i;
    while (j + 1 < pts.size() && pts[j + 1].lap == pts[i].lap) ++j;
    const std::size_t n = j - i + 1;
    const std::size_t parts = (n + per_module - 1) / per_module;
    for (std::size_t k = 0; k < parts; ++k) {
      const std::string name = "L" + std::to_string(pts[i].lap) + "P" + std::to_string(k + 1);
      out.push_back({module.substr(0, kMaxKrlName - name.size() - 1) + "_" + name,
                     i + n * k / parts, i + n * (k + 1) / parts - 1, pts[i].lap, k == 0});
    }
    i = j + 1;
  }
  return out;
}

}  // namespace

std::string krl_module_name(const std::string& base) {
  std::string out;
  for (char c : base) out += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  if (out.empty() || std::isdigit(static_cast<unsigned char>(out[0]))) out = "S" + out;
  return out.substr(0, kMaxKrlName - 8);  // room for the sub-program suffixes
}

Eigen::Matrix3d nozzle_frame_rotation(const RobotCell& c) {
  Eigen::Matrix3d r;
  r.col(0) = c.nozzle_axis.cross(c.substrate_axis);
  r.col(1) = -c.substrate_axis;
  r.col(2) = c.nozzle_axis;
  return r;
}

Vec3 kuka_abc_deg(const Eigen::Matrix3d& m) {
  const double a = std::atan2(m(1, 0), m(0, 0));
  const double b = std::atan2(-m(2, 0), std::hypot(m(2, 1), m(2, 2)));
  const double c = std::atan2(m(2, 1), m(2, 2));
  return Vec3(slicer::rad_to_deg(a), slicer::rad_to_deg(b), slicer::rad_to_deg(c));
}

KrlProgram write_krl(const slicer::PoseProgram& p, const MachineProfile& m, const std::string& base,
                     const std::vector<std::string>& header, double blend_mm) {
  const RobotCell& c = m.robot;
  const std::string module = krl_module_name(base);
  const Eigen::Matrix3d nozzle = nozzle_frame_rotation(c);
  KrlProgram out;
  const auto subs = pieces(p, module, c.programs.krl_points_per_module);
  out.sub_programs = static_cast<int>(subs.size());
  std::string& s = out.src;
  s = "&ACCESS RVP\nDEF " + module + "()\n";
  for (const auto& h : header) s += "; " + h + "\n";
  if (module != base)
    s += "; KSS loads a module whose file name is its DEF name: save as " + module + ".src/.dat\n";
  s += "  BAS(#INITMOV, 0)\n  $TOOL = workpiece_on_flange\n  $BASE = nozzle_in_world\n";
  s +=
      "  $IPO_MODE = #BASE ; external TCP: the robot carries the workpiece past the fixed nozzle\n";
  s += "  $APO.CDIS = " + fmt_fixed(blend_mm, 3) + "\n  $ADVANCE = 3\n";
  const Vec3& first = p.points.front().contact_mm;
  const Eigen::Matrix3d r0 = rotation_of(p.points.front().workpiece_wxyz).transpose() * nozzle;
  s += "  PTP " + frame_text(first, kuka_abc_deg(r0)) + " ; backed off above the first point\n";
  for (const auto& sub : subs) s += "  " + sub.name + "()\n";
  s += "END\n";
  for (const auto& sub : subs) {
    s += "\nDEF " + sub.name + "()\n";
    if (sub.starts_lap) {
      // Switched on the path (not in the advance run) as the lap's first motion starts.
      s += "  TRIGGER WHEN DISTANCE=0 DELAY=0 DO $OUT[" +
           std::to_string(c.programs.krl_lap_output) +
           "]=" + (lap_signal_level(c, sub.lap) == 1 ? "TRUE" : "FALSE") + " ; lap " +
           std::to_string(sub.lap) + " starts\n";
    }
    double speed = -1.0;
    for (std::size_t i = sub.first; i <= sub.last; ++i) {
      const auto& pt = p.points[i];
      if (pt.speed_mm_per_s != speed) {
        speed = pt.speed_mm_per_s;
        s += "  $VEL.CP = " + fmt_fixed(speed / 1000.0, 6) + " ; m/s\n";
      }
      const Eigen::Matrix3d r = rotation_of(pt.workpiece_wxyz).transpose() * nozzle;
      s += "  LIN " + frame_text(pt.contact_mm, kuka_abc_deg(r)) + " C_DIS\n";
      ++out.lin_points;
    }
    s += "END\n";
  }
  out.dat = "&ACCESS RVP\nDEFDAT " + module + "\n";
  out.dat +=
      "; $TOOL: the workpiece (cylinder) frame on the flange; $BASE: the nozzle tip (external TCP) "
      "in the world\n";
  const Eigen::Isometry3d wf = workpiece_in_flange(c);
  out.dat += "DECL FRAME workpiece_on_flange = " +
             frame_text(wf.translation(), kuka_abc_deg(wf.linear())) + "\n";
  out.dat += "DECL FRAME nozzle_in_world = " + frame_text(c.nozzle_tip_mm, kuka_abc_deg(nozzle)) +
             " ; calibration value of the profile\n";
  out.dat += "DECL REAL v_cart_m_s = " + fmt_fixed(c.v_cart_mm_per_s / 1000.0, 6) + "\nENDDAT\n";
  return out;
}

}  // namespace strand::machines
