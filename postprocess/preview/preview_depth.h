// Hidden surfaces for the cairo previews of 3D scenes: a screen-space depth test telling
// whether a point of a path lies behind the substrate, so the far side of a sleeve is not
// drawn (cairo has no depth buffer).
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "slicer/surface.h"

namespace strand::post {

using Triangle = std::array<slicer::Vec3, 3>;

// Projected triangles binned into square cells of the picture.
struct DepthMap {
  std::vector<std::array<slicer::Vec2, 3>> screen;  // px
  std::vector<std::array<double, 3>> nearness;      // towards the viewer, mm, per corner
  double cell_px = 8.0;
  int cols = 0, rows = 0;
  std::vector<std::vector<int>> cells;  // triangle indices per cell, row-major
};

// Bins triangles (screen corners in px, nearness per corner) over a width x height picture.
DepthMap depth_map(std::vector<std::array<slicer::Vec2, 3>> screen,
                   std::vector<std::array<double, 3>> nearness, int width_px, int height_px);

// True when a triangle covers screen point `at_px` nearer to the viewer than `nearness_mm`.
bool behind(const DepthMap& map, const slicer::Vec2& at_px, double nearness_mm);

}  // namespace strand::post
