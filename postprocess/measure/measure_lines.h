// `strand measure --test lines`: every line of a line-width matrix measured in a photo of
// the print, against the job report that says where the lines and marks are.
#pragma once

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "postprocess/measure/measure_setup.h"

namespace strand::post::measure {

struct LineWidth {
  int index = 0;
  double speed_mm_per_min = 0.0;
  double flow = 0.0;
  double intended_width_mm = 0.0;
  double width_mm = 0.0;   // median over the stations where ink was found
  double width_cv = 0.0;   // spread along the line: standard deviation / mean
  double coverage = 0.0;   // share of the stations (inner 80 % of the line) with ink
};

struct LinesMeasured {
  std::vector<LineWidth> lines;
  nlohmann::json json;  // what `strand measure` writes
  cv::Mat overlay;      // rectified photo with the intended lines and measured widths
};

// Measures the photo against a line-matrix job report (its "derived" lines, fiducials,
// nozzle and spacing). Width at a station is the ink's contrast integrated across the line
// over its full contrast, so blur (which spreads but keeps the integral) does not bias it,
// and contrast is taken relative to the local bed brightness, so uneven light cancels.
// InputError: a report of another test, marks not found, contrast too low (blurred photo).
LinesMeasured measure_lines(const cv::Mat& photo, const nlohmann::json& report, const std::string& what);

// The result as the command prints and writes it.
Measured lines_measured(const LinesMeasured& m);

}  // namespace strand::post::measure
