// potrace on thresholded bitmaps: pixels packed into potrace's words (row 0 at the bottom,
// as potrace counts y upwards), curves read back as exact cubics and lines in mm.
#include "slicer/trace.h"

#include <potracelib.h>

#include <array>
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
      if (img.at(x, r) < t) row[x / kWordBits] |= potrace_word(1) << (kWordBits - 1 - x % kWordBits);
    }
  }
  return map;
}

// potrace's y-up pixel coordinates -> mm, y down from the top-left corner.
Vec2 to_mm(const potrace_dpoint_t& p, double h, double px) { return Vec2(p.x * px, (h - p.y) * px); }

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
  if (!state || state->status != POTRACE_STATUS_OK) throw std::bad_alloc();  // potrace fails only on memory
  std::vector<SubPath> out;
  for (const potrace_path_t* p = state->plist; p != nullptr; p = p->next) {
    if (p->curve.n > 0) out.push_back(subpath_of(p->curve, img.height, o.pixel_mm));
  }
  return out;
}

void check(const TraceOptions& o) {
  std::vector<std::string> problems;
  if (o.threshold && !(*o.threshold > 0.0 && *o.threshold <= 1.0)) problems.push_back("trace.threshold: must be in (0, 1]");
  if (o.levels < 1 || o.levels > 8) problems.push_back("trace.levels = " + std::to_string(o.levels) + ": must be in [1, 8]");
  if (o.turdsize < 0) problems.push_back("trace.turdsize: must be >= 0 (px)");
  if (!(o.alphamax >= 0.0 && o.alphamax <= 1.3334)) problems.push_back("trace.alphamax: must be in [0, 1.3334]");
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
  int first = 127, last = 127;  // the range of greys that reach the best variance
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

Trace trace_image(const GreyImage& image, const TraceOptions& o) {
  check(o);
  Trace out;
  out.size_mm = Vec2(image.width, image.height) * o.pixel_mm;
  const double top = o.threshold ? *o.threshold : otsu_threshold(image);
  for (int k = 1; k <= o.levels; ++k) {
    TraceLevel level;
    level.threshold = top * (o.levels + 1 - k) / o.levels;
    level.paths = trace_bitmap(image, level.threshold, o);
    out.levels.push_back(std::move(level));
  }
  return out;
}

}  // namespace strand::slicer
