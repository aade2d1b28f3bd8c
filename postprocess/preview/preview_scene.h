// Room postprocess/preview (library strand_preview; links inspect, plan): pictures of a
// MotionProgram for people. It owns the scene (this file: polylines by layer and feature,
// colours), the cairo PNG/SVG views with optional check marks (preview_image.h), the
// self-contained HTML viewer and the glTF tubes. It never changes a program.
//
// What previews draw: a MotionProgram cut into polylines (deposit or travel, one layer and
// feature each, arcs flattened), with bounds and the colour scheme shared by every format.
#pragma once

#include <string>
#include <vector>

#include "slicer/motion.h"

namespace strand::post {

struct PreviewPath {
  int layer = -1;
  slicer::Feature feature = slicer::Feature::Infill;
  bool travel = false;
  std::vector<slicer::Vec3> points_mm;  // at least two
};

struct PreviewScene {
  std::vector<PreviewPath> paths;
  std::vector<double> layer_z_mm;  // one per layer of the program
  slicer::Vec3 min_mm = slicer::Vec3::Zero();  // bounds of the deposits (all paths if none)
  slicer::Vec3 max_mm = slicer::Vec3::Zero();
  double bead_width_mm = 0.0;  // widest deposit (0 when the file gives no ;WIDTH:)
};

// Arcs become chords within `arc_tolerance_mm`.
PreviewScene preview_scene(const slicer::MotionProgram& program, double arc_tolerance_mm);

struct Rgb {
  double r = 0, g = 0, b = 0;  // 0..1
};
// Fixed colours per feature, close to PrusaSlicer's role colours where one exists.
Rgb feature_colour(slicer::Feature f);
// Blue (first layer) to red (last).
Rgb layer_colour(int layer, int layer_count);
std::string hex_colour(const Rgb& c);  // "#rrggbb"

}  // namespace strand::post
