// `strand measure PHOTO --test lines|pore|fusion|collapse --job REPORT.json`: the test chosen,
// the photo and report read (bounded), measured, and the results written.
#pragma once

#include <string>

#include "postprocess/measure/measure_setup.h"

namespace strand::post::measure {

// Measures a decoded photo against a report for `test` (lines, pore, fusion or collapse).
// InputError "measure.test = T: ..." for an unknown test, or when the report says it is of
// another test.
Measured measure_test(const cv::Mat& photo, const std::string& test, const nlohmann::json& report,
                      const std::string& what);

// The whole command: reads the photo (bounded) and the report, measures, then writes the
// JSON to `out_json` and the overlay to `out_png` (each atomically; nothing on error; never
// over an input).
Measured measure_files(const std::string& photo_path, const std::string& test, const std::string& report_path,
                       const std::string& out_json, const std::string& out_png);

}  // namespace strand::post::measure
