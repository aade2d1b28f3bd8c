// Raster images for tracing: PNG, JPEG, BMP, GIF (stb_image) and the netpbm formats PBM,
// PGM, PPM (libnetpbm) decoded into one grey channel, the size bounded before decoding.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace strand::slicer {

// Images larger than this are refused before their pixels are decoded (16 Mpx: a 4096 x
// 4096 scan; tracing time and memory grow with it).
inline constexpr long kMaxImagePixels = 16L * 1024 * 1024;

struct GreyImage {
  int width = 0, height = 0;
  std::vector<std::uint8_t> grey;  // row-major from the top row; 0 black, 255 white
  // Transparent pixels are composited over white paper.

  std::uint8_t at(int x, int y) const { return grey[static_cast<std::size_t>(y) * width + x]; }
  bool operator==(const GreyImage&) const = default;
};

// Decodes image bytes; throws InputError naming `origin` when the data is no image these
// decoders know, is damaged, or is larger than kMaxImagePixels.
GreyImage decode_image(std::string_view bytes, const std::string& origin);

}  // namespace strand::slicer
