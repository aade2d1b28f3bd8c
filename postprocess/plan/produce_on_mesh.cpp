// Mesh jobs: the mesh read and mapped, the pattern centred on its map, the plan, the report.
#include "postprocess/plan/produce_on_mesh.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "machines/gcode_format.h"
#include "postprocess/plan/pose_report.h"
#include "postprocess/plan/report.h"
#include "slicer/file_io.h"
#include "slicer/input_error.h"
#include "slicer/json_input.h"
#include "slicer/mesh_io.h"
#include "slicer/mesh_substrate.h"
#include "slicer/params.h"
#include "slicer/units.h"

namespace strand::post {

namespace {

using machines::fmt_fixed;

constexpr const char* kPlacement =
    "pattern x -> u, y -> v on the mesh's (u, v) map, the pattern's centre on the map's; the "
    "mesh file's coordinates (mm) are the workpiece frame on the flange";

slicer::Toolpath shifted(slicer::Toolpath t, const slicer::Vec2& d) {
  for (auto& l : t.layers) {
    for (auto& s : l.strokes) {
      s.start_mm += d;
      for (auto& seg : s.segments) seg.end_mm += d, seg.center_mm += d;
    }
  }
  return t;
}

// "mesh = FILE: ..." from the mesh reader, as the substrate's key.
slicer::Mesh read_substrate_mesh(const std::string& path) {
  try {
    return slicer::read_mesh_file(path);
  } catch (const InputError& e) {
    const std::string m = e.what();
    throw InputError(m.rfind("mesh = ", 0) == 0 ? "substrate." + m
                                                : "substrate.mesh = " + path + ": " + m);
  }
}

// The mesh as the record names it: a mesh given by a relative path is named relative to the
// CSV's folder (a folder moved with its mesh still finds it), an absolute one as given.
std::string mesh_relative_to(const std::string& mesh, const std::string& csv) {
  namespace fs = std::filesystem;
  if (fs::path(mesh).is_absolute()) return mesh;
  std::error_code ec;
  const fs::path folder = fs::path(csv).parent_path();
  const fs::path from = fs::absolute(folder.empty() ? fs::path(".") : folder, ec);
  if (ec) return mesh;
  const fs::path to = fs::absolute(fs::path(mesh), ec);
  if (ec) return mesh;
  const fs::path rel = to.lexically_normal().lexically_relative(from.lexically_normal());
  return rel.empty() ? mesh : rel.generic_string();
}

std::vector<std::string> header_lines(const slicer::Toolpath& t, const slicer::SubstrateSpec& s,
                                      const slicer::MeshSubstrate& sub,
                                      const std::string& fingerprint,
                                      const machines::MachineProfile& m, double tol) {
  const slicer::MapDistortion& d = sub.distortion();
  std::vector<std::string> h;
  h.push_back("Strand " + t.generator + " on a robot-held mesh (curved substrate)");
  h.push_back("machine: " + m.name + " (" + machines::to_string(m.volume.kind) + ")");
  h.push_back("substrate: mesh " + s.mesh_path + ", " +
              std::to_string(sub.mesh().triangles.size()) + " triangles, fnv1a " + fingerprint +
              "; (u, v) from " + sub.uv_source() + ", 3D/uv area ratio " +
              fmt_fixed(d.area_ratio_min, 3) + " to " + fmt_fixed(d.area_ratio_max, 3) +
              ", conformal stretch up to " + fmt_fixed(d.stretch_max, 3));
  h.push_back(std::string("placement: ") + kPlacement);
  h.push_back(
      "orientation: the contact normal against the nozzle axis by the smallest tilt from "
      "the reference pose, then each pass's rotation about the nozzle axis");
  h.push_back("units: mm, s, deg");
  for (const auto& [k, v] : t.parameters.items())
    h.push_back("param " + k + " = " + slicer::value_text(v));
  h.push_back("param arc-tolerance = " + slicer::short_number(tol) +
              " (chord error on the surface)");
  for (const auto& [k, v] : t.derived.items()) {
    if (!v.is_string())
      h.push_back("derived " + k + " = " +
                  (v.is_number_float() ? fmt_fixed(v.get<double>(), 4) : slicer::value_text(v)));
  }
  return h;
}

}  // namespace

void require_mesh_machine(const machines::MachineProfile& m) {
  if (m.robot.enabled) return;
  throw InputError("machine = " + m.name + " (" + machines::to_string(m.volume.kind) +
                   "): substrate.type = mesh needs a robot-holds-substrate machine (the robot "
                   "holds the mesh under a fixed nozzle: kuka-iiwa14-wasp-cylinder, "
                   "ur10e-wasp-cylinder, abb-irb1200-wasp-cylinder)");
}

MeshJob plan_mesh_job(const slicer::Toolpath& t, const slicer::SubstrateSpec& s,
                      const machines::MachineProfile& m, double tol, const std::string& output) {
  require_mesh_machine(m);
  if (t.layers.empty()) throw InputError("the pattern has no layers to place on the mesh");
  const slicer::Mesh mesh = read_substrate_mesh(s.mesh_file());
  const std::string fingerprint = slicer::content_fingerprint(slicer::read_file(s.mesh_file()));
  const slicer::MeshSubstrate sub(mesh, s.mesh_path);
  MeshJob job;
  const auto [lo, hi] = slicer::bounds(t);
  const slicer::UvBox box = sub.domain();
  job.placed = shifted(t, (box.min_mm + box.max_mm) / 2.0 - (lo + hi) / 2.0);
  PosePlanOptions o;
  o.arc_tolerance_mm = tol;
  o.default_deposit_speed_mm_per_s = m.robot.v_cart_mm_per_s;
  o.travel_speed_mm_per_s = o.lift_speed_mm_per_s = m.robot.travel_speed_mm_per_s;
  o.lift_mm = m.robot.lift_mm;
  job.plan = plan_poses_on_mesh(job.placed, sub, m.robot, o);
  const slicer::PoseProgram& p = job.plan.program;

  job.report = pose_report(job.placed, s, m, p);
  nlohmann::json substrate = p.substrate;
  substrate["mesh"] = s.mesh_path;
  substrate["fnv1a"] = fingerprint;
  substrate["placement"] = kPlacement;
  job.report["substrate"] = substrate;
  for (auto& lap : job.report["laps"]) {  // a mesh has no turning axis: laps are passes
    for (const char* key : {"direction", "turn_min_deg", "turn_max_deg", "turn_range_deg"})
      lap.erase(key);
  }
  for (auto& layer : job.report["layers"]) layer.erase("u_stretch");
  const auto& cone = m.robot.nozzle_cone;
  job.report["mesh_plan"] = {
      {"passes", p.laps.size()},
      {"restarts", job.plan.restarts},
      {"first_rotation_deg", job.plan.first_rotation_deg},
      {"rotation_about_nozzle_deg",
       {round_to(job.plan.rotation_min_deg, 2), round_to(job.plan.rotation_max_deg, 2)}},
      {"max_tilt_deg", round_to(job.plan.max_tilt_deg, 2)},
      {"offset_surface",
       {{"worst_deposit_mm", round_to(job.plan.worst_offset_mm, 4)},
        {"worst_deposit_row", job.plan.worst_offset_row},
        {"max_raise_mm", round_to(job.plan.max_raise_mm, 4)},
        {"rule",
         "layer k's contact points (k + 1) h from the faceted mesh, raised along the "
         "interpolated vertex normal at their foot where the mesh is concave; every row's "
         "normal the interpolated vertex normal where the line along it meets the mesh"}}},
      {"nozzle_cone",
       {{"half_angle_deg", cone.half_angle_deg},
        {"length_mm", cone.length_mm},
        {"tip_radius_mm", cone.tip_radius_mm}}},
      {"rule",
       "the contact point at the nozzle tip, the contact normal against the nozzle axis by the "
       "smallest tilt from the reference pose (the mesh's facing against the nozzle, the flange "
       "axis along robot.substrate_axis), then the pass's rotation about the nozzle axis; a pass "
       "restarts turned about the nozzle axis where the arm's joint range or reach ends"}};
  job.header = header_lines(job.placed, s, sub, fingerprint, m, tol);

  slicer::MeshSubstrateRecord record;
  record.mesh = mesh_relative_to(s.mesh_path, output);
  record.fingerprint = fingerprint;
  record.machine = m.name;
  for (const auto& l : p.layers) record.layer_offsets_mm.push_back(l.offset_mm);
  record.cone = cone;
  job.record_file = {slicer::mesh_record_path(output),
                     slicer::dump_json(slicer::to_json(record)) + "\n"};
  return job;
}

std::string mesh_job_summary(const nlohmann::json& r) {
  std::ostringstream o;
  const auto& tot = r.at("totals");
  const auto& sub = r.at("substrate");
  const auto& plan = r.at("mesh_plan");
  o << r.at("generator").get<std::string>() << " on a robot-held mesh -> "
    << r.at("outputs").at("main").get<std::string>() << " ("
    << r.at("machine").at("name").get<std::string>() << ")\n";
  const auto& size = sub.at("size_mm");
  o << "  substrate      mesh " << sub.at("mesh").get<std::string>() << ": "
    << sub.at("triangles").get<std::size_t>() << " triangles, "
    << fmt_fixed(size[0].get<double>(), 1) << " x " << fmt_fixed(size[1].get<double>(), 1) << " x "
    << fmt_fixed(size[2].get<double>(), 1) << " mm\n";
  o << "  map            " << sub.at("uv_source").get<std::string>() << ", 3D/uv area ratio "
    << fmt_fixed(sub.at("area_ratio_3d_to_uv")[0].get<double>(), 3) << " to "
    << fmt_fixed(sub.at("area_ratio_3d_to_uv")[1].get<double>(), 3) << ", conformal stretch up to "
    << fmt_fixed(sub.at("conformal_stretch_max").get<double>(), 3) << "\n";
  std::vector<int> per_layer;
  for (const auto& l : r.at("layers")) per_layer.push_back(l.at("laps").get<int>());
  std::string counts;
  const bool same = std::all_of(per_layer.begin(), per_layer.end(),
                                [&](int c) { return c == per_layer.front(); });
  for (std::size_t i = 0; i < per_layer.size(); ++i) {
    if (same && i > 0) break;
    counts += (i ? "/" : "") + std::to_string(per_layer[i]);
  }
  o << "  passes         " << tot.at("laps").get<int>() << " in " << tot.at("layers").get<int>()
    << " layers, " << counts << " per layer, " << plan.at("restarts").get<int>()
    << " restarted for the arm's range\n";
  const double lo = plan.at("rotation_about_nozzle_deg")[0].get<double>();
  const double hi = plan.at("rotation_about_nozzle_deg")[1].get<double>();
  o << "  orientation    normals up to " << fmt_fixed(plan.at("max_tilt_deg").get<double>(), 1)
    << " deg from the mesh's facing, turned " << fmt_fixed(lo, 1)
    << (hi - lo >= 0.05 ? ".." + fmt_fixed(hi, 1) : std::string())
    << " deg about the nozzle axis\n";
  const auto& surface = plan.at("offset_surface");
  o << "  offsets        deposits within "
    << fmt_fixed(surface.at("worst_deposit_mm").get<double>(), 4)
    << " mm of their layer's offset surface (worst: row "
    << surface.at("worst_deposit_row").get<std::size_t>() << "), raised up to "
    << fmt_fixed(surface.at("max_raise_mm").get<double>(), 3)
    << " mm along the normal over concave facets\n";
  o << "  deposited      " << fmt_fixed(tot.at("deposit_length_mm").get<double>() / 1000.0, 3)
    << " m on the surface, " << tot.at("poses").get<int>() << " poses\n";
  o << "  time           " << clock_text(tot.at("time_s").get<double>()) << "\n";
  if (r.contains("ink"))
    o << "  ink            " << r.at("ink").at("text").get<std::string>() << "\n";
  if (r.contains("programs"))
    o << "  programs       " << r.at("programs").at("text").get<std::string>() << "\n";
  if (r.contains("robot"))
    o << "  joints         " << r.at("robot").at("text").get<std::string>() << "\n";
  if (r.contains("warnings"))
    for (const auto& w : r.at("warnings")) o << "  warning        " << w.get<std::string>() << "\n";
  return o.str();
}

}  // namespace strand::post
