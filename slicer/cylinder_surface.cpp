// Cylinder frames, period and preview mesh in closed form.
#include "slicer/cylinder_surface.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "slicer/units.h"

namespace strand::slicer {

namespace {

// Slack on the axial domain so points exactly on an end face (rounding) still map, mm.
constexpr double kDomainSlackMm = 1e-6;
// Facets around the preview cylinder: enough for a smooth silhouette, bounded for memory.
constexpr int kMinPreviewFacets = 24;
constexpr int kMaxPreviewFacets = 2048;

}  // namespace

std::string to_string(ArcLengthAt a) {
  return a == ArcLengthAt::Surface ? "surface" : "deposition";
}

CylinderSurface::CylinderSurface(const CylinderSpec& spec) : spec_(spec) {
  assert(spec.radius_mm > 0 && spec.length_mm > 0);
}

double CylinderSurface::u_radius_mm(double offset_mm) const {
  if (spec_.arc_length_at == ArcLengthAt::Surface) return spec_.radius_mm;
  const double measured_at =
      spec_.fixed_measure_offset_mm > 0 ? spec_.fixed_measure_offset_mm : offset_mm;
  return std::max(spec_.radius_mm + measured_at - spec_.bead_inset_mm, spec_.radius_mm);
}

double CylinderSurface::angle_rad(double u_mm, double offset_mm) const {
  return u_mm / u_radius_mm(offset_mm);
}

double CylinderSurface::u_stretch(double offset_mm) const {
  return (spec_.radius_mm + offset_mm) / u_radius_mm(offset_mm);
}

SurfaceFrame CylinderSurface::frame_at(const Vec2& uv, double offset_mm) const {
  return frame_at_turn(angle_rad(uv.x(), offset_mm), uv.y(), offset_mm);
}

SurfaceFrame CylinderSurface::frame_at_turn(double turn_rad, double v_mm, double offset_mm) const {
  const double c = std::cos(turn_rad), s = std::sin(turn_rad);
  const double r = spec_.radius_mm + offset_mm;
  SurfaceFrame f;
  f.normal = Vec3(c, s, 0.0);
  f.point_mm = Vec3(r * c, r * s, v_mm);
  f.d_du = u_stretch(offset_mm) * Vec3(-s, c, 0.0);
  f.d_dv = Vec3::UnitZ();
  return f;
}

UvBox CylinderSurface::domain() const {
  const double half = kPi * spec_.radius_mm;
  return {Vec2(-half, 0.0), Vec2(half, spec_.length_mm)};
}

std::optional<double> CylinderSurface::u_period_mm(double offset_mm) const {
  return kTwoPi * u_radius_mm(offset_mm);
}

bool CylinderSurface::in_domain(const Vec2& uv) const {
  return std::isfinite(uv.x()) && uv.y() >= -kDomainSlackMm &&
         uv.y() <= spec_.length_mm + kDomainSlackMm;
}

nlohmann::json CylinderSurface::describe() const {
  nlohmann::json j = {{"type", "cylinder"},
                      {"radius_mm", spec_.radius_mm},
                      {"length_mm", spec_.length_mm},
                      {"arc_length_at", to_string(spec_.arc_length_at)},
                      {"circumference_mm", kTwoPi * spec_.radius_mm}};
  return j;
}

TriangleMesh CylinderSurface::preview_mesh(double tolerance_mm) const {
  // Sagitta r (1 - cos(pi / n)) <= tolerance.
  const double r = spec_.radius_mm;
  const double tol = std::clamp(tolerance_mm, 1e-6, r);
  const double step = 2.0 * std::acos(1.0 - tol / r);
  const int n =
      std::clamp(static_cast<int>(std::ceil(kTwoPi / step)), kMinPreviewFacets, kMaxPreviewFacets);
  TriangleMesh m;
  for (int end = 0; end < 2; ++end) {
    for (int i = 0; i < n; ++i) {
      const double a = kTwoPi * i / n;
      m.vertices_mm.emplace_back(r * std::cos(a), r * std::sin(a), end * spec_.length_mm);
    }
  }
  const int c0 = static_cast<int>(m.vertices_mm.size());
  m.vertices_mm.emplace_back(0.0, 0.0, 0.0);
  m.vertices_mm.emplace_back(0.0, 0.0, spec_.length_mm);
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    m.triangles.push_back({i, j, n + j});  // side, outward normals
    m.triangles.push_back({i, n + j, n + i});
    m.triangles.push_back({c0, j, i});              // mounted end face, normal -z
    m.triangles.push_back({c0 + 1, n + i, n + j});  // free end face, normal +z
  }
  return m;
}

}  // namespace strand::slicer
