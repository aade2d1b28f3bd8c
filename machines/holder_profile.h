// The curved-substrate part of a machine profile: a robot that holds the substrate under a
// fixed nozzle (with the fixed printer used only as an extruder), or a rotary axis that turns
// the substrate under an XYZ nozzle. Both reduce to one holder: where the nozzle is, which
// way it points and about which line the workpiece turns.
#pragma once

#include <array>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "slicer/geometry.h"
#include "slicer/mesh_collision.h"

namespace strand::machines {

using slicer::Vec3;

// The fixed printer of a robot cell, used only to extrude (E-only G-code on the same time line).
struct ExtruderSetup {
  Vec3 park_mm = Vec3::Zero();  // where it parks its nozzle, printer frame (thesis 0,-90,244)
  double park_feed_mm_per_min = 3000.0;
  double v_ext_mm_per_min = 100.0;  // E feed while depositing (time-based)
  bool time_based = true;           // E per mm = v_ext / v_cart; false: bead volume / mm3 per E
  int handshake_pin = -1;           // M226 P<pin> S<state> before each lap; -1 = none
  int handshake_state = 1;
  int ready_pin = -1;  // M42 P<pin>: "parked and ready for lap k" to the robot; -1 = none
};

// What the Sunrise and KRL programs need beyond the geometry.
struct RobotPrograms {
  std::string sunrise_io_group = "ExtruderIO";  // Sunrise I/O group class with the lap signal
  std::string sunrise_lap_signal = "LapStart";  // its boolean output set at each lap start
  std::string sunrise_csv_dir = "C:/KRC/ROBOTER/UserFiles";  // where the CSV is copied
  // Sunrise project data instead of the profile's values: the workpiece as a tool template
  // (its calibrated frames and load data) with the frame of the cylinder in it, and the fixed
  // nozzle tip as a frame of the application data; empty = the profile's values.
  std::string sunrise_tool_template;  // createFromTemplate(...), attached to the flange
  std::string sunrise_tool_frame;     // the cylinder frame in the template, "/Cylinder"
  std::string sunrise_nozzle_frame;   // getApplicationData().getFrame(...), "/Nozzle"
  // Tool and base from the controller's calibrated data instead of the profile's values:
  // $TOOL = TOOL_DATA[n] (the workpiece frame on the flange, with $LOAD = LOAD_DATA[n]) and
  // $BASE = BASE_DATA[m] (the fixed nozzle, external TCP); 0 = the profile's frames in the .dat.
  int krl_tool_data = 0;
  int krl_base_data = 0;
  int krl_lap_output = 1;            // $OUT[n] pulsed at each lap start
  int krl_points_per_module = 2000;  // LIN points per sub-program
  // Two-way handshake: the robot waits for the extruder's ready level before each lap.
  std::string sunrise_ready_signal;  // boolean input of the I/O group; empty = no wait
  int krl_ready_input = 0;           // $IN[n]; 0 = no wait
  // URScript (UR e-Series): standard digital output pulsed at each lap start, input the
  // robot waits on (-1 = no wait), Cartesian acceleration of movel.
  int ur_lap_output = 0;
  int ur_ready_input = -1;
  double ur_acceleration_mm_per_s2 = 500.0;
  // RAPID (ABB IRC5/OmniCore): names of the stationary tool, the robot-held work object and
  // the I/O signals (digital output at each lap start; digital input waited on, empty = none).
  std::string rapid_tool = "tNozzle";
  std::string rapid_wobj = "wobjWorkpiece";
  std::string rapid_lap_signal = "doLapStart";
  std::string rapid_ready_signal;
  // The tool / work object is PERS data on the controller (calibrated there, in a system
  // module): the module uses the name without declaring it.
  bool rapid_tool_on_controller = false;
  bool rapid_wobj_on_controller = false;
};

// Where the robot program starts and ends, and what it carries.
struct RobotMotionSetup {
  double approach_mm = 20.0;  // first pose approached from this far along the nozzle axis
  double retract_mm = 20.0;   // and left the same way after the last
  // The joint moves from and to home end and start this far from the first and last pose
  // along the nozzle axis (a linear move joins it to the approach): robot_transit.h.
  double clearance_mm = 100.0;
  // Every motion outside the laps keeps the workpiece this far from the nozzle's cone and
  // the keep-out (the final approach and the first retract, which end at the nozzle, excepted).
  double transit_margin_mm = 5.0;
  std::optional<std::array<double, 7>>
      home_joints_deg;              // PTP here first and last (A7 = 0 on 6 axes)
  int ptp_velocity_percent = 10;    // of each axis' maximum
  double load_mass_kg = 0.0;        // the workpiece and its adapter
  Vec3 load_cog_mm = Vec3::Zero();  // in the flange frame
  // Path acceleration of the moved frame, mm/s^2: commanded by the programs when given
  // ($ACC.CP, setCartAcceleration, movel a, PathAccLim) and used to time laps with their
  // corner slowdowns (corner_acceleration_mm_per_s2).
  std::optional<double> path_acceleration_mm_per_s2;
};

// The acceleration the lap timing assumes when the profile commands none, mm/s^2.
inline constexpr double kDefaultPathAccelerationMmPerS2 = 500.0;

// Which controller's programs a cell gets beside the pose CSV.
enum class RobotController { Kuka, UniversalRobots, Abb };

struct RobotCell {
  bool enabled = false;
  std::string arm = "lbr-iiwa-14-r820";  // or "ur10e", "irb1200-5-0.9"
  RobotController controller = RobotController::Kuka;
  int axes = 7;
  double v_cart_mm_per_s = 6.0;         // contact speed while depositing
  double travel_speed_mm_per_s = 20.0;  // contact speed for travels
  double lift_mm = 3.0;                 // the substrate backs off the nozzle this far for travels
  std::array<double, 7> joint_limits_deg = {170, 120, 170, 120, 170, 120, 175};  // upper
  std::optional<std::array<double, 7>> joint_min_deg;  // lower limits; unset: -joint_limits_deg
  double joint_margin_deg = 5.0;  // laps keep this far from the last joint's limit
  double reach_mm = 820.0;        // wrist centre from the shoulder
  // Calibration: the nozzle tip and the nozzle axis (direction of flow) in the robot base frame.
  Vec3 nozzle_tip_mm = Vec3(650.0, 0.0, 450.0);
  Vec3 nozzle_axis = Vec3(0.0, 0.0, -1.0);
  Vec3 substrate_axis = Vec3(1.0, 0.0, 0.0);  // cylinder axis in the base frame (flange z)
  double mount_mm = 40.0;           // flange face to the cylinder's mounted end, along flange z
  double mount_rotation_deg = 0.0;  // cylinder u = 0 line about flange z from flange +x
  // The nozzle's outside near the tip, checked against a robot-held substrate mesh.
  slicer::NozzleCone nozzle_cone;
  // The extruder's body above the cone: a cylinder about the nozzle axis from the cone's top,
  // which no motion outside the laps may bring the workpiece into.
  struct KeepOut {
    double radius_mm = 40.0;
    double length_mm = 200.0;
    bool operator==(const KeepOut&) const = default;
  } keep_out;
  ExtruderSetup extruder;
  RobotPrograms programs;
  RobotMotionSetup motion;
};

struct RotaryAxis {
  bool enabled = false;
  char letter = 'A';
  Vec3 axis_dir = Vec3::UnitX();      // unit, machine frame; the workpiece turns about it
  Vec3 axis_point_mm = Vec3::Zero();  // chuck face centre on the axis: the cylinder's v = 0
  double max_radius_mm = 50.0;        // largest substrate the axis clears above the bed
  double lift_mm = 2.0;               // nozzle lift for travels
  bool inverse_time = false;          // G93 feeds (RepRapFirmware 3.5+ only)
};

// The path acceleration that times the laps: robot.acceleration_mm_per_s2, or what the
// URScript program commands (robot.urscript.acceleration_mm_per_s2), or the default.
double corner_acceleration_mm_per_s2(const RobotCell& cell);

// Reads j["robot"], j["extruder"] and j["rotary"] (schema already checked) and the kinematics
// type; problems are appended in the profile loader's format.
RobotCell read_robot_cell(const nlohmann::json& j, const std::string& origin,
                          std::vector<std::string>& problems);
RotaryAxis read_rotary_axis(const nlohmann::json& j, const std::string& origin,
                            std::vector<std::string>& problems);

}  // namespace strand::machines
