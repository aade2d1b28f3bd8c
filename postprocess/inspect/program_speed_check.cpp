// Reading the vendor programs beside a pose CSV back for their contact speed.
#include "postprocess/inspect/program_speed_check.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <optional>
#include <regex>
#include <sstream>

#include "machines/gcode_format.h"
#include "machines/urscript_writer.h"
#include "machines/workpiece_pose.h"
#include "postprocess/plan/produce_curved.h"
#include "slicer/file_io.h"
#include "slicer/input_error.h"

namespace strand::post {

namespace {

using slicer::Vec3;

// A program's motion matches the CSV row whose contact point is this close (programs round
// positions to 0.0001 m or mm).
constexpr double kMatchMm = 2e-3;
// Larger programs than this are not read back (the writers' own programs stay far below).
constexpr std::uintmax_t kMaxProgramBytes = 512u << 20;

// One motion as a program commands it: where the contact point ends, the chord its moved
// frame travels and the commanded speed.
struct ReadMotion {
  Vec3 contact = Vec3::Zero();
  double frame_chord_mm = 0.0;
  double speed_mm_per_s = 0.0;
};

// Motions after "onto the first pose", matched to rows in order; rows a program skips (a
// zero-length motion) keep no motion. Returns the row-aligned list or a problem.
std::vector<machines::ProgrammedMotion> align(const std::vector<ReadMotion>& motions,
                                              const std::vector<slicer::PosePoint>& rows,
                                              std::string& problem) {
  std::vector<machines::ProgrammedMotion> out(rows.size());
  std::size_t row = 0;
  for (std::size_t k = 0; k < motions.size(); ++k) {
    std::size_t j = row + 1;
    while (j < rows.size() && (rows[j].contact_mm - motions[k].contact).norm() > kMatchMm) ++j;
    if (j >= rows.size()) {
      problem = "motion " + std::to_string(k + 1) + " of the laps reaches no later CSV row";
      return {};
    }
    out[j] = {motions[k].frame_chord_mm, motions[k].speed_mm_per_s};
    row = j;
  }
  return out;
}

bool is_transit_comment(const std::string& comment) {
  return comment.find("approach") != std::string::npos ||
         comment.find("retract") != std::string::npos ||
         comment.find("clearance pose") != std::string::npos;
}

const std::string kNum = R"((-?[0-9.eE+-]+))";

Eigen::Isometry3d ur_pose(const std::string& six) {
  std::istringstream in(six);
  double v[6];
  char comma;
  for (int i = 0; i < 6; ++i) {
    in >> v[i];
    if (i < 5) in >> comma;
  }
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translate(Vec3(v[0], v[1], v[2]) * 1000.0);
  t.rotate(machines::rotation_of_vector(Vec3(v[3], v[4], v[5])));
  return t;
}

std::vector<ReadMotion> urscript_motions(const std::string& text, const machines::RobotCell& c) {
  static const std::regex tcp_re(R"(^  set_tcp\(p\[([^\]]*)\]\))");
  static const std::regex movel_re(R"(^  movel\(p\[([^\]]*)\], a=[0-9.]+, v=([0-9.]+), r=[0-9.]+\)(.*))");
  const Eigen::Isometry3d wif = machines::workpiece_in_flange(c);
  Eigen::Isometry3d tcp = Eigen::Isometry3d::Identity(), flange = tcp;
  bool started = false;
  std::vector<ReadMotion> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    std::smatch g;
    if (std::regex_search(line, g, tcp_re)) tcp = ur_pose(g[1]);
    if (!std::regex_search(line, g, movel_re) || is_transit_comment(g[3])) continue;
    const Eigen::Isometry3d target = ur_pose(g[1]);
    const Eigen::Isometry3d new_flange = target * tcp.inverse();
    const Vec3 contact = (new_flange * wif).inverse() * c.nozzle_tip_mm;
    if (started)
      out.push_back({contact, (target.translation() - (flange * tcp).translation()).norm(),
                     1000.0 * std::stod(g[2])});
    started = true;
    flange = new_flange;
  }
  return out;
}

// KRL and RAPID move the contact point itself: its chord at the commanded speed.
std::vector<ReadMotion> krl_motions(const std::string& text) {
  static const std::regex lin_re("^  LIN \\{X " + kNum + ", Y " + kNum + ", Z " + kNum + "(.*)");
  static const std::regex vel_re("\\$VEL.CP = " + kNum);
  std::vector<ReadMotion> out;
  std::optional<Vec3> previous;
  double v = 0.0;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    std::smatch g;
    if (std::regex_search(line, g, vel_re)) v = 1000.0 * std::stod(g[1]);
    if (!std::regex_search(line, g, lin_re) || is_transit_comment(g[4])) continue;
    const Vec3 p(std::stod(g[1]), std::stod(g[2]), std::stod(g[3]));
    if (previous) out.push_back({p, (p - *previous).norm(), v});
    previous = p;
  }
  return out;
}

std::vector<ReadMotion> rapid_motions(const std::string& text) {
  static const std::regex speed_re("CONST speeddata (\\w+) := \\[" + kNum);
  static const std::regex move_re("MoveL \\[\\[" + kNum + ", " + kNum + ", " + kNum +
                                  "\\].*\\], (\\w+), ");
  std::map<std::string, double> speeds;
  std::vector<ReadMotion> out;
  std::optional<Vec3> previous;
  std::string comment;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    std::smatch g;
    if (std::regex_search(line, g, speed_re)) speeds[g[1]] = std::stod(g[2]);
    if (std::regex_search(line, g, move_re) && !is_transit_comment(comment)) {
      const Vec3 p(std::stod(g[1]), std::stod(g[2]), std::stod(g[3]));
      const auto s = speeds.find(g[4]);
      if (previous) out.push_back({p, (p - *previous).norm(), s == speeds.end() ? 0.0 : s->second});
      previous = p;
    }
    const auto bang = line.find("! ");
    comment = bang == std::string::npos ? "" : line.substr(bang + 2);
  }
  return out;
}

// Sunrise reads the CSV itself: its moved frame is the workpiece point at CONTACT_RADIUS_MM
// of the row's layer; it scales each motion's speed when it has frameSpeed, else it moves at
// the rows' own speeds.
std::vector<machines::ProgrammedMotion> sunrise_motions(const std::string& text,
                                                        const std::vector<slicer::PosePoint>& rows,
                                                        std::string& problem) {
  static const std::regex radii_re(R"(CONTACT_RADIUS_MM = \{([^}]*)\})");
  std::smatch g;
  if (!std::regex_search(text, g, radii_re)) {
    problem = "no CONTACT_RADIUS_MM in the application";
    return {};
  }
  std::vector<double> radii;
  std::istringstream in(g[1].str());
  for (std::string cell; std::getline(in, cell, ',');) radii.push_back(std::stod(cell));
  const bool scaled = text.find("frameSpeed(") != std::string::npos;
  std::vector<machines::ProgrammedMotion> out(rows.size());
  const auto frame_point = [&](const slicer::PosePoint& r) {
    const std::size_t layer = static_cast<std::size_t>(std::max(r.layer, 0));
    const double radius = layer < radii.size() ? radii[layer] : 0.0;
    return Vec3(machines::rotation_of(r.workpiece_wxyz) * Vec3(radius, 0.0, 0.0) +
                r.workpiece_origin_mm);
  };
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const double frame = (frame_point(rows[i]) - frame_point(rows[i - 1])).norm();
    const double contact = (rows[i].contact_mm - rows[i - 1].contact_mm).norm();
    out[i] = {frame, scaled ? machines::frame_speed_mm_per_s(rows[i].speed_mm_per_s, frame, contact)
                            : rows[i].speed_mm_per_s};
  }
  return out;
}

std::optional<std::string> read_program(const std::string& path, std::string& problem) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return std::nullopt;
  const auto size = std::filesystem::file_size(path, ec);
  if (ec || size > kMaxProgramBytes) {
    problem = "too large to read back";
    return std::nullopt;
  }
  try {
    return slicer::read_file(path);
  } catch (const std::exception& e) {
    problem = e.what();
    return std::nullopt;
  }
}

}  // namespace

bool ProgramSpeed::ok() const {
  return !read || (std::abs(figures.worst_ratio - 1.0) <= 0.02 &&
                   std::abs(figures.worst_lap_difference) <= 0.02);
}

std::vector<ProgramSpeed> check_program_speeds(const std::vector<slicer::PosePoint>& rows,
                                               const std::string& csv_file,
                                               const machines::MachineProfile& m) {
  std::vector<ProgramSpeed> out;
  if (rows.size() < 2) return out;
  std::vector<std::string> paths;
  try {
    paths = curved_output_paths(m, csv_file);
  } catch (const InputError&) {
    return out;  // not a name the cell writes programs beside
  }
  slicer::PoseProgram program;
  program.points = rows;
  int laps = 0;
  for (const auto& r : rows) laps = std::max(laps, r.lap + 1);
  program.laps.resize(static_cast<std::size_t>(laps));
  const bool kuka = m.robot.controller == machines::RobotController::Kuka;
  for (const auto& vendor : machines::vendor_programs(m.robot)) {
    ProgramSpeed s;
    s.program = vendor.name;
    s.file = vendor.name == "Sunrise" ? paths[1] : vendor.name == "KRL" && kuka ? paths[2] : paths[1];
    const auto text = read_program(s.file, s.problem);
    if (!text) {
      out.push_back(std::move(s));
      continue;
    }
    std::vector<machines::ProgrammedMotion> motions;
    try {
      if (vendor.name == "Sunrise") {
        motions = sunrise_motions(*text, rows, s.problem);
      } else {
        const std::vector<ReadMotion> read = vendor.name == "URScript" ? urscript_motions(*text, m.robot)
                                             : vendor.name == "KRL"    ? krl_motions(*text)
                                                                       : rapid_motions(*text);
        motions = align(read, rows, s.problem);
      }
    } catch (const std::exception&) {  // a number out of range or malformed (std::stod)
      s.problem = "a number in it cannot be read";
      motions.clear();
    }
    s.read = s.problem.empty() && !motions.empty();
    if (s.read) s.figures = machines::contact_speed_figures(program, motions);
    out.push_back(std::move(s));
  }
  return out;
}

nlohmann::json program_speeds_json(const std::vector<ProgramSpeed>& speeds) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& s : speeds) {
    nlohmann::json j = {{"program", s.program},
                        {"file", std::filesystem::path(s.file).filename().string()},
                        {"read", s.read},
                        {"ok", s.ok()}};
    if (!s.problem.empty()) j["problem"] = s.problem;
    if (s.read) {
      j["worst_contact_speed_ratio"] = std::round(s.figures.worst_ratio * 1e4) / 1e4;
      j["worst_ratio_row"] = s.figures.worst_ratio_row;
      j["worst_lap_difference"] = std::round(s.figures.worst_lap_difference * 1e5) / 1e5;
      j["worst_lap"] = s.figures.worst_lap;
    }
    out.push_back(j);
  }
  return out;
}

std::string program_speeds_text(const std::vector<ProgramSpeed>& speeds) {
  std::string t;
  for (const auto& s : speeds) {
    const std::string file = std::filesystem::path(s.file).filename().string();
    t += "contact speed: " + s.program + " (" + file + ") ";
    if (!s.read) {
      t += s.problem.empty() ? "not beside the CSV, not checked\n" : "not read: " + s.problem + "\n";
      continue;
    }
    t += machines::fmt_fixed(s.figures.worst_ratio, 3) + " x the planned speed at row " +
         std::to_string(s.figures.worst_ratio_row) + ", lap " + std::to_string(s.figures.worst_lap) +
         " " + (s.figures.worst_lap_difference >= 0 ? "+" : "") +
         machines::fmt_fixed(100.0 * s.figures.worst_lap_difference, 1) +
         " % against the extruder's time" + (s.ok() ? "" : " (more than 2 % off: FAILED)") + "\n";
  }
  return t;
}

}  // namespace strand::post
