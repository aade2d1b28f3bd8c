// PNG decoding with cairo for tests.
#include "tests/support/png_pixels.h"

#include <cairo.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <vector>

namespace strand::testing {

namespace {

struct Reader {
  const std::string* bytes;
  std::size_t at = 0;
};

cairo_status_t read(void* closure, unsigned char* data, unsigned int length) {
  auto* r = static_cast<Reader*>(closure);
  if (r->at + length > r->bytes->size()) return CAIRO_STATUS_READ_ERROR;
  std::memcpy(data, r->bytes->data() + r->at, length);
  r->at += length;
  return CAIRO_STATUS_SUCCESS;
}

// Decoded RGB24 pixels (0x00rrggbb); width 0 when the bytes are not a PNG.
struct Image {
  int width = 0, height = 0;
  std::vector<std::uint32_t> pixels;
  std::uint32_t at(int x, int y) const { return pixels[static_cast<std::size_t>(y * width + x)]; }
};

Image decode(const std::string& png_bytes) {
  Reader r{&png_bytes};
  cairo_surface_t* s = cairo_image_surface_create_from_png_stream(&read, &r);
  Image img;
  if (cairo_surface_status(s) == CAIRO_STATUS_SUCCESS) {
    cairo_surface_flush(s);
    img.width = cairo_image_surface_get_width(s);
    img.height = cairo_image_surface_get_height(s);
    const int stride = cairo_image_surface_get_stride(s);
    const unsigned char* px = cairo_image_surface_get_data(s);
    for (int y = 0; y < img.height; ++y) {
      for (int x = 0; x < img.width; ++x) {
        std::uint32_t v;
        std::memcpy(&v, px + y * stride + 4 * x, 4);
        img.pixels.push_back(v & 0xffffffu);
      }
    }
  }
  cairo_surface_destroy(s);
  return img;
}

int difference(std::uint32_t a, std::uint32_t b) {
  int diff = 0;
  for (int c = 0; c < 3; ++c) {
    diff += std::abs(static_cast<int>((a >> (8 * c)) & 0xff) - static_cast<int>((b >> (8 * c)) & 0xff));
  }
  return diff;
}

}  // namespace

PngStats png_stats(const std::string& png_bytes) {
  const Image img = decode(png_bytes);
  PngStats st{img.width, img.height};
  if (img.width == 0) return st;
  const std::uint32_t bg = img.at(0, 0);
  long drawn = 0;
  for (const std::uint32_t v : img.pixels) drawn += difference(v, bg) > 48;
  st.drawn_fraction = static_cast<double>(drawn) / (static_cast<double>(st.width) * st.height);
  return st;
}

ColourSpot colour_spot(const std::string& png_bytes, int r, int g, int b, int tolerance) {
  return colour_spot(png_bytes, r, g, b, tolerance, PxBox{});
}

ColourSpot colour_spot(const std::string& png_bytes, int r, int g, int b, int tolerance,
                       const PxBox& box) {
  const Image img = decode(png_bytes);
  const auto wanted = static_cast<std::uint32_t>((r << 16) | (g << 8) | b);
  ColourSpot spot;
  for (int y = std::max(0, box.y0); y < std::min(img.height, box.y1); ++y) {
    for (int x = std::max(0, box.x0); x < std::min(img.width, box.x1); ++x) {
      if (difference(img.at(x, y), wanted) > tolerance) continue;
      ++spot.count;
      spot.x_px += x;
      spot.y_px += y;
    }
  }
  if (spot.count > 0) spot.x_px /= static_cast<double>(spot.count), spot.y_px /= static_cast<double>(spot.count);
  return spot;
}

}  // namespace strand::testing
