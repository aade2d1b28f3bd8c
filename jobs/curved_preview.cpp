// Paths grouped by layer, feature and travel; the cylinder (or the mesh) turned into the
// viewing frame.
#include "jobs/curved_preview.h"

#include <functional>

#include "postprocess/inspect/mesh_pose_check.h"
#include "slicer/cylinder_surface.h"

namespace strand::jobs {

namespace {

std::vector<post::PreviewPath> paths_of(
    const post::CurvedPart& part, const std::function<slicer::Vec3(const slicer::Vec3&)>& view) {
  std::vector<post::PreviewPath> paths;
  const auto& s = part.samples;
  for (std::size_t i = 1; i < s.size(); ++i) {
    const bool travel = !s[i].extrude;
    post::PreviewPath* last = paths.empty() ? nullptr : &paths.back();
    const bool joins = last && last->layer == s[i].layer && last->travel == travel &&
                       (travel || last->feature == s[i].feature) &&
                       last->points_mm.back() == view(s[i - 1].p_mm);
    if (!joins) paths.push_back({s[i].layer, s[i].feature, travel, {view(s[i - 1].p_mm)}});
    paths.back().points_mm.push_back(view(s[i].p_mm));
  }
  return paths;
}

}  // namespace

post::PreviewScene curved_scene(const post::CurvedPart& part, double tolerance_mm) {
  std::vector<post::PreviewPath> paths =
      paths_of(part, [](const slicer::Vec3& p) { return post::viewing_frame(p); });
  slicer::TriangleMesh mesh;
  if (part.radius_mm > 0 && part.length_mm > 0) {
    mesh = slicer::CylinderSurface({part.radius_mm, part.length_mm}).preview_mesh(tolerance_mm);
    for (auto& v : mesh.vertices_mm) v = post::viewing_frame(v);
  }
  return post::scene_from_paths(std::move(paths), part.layer_offsets_mm, std::move(mesh),
                                part.bead_width_mm);
}

post::PreviewScene mesh_scene(const post::CurvedPart& part, const slicer::MeshSubstrate& mesh,
                              const std::vector<double>& layer_offsets_mm) {
  const Eigen::Matrix3d q = mesh.map_rotation();
  std::vector<post::PreviewPath> paths =
      paths_of(part, [&](const slicer::Vec3& p) { return slicer::Vec3(q * p); });
  slicer::TriangleMesh triangles = mesh.preview_mesh(0.0);
  for (auto& v : triangles.vertices_mm) v = q * v;
  std::vector<double> offsets = layer_offsets_mm;
  std::size_t layers = 0;
  for (const auto& s : part.samples)
    if (s.layer >= 0) layers = std::max(layers, static_cast<std::size_t>(s.layer) + 1);
  if (offsets.size() < layers) offsets.resize(layers, offsets.empty() ? 0.0 : offsets.back());
  // The bead drawn as wide as the layers are apart (as a CSV on a cylinder).
  const double bead = offsets.size() >= 2 ? offsets[1] - offsets[0]
                      : offsets.empty()   ? 0.0
                                          : offsets[0];
  return post::scene_from_paths(std::move(paths), offsets, std::move(triangles), bead);
}

post::PreviewScene curved_file_scene(const std::string& file, std::string_view text,
                                     double tolerance_mm) {
  const post::CurvedPart part = post::read_curved_part(text, file);
  if (file.size() > 4 && file.ends_with(".csv")) {
    if (const auto m = post::find_csv_mesh(file, "")) {
      const auto mesh = post::load_csv_mesh(*m);
      return mesh_scene(part, *mesh,
                        m->record ? m->record->layer_offsets_mm : std::vector<double>{});
    }
  }
  return curved_scene(part, tolerance_mm);
}

}  // namespace strand::jobs
