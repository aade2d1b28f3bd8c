// Slice settings given as text (--threads, --scale-to-fit, --rotate), checked (jobs/slice_job.h).
#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>

#include "jobs/slice_job.h"
#include "slicer/input_error.h"
#include "slicer/params.h"
#include "slicer/unit_values.h"

namespace strand::jobs {

void check_threads(const std::optional<int>& threads) {
  if (threads && (*threads < 1 || *threads > kMaxSliceThreads)) {
    throw InputError("slice.threads = " + std::to_string(*threads) + ": must be in [1, " +
                     std::to_string(kMaxSliceThreads) + "]");
  }
}

int threads_from_text(const std::string& text) {
  int n = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), n);
  if (ec != std::errc() || end != text.data() + text.size()) {
    throw InputError("slice.threads = " + text + ": must be a whole number in [1, " +
                     std::to_string(kMaxSliceThreads) + "]");
  }
  check_threads(n);
  return n;
}

double scale_to_fit(const slicer::Vec3& size_mm, const std::string& box) {
  // "30x30x30", "3 x 3 x 3 cm", "30mm x 30mm x 1in" (slicer/unit_values.h).
  const slicer::UnitValues given = slicer::parse_quantities(box, "mm", 'x');
  const std::vector<double>& v = given.values;
  if (!given.ok() || v.size() != 3 || !std::all_of(v.begin(), v.end(), [](double d) { return d > 0.0 && d <= 100000.0; })) {
    throw InputError("slice.scale-to-fit = " + box + ": must be WxDxH in mm, each in (0, 100000], e.g. 30x30x30" +
                     (given.unit_problem.empty() ? "" : " (" + given.unit_problem + ")"));
  }
  double f = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    if (size_mm[k] > 0.0) f = std::min(f, v[static_cast<std::size_t>(k)] / size_mm[k]);
  }
  if (!std::isfinite(f)) throw InputError("slice.scale-to-fit = " + box + ": the part has no size");
  return f;
}

slicer::Vec3 rotation_from_text(const std::string& text) {
  // "90,0,0", "0,0,1.5708rad", "0, 0, 45 deg" (slicer/unit_values.h).
  const slicer::UnitValues given = slicer::parse_quantities(text, "deg", ',');
  const std::vector<double>& v = given.values;
  if (!given.ok() || v.size() != 3 || !std::all_of(v.begin(), v.end(), [](double d) { return std::abs(d) <= 360.0; })) {
    throw InputError("slice.rotate = " + text + ": must be X,Y,Z in degrees, each in [-360, 360]" +
                     (given.unit_problem.empty() ? "" : " (" + given.unit_problem + ")"));
  }
  return {v[0], v[1], v[2]};
}

}  // namespace strand::jobs
