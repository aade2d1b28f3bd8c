// The row rule on a robot-held mesh: rows placed from their foot and raised off concave
// facets, read back along their normal, judged with the lines `strand check` prints.
#include "slicer/mesh_row_rule.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "slicer/units.h"

namespace strand::slicer {

namespace {

// A row is raised until it is this close to its offset from the mesh, mm (far inside
// kMeshSurfaceMm), in at most kRaiseSteps steps (each closes most of the gap: the distance to
// the mesh grows at nearly the rate the row rises).
constexpr double kRaiseToleranceMm = 1e-5;
constexpr int kRaiseSteps = 40;

std::string fixed(double v, int decimals) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, v == 0.0 ? 0.0 : v);
  return text;
}

}  // namespace

SurfaceFrame mesh_row_frame(const MeshSubstrate& s, const Vec2& uv, double offset_mm) {
  SurfaceFrame f = s.frame_at(uv, 0.0);
  const Vec3 foot = f.point_mm;
  double t = offset_mm;
  if (offset_mm > 0.0) {
    for (int i = 0; i < kRaiseSteps; ++i) {
      const double short_by = offset_mm - s.distance_mm(foot + t * f.normal);
      if (short_by <= kRaiseToleranceMm) break;
      t += short_by;
    }
  }
  f.point_mm = foot + t * f.normal;
  return f;
}

MeshRowReading read_mesh_row(const MeshSubstrate& s, const Vec3& p, const Vec3& n) {
  MeshRowReading r;
  r.clearance_mm = s.distance_mm(p);
  const auto foot = s.foot_along(p, n.normalized());
  if (!foot) return r;
  r.over_mesh = true;
  r.uv_mm = foot->uv_mm;
  r.along_mm = foot->offset_mm;
  const double cosine = std::clamp(n.normalized().dot(foot->normal), -1.0, 1.0);
  r.normal_off_deg = rad_to_deg(std::acos(cosine));
  return r;
}

MeshRowJudgement judge_mesh_rows(const std::vector<PosePoint>& rows,
                                 const std::vector<MeshRowReading>& at,
                                 const std::vector<double>& offsets) {
  MeshRowJudgement j;
  if (offsets.empty()) return j;
  const auto offset_of = [&](int layer) {
    return offsets[static_cast<std::size_t>(std::clamp(layer, 0, int(offsets.size()) - 1))];
  };
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const PosePoint& p = rows[i];
    const MeshRowReading& a = at[i];
    const int k = std::max(0, p.layer);
    const double o_k = offset_of(k);
    const std::string layer = "layer " + std::to_string(k) + "'s offset surface";
    if (!a.over_mesh) {
      j.off_surface.push_back({i, std::string(p.extrude ? "deposit" : "travel") +
                                      " beside the mesh (the line along its normal misses it)"});
      continue;
    }
    if (a.normal_off_deg > kMeshNormalDeg) {
      j.normals.push_back({i, "normal " + fixed(a.normal_off_deg, 3) +
                                  " deg off the mesh's normal at its foot (its vertex normals "
                                  "interpolated where the line along it meets the mesh)"});
    }
    if (p.extrude) {
      const double off = std::abs(a.clearance_mm - o_k);
      if (off > j.worst_deposit_mm) j.worst_deposit_mm = off, j.worst_deposit_row = i;
      if (off > kMeshSurfaceMm) {
        j.off_surface.push_back({i, "contact " + fixed(off, 4) + " mm off " + layer + " (" +
                                        fixed(o_k, 3) + " mm from the mesh; it is " +
                                        fixed(a.clearance_mm, 4) + " mm from it, " +
                                        fixed(a.along_mm, 4) + " mm along its normal)"});
      }
      if (i > 0 && !rows[i - 1].extrude && at[i - 1].over_mesh &&
          std::abs(at[i - 1].clearance_mm - o_k) > kMeshSurfaceMm) {
        j.off_surface.push_back({i, "deposit starts " +
                                        fixed(std::abs(at[i - 1].clearance_mm - o_k), 4) +
                                        " mm off " + layer + " (a travel marked as depositing?)"});
      }
    } else if (a.clearance_mm < o_k - kMeshSurfaceMm || a.along_mm < o_k - kMeshSurfaceMm) {
      j.off_surface.push_back({i, "travel " + fixed(a.clearance_mm, 4) + " mm from the mesh (" +
                                      fixed(a.along_mm, 4) + " mm along its normal), under " +
                                      layer + " (" + fixed(o_k, 3) + " mm)"});
    }
  }
  return j;
}

}  // namespace strand::slicer
