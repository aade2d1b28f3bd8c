// Chords of the moved frame, speeds that keep the time line, and the figures of a program.
#include "machines/contact_speed.h"

#include <algorithm>
#include <cmath>

#include "machines/workpiece_pose.h"

namespace strand::machines {

namespace {

// Chords below this are no motion of that point (the programs round to 0.0001 mm).
constexpr double kNoChordMm = 1e-9;

Vec3 frame_point(const slicer::PosePoint& pt, double radius_mm) {
  return pt.workpiece_origin_mm + rotation_of(pt.workpiece_wxyz) * Vec3(radius_mm, 0.0, 0.0);
}

}  // namespace

std::vector<VendorProgram> vendor_programs(const RobotCell& cell) {
  switch (cell.controller) {
    case RobotController::UniversalRobots:
      return {{"URScript", MovedFrame::WorkpieceFrame}};
    case RobotController::Abb:
      return {{"RAPID", MovedFrame::Contact}};
    default:
      return {{"KRL", MovedFrame::Contact}, {"Sunrise", MovedFrame::WorkpieceFrame}};
  }
}

double moved_frame_radius_mm(const slicer::PoseProgram& p, int layer) {
  return p.substrate.value("radius_mm", 0.0) + p.layers[static_cast<std::size_t>(layer)].offset_mm;
}

std::vector<double> frame_chords_mm(const slicer::PoseProgram& p, MovedFrame frame) {
  const auto& pts = p.points;
  std::vector<double> out(pts.size(), 0.0);
  for (std::size_t i = 1; i < pts.size(); ++i) {
    if (frame == MovedFrame::Contact) {
      out[i] = (pts[i].contact_mm - pts[i - 1].contact_mm).norm();
      continue;
    }
    // The frame of row i's layer: the program moves it from where row i - 1 left the arm.
    const double r = moved_frame_radius_mm(p, pts[i].layer);
    out[i] = (frame_point(pts[i], r) - frame_point(pts[i - 1], r)).norm();
  }
  return out;
}

double frame_speed_mm_per_s(double contact_speed_mm_per_s, double frame_chord_mm,
                            double contact_chord_mm) {
  if (frame_chord_mm < kNoChordMm || contact_chord_mm < kNoChordMm) return contact_speed_mm_per_s;
  return contact_speed_mm_per_s * frame_chord_mm / contact_chord_mm;
}

std::vector<ProgrammedMotion> timed_motions(const slicer::PoseProgram& p, MovedFrame frame) {
  const std::vector<double> chords = frame_chords_mm(p, frame);
  std::vector<ProgrammedMotion> out(p.points.size());
  for (std::size_t i = 1; i < p.points.size(); ++i) {
    const double contact = (p.points[i].contact_mm - p.points[i - 1].contact_mm).norm();
    out[i] = {chords[i], frame_speed_mm_per_s(p.points[i].speed_mm_per_s, chords[i], contact)};
  }
  return out;
}

ContactSpeedFigures contact_speed_figures(const slicer::PoseProgram& p,
                                          const std::vector<ProgrammedMotion>& motions) {
  ContactSpeedFigures f;
  const auto& pts = p.points;
  std::vector<double> program_s(p.laps.size(), 0.0), extruder_s(p.laps.size(), 0.0);
  for (std::size_t i = 1; i < pts.size() && i < motions.size(); ++i) {
    const double contact = (pts[i].contact_mm - pts[i - 1].contact_mm).norm();
    const ProgrammedMotion& mo = motions[i];
    // A turn in place (no contact motion) is off the time line by design: it ends a lap.
    if (contact < kNoChordMm) continue;
    const auto lap = static_cast<std::size_t>(pts[i].lap);
    if (lap < program_s.size() && mo.speed_mm_per_s > 0) {
      program_s[lap] += mo.frame_chord_mm / mo.speed_mm_per_s;
      extruder_s[lap] += pts[i].t_s - pts[i - 1].t_s;
    }
    if (!pts[i].extrude || contact < kContactSpeedMinChordMm || mo.frame_chord_mm < kNoChordMm ||
        pts[i].speed_mm_per_s <= 0)
      continue;
    ++f.deposit_moves;
    const double ratio = mo.speed_mm_per_s * contact / mo.frame_chord_mm / pts[i].speed_mm_per_s;
    if (std::abs(ratio - 1.0) > std::abs(f.worst_ratio - 1.0)) {
      f.worst_ratio = ratio;
      f.worst_ratio_row = i;
    }
  }
  for (std::size_t k = 0; k < program_s.size(); ++k) {
    if (extruder_s[k] <= 0) continue;
    const double d = (program_s[k] - extruder_s[k]) / extruder_s[k];
    if (f.worst_lap < 0 || std::abs(d) > std::abs(f.worst_lap_difference)) {
      f.worst_lap_difference = d;
      f.worst_lap = static_cast<int>(k);
    }
  }
  return f;
}

}  // namespace strand::machines
