// Placement of a pattern on the cylinder and the fit checks.
#include "postprocess/plan/cylinder_placement.h"

#include <algorithm>
#include <cmath>

#include "slicer/input_error.h"
#include "slicer/params.h"
#include "slicer/units.h"

namespace strand::post {

namespace {

double bead_width(const slicer::Toolpath& t) {
  double w = 0.0;
  for (const auto& l : t.layers) {
    for (const auto& s : l.strokes) w = std::max(w, s.width_mm);
  }
  return w;
}

slicer::Toolpath shifted(slicer::Toolpath t, const slicer::Vec2& d) {
  for (auto& l : t.layers) {
    for (auto& s : l.strokes) {
      s.start_mm += d;
      for (auto& seg : s.segments) seg.end_mm += d, seg.center_mm += d;
    }
  }
  return t;
}

std::string mm(double v) { return slicer::short_number(std::round(v * 1000.0) / 1000.0); }

}  // namespace

std::string placement_text(const slicer::SubstrateSpec& s) {
  return s.wrap == slicer::Wrap::Patch ? "pattern x -> u around the cylinder, centred on u = 0 "
                                         "(the line facing the nozzle at turn 0); "
                                         "y -> v along the axis, centred at mid-length"
                                       : "pattern x -> u around the cylinder, one period = one "
                                         "circumference, x = 0 at u = 0; "
                                         "y -> v along the axis, centred at mid-length";
}

slicer::Toolpath place_on_cylinder(const slicer::Toolpath& t, const slicer::SubstrateSpec& s,
                                   const slicer::CylinderSurface& c) {
  if (t.layers.empty()) throw InputError("the pattern has no layers to place on the cylinder");
  const auto [lo, hi] = slicer::bounds(t);
  const double bead = bead_width(t);
  std::vector<std::string> problems;
  const double depth = hi.y() - lo.y() + bead;
  if (depth > s.length_mm + 1e-9) {
    problems.push_back("substrate.length = " + slicer::short_number(s.length_mm) +
                       ": must be >= the pattern's " + mm(depth) +
                       " along the axis, bead included (mm)");
  }
  if (s.wrap == slicer::Wrap::Patch) {
    const double period = *c.u_period_mm(t.layers.front().z_mm);
    const double around = hi.x() - lo.x() + bead;
    if (around > period + 1e-9) {
      const double r_min = around / slicer::kTwoPi + (period / slicer::kTwoPi - s.radius_mm);
      problems.push_back("substrate.wrap = patch: the pattern is " + mm(around) +
                         " around, bead included, more than the circumference " + mm(period) +
                         " where u is measured; use --wrap full or a radius >= " +
                         mm(std::ceil(r_min * 100.0) / 100.0) + " (mm)");
    }
  }
  if (!problems.empty()) throw InputError(problems);
  const double dx = s.wrap == slicer::Wrap::Patch ? -(lo.x() + hi.x()) / 2.0 : 0.0;
  return shifted(t, slicer::Vec2(dx, s.length_mm / 2.0 - (lo.y() + hi.y()) / 2.0));
}

}  // namespace strand::post
