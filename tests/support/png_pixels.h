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

}  // namespace strand::testing
