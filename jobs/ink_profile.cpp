// The width model's fit, the profile it goes into, and reading a profile back for a job.
#include "jobs/ink_profile.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <set>

#include "slicer/file_io.h"
#include "slicer/input_error.h"
#include "slicer/json_input.h"

namespace strand::jobs {

namespace {

double round_to(double v, int digits) {
  const double f = std::pow(10.0, digits);
  return std::round(v * f) / f;
}

struct Point {
  double flow, speed, width;
};

std::vector<Point> points_of(const std::vector<nlohmann::json>& measurements) {
  std::vector<Point> pts;
  for (const auto& m : measurements) {
    for (const auto& l : m.at("lines")) {
      const double w = l.at("width_mm").get<double>(), f = l.at("flow").get<double>();
      const double v = l.at("speed_mm_min").get<double>();
      if (l.at("coverage").get<double>() >= kLeastCoverage && w > 0 && f > 0 && v > 0) pts.push_back({f, v, w});
    }
  }
  return pts;
}

}  // namespace

double WidthModel::width_mm(double flow, double speed_mm_per_min) const {
  return a * std::pow(flow, p) * std::pow(speed_mm_per_min, q);
}

WidthModel fit_width_model(const std::vector<nlohmann::json>& measurements) {
  const std::vector<Point> pts = points_of(measurements);
  std::set<double> flows, speeds;
  for (const auto& pt : pts) {
    flows.insert(pt.flow);
    speeds.insert(pt.speed);
  }
  if (pts.size() < 4 || flows.size() < 2 || speeds.size() < 2) {
    throw InputError("calibrate: " + std::to_string(pts.size()) + " measured lines with " + std::to_string(flows.size()) +
                     " flows and " + std::to_string(speeds.size()) +
                     " speeds; the fit needs at least 4 lines, 2 flows and 2 speeds (lines covered >= 50 %)");
  }
  // ln w = ln a + p ln flow + q ln speed: linear in (ln a, p, q).
  Eigen::MatrixXd x(static_cast<Eigen::Index>(pts.size()), 3);
  Eigen::VectorXd y(static_cast<Eigen::Index>(pts.size()));
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const auto r = static_cast<Eigen::Index>(i);
    x(r, 0) = 1.0;
    x(r, 1) = std::log(pts[i].flow);
    x(r, 2) = std::log(pts[i].speed);
    y(r) = std::log(pts[i].width);
  }
  const Eigen::Vector3d c = x.colPivHouseholderQr().solve(y);
  WidthModel m{std::exp(c(0)), c(1), c(2), 0.0, static_cast<int>(pts.size())};
  double sum = 0.0;
  for (const auto& pt : pts) sum += std::pow(m.width_mm(pt.flow, pt.speed) - pt.width, 2);
  m.rms_mm = std::sqrt(sum / static_cast<double>(pts.size()));
  return m;
}

nlohmann::json ink_profile(const std::string& name, const std::vector<nlohmann::json>& measurements,
                           const std::vector<std::string>& sources) {
  const WidthModel m = fit_width_model(measurements);
  const double nozzle = measurements.front().at("nozzle_mm").get<double>();
  for (const auto& j : measurements) {
    if (std::abs(j.at("nozzle_mm").get<double>() - nozzle) > 1e-9) {
      throw InputError("calibrate: the measurements were printed with different nozzles; calibrate one nozzle at a time");
    }
  }
  double lo = 1e300, hi = 0.0;
  for (const auto& pt : points_of(measurements)) {
    lo = std::min(lo, pt.speed);
    hi = std::max(hi, pt.speed);
  }
  // Flow 1 at the speed where the model's bead is as wide as the nozzle; outside the
  // measured speeds the model is not trusted, so the speed is held at the nearest end and
  // the flow makes up the difference.
  double flow = 1.0, speed = std::abs(m.q) > 1e-6 ? std::pow(nozzle / m.a, 1.0 / m.q) : lo;
  if (!(speed >= lo && speed <= hi)) {
    speed = std::clamp(std::isfinite(speed) ? speed : lo, lo, hi);
    flow = std::abs(m.p) > 1e-6 ? std::pow(nozzle / (m.a * std::pow(speed, m.q)), 1.0 / m.p) : 1.0;
  }
  const double layer_height = measurements.front().value("layer_height_mm", 0.8 * nozzle);
  return {{"name", name},
          {"nozzle_mm", nozzle},
          {"width_model", {{"a", m.a}, {"p", round_to(m.p, 5)}, {"q", round_to(m.q, 5)},
                           {"rms_mm", round_to(m.rms_mm, 5)}, {"points", m.points}}},
          {"print", {{"speed_mm_min", round_to(speed, 1)}, {"flow", round_to(flow, 3)},
                     {"layer_height_mm", round_to(layer_height, 4)}}},
          // From the collapse and fusion tests' measurements (calibrate_files).
          {"min_gap_without_collapse_mm", nullptr},
          {"min_spacing_without_fusion_mm", nullptr},
          {"measurements", sources}};
}

nlohmann::json calibrate_files(const std::vector<std::string>& paths, const std::string& out_path) {
  if (paths.empty()) throw InputError("calibrate: give at least one measurement file (strand measure output)");
  std::vector<nlohmann::json> ms;
  nlohmann::json closest_separate = nullptr;  // the widest over the fusion prints: safe on all
  nlohmann::json spanned = nullptr;           // the narrowest over the collapse prints: safe on all
  for (const auto& p : paths) {
    if (std::filesystem::weakly_canonical(p) == std::filesystem::weakly_canonical(out_path)) {
      throw InputError("calibrate.output = " + out_path + ": would overwrite a measurement file");
    }
    nlohmann::json j = slicer::parse_json(slicer::read_file(p), "calibrate.measurement = " + p);
    if (j.is_object() && j.value("test", "") == "fusion" && j.contains("closest_separate_spacing_mm")) {
      const auto& v = j.at("closest_separate_spacing_mm");
      if (v.is_number() && (closest_separate.is_null() || v.get<double>() > closest_separate.get<double>())) closest_separate = v;
      continue;
    }
    if (j.is_object() && j.value("test", "") == "collapse" && j.contains("widest_spanned_gap_mm")) {
      const auto& v = j.at("widest_spanned_gap_mm");
      const double gap = v.is_number() ? v.get<double>() : 0.0;  // null: not even the narrowest gap spanned
      if (spanned.is_null() || gap < spanned.get<double>()) spanned = gap;
      continue;
    }
    if (!j.is_object() || j.value("test", "") != "lines" || !j.contains("lines") || !j.contains("nozzle_mm")) {
      throw InputError("calibrate.measurement = " + p +
                       ": not a `strand measure --test lines` output (nor a --test fusion or collapse one)");
    }
    ms.push_back(std::move(j));
  }
  if (ms.empty()) throw InputError("calibrate: the width model needs at least one `strand measure --test lines` output");
  const std::string name = std::filesystem::path(out_path).stem().string();
  nlohmann::json profile = ink_profile(name, ms, paths);
  profile["min_spacing_without_fusion_mm"] = closest_separate;
  profile["min_gap_without_collapse_mm"] = spanned;
  slicer::write_file_atomic(out_path, profile.dump(2) + "\n");
  return profile;
}

nlohmann::json load_ink_profile(const std::string& name) {
  const std::string what = "material = " + name;
  std::filesystem::path path;
  if (name.ends_with(".json")) {
    path = name;
  } else {
    if (name.empty() || name.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789._-") !=
                            std::string::npos) {
      throw InputError(what + ": a name is letters, digits, '.', '_' and '-' (or give a path ending .json)");
    }
    std::vector<std::filesystem::path> dirs = {"materials"};
    if (const char* x = std::getenv("XDG_CONFIG_HOME"); x && *x) {
      dirs.push_back(std::filesystem::path(x) / "strand" / "materials");
    } else if (const char* h = std::getenv("HOME"); h && *h) {
      dirs.push_back(std::filesystem::path(h) / ".config" / "strand" / "materials");
    }
    for (const auto& d : dirs) {
      if (std::filesystem::is_regular_file(d / (name + ".json"))) {
        path = d / (name + ".json");
        break;
      }
    }
    if (path.empty()) {
      throw InputError(what + ": no materials/" + name + ".json here or in the user's strand/materials folder; "
                       "make one with strand calibrate");
    }
  }
  const nlohmann::json j = slicer::parse_json(slicer::read_file(path.string()), what);
  const auto& pr = j.is_object() ? j.value("print", nlohmann::json()) : nlohmann::json();
  if (!pr.is_object() || !pr.contains("speed_mm_min") || !pr.at("speed_mm_min").is_number() ||
      !pr.contains("layer_height_mm") || !pr.at("layer_height_mm").is_number() ||
      !j.contains("nozzle_mm") || !j.at("nozzle_mm").is_number()) {
    throw InputError(what + ": " + path.string() + " lacks nozzle_mm or print.speed_mm_min / layer_height_mm numbers");
  }
  nlohmann::json out = j;
  out["file"] = path.string();
  return out;
}

nlohmann::json apply_ink_profile(const nlohmann::json& profile, const std::string& name,
                                 const slicer::ParamTable& table, nlohmann::json& given) {
  auto has = [&](const char* key) {
    return std::any_of(table.defs.begin(), table.defs.end(), [&](const auto& d) { return d.key == key; });
  };
  const double nozzle = profile.at("nozzle_mm").get<double>();
  if (given.contains("nozzle") && given.at("nozzle").is_number() &&
      std::abs(given.at("nozzle").get<double>() - nozzle) > 0.01 * nozzle) {
    throw InputError(table.name + ".nozzle = " + slicer::short_number(given.at("nozzle").get<double>()) +
                     ": material " + name + " was calibrated with a " + slicer::short_number(nozzle) +
                     " mm nozzle; use that nozzle or calibrate this one");
  }
  const auto& pr = profile.at("print");
  nlohmann::json applied = nlohmann::json::object();
  if (has("speed") && !given.contains("speed")) applied["speed"] = given["speed"] = pr.at("speed_mm_min");
  if (has("layer-height") && !given.contains("layer-height")) {
    applied["layer-height"] = given["layer-height"] = pr.at("layer_height_mm");
  }
  return {{"name", name},
          {"file", profile.value("file", "")},
          {"applied", applied},
          {"flow", pr.value("flow", 1.0)},
          {"measurements", profile.value("measurements", nlohmann::json::array())}};
}

}  // namespace strand::jobs
