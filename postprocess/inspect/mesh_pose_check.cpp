// Pose CSVs on a mesh: contact points mapped back onto the mesh, offsets and normals against
// it, strands and crossings in its (u, v), and the cell's checks shared with cylinders.
#include "postprocess/inspect/mesh_pose_check.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "machines/gcode_format.h"
#include "machines/pose_csv.h"
#include "postprocess/inspect/cylinder_contacts.h"
#include "slicer/file_io.h"
#include "slicer/input_error.h"
#include "slicer/json_input.h"
#include "slicer/mesh_io.h"
#include "slicer/tolerances.h"
#include "slicer/units.h"

namespace strand::post {

using machines::fmt_fixed;

namespace {

// Strands are laid out in (u + kShiftMm, v) on a "cylinder" this long around: no seam is met.
constexpr double kShiftMm = 1e6;
constexpr double kPeriodMm = 1e7;

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

}  // namespace

std::optional<CsvMesh> find_csv_mesh(const std::string& csv_file, const std::string& given) {
  CsvMesh m;
  const std::string record = slicer::mesh_record_path(csv_file);
  std::error_code ec;
  if (std::filesystem::is_regular_file(record, ec)) {
    m.record_path = record;
    m.record = slicer::mesh_record_from_json(
        slicer::parse_json(slicer::read_file(record), "input = " + record), record);
  }
  if (!given.empty()) {
    m.mesh_path = given;
  } else if (m.record) {
    m.mesh_path = slicer::mesh_path_from_record(*m.record, csv_file);
  } else {
    return std::nullopt;
  }
  return m;
}

std::unique_ptr<slicer::MeshSubstrate> load_csv_mesh(const CsvMesh& m) {
  slicer::Mesh mesh;
  try {
    mesh = slicer::read_mesh_file(m.mesh_path);
  } catch (const InputError& e) {
    const std::string what = e.what();
    throw InputError(what.rfind("mesh = ", 0) == 0
                         ? "substrate." + what
                         : "substrate.mesh = " + m.mesh_path + ": " + what);
  }
  return std::make_unique<slicer::MeshSubstrate>(mesh, m.mesh_path);
}

PoseCheckReport check_mesh_pose_csv(std::string_view text, const std::string& file,
                                    const machines::MachineProfile& m, const CsvMesh& cm) {
  if (!m.robot.enabled) {
    throw InputError("machine = " + m.name +
                     ": a pose CSV is checked against a robot-holds-substrate machine (e.g. "
                     "kuka-iiwa14-wasp-cylinder)");
  }
  const std::vector<slicer::PosePoint> rows = machines::read_pose_csv(text, file);
  if (rows.empty()) {
    throw InputError("input = " + file +
                     ": no poses (a pose CSV has one row per pose after its header)");
  }
  const std::unique_ptr<slicer::MeshSubstrate> mesh = load_csv_mesh(cm);
  PoseCheckReport r;
  r.kind = "pose CSV on a mesh";
  r.on_mesh = true;
  r.machine = m.name;
  r.rows = rows.size();
  const std::string fingerprint = slicer::content_fingerprint(slicer::read_file(cm.mesh_path));
  r.substrate_note = "substrate: mesh " + cm.mesh_path + " (fnv1a " + fingerprint +
                     (cm.record ? ", record " + cm.record_path : std::string(", no record")) + ")";
  if (cm.record && cm.record->fingerprint != fingerprint) {
    r.parse.add(0, "the mesh " + cm.mesh_path +
                       " is not the one the program was planned on (fnv1a " + fingerprint + ", " +
                       cm.record_path + " says " + cm.record->fingerprint + ")");
  }
  check_pose_rows(rows, m.robot, r);
  check_pose_numbering(text, rows, false, r);

  std::vector<slicer::MeshRowReading> at;
  at.reserve(rows.size());
  int layers = 0;
  for (const auto& p : rows) {
    at.push_back(slicer::read_mesh_row(*mesh, p.contact_mm, p.normal));
    layers = std::max(layers, p.layer + 1);
  }
  // Each layer's offset: the record's, else the deposits' median distance to the mesh.
  std::vector<double> offsets(static_cast<std::size_t>(layers), 0.0);
  for (int k = 0; k < layers; ++k) {
    const std::size_t ku = static_cast<std::size_t>(k);
    if (cm.record && ku < cm.record->layer_offsets_mm.size()) {
      offsets[ku] = cm.record->layer_offsets_mm[ku];
      continue;
    }
    std::vector<double> v;
    for (std::size_t i = 0; i < rows.size(); ++i)
      if (rows[i].layer == k && rows[i].extrude) v.push_back(at[i].clearance_mm);
    offsets[ku] = median(v);
  }
  const slicer::MeshRowJudgement judged = slicer::judge_mesh_rows(rows, at, offsets);
  for (const auto& f : judged.normals) r.normals.add(f.row, f.what);
  for (const auto& f : judged.off_surface) r.off_surface.add(f.row, f.what);
  // Strands and contacts per layer in (u, v).
  std::vector<CylinderLayer> strand_layers;
  for (std::size_t b = 0; b < rows.size();) {
    std::size_t e = b;
    while (e + 1 < rows.size() && rows[e + 1].layer == rows[b].layer) ++e;
    std::vector<double> deposit_offsets;
    PoseLayerCheck lc{rows[b].layer, 0.0};
    CylinderLayer cl{rows[b].layer, kPeriodMm, {}};
    for (std::size_t i = b; i <= e; ++i) {
      if (!rows[i].extrude) continue;
      deposit_offsets.push_back(at[i].clearance_mm);
      if (i == 0) continue;
      const std::size_t from = i - 1;
      if (cl.strands.empty() || i == b || !rows[from].extrude) {
        cl.strands.push_back(
            {{slicer::Vec2(at[from].uv_mm.x() + kShiftMm, at[from].uv_mm.y()), from}});
        ++lc.strands;
      }
      cl.strands.back().push_back({slicer::Vec2(at[i].uv_mm.x() + kShiftMm, at[i].uv_mm.y()), i});
    }
    lc.radius_mm = median(deposit_offsets);
    r.layers.push_back(lc);
    strand_layers.push_back(std::move(cl));
    b = e + 1;
  }
  const ContactReport contacts = find_cylinder_contacts(strand_layers, slicer::kGcodeResolutionMm);
  for (auto& l : r.layers) {
    for (auto c : contacts.crossings) {
      c.at_mm.x() -= kShiftMm;
      if (c.layer == l.layer) l.crossings.push_back(c);
    }
    for (auto c : contacts.touches) {
      c.at_mm.x() -= kShiftMm;
      if (c.layer == l.layer) l.touches.push_back(c);
    }
  }
  r.joints = machines::analyse_joints(machines::arm_model(m.robot), m.robot, rows, true);
  r.joints_checked = true;
  // The start and end as the writers move (robot_transit.h), the mesh with every layer on it
  // on the way home.
  if (r.joints.ok()) {
    check_pose_transit(rows, m.robot,
                       machines::mesh_workpiece(slicer::read_mesh_file(cm.mesh_path),
                                                offsets.empty() ? 0.0 : offsets.back()),
                       r);
  }
  r.program_speeds = check_program_speeds(rows, file, m);
  return r;
}

}  // namespace strand::post
