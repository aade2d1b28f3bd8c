// Paths grouped by layer, feature and travel; the cylinder mesh turned into the viewing frame.
#include "cli/curved_preview.h"

#include "slicer/cylinder_surface.h"

namespace strand::cli {

post::PreviewScene curved_scene(const post::CurvedPart& part, double tolerance_mm) {
  std::vector<post::PreviewPath> paths;
  const auto& s = part.samples;
  for (std::size_t i = 1; i < s.size(); ++i) {
    const bool travel = !s[i].extrude;
    post::PreviewPath* last = paths.empty() ? nullptr : &paths.back();
    const bool joins = last && last->layer == s[i].layer && last->travel == travel &&
                       (travel || last->feature == s[i].feature) &&
                       last->points_mm.back() == post::viewing_frame(s[i - 1].p_mm);
    if (!joins)
      paths.push_back({s[i].layer, s[i].feature, travel, {post::viewing_frame(s[i - 1].p_mm)}});
    paths.back().points_mm.push_back(post::viewing_frame(s[i].p_mm));
  }
  slicer::TriangleMesh mesh;
  if (part.radius_mm > 0 && part.length_mm > 0) {
    mesh = slicer::CylinderSurface({part.radius_mm, part.length_mm}).preview_mesh(tolerance_mm);
    for (auto& v : mesh.vertices_mm) v = post::viewing_frame(v);
  }
  return post::scene_from_paths(std::move(paths), part.layer_offsets_mm, std::move(mesh),
                                part.bead_width_mm);
}

}  // namespace strand::cli
