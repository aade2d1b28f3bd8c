// Build-volume containment with a reason naming the failing dimension.
#include "machines/kinematics.h"

#include <cmath>

#include "slicer/params.h"
#include "slicer/tolerances.h"

namespace strand::machines {

namespace {

std::string mm(double v) {
  return slicer::short_number(std::round(v * 1000.0) / 1000.0) + " mm";
}

}  // namespace

std::optional<std::string> outside_reason(const BuildVolume& v, const Vec3& p) {
  const double s = slicer::kBoundsSlackMm;
  if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p.z())) {
    return "a coordinate is not a finite number";
  }
  if (v.kind == KinematicsKind::Delta) {
    const double r = std::hypot(p.x(), p.y());
    if (r > v.radius_mm + s) return "radius " + mm(r) + " > build radius " + mm(v.radius_mm);
    if (p.z() < -s) return "z " + mm(p.z()) + " < 0 mm";
    if (p.z() > v.height_mm + s) return "z " + mm(p.z()) + " > build height " + mm(v.height_mm);
    return std::nullopt;
  }
  const char* axis[3] = {"x", "y", "z"};
  for (int i = 0; i < 3; ++i) {
    if (p[i] < v.min_mm[i] - s) return std::string(axis[i]) + " " + mm(p[i]) + " < " + mm(v.min_mm[i]);
    if (p[i] > v.max_mm[i] + s) return std::string(axis[i]) + " " + mm(p[i]) + " > " + mm(v.max_mm[i]);
  }
  return std::nullopt;
}

}  // namespace strand::machines
