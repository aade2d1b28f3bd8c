// Image decoding: netpbm files through libnetpbm (its errors caught with its jump buffer, its
// messages kept from stderr), everything else through stb_image; pixels to grey (Rec. 601
// luma), alpha over white.
#include "slicer/image.h"

#include <csetjmp>
#include <cstdio>
#include <memory>

extern "C" {
#include <netpbm/pnm.h>
}
#include <stb_image.h>

#include "slicer/input_error.h"

namespace strand::slicer {

namespace {

std::uint8_t luma(int r, int g, int b) {
  return static_cast<std::uint8_t>((299 * r + 587 * g + 114 * b + 500) / 1000);
}

void check_size(long w, long h, const std::string& origin) {
  if (w <= 0 || h <= 0 || w > kMaxImagePixels || h > kMaxImagePixels || w * h > kMaxImagePixels) {
    throw InputError(origin + ": image " + std::to_string(w) + " x " + std::to_string(h) +
                     " px: must have at most " + std::to_string(kMaxImagePixels) + " pixels (scale it down)");
  }
}

// libnetpbm reports errors by longjmp when given a jump buffer; its message goes here
// instead of stderr.
thread_local std::string netpbm_message;
void keep_message(const char* msg) { netpbm_message = msg ? msg : ""; }

bool is_netpbm(std::string_view b) { return b.size() >= 2 && b[0] == 'P' && b[1] >= '1' && b[1] <= '6'; }

struct NetpbmHeader {
  int cols = 0, rows = 0, format = 0;
  xelval maxval = 0;
};

// Each libnetpbm call runs under its own jump buffer with only plain data alive across
// setjmp; an error returns false with the library's message in netpbm_message.
bool read_header(FILE* f, NetpbmHeader* h) {
  jmp_buf jump;
  jmp_buf* saved = nullptr;
  pm_setjmpbufsave(&jump, &saved);
  if (setjmp(jump) != 0) {
    pm_setjmpbuf(saved);
    return false;
  }
  pnm_readpnminit(f, &h->cols, &h->rows, &h->maxval, &h->format);
  pm_setjmpbuf(saved);
  return true;
}

bool read_pixels(FILE* f, const NetpbmHeader* h, std::uint8_t* out) {
  xel* volatile row = pnm_allocrow(h->cols);
  jmp_buf jump;
  jmp_buf* saved = nullptr;
  pm_setjmpbufsave(&jump, &saved);
  if (setjmp(jump) != 0) {
    pm_setjmpbuf(saved);
    pnm_freerow(row);
    return false;
  }
  const bool colour = PNM_FORMAT_TYPE(h->format) == PPM_TYPE;
  const long maxval = h->maxval;
  const auto scale = [maxval](xelval v) { return static_cast<int>((255L * v + maxval / 2) / maxval); };
  for (int y = 0; y < h->rows; ++y) {
    pnm_readpnmrow(f, row, h->cols, h->maxval, h->format);
    for (int x = 0; x < h->cols; ++x) {
      const xel p = row[x];
      out[static_cast<std::size_t>(y) * h->cols + x] =
          colour ? luma(scale(PPM_GETR(p)), scale(PPM_GETG(p)), scale(PPM_GETB(p)))
                 : static_cast<std::uint8_t>(scale(PNM_GET1(p)));
    }
  }
  pm_setjmpbuf(saved);
  pnm_freerow(row);
  return true;
}

struct FileCloser {
  void operator()(FILE* f) const { std::fclose(f); }
};

GreyImage decode_netpbm(std::string_view bytes, const std::string& origin) {
  static const bool initialised = [] {
    static char name[] = "strand";
    pm_init(name, 0);
    pm_setusererrormsgfn(&keep_message);
    return true;
  }();
  (void)initialised;
  std::unique_ptr<FILE, FileCloser> f(fmemopen(const_cast<char*>(bytes.data()), bytes.size(), "rb"));
  if (!f) throw InputError(origin + ": cannot read the image data");
  NetpbmHeader h;
  if (!read_header(f.get(), &h)) throw InputError(origin + ": not a readable netpbm image (" + netpbm_message + ")");
  check_size(h.cols, h.rows, origin);
  GreyImage img;
  img.width = h.cols;
  img.height = h.rows;
  img.grey.resize(static_cast<std::size_t>(h.cols) * h.rows);
  if (!read_pixels(f.get(), &h, img.grey.data())) {
    throw InputError(origin + ": damaged netpbm image (" + netpbm_message + ")");
  }
  return img;
}

struct StbFree {
  void operator()(stbi_uc* p) const { stbi_image_free(p); }
};

GreyImage decode_stb(std::string_view bytes, const std::string& origin) {
  const auto* data = reinterpret_cast<const stbi_uc*>(bytes.data());
  const int len = static_cast<int>(bytes.size());
  int w = 0, h = 0, comp = 0;
  if (bytes.size() > 0x7fffffff || !stbi_info_from_memory(data, len, &w, &h, &comp)) {
    throw InputError(origin + ": not an image Strand can decode (PNG, JPEG, BMP, GIF, PBM, PGM, PPM)");
  }
  check_size(w, h, origin);
  std::unique_ptr<stbi_uc, StbFree> pixels(stbi_load_from_memory(data, len, &w, &h, &comp, 4));
  if (!pixels) throw InputError(origin + ": damaged image (" + std::string(stbi_failure_reason()) + ")");
  GreyImage img;
  img.width = w;
  img.height = h;
  img.grey.resize(static_cast<std::size_t>(w) * h);
  for (std::size_t i = 0; i < img.grey.size(); ++i) {
    const stbi_uc* p = pixels.get() + 4 * i;
    const int y = luma(p[0], p[1], p[2]);
    img.grey[i] = static_cast<std::uint8_t>((y * p[3] + 255 * (255 - p[3]) + 127) / 255);  // over white
  }
  return img;
}

}  // namespace

GreyImage decode_image(std::string_view bytes, const std::string& origin) {
  return is_netpbm(bytes) ? decode_netpbm(bytes, origin) : decode_stb(bytes, origin);
}

}  // namespace strand::slicer
