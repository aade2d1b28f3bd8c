// PNG decoding with cairo for tests.
#include "tests/support/png_pixels.h"

#include <cairo.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>

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

}  // namespace

PngStats png_stats(const std::string& png_bytes) {
  Reader r{&png_bytes};
  cairo_surface_t* s = cairo_image_surface_create_from_png_stream(&read, &r);
  PngStats st;
  if (cairo_surface_status(s) != CAIRO_STATUS_SUCCESS) {
    cairo_surface_destroy(s);
    return st;
  }
  cairo_surface_flush(s);
  st.width = cairo_image_surface_get_width(s);
  st.height = cairo_image_surface_get_height(s);
  const int stride = cairo_image_surface_get_stride(s);
  const unsigned char* px = cairo_image_surface_get_data(s);
  auto pixel = [&](int x, int y) {
    std::uint32_t v;
    std::memcpy(&v, px + y * stride + 4 * x, 4);
    return v & 0xffffffu;
  };
  const std::uint32_t bg = pixel(0, 0);
  long drawn = 0;
  for (int y = 0; y < st.height; ++y) {
    for (int x = 0; x < st.width; ++x) {
      const std::uint32_t v = pixel(x, y);
      int diff = 0;
      for (int c = 0; c < 3; ++c) diff += std::abs(static_cast<int>((v >> (8 * c)) & 0xff) - static_cast<int>((bg >> (8 * c)) & 0xff));
      drawn += diff > 48;
    }
  }
  st.drawn_fraction = static_cast<double>(drawn) / (static_cast<double>(st.width) * st.height);
  cairo_surface_destroy(s);
  return st;
}

}  // namespace strand::testing
