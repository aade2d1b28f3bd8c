// potrace on thresholded bitmaps: pixels packed into potrace's words (row 0 at the bottom,
// as potrace counts y upwards), curves read back as exact cubics and lines in mm.
#include "slicer/trace.h"

#include <potracelib.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <memory>

#include "slicer/input_error.h"

namespace strand::slicer {

namespace {

constexpr int kWordBits = 8 * sizeof(potrace_word);

struct ParamFree {
  void operator()(potrace_param_t* p) const { potrace_param_free(p); }
};
struct StateFree {
  void operator()(potrace_state_t* s) const { potrace_state_free(s); }
};

// Pixels darker than `threshold` (0..255 scale) set, image row r stored as potrace row h-1-r.
std::vector<potrace_word> bitmap_words(const GreyImage& img, double threshold, int dy) {
  std::vector<potrace_word> map(static_cast<std::size_t>(dy) * img.height, 0);
  const double t = threshold * 255.0;
  for (int r = 0; r < img.height; ++r) {
    potrace_word* row = map.data() + static_cast<std::size_t>(img.height - 1 - r) * dy;
    for (int x = 0; x < img.width; ++x) {
      if (img.at(x, r) < t)
        row[x / kWordBits] |= potrace_word(1) << (kWordBits - 1 - x % kWordBits);
    }
  }
  return map;
}

// potrace's y-up pixel coordinates -> mm, y down from the top-left corner.
Vec2 to_mm(const potrace_dpoint_t& p, double h, double px) {
  return Vec2(p.x * px, (h - p.y) * px);
}

SubPath subpath_of(const potrace_curve_t& c, double h, double px) {
  SubPath s;
  s.start = to_mm(c.c[c.n - 1][2], h, px);
  s.closed = true;
  for (int i = 0; i < c.n; ++i) {
    CurvePiece piece;
    if (c.tag[i] == POTRACE_CORNER) {
      piece.p[0] = to_mm(c.c[i][1], h, px);
      s.pieces.push_back(piece);
      piece.p[0] = to_mm(c.c[i][2], h, px);
      s.pieces.push_back(piece);
    } else {
      piece.kind = CurveKind::Cubic;
      for (int k = 0; k < 3; ++k) piece.p[k] = to_mm(c.c[i][k], h, px);
      s.pieces.push_back(piece);
    }
  }
  return s;
}

std::vector<SubPath> trace_bitmap(const GreyImage& img, double threshold, const TraceOptions& o) {
  const int dy = (img.width + kWordBits - 1) / kWordBits;
  std::vector<potrace_word> words = bitmap_words(img, threshold, dy);
  potrace_bitmap_t bm{img.width, img.height, dy, words.data()};
  std::unique_ptr<potrace_param_t, ParamFree> param(potrace_param_default());
  if (!param) throw std::bad_alloc();
  param->turdsize = o.turdsize;
  param->alphamax = o.alphamax;
  param->opticurve = o.opttolerance > 0 ? 1 : 0;
  param->opttolerance = o.opttolerance;
  std::unique_ptr<potrace_state_t, StateFree> state(potrace_trace(param.get(), &bm));
  if (!state || state->status != POTRACE_STATUS_OK)
    throw std::bad_alloc();  // potrace fails only on memory
  std::vector<SubPath> out;
  for (const potrace_path_t* p = state->plist; p != nullptr; p = p->next) {
    if (p->curve.n > 0) out.push_back(subpath_of(p->curve, img.height, o.pixel_mm));
  }
  return out;
}

// Pixel edges between ink (grey below `threshold`, 0..1) and paper, the image's border
// counting as paper: the length of the outlines potrace would follow.
long outline_edges(const GreyImage& img, double threshold) {
  const double t = threshold * 255.0;
  long edges = 0;
  for (int y = 0; y < img.height; ++y) {
    bool left = false;
    for (int x = 0; x < img.width; ++x) {
      const bool ink = img.at(x, y) < t;
      const bool up = y > 0 && img.at(x, y - 1) < t;
      edges += (ink != left) + (ink != up);
      left = ink;
    }
    edges += left;  // the right border
  }
  for (int x = 0; x < img.width; ++x) edges += img.height > 0 && img.at(x, img.height - 1) < t;
  return edges;
}

// A float copy of the image for filtering (0..255).
using Plane = std::vector<float>;

// Gaussian blur of standard deviation `sigma` approximated by three box blurs (W. Wells,
// 1986): time independent of the radius. Edges repeat the border pixel.
void gaussian(Plane& p, int w, int h, double sigma) {
  // box width for three passes: sqrt(12 sigma^2 / 3 + 1), odd, at least 1
  int r = static_cast<int>(std::lround((std::sqrt(4.0 * sigma * sigma + 1.0) - 1.0) / 2.0));
  r = std::clamp(r, 0, std::max(w, h));
  if (r == 0) return;
  std::vector<float> line(static_cast<std::size_t>(std::max(w, h)));
  const auto pass = [&](std::size_t base, std::size_t stride, int n) {
    for (int i = 0; i < n; ++i) line[i] = p[base + i * stride];
    const auto at = [&](int i) { return line[std::clamp(i, 0, n - 1)]; };
    double sum = 0.0;
    for (int i = -r; i <= r; ++i) sum += at(i);
    for (int i = 0; i < n; ++i) {
      p[base + i * stride] = static_cast<float>(sum / (2 * r + 1));
      sum += at(i + r + 1) - at(i - r);
    }
  };
  for (int k = 0; k < 3; ++k) {
    for (int y = 0; y < h; ++y) pass(static_cast<std::size_t>(y) * w, 1, w);
    for (int x = 0; x < w; ++x) pass(static_cast<std::size_t>(x), static_cast<std::size_t>(w), h);
  }
}

std::uint8_t grey_of(double v) {
  return static_cast<std::uint8_t>(std::clamp(std::lround(v), 0L, 255L));
}

// Ink (0) where a pixel is 10 % darker than its neighbourhood's Gaussian mean, else paper.
GreyImage adaptive_bitmap(const GreyImage& img, double radius) {
  Plane mean(img.grey.begin(), img.grey.end());
  gaussian(mean, img.width, img.height, radius);
  GreyImage out = img;
  for (std::size_t i = 0; i < out.grey.size(); ++i)
    out.grey[i] = img.grey[i] < 0.9 * mean[i] ? 0 : 255;
  return out;
}

void check(const TraceOptions& o) {
  std::vector<std::string> problems;
  if (!(o.highpass_px >= 0.0 && o.highpass_px <= 1000.0))
    problems.push_back("trace.highpass: must be in [0, 1000] (px)");
  if (!(o.blur_px >= 0.0 && o.blur_px <= 1000.0))
    problems.push_back("trace.blur: must be in [0, 1000] (px)");
  if (o.upscale < 1 || o.upscale > 8)
    problems.push_back("trace.upscale = " + std::to_string(o.upscale) + ": must be in [1, 8]");
  if (o.adaptive && o.levels != 1)
    problems.push_back("trace.levels = " + std::to_string(o.levels) +
                       ": must be 1 with an adaptive threshold");
  if (o.threshold && !(*o.threshold > 0.0 && *o.threshold <= 1.0))
    problems.push_back("trace.threshold: must be in (0, 1]");
  if (o.levels < 1 || o.levels > 8)
    problems.push_back("trace.levels = " + std::to_string(o.levels) + ": must be in [1, 8]");
  if (o.turdsize < 0) problems.push_back("trace.turdsize: must be >= 0 (px)");
  if (!(o.alphamax >= 0.0 && o.alphamax <= 1.3334))
    problems.push_back("trace.alphamax: must be in [0, 1.3334]");
  if (!(o.opttolerance >= 0.0)) problems.push_back("trace.opttolerance: must be >= 0 (px)");
  if (!(o.pixel_mm > 0.0)) problems.push_back("trace.pixel-size: must be > 0 (mm)");
  if (!problems.empty()) throw InputError(problems);
}

}  // namespace

double otsu_threshold(const GreyImage& image) {
  std::array<double, 256> hist{};
  for (auto g : image.grey) hist[g] += 1.0;
  const double total = static_cast<double>(image.grey.size());
  double sum_all = 0.0;
  for (int i = 0; i < 256; ++i) sum_all += i * hist[i];
  double w0 = 0.0, sum0 = 0.0, best = -1.0;
  int first = 127, last = 127;     // the range of greys that reach the best variance
  for (int t = 0; t < 256; ++t) {  // class 0: grey <= t
    w0 += hist[t];
    sum0 += t * hist[t];
    const double w1 = total - w0;
    if (w0 == 0.0 || w1 == 0.0) continue;
    const double m0 = sum0 / w0, m1 = (sum_all - sum0) / w1;
    const double between = w0 * w1 * (m0 - m1) * (m0 - m1);
    if (between > best * (1 + 1e-12)) {
      best = between;
      first = last = t;
    } else if (between >= best * (1 - 1e-12)) {
      last = t;  // empty greys between two classes give the same split: take the middle
    }
  }
  const int best_t = (first + last) / 2;
  return (best_t + 1) / 255.0;  // ink: grey < threshold, so grey <= best_t is ink
}

GreyImage filter_image(const GreyImage& image, const TraceOptions& o) {
  check(o);
  if (o.highpass_px == 0.0 && o.blur_px == 0.0 && o.upscale == 1) return image;
  const int w = image.width, h = image.height;
  Plane p(image.grey.begin(), image.grey.end());
  if (o.highpass_px > 0.0) {  // the background (lighting) removed, paper at mid grey
    Plane background = p;
    gaussian(background, w, h, o.highpass_px);
    for (std::size_t i = 0; i < p.size(); ++i) p[i] = p[i] - background[i] + 128.0f;
  }
  if (o.blur_px > 0.0) gaussian(p, w, h, o.blur_px);
  const int n = o.upscale;
  GreyImage out;
  out.width = w * n;
  out.height = h * n;
  out.grey.resize(static_cast<std::size_t>(out.width) * out.height);
  for (int y = 0; y < out.height; ++y) {
    // the centre of output pixel y in input pixel coordinates
    const double sy = std::clamp((y + 0.5) / n - 0.5, 0.0, h - 1.0);
    const int y0 = std::min(static_cast<int>(sy), h - 1), y1 = std::min(y0 + 1, h - 1);
    const double fy = sy - y0;
    for (int x = 0; x < out.width; ++x) {
      const double sx = std::clamp((x + 0.5) / n - 0.5, 0.0, w - 1.0);
      const int x0 = std::min(static_cast<int>(sx), w - 1), x1 = std::min(x0 + 1, w - 1);
      const double fx = sx - x0;
      const auto at = [&](int xx, int yy) {
        return static_cast<double>(p[static_cast<std::size_t>(yy) * w + xx]);
      };
      const double v = (1 - fy) * ((1 - fx) * at(x0, y0) + fx * at(x1, y0)) +
                       fy * ((1 - fx) * at(x0, y1) + fx * at(x1, y1));
      out.grey[static_cast<std::size_t>(y) * out.width + x] = grey_of(v);
    }
  }
  return out;
}

Trace trace_image(const GreyImage& image, const TraceOptions& o) {
  check(o);
  const long upscaled = static_cast<long>(image.width) * image.height * o.upscale * o.upscale;
  if (upscaled > kMaxTracePixels) {
    throw InputError("trace.upscale = " + std::to_string(o.upscale) + ": the " +
                     std::to_string(image.width) + " x " + std::to_string(image.height) +
                     " px image would become " + std::to_string(upscaled) + " px (at most " +
                     std::to_string(kMaxTracePixels) + ")");
  }
  GreyImage img = filter_image(image, o);
  TraceOptions scaled = o;
  scaled.pixel_mm = o.pixel_mm / o.upscale;
  Trace out;
  out.size_mm = Vec2(image.width, image.height) * o.pixel_mm;
  if (o.adaptive) {
    const double radius = o.highpass_px > 0.0
                              ? o.highpass_px * o.upscale
                              : std::max(8.0, std::min(img.width, img.height) / 16.0);
    img = adaptive_bitmap(img, radius);
  }
  const double top = o.adaptive            ? 0.5  // of the adaptive bitmap: ink 0, paper 255
                     : o.threshold         ? *o.threshold
                     : o.highpass_px > 0.0 ? 0.45
                                           : otsu_threshold(img);
  const int levels = o.adaptive ? 1 : o.levels;
  std::vector<double> thresholds;
  long edges = 0;  // bounded before any tracing
  for (int k = 1; k <= levels; ++k) {
    thresholds.push_back(top * (levels + 1 - k) / levels);
    edges += outline_edges(img, thresholds.back());
  }
  if (edges > kMaxTraceEdges) {
    throw InputError(
        "trace: the " + std::to_string(img.width) + " x " + std::to_string(img.height) +
        " px bitmap" + (levels > 1 ? "s" : "") + " would be traced along " + std::to_string(edges) +
        " pixel edges between ink and paper (at most " + std::to_string(kMaxTraceEdges) +
        "); use a smaller image, --blur, fewer --levels or a lower --upscale");
  }
  for (double threshold : thresholds) {
    TraceLevel level;
    level.threshold = threshold;
    level.paths = trace_bitmap(img, threshold, scaled);
    out.levels.push_back(std::move(level));
  }
  return out;
}

}  // namespace strand::slicer
