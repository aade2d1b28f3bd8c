// `strand measure PHOTO --test lines|pore|fusion|collapse --job REPORT.json`: flags and
// printing; the work is in postprocess/measure/.
#include <filesystem>
#include <iostream>
#include <memory>

#include "cli/commands.h"
#include "postprocess/measure/measure_job.h"

namespace strand::cli {

namespace {

struct MeasureArgs {
  std::string photo;
  std::string test;
  std::string job;
  std::string output;
  std::string overlay;
};

int run_measure(const MeasureArgs& a) {
  const std::string stem = std::filesystem::path(a.photo).stem().string();
  const std::string out = a.output.empty() ? stem + ".measure.json" : a.output;
  const std::string png = a.overlay.empty() ? std::filesystem::path(out).replace_extension(".png").string() : a.overlay;
  const auto m = post::measure::measure_files(a.photo, a.test, a.job, out, png);
  std::cout << "strand measure: " << m.items << " in " << a.photo << " (ink " << m.json.at("ink").get<std::string>()
            << ", contrast " << m.json.at("contrast").get<double>() << ")\n";
  std::cout << m.details;
  std::cout << "  measurements   " << out << "\n  overlay        " << png << "\n";
  return 0;
}

}  // namespace

void add_measure_command(CLI::App& app, Action& action) {
  auto a = std::make_shared<MeasureArgs>();
  CLI::App* sub = app.add_subcommand("measure", "measure a photo of a printed ink test against its job report");
  sub->add_option("photo", a->photo,
                  "photo of the print (PNG or JPEG; all four marks in view, or for collapse the pillars from the side)")
      ->required();
  sub->add_option("--test", a->test, "which test the photo shows: lines, pore, fusion or collapse")
      ->required();
  sub->add_option("--job", a->job, "the --report JSON written when the test was generated")->required();
  sub->add_option("-o,--output", a->output, "measurements JSON (default PHOTO-stem.measure.json)");
  sub->add_option("--overlay", a->overlay, "annotated PNG (default: the output's name with .png)");
  sub->callback([&action, a] { action = [a] { return run_measure(*a); }; });
}

}  // namespace strand::cli
