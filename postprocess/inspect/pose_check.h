// `strand check` for curved substrates: a robot cell's pose CSV or a rotary printer's 4-axis
// G-code mapped back onto the cylinder. Reports per layer the deposit radius, strands and
// crossings/touches in (u, v) (u periodic: the seam is handled), and the poses off the nozzle
// tip, normals not facing the nozzle, points off the layer's offset surface, speed deviations,
// moves outside the envelope, and (robot) reach and joint limits from inverse kinematics.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "machines/joint_analysis.h"
#include "machines/profile.h"
#include "machines/robot_transit.h"
#include "postprocess/inspect/crossings.h"
#include "postprocess/inspect/curved_files.h"
#include "postprocess/inspect/gcode_parser.h"
#include "postprocess/inspect/program_speed_check.h"

namespace strand::post {

struct PoseFinding {
  std::size_t row = 0;  // CSV row index (pose CSV) or G-code line (rotary)
  std::string what;
};

struct PoseLayerCheck {
  int layer = 0;
  double radius_mm = 0.0;  // median deposit radius from the cylinder axis (a mesh: offset)
  int strands = 0;
  std::vector<Contact> crossings, touches;  // at_mm = (u, v); move_a/b = rows or lines
};

struct PoseFindings {
  std::vector<PoseFinding> listed;  // the first kMaxListed
  std::size_t total = 0;
  static constexpr std::size_t kMaxListed = 1000;
  void add(std::size_t row, std::string what);
};

struct PoseCheckReport {
  std::string kind;  // "pose CSV" or "rotary G-code"
  std::string machine;
  std::size_t rows = 0;  // poses, or moves
  std::vector<PoseLayerCheck> layers;
  PoseFindings off_tip, normals, off_surface, speed, outside, parse;
  // What the program promises about itself: consecutive indices, layer and lap numbering,
  // turn direction per lap (numbering); unit quaternions (quaternions); deposits flagged as the
  // feature and ink say (extrusion: the extrude flag against the feature, E per mm).
  PoseFindings numbering, quaternions, extrusion;
  bool joints_checked = false;
  machines::JointReport joints;
  // The program's start and end as its writers move (robot_transit.h): home, clearance pose,
  // approach, first row; last row, retract, clearance pose, home.
  bool transit_checked = false;
  machines::TransitPlan transit;
  // The vendor programs beside the CSV read back for their contact speed (issue 37).
  std::vector<ProgramSpeed> program_speeds;
  // A pose CSV on a robot-held mesh (mesh_pose_check.h): layers list the deposits' offset
  // from the mesh, and the note says which mesh.
  bool on_mesh = false;
  std::string substrate_note;

  bool ok() const;
  std::size_t crossing_count() const;
};

// The pose CSV against a robot-holds-substrate profile (required: it holds the nozzle tip and
// axis). Throws InputError for a file that is not a pose CSV.
PoseCheckReport check_pose_csv(std::string_view text, const std::string& file,
                               const machines::MachineProfile& robot_cell);

// A rotary file mapped back onto its cylinder (;ROTARY_AXIS_DIR/POINT, ;SUBSTRATE: header);
// `machine` (optional) adds the envelope. Throws InputError when the header is incomplete.
PoseCheckReport check_rotary_gcode(std::string_view text, const std::string& file,
                                   const machines::MachineProfile* machine);

// Shared with the mesh check (mesh_pose_check.h): the rows against the cell (nozzle tip and
// axis, unit quaternions, times and speeds), and the file's numbering (indices, layers, laps,
// extrude flags; with `laps_by_turn` also every lap turning one way, as on a cylinder).
void check_pose_rows(const std::vector<slicer::PosePoint>& rows, const machines::RobotCell& cell,
                     PoseCheckReport& report);
void check_pose_numbering(std::string_view text, const std::vector<slicer::PosePoint>& rows,
                          bool laps_by_turn, PoseCheckReport& report);

// The start and end of the program the rows are (robot_transit.h) for `workpiece` held by
// `cell`: a start or end that cannot be planned clear of the nozzle fails the check.
void check_pose_transit(const std::vector<slicer::PosePoint>& rows, const machines::RobotCell& cell,
                        const machines::TransitWorkpiece& workpiece, PoseCheckReport& report);

nlohmann::json to_json(const PoseCheckReport& r);
std::string to_text(const PoseCheckReport& r);

// Shared by both checks: deposit radius per layer, strands and their contacts on the cylinder;
// a deposit must start and end on its layer's offset surface.
void check_on_cylinder(const std::vector<CylinderSample>& samples, double touch_mm,
                       PoseCheckReport& report);

}  // namespace strand::post
