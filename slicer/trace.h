// Tracing a grey image into filled outlines with potrace: a threshold (Otsu's by default)
// makes a bitmap, potrace turns its black regions into smooth closed curves; `levels`
// thresholds at several greys give nested regions, one per pen layer (darkest innermost).
#pragma once

#include <optional>
#include <vector>

#include "slicer/curves.h"
#include "slicer/image.h"

namespace strand::slicer {

// Pixels of the bitmap traced after --upscale (the image's pixels times upscale squared).
inline constexpr long kMaxTracePixels = 64L * 1024 * 1024;

// Pixel edges between ink and paper of all bitmaps traced (one per level), counted before
// tracing: potrace's work grows faster than this length (a 1000 x 1000 checkerboard, 2
// million edges, takes 15 s), and every edge can become an outline point to plot.
inline constexpr long kMaxTraceEdges = 3'000'000;

struct TraceOptions {
  // 0..1 grey below which a pixel is ink; none = Otsu's (0.45 after a high-pass filter, as
  // mkbitmap's default)
  std::optional<double> threshold;
  // Ink where a pixel is 10 % darker than the mean of its neighbourhood (a Gaussian of the
  // high-pass radius, or 1/16 of the image's smaller side): for unevenly lit scans.
  bool adaptive = false;
  // mkbitmap's filters, applied in this order before the threshold:
  double highpass_px = 0.0;   // subtract a Gaussian blur of this radius (0 = off; -f)
  double blur_px = 0.0;       // then blur with a Gaussian of this radius (0 = off; -b)
  int upscale = 1;            // then interpolate each pixel into N x N (bilinear; -s)
  int levels = 1;             // pen layers; level k is darker than threshold (N+1-k)/N
  int turdsize = 2;           // speckles up to this many pixels are dropped (potrace -t)
  double alphamax = 1.0;      // corner threshold: 0 = polygons, 1.334 = no corners (-a)
  double opttolerance = 0.2;  // curve joining tolerance in pixels, 0 = none (-O)
  double pixel_mm = 0.25;     // size of one image pixel in the output (before upscale)
};

struct TraceLevel {
  double threshold = 0.5;      // grey (0..1) below which this level's pixels lie
  std::vector<SubPath> paths;  // closed, mm, y down from the image's top-left corner;
                               // nested outlines and holes: fill with the even-odd rule
};

struct Trace {
  std::vector<TraceLevel> levels;  // lightest threshold (largest region) first
  Vec2 size_mm = Vec2::Zero();
};

// Otsu's threshold of the image's grey histogram, in 0..1 (the grey that best separates
// two classes by between-class variance).
double otsu_threshold(const GreyImage& image);

// The image after the high-pass, blur and upscale filters of `o` (the image itself when all
// are off); the grey stays on 0..255, a flat background at 128 after the high-pass filter.
GreyImage filter_image(const GreyImage& image, const TraceOptions& o);

// Throws InputError for options out of range, for an upscaled bitmap larger than
// kMaxTracePixels and for bitmaps whose outlines are longer than kMaxTraceEdges.
Trace trace_image(const GreyImage& image, const TraceOptions& o);

}  // namespace strand::slicer
