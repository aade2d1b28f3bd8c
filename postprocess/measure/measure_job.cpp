// The measure command's work: which test, the files read and written.
#include "postprocess/measure/measure_job.h"

#include <filesystem>
#include <utility>

#include "postprocess/measure/measure_collapse.h"
#include "postprocess/measure/measure_fusion.h"
#include "postprocess/measure/measure_lines.h"
#include "postprocess/measure/measure_pores.h"
#include "slicer/file_io.h"
#include "slicer/input_error.h"
#include "slicer/json_input.h"

namespace strand::post::measure {

namespace {

constexpr char kTests[] = "lines, pore, fusion or collapse";

bool known(const std::string& test) {
  return test == "lines" || test == "pore" || test == "fusion" || test == "collapse";
}

void check_test(const std::string& test, const nlohmann::json& report) {
  if (!known(test)) {
    throw InputError("measure.test = " + test + ": must be " + kTests);
  }
  const auto& d = report.is_object() ? report.value("derived", nlohmann::json::object()) : nlohmann::json();
  if (d.is_object() && d.contains("test") && d.at("test").is_string() && d.at("test").get<std::string>() != test) {
    const std::string printed = d.at("test").get<std::string>();
    throw InputError("measure.test = " + test + ": the job report is of the " + printed + " test (derived.test = \"" +
                     printed + "\"); measure the photo with --test " + printed);
  }
}

}  // namespace

Measured measure_test(const cv::Mat& photo, const std::string& test, const nlohmann::json& report,
                      const std::string& what) {
  check_test(test, report);
  if (test == "pore") return measure_pores(photo, report, what);
  if (test == "fusion") return measure_fusion(photo, report, what);
  if (test == "collapse") return measure_collapse(photo, report, what);
  return lines_measured(measure_lines(photo, report, what));
}

Measured measure_files(const std::string& photo_path, const std::string& test, const std::string& report_path,
                       const std::string& out_json, const std::string& out_png) {
  if (!known(test)) check_test(test, nullptr);
  // The outputs never replace an input (say -o photo.json beside photo.png).
  const auto same = [](const std::string& a, const std::string& b) {
    return std::filesystem::weakly_canonical(a) == std::filesystem::weakly_canonical(b);
  };
  for (const auto& [flag, path] : {std::pair{"output", out_json}, std::pair{"overlay", out_png}}) {
    if (same(path, photo_path) || same(path, report_path) || (flag == std::string("overlay") && same(path, out_json))) {
      throw InputError(std::string("measure.") + flag + " = " + path + ": would overwrite an input or the other output");
    }
  }
  const nlohmann::json report = slicer::parse_json(slicer::read_file(report_path), "measure.job = " + report_path);
  check_test(test, report);
  const cv::Mat photo = load_photo(photo_path);
  Measured m = measure_test(photo, test, report, "measure.photo = " + photo_path);
  m.json["photo"] = photo_path;
  m.json["job"] = report_path;
  slicer::write_file_atomic(out_png, encode_png(m.overlay));
  slicer::write_file_atomic(out_json, m.json.dump(2) + "\n");
  return m;
}

}  // namespace strand::post::measure
