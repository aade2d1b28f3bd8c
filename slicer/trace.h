// Tracing a grey image into filled outlines with potrace: a threshold (Otsu's by default)
// makes a bitmap, potrace turns its black regions into smooth closed curves; `levels`
// thresholds at several greys give nested regions, one per pen layer (darkest innermost).
#pragma once

#include <optional>
#include <vector>

#include "slicer/curves.h"
#include "slicer/image.h"

namespace strand::slicer {

struct TraceOptions {
  std::optional<double> threshold;  // 0..1 grey below which a pixel is ink; none = Otsu
  int levels = 1;                   // pen layers; level k is darker than threshold (N+1-k)/N
  int turdsize = 2;                 // speckles up to this many pixels are dropped (potrace -t)
  double alphamax = 1.0;            // corner threshold: 0 = polygons, 1.334 = no corners (-a)
  double opttolerance = 0.2;        // curve joining tolerance in pixels, 0 = none (-O)
  double pixel_mm = 0.25;           // size of one pixel in the output
};

struct TraceLevel {
  double threshold = 0.5;           // grey (0..1) below which this level's pixels lie
  std::vector<SubPath> paths;       // closed, mm, y down from the image's top-left corner;
                                    // nested outlines and holes: fill with the even-odd rule
};

struct Trace {
  std::vector<TraceLevel> levels;   // lightest threshold (largest region) first
  Vec2 size_mm = Vec2::Zero();
};

// Otsu's threshold of the image's grey histogram, in 0..1 (the grey that best separates
// two classes by between-class variance).
double otsu_threshold(const GreyImage& image);

// Throws InputError for options out of range.
Trace trace_image(const GreyImage& image, const TraceOptions& o);

}  // namespace strand::slicer
