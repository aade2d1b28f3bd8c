// Raster (PNG) and vector (SVG) previews of a PreviewScene, drawn with cairo: a top view
// and/or an isometric view, coloured by feature or by layer, with a scale bar in mm and a
// colour legend. A 3D scene (a substrate, or paths off their layer's plane) is drawn back to
// front with its substrate as a light shaded solid, so the far side of a sleeve is hidden.
#pragma once

#include <string>
#include <vector>

#include "postprocess/inspect/check.h"
#include "postprocess/preview/preview_scene.h"

namespace strand::post {

enum class PreviewView { Top, Iso, Both };  // Both: top left, isometric right
enum class PreviewColouring { Feature, Layer };

// A point the check found, circled on the drawing: a crossing in red, a touch in orange.
struct PreviewMark {
  int layer = 0;
  slicer::Vec2 at_mm = slicer::Vec2::Zero();
  bool crossing = true;  // false: a touch
};
// Every crossing and touch of the report, in layer order.
std::vector<PreviewMark> marks_from(const CheckReport& report);

struct ImageOptions {
  int width_px = 1200;  // SVG: points
  int height_px = 700;
  PreviewView view = PreviewView::Both;
  PreviewColouring colouring = PreviewColouring::Feature;
  int layer = -1;           // -1: every layer; else only this layer (0-based, as ;LAYER:n)
  bool travel = false;      // draw travel moves as thin grey lines
  bool scale_bar = true;    // and a caption with the view name, and the colour legend
  double px_per_mm = 0.0;   // 0: fit the part into each panel
  std::vector<PreviewMark> marks;  // drawn on the visible layers, above the paths
};

// Throws InputError when options.layer is not a layer of the scene or the size is not positive.
std::string render_png(const PreviewScene& scene, const ImageOptions& options);
std::string render_svg(const PreviewScene& scene, const ImageOptions& options);

}  // namespace strand::post
