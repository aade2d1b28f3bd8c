// Java source text for KUKA Sunrise.OS; the data stays in the CSV.
#include "machines/sunrise_writer.h"

#include <cctype>
#include <cmath>

#include "machines/extruder_gcode.h"
#include "machines/gcode_format.h"
#include "machines/joint_analysis.h"
#include "machines/krl_writer.h"
#include "machines/program_text.h"
#include "machines/sunrise_java_text.h"
#include "machines/workpiece_pose.h"
#include "slicer/input_error.h"
#include "slicer/units.h"

namespace strand::machines {

namespace {

constexpr std::size_t kMaxClassName = 64;
// How long the robot waits for the extruder's ready level before a lap, ms.
constexpr long kReadyTimeoutMs = 600000;

std::string radii(const slicer::PoseProgram& p, const MachineProfile&) {
  std::string out;
  const double r = p.substrate.value("radius_mm", 0.0);
  for (const auto& l : p.layers) out += (out.empty() ? "" : ", ") + fmt_fixed(r + l.offset_mm, 4);
  return out;
}

}  // namespace

std::string java_class_name(const std::string& base) {
  std::string out;
  bool upper = true;
  for (char c : base) {
    if (std::isalnum(static_cast<unsigned char>(c))) {
      out += upper ? static_cast<char>(std::toupper(static_cast<unsigned char>(c))) : c;
      upper = false;
    } else {
      upper = true;
    }
  }
  if (out.empty() || std::isdigit(static_cast<unsigned char>(out[0]))) out = "Strand" + out;
  out = out.substr(0, kMaxClassName);
  // A name the program already uses for an imported class or its own I/O group would not
  // compile (or would shadow it).
  static const char* const kTaken[] = {"BufferedReader",
                                       "FileReader",
                                       "IOException",
                                       "ArrayList",
                                       "List",
                                       "Inject",
                                       "LBR",
                                       "JointPosition",
                                       "Frame",
                                       "ObjectFrame",
                                       "Tool",
                                       "World",
                                       "Transformation",
                                       "LIN",
                                       "MotionBatch",
                                       "RoboticsAPIApplication",
                                       "Math",
                                       "String",
                                       "Object",
                                       "Override",
                                       "IllegalStateException",
                                       "System",
                                       "Double",
                                       "Integer"};
  for (const char* taken : kTaken)
    if (out == taken) return out + "Application";
  return out;
}

std::string write_sunrise_java(const slicer::PoseProgram& p, const MachineProfile& m,
                               const std::string& base, const std::string& csv_name,
                               const std::vector<std::string>& header,
                               const TransitPlan& transit) {
  const RobotCell& c = m.robot;
  // Checked when the profile is read; again here, as these two are pasted into code.
  require_java_identifier("robot.sunrise.io_group", c.programs.sunrise_io_group);
  require_java_identifier("robot.sunrise.lap_signal", c.programs.sunrise_lap_signal);
  if (!c.programs.sunrise_ready_signal.empty())
    require_java_identifier("robot.sunrise.ready_signal", c.programs.sunrise_ready_signal);
  if (!c.programs.sunrise_tool_template.empty()) {
    require_sunrise_name("robot.sunrise.tool_template", c.programs.sunrise_tool_template);
    require_sunrise_frame_path("robot.sunrise.tool_frame", c.programs.sunrise_tool_frame);
  }
  if (!c.programs.sunrise_nozzle_frame.empty())
    require_sunrise_frame_path("robot.sunrise.nozzle_frame", c.programs.sunrise_nozzle_frame);
  const std::string cls = java_class_name(base);
  if (c.programs.sunrise_io_group + "IOGroup" == cls) {
    throw InputError("output = " + base + ": its class name " + cls +
                     " is the I/O group's class (robot.sunrise.io_group): choose another name");
  }
  std::string out = "package application;\n\n";
  for (const auto& h : header) out += "// " + java_comment_text(h) + "\n";
  out += R"(
import static com.kuka.roboticsAPI.motionModel.BasicMotions.lin;
import static com.kuka.roboticsAPI.motionModel.BasicMotions.ptp;

import java.io.BufferedReader;
import java.io.FileReader;
import java.io.IOException;
import java.util.ArrayList;
import java.util.List;

import javax.inject.Inject;

import com.kuka.generated.ioAccess.__IO_GROUP__IOGroup;
import com.kuka.roboticsAPI.applicationModel.RoboticsAPIApplication;
import com.kuka.roboticsAPI.deviceModel.JointPosition;
import com.kuka.roboticsAPI.deviceModel.LBR;
import com.kuka.roboticsAPI.geometricModel.Frame;
import com.kuka.roboticsAPI.geometricModel.ObjectFrame;
import com.kuka.roboticsAPI.geometricModel.Tool;
import com.kuka.roboticsAPI.geometricModel.World;
import com.kuka.roboticsAPI.geometricModel.math.Transformation;
import com.kuka.roboticsAPI.motionModel.LIN;
import com.kuka.roboticsAPI.motionModel.MotionBatch;

)";
  out += "public class " + cls + " extends RoboticsAPIApplication {\n";
  out += "  private static final String CSV_DIR = " +
         java_string_literal(c.programs.sunrise_csv_dir, "robot.sunrise.csv_dir") + ";\n";
  out +=
      "  private static final String CSV_NAME = " + java_string_literal(csv_name, "output") + ";\n";
  const RobotMotionSetup& mo = c.motion;
  const Joints q0 = transit.start_clearance_joints;
  const auto numbers = [](const auto& values, int n, int digits) {
    std::string t;
    for (int i = 0; i < n; ++i) t += (i ? ", " : "") + fmt_fixed(values[i], digits);
    return t;
  };
  out += "  // The clearance pose, START_CLEARANCE_MM from the first pose along the nozzle axis, by\n";
  out += "  // axis values (A1..A7, rad); the joint moves to and from it are checked clear of the\n";
  out += "  // nozzle along their joint interpolation (Strand's robot_transit).\n";
  out += "  private static final double START_CLEARANCE_MM = " +
         fmt_fixed(transit.start_clearance_mm, 3) + ";\n";
  out += "  private static final double END_CLEARANCE_MM = " + fmt_fixed(transit.end_clearance_mm, 3) +
         ";\n";
  out += "  // Its axis values come from the cell's inverse kinematics: no redundancy is left to\n";
  out += "  // the controller.\n";
  out += "  private static final double[] START_JOINTS_RAD = {" + numbers(q0, 7, 6) + "};\n";
  out += "  private static final double APPROACH_MM = " + fmt_fixed(mo.approach_mm, 3) + ";\n";
  out += "  private static final double RETRACT_MM = " + fmt_fixed(mo.retract_mm, 3) + ";\n";
  out += "  private static final double[] NOZZLE_AXIS = {" + numbers(c.nozzle_axis, 3, 9) +
         "};  // flow direction\n";
  std::array<double, 7> home_rad{};
  if (mo.home_joints_deg)
    for (std::size_t i = 0; i < 7; ++i) home_rad[i] = slicer::deg_to_rad((*mo.home_joints_deg)[i]);
  out += "  private static final double[] HOME_JOINTS_RAD = {" +
         (mo.home_joints_deg ? numbers(home_rad, 7, 6) : std::string()) + "};  // none: {}\n";
  out += "  private static final double PTP_VELOCITY_REL = " +
         fmt_fixed(mo.ptp_velocity_percent / 100.0, 3) + ";\n";
  out += "  private static final double TRAVEL_MM_S = " + fmt_fixed(c.travel_speed_mm_per_s, 3) +
         ";\n";
  out += "  private static final double LOAD_MASS_KG = " + fmt_fixed(mo.load_mass_kg, 3) +
         ";  // the workpiece on the flange\n";
  out += "  private static final double[] LOAD_COG_MM = {" + numbers(mo.load_cog_mm, 3, 3) + "};\n";
  out +=
      "  private static final long READY_TIMEOUT_MS = " + std::to_string(kReadyTimeoutMs) + ";\n";
  out += "  private static final double V_CART_MM_S = " + fmt_fixed(c.v_cart_mm_per_s, 3) +
         ";  // deposits (rows carry their speed)\n";
  out += "  private static final double BLEND_MM = 0.01;\n";
  if (mo.path_acceleration_mm_per_s2) {
    out += "  private static final double CART_ACCELERATION_MM_S2 = " +
           fmt_fixed(*mo.path_acceleration_mm_per_s2, 3) + ";  // as the lap timing assumes\n";
  }
  // Project data named in the profile: the workpiece tool template and the nozzle frame.
  if (!c.programs.sunrise_tool_template.empty()) {
    out += "  private static final String TOOL_TEMPLATE = " +
           java_string_literal(c.programs.sunrise_tool_template, "robot.sunrise.tool_template") +
           ";\n";
    out += "  private static final String TOOL_FRAME = " +
           java_string_literal(c.programs.sunrise_tool_frame, "robot.sunrise.tool_frame") + ";\n";
  }
  if (!c.programs.sunrise_nozzle_frame.empty()) {
    const Eigen::Matrix3d n = nozzle_frame_rotation(c);
    out += "  private static final String NOZZLE_FRAME = " +
           java_string_literal(c.programs.sunrise_nozzle_frame, "robot.sunrise.nozzle_frame") +
           ";\n";
    out += "  private static final double[] NOZZLE_TIP_MM = {" + numbers(c.nozzle_tip_mm, 3, 4) +
           "};\n";
    out += "  private static final double[][] NOZZLE_ROTATION = {{" + numbers(n.row(0), 3, 9) +
           "}, {" + numbers(n.row(1), 3, 9) + "}, {" + numbers(n.row(2), 3, 9) + "}};\n";
  }
  out += "  private static final double MOUNT_MM = " + fmt_fixed(c.mount_mm, 3) + ";\n";
  out +=
      "  private static final double MOUNT_ROTATION_DEG = " + fmt_fixed(c.mount_rotation_deg, 3) +
      ";\n";
  out +=
      "  private static final int FIRST_LEVEL = " + std::to_string(lap_signal_level(c, 0)) + ";\n";
  out += "  // Contact radius per layer: cylinder radius + nozzle tip offset (k + 1) h, mm.\n";
  out += "  private static final double[] CONTACT_RADIUS_MM = {" + radii(p, m) + "};\n";
  out += sunrise_text::kBody;
  const std::string& ready = c.programs.sunrise_ready_signal;
  out = replace_all(
      out, "__WAIT_FOR_EXTRUDER__",
      ready.empty()
          ? "    // No ready input in the profile (robot.sunrise.ready_signal): no wait.\n"
          : "    long until = System.currentTimeMillis() + READY_TIMEOUT_MS;\n"
            "    while (extruder.get" +
                ready +
                "() != level) {\n"
                "      if (System.currentTimeMillis() > until) {\n"
                "        throw new IllegalStateException(\"the extruder is not ready for lap \" + "
                "lap);\n"
                "      }\n"
                "      try {\n"
                "        Thread.sleep(10);\n"
                "      } catch (InterruptedException e) {\n"
                "        throw new IllegalStateException(e);\n"
                "      }\n"
                "    }\n");
  const RobotPrograms& pr = c.programs;
  const bool tool_template = !pr.sunrise_tool_template.empty();
  const bool nozzle_frame = !pr.sunrise_nozzle_frame.empty();
  out = replace_all(out, "__INITIALIZE__",
                    std::string(tool_template ? sunrise_text::kInitializeTemplateTool : sunrise_text::kInitializeProfileTool) +
                        (nozzle_frame ? "    nozzle = getApplicationData().getFrame(NOZZLE_FRAME);\n"
                                      : ""));
  out = replace_all(out, "__NOZZLE_FIELD__",
                    nozzle_frame ? "  private ObjectFrame nozzle;  // the calibrated nozzle tip\n"
                                 : "");
  out = replace_all(out, "__NOZZLE_RELATIVE__", nozzle_frame ? sunrise_text::kNozzleRelative : "");
  out = replace_all(out, "__RETURN_TARGET__",
                    nozzle_frame ? sunrise_text::kReturnNozzleTarget : sunrise_text::kReturnWorldTarget);
  out = replace_all(out, "__CART_ACCELERATION__",
                    mo.path_acceleration_mm_per_s2
                        ? ".setCartAcceleration(CART_ACCELERATION_MM_S2)"
                        : "");
  out = replace_all(out, "__IO_GROUP__", c.programs.sunrise_io_group);
  return replace_all(out, "__LAP_SIGNAL__", c.programs.sunrise_lap_signal);
}

}  // namespace strand::machines
