// The contact point's speed as a robot program moves it. The pose program plans the contact
// point (the nozzle tip on the workpiece) at each row's speed, and the extruder follows that
// time line; a program that moves another frame (URScript's TCP, Sunrise's moved frame: a
// point fixed in the workpiece) at the row's speed moves the contact point at another speed
// wherever the workpiece tilts under the nozzle. Here: the chord each program's frame moves
// per row, the speed that keeps the row's duration, and the figures that compare a program's
// motions with the time line.
#pragma once

#include <string>
#include <vector>

#include "machines/profile.h"
#include "slicer/pose_program.h"

namespace strand::machines {

// What a vendor program moves: the contact point itself (KRL's external TCP, RAPID's
// stationary tool) or a frame fixed in the workpiece (URScript, Sunrise).
enum class MovedFrame { Contact, WorkpieceFrame };

// The robot program(s) a cell's controller runs, with the frame each moves.
struct VendorProgram {
  std::string name;  // "KRL", "Sunrise", "URScript", "RAPID"
  MovedFrame frame = MovedFrame::Contact;
};
std::vector<VendorProgram> vendor_programs(const RobotCell& cell);

// The workpiece frame's point a program moves for rows of `layer`: (radius of the layer's
// contact, 0, 0) in the workpiece frame (the substrate's radius, 0 on a mesh, + the offset).
double moved_frame_radius_mm(const slicer::PoseProgram& p, int layer);

// One programmed motion per row (index i: from row i - 1 to row i; index 0 unused): the chord
// the program's frame moves and the speed it is commanded at.
struct ProgrammedMotion {
  double frame_chord_mm = 0.0;
  double speed_mm_per_s = 0.0;
};

// The chords a program moving `frame` sees: the contact chord |p_i - p_{i-1}|, or the chord
// of the workpiece point of row i's layer (moved_frame_radius_mm) in the robot base frame.
std::vector<double> frame_chords_mm(const slicer::PoseProgram& p, MovedFrame frame);

// The speed that moves a frame `frame_chord_mm` in the time the contact point takes for
// `contact_chord_mm` at `contact_speed_mm_per_s` (the row's speed where either chord is 0:
// a turn in place, or a motion the controller times by its rotation).
double frame_speed_mm_per_s(double contact_speed_mm_per_s, double frame_chord_mm,
                            double contact_chord_mm);

// The motions of a program that keeps the time line: chords of `frame`, speeds scaled.
std::vector<ProgrammedMotion> timed_motions(const slicer::PoseProgram& p, MovedFrame frame);

// A program's motions against the time line. ratio = the contact point's speed at the
// programmed speed / the row's planned speed, over deposit rows; a lap's time at the
// programmed speeds (sum of frame chord / speed) against the extruder's (the rows' t_s).
struct ContactSpeedFigures {
  double worst_ratio = 1.0;  // the ratio farthest from 1
  std::size_t worst_ratio_row = 0;
  double worst_lap_difference = 0.0;  // (program lap time - extruder lap time) / extruder's
  int worst_lap = -1;
  int deposit_moves = 0;
};
// Deposit rows whose contact chord is below this are left out of the ratio (their time is in
// the lap's); programs round positions to 0.0001 mm.
constexpr double kContactSpeedMinChordMm = 0.05;
ContactSpeedFigures contact_speed_figures(const slicer::PoseProgram& p,
                                          const std::vector<ProgrammedMotion>& motions);

}  // namespace strand::machines
