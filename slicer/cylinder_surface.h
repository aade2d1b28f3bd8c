// The analytic cylinder substrate: pattern x -> u around the circumference (arc length),
// pattern y -> v along the axis, exact normals. Its workpiece frame has its origin at the
// centre of the mounted end face, +z along the axis towards the free end (v in [0, length]),
// u = 0 on the +x side; (u, v, normal) is right-handed, so a pattern seen from outside is
// not mirrored (a chiral lattice keeps its handedness).
#pragma once

#include "slicer/surface.h"

namespace strand::slicer {

// Where the arc length u around the cylinder is measured.
enum class ArcLengthAt {
  Surface,     // at the substrate radius: the flat pattern's u lands unchanged on the substrate
  Deposition,  // at each layer's bead centre, so the pattern's pitch holds on outer layers
};
std::string to_string(ArcLengthAt a);

struct CylinderSpec {
  double radius_mm = 10.0;
  double length_mm = 10.0;
  ArcLengthAt arc_length_at = ArcLengthAt::Surface;
  // Deposition: the bead centre lies this far inside the nozzle tip (half a layer height), mm.
  double bead_inset_mm = 0.0;
  // Deposition with a lattice that must close around the cylinder: u is measured at the
  // first layer's bead centre on every layer (the cells keep their angle), mm of offset of
  // that first nozzle tip; 0 = measure each layer at its own radius.
  double fixed_measure_offset_mm = 0.0;

  bool operator==(const CylinderSpec&) const = default;
};

class CylinderSurface : public Surface {
 public:
  // Precondition: radius_mm > 0 and length_mm > 0 (checked by the substrate parameters).
  explicit CylinderSurface(const CylinderSpec& spec);

  SurfaceFrame frame_at(const Vec2& uv_mm, double offset_mm) const override;
  UvBox domain() const override;
  std::optional<double> u_period_mm(double offset_mm) const override;
  bool in_domain(const Vec2& uv_mm) const override;
  std::string kind() const override { return "cylinder"; }
  nlohmann::json describe() const override;
  TriangleMesh preview_mesh(double tolerance_mm) const override;

  const CylinderSpec& spec() const { return spec_; }
  // Radius at which u is measured for a nozzle tip at `offset_mm`, mm.
  double u_radius_mm(double offset_mm) const;
  // Angle (rad) of pattern coordinate u for a nozzle tip at `offset_mm`; unwrapped.
  double angle_rad(double u_mm, double offset_mm) const;
  // Length on the surface raised by `offset_mm` per mm of u: (radius + offset) / u radius.
  double u_stretch(double offset_mm) const;
  // The frame at angle `turn_rad` around the axis, `v_mm` along it, `offset_mm` above the
  // substrate (travels keep their angle while the nozzle backs off).
  SurfaceFrame frame_at_turn(double turn_rad, double v_mm, double offset_mm) const;

 private:
  CylinderSpec spec_;
};

}  // namespace strand::slicer
