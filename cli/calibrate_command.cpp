// `strand calibrate MEASURE.json... -o materials/NAME.json`: flags and printing; the fit is
// in jobs/ink_profile.
#include <iostream>
#include <memory>
#include <vector>

#include "cli/commands.h"
#include "jobs/ink_profile.h"
#include "slicer/params.h"

namespace strand::cli {

using jobs::calibrate_files;

void add_calibrate_command(CLI::App& app, Action& action) {
  auto files = std::make_shared<std::vector<std::string>>();
  auto output = std::make_shared<std::string>();
  CLI::App* sub = app.add_subcommand("calibrate", "fit an ink's width model to strand measure outputs; write its profile");
  sub->add_option("measurements", *files, "strand measure outputs (JSON)")->required();
  sub->add_option("-o,--output", *output, "ink profile to write, e.g. materials/NAME.json (--material NAME reads it)")
      ->required();
  sub->callback([&action, files, output] {
    action = [files, output] {
      const nlohmann::json p = calibrate_files(*files, *output);
      const auto& m = p.at("width_model");
      const auto& pr = p.at("print");
      std::cout << "strand calibrate: " << p.at("name").get<std::string>() << " from " << files->size()
                << " measurement file(s), " << m.at("points") << " lines\n"
                << "  width = " << m.at("a") << " * flow^" << m.at("p") << " * speed^" << m.at("q")
                << " mm (speed in mm/min), rms " << m.at("rms_mm") << " mm\n"
                << "  nozzle-wide bead (" << p.at("nozzle_mm") << " mm): speed " << pr.at("speed_mm_min")
                << " mm/min, flow " << pr.at("flow") << ", layer height " << pr.at("layer_height_mm") << " mm\n";
      // From the fusion and collapse measurements, when there were any.
      if (!p.at("min_spacing_without_fusion_mm").is_null()) {
        std::cout << "  filaments stay separate from "
                  << slicer::short_number(p.at("min_spacing_without_fusion_mm").get<double>()) << " mm apart\n";
      }
      if (const auto& gap = p.at("min_gap_without_collapse_mm"); !gap.is_null()) {
        if (gap.get<double>() > 0) {
          std::cout << "  spans gaps up to " << slicer::short_number(gap.get<double>()) << " mm without collapse\n";
        } else {
          std::cout << "  spans no gap without collapse\n";
        }
      }
      std::cout << "  profile        " << *output << "\n";
      return 0;
    };
  });
}

}  // namespace strand::cli
