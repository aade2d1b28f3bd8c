// Reads PNG bytes (via cairo) and measures how much of the picture is drawn.
#pragma once

#include <string>

namespace strand::testing {

struct PngStats {
  int width = 0, height = 0;
  double drawn_fraction = 0.0;  // pixels farther than a small tolerance from the background
};

// The background is the colour of the top-left pixel. width = 0 if the bytes are not a PNG.
PngStats png_stats(const std::string& png_bytes);

// Pixels within `tolerance` (sum of channel differences, 0..765) of the colour r, g, b (0..255):
// how many, and their centre in pixels. count = 0 if none or not a PNG.
struct ColourSpot {
  long count = 0;
  double x_px = 0.0, y_px = 0.0;
};
ColourSpot colour_spot(const std::string& png_bytes, int r, int g, int b, int tolerance);
// The same inside the pixel box [x0, x1) x [y0, y1) only.
struct PxBox {
  int x0 = 0, y0 = 0, x1 = 1 << 30, y1 = 1 << 30;
};
ColourSpot colour_spot(const std::string& png_bytes, int r, int g, int b, int tolerance,
                       const PxBox& box);

}  // namespace strand::testing
