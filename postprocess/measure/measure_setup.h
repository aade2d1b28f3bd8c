// What every `strand measure --test` shares: the job report read and checked against the
// test, the photo's marks found and the bed plane rectified, and the small statistics the
// measurements use. Each test's measurer (measure_lines, measure_pores, ...) starts here.
#pragma once

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "postprocess/measure/photo.h"

namespace strand::post::measure {

// A photo measured against a report: the JSON `strand measure` writes, the annotated
// overlay, and the lines it prints after its first line.
struct Measured {
  std::string items;  // "16 lines", "16 pores": what was measured, for the first line
  nlohmann::json json;
  cv::Mat overlay;
  std::string details;  // one line per item, each ending in '\n'
};

// The report's "derived" object when its "test" is `test`; else InputError "the job report is
// not a GENERATOR report (derived.test = "TEST" expected); ...".
nlohmann::json derived_of_test(const nlohmann::json& report, const std::string& test, const std::string& generator,
                               const std::string& what);
// The report's four fiducial marks (x_mm, y_mm, size_mm); InputError when absent or not four.
std::vector<Fiducial> fiducials_of(const nlohmann::json& derived, const std::string& what);

// Finds the marks in the photo and maps it onto the bed plane (see find_marks, rectify).
Rectified rectified_photo(const cv::Mat& photo, const std::vector<Fiducial>& marks, double px_per_mm,
                          double margin_mm, const std::string& what);

double median(std::vector<double> v);
// The q-quantile (0..1) by rank, no interpolation.
double percentile(std::vector<double> v, double q);
double round_to(double v, int digits);

}  // namespace strand::post::measure
