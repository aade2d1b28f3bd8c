// The placement record of a slice and the mesh read back by it.
#include "jobs/slice_placement.h"

#include <cmath>
#include <filesystem>

#include "slicer/input_error.h"
#include "slicer/mesh_decimate.h"
#include "slicer/mesh_io.h"
#include "slicer/params.h"

namespace strand::jobs {

using nlohmann::json;

namespace {

// 12 decimals: exact for what placements hold (degrees' sines, unit factors, shifts in mm)
// without printing 6.1e-17 for a cosine of 90 degrees.
double rounded(double v) {
  const double r = std::round(v * 1e12) / 1e12;
  return r == 0.0 ? 0.0 : r;  // no -0
}

Eigen::Affine3d matrix_from(const json& m) {
  const auto bad = [] { return InputError("mesh_placement.file_to_machine: must be 4 rows of 4 numbers"); };
  if (!m.is_array() || m.size() != 4) throw bad();
  Eigen::Matrix4d out;
  for (int i = 0; i < 4; ++i) {
    if (!m[i].is_array() || m[i].size() != 4) throw bad();
    for (int j = 0; j < 4; ++j) {
      if (!m[i][j].is_number() || !std::isfinite(m[i][j].get<double>())) throw bad();
      out(i, j) = m[i][j].get<double>();
    }
  }
  Eigen::Affine3d a;
  a.matrix() = out;
  return a;
}

}  // namespace

json mesh_placement_json(const std::string& role, const std::vector<std::string>& files,
                         const Eigen::Affine3d& to_part_frame, const machines::MachineProfile& machine) {
  const slicer::Vec2 c = machine.volume.part_center_mm;
  const Eigen::Matrix4d m = (Eigen::Translation3d(c.x(), c.y(), 0.0) * to_part_frame).matrix();
  json rows = json::array();
  for (int i = 0; i < 4; ++i) rows.push_back({rounded(m(i, 0)), rounded(m(i, 1)), rounded(m(i, 2)), rounded(m(i, 3))});
  return {{"role", role}, {"files", files}, {"file_to_machine", rows}};
}

std::vector<std::string> slice_inputs(const SliceSettings& s) {
  std::vector<std::string> out;
  if (!s.part.empty()) out.push_back(s.part_name.empty() ? s.part : s.part_name);
  for (const SlicePart& p : s.parts) out.push_back(p.path);
  return out;
}

PlacedMesh placed_mesh_from(const json& placement, const std::string& folder, std::size_t max_triangles) {
  if (!placement.is_object() || !placement.contains("files") || !placement["files"].is_array() ||
      placement["files"].empty()) {
    throw InputError("mesh_placement.files: must list the mesh files the slice read");
  }
  const Eigen::Affine3d to_machine = matrix_from(placement.value("file_to_machine", json()));
  std::vector<slicer::Mesh> meshes;
  PlacedMesh out;
  for (const json& f : placement["files"]) {
    if (!f.is_string()) throw InputError("mesh_placement.files: must be file names");
    std::string path = f.get<std::string>();
    if (!folder.empty()) {
      const std::string name = std::filesystem::path(path).filename().string();
      if (name.empty() || name == "." || name == "..")
        throw InputError("mesh_placement.files: " + path.substr(0, 200) + ": not a file name");
      path = (std::filesystem::path(folder) / name).string();
    }
    meshes.push_back(slicer::read_mesh_file(path));
    out.triangles += meshes.back().triangles.size();
  }
  slicer::Mesh all = slicer::merge_meshes(meshes);
  meshes.clear();
  for (slicer::Vec3& v : all.vertices_mm) v = to_machine * v;
  if (out.triangles > max_triangles) {  // drawn coarse: its index would outgrow the paths' blocks
    slicer::Decimated d = slicer::decimate_for_drawing(all, max_triangles);
    all = std::move(d.mesh);
    out.note = "the " + placement.value("role", std::string("part")) + " mesh (" + std::to_string(out.triangles) +
               " triangles) is drawn simplified to " + std::to_string(all.triangles.size()) + " (" +
               slicer::short_number(std::round(d.cell_mm * 1000) / 1000) + " mm cells)";
  }
  out.mesh.triangles = std::move(all.triangles);
  out.mesh.vertices_mm = std::move(all.vertices_mm);
  return out;
}

}  // namespace strand::jobs
