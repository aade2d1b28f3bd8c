// The report check, the rectified photo and the statistics every measured test shares.
#include "postprocess/measure/measure_setup.h"

#include <algorithm>
#include <cmath>

#include "slicer/input_error.h"

namespace strand::post::measure {

nlohmann::json derived_of_test(const nlohmann::json& report, const std::string& test, const std::string& generator,
                               const std::string& what) {
  const nlohmann::json derived = report.is_object() ? report.value("derived", nlohmann::json::object()) : nlohmann::json();
  if (!derived.is_object() || !derived.contains("test") || !derived.at("test").is_string() ||
      derived.at("test").get<std::string>() != test) {
    throw InputError(what + ": the job report is not a " + generator + " report (derived.test = \"" + test +
                     "\" expected); measure the photo with the --test of the job that printed it");
  }
  return derived;
}

std::vector<Fiducial> fiducials_of(const nlohmann::json& derived, const std::string& what) {
  std::vector<Fiducial> marks;
  try {
    for (const auto& f : derived.at("fiducials")) marks.push_back({f.at("x_mm"), f.at("y_mm"), f.at("size_mm")});
  } catch (const nlohmann::json::exception&) {
    throw InputError(what + ": the job report lacks derived.fiducials (x_mm, y_mm, size_mm)");
  }
  if (marks.size() != 4) throw InputError(what + ": the job report needs 4 fiducials");
  return marks;
}

Rectified rectified_photo(const cv::Mat& photo, const std::vector<Fiducial>& marks, double px_per_mm,
                          double margin_mm, const std::string& what) {
  return rectify(photo, marks, find_marks(photo, marks, what), px_per_mm, margin_mm);
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(q * static_cast<double>(v.size() - 1))];
}

double round_to(double v, int digits) {
  const double f = std::pow(10.0, digits);
  return std::round(v * f) / f;
}

}  // namespace strand::post::measure
