// The generators the CLI and job files can run, by name.
#pragma once

#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "slicer/layer_source.h"
#include "slicer/params.h"
#include "slicer/toolpath.h"

namespace strand::patterns {

// Most segments (plus strokes) one generated specimen may have: about 4 million moves, a G-code
// file of some 100 MB and seconds of work (memory no longer grows with it: jobs run layer by
// layer); larger stacks are refused before they are built.
inline constexpr std::size_t kMaxToolpathSegments = 4'000'000;

struct GeneratorSpec {
  std::string name;     // CLI sub-command and job "generator"
  std::string summary;  // one line for --help
  const slicer::ParamTable& (*table)();
  // Builds the whole toolpath from values already checked by resolve_params (layers()
  // collected); checks the rules that tie parameters together and throws InputError listing
  // every violation.
  slicer::Toolpath (*generate)(const nlohmann::json& values);
  // For `--wrap full` on a cylinder: the same design made periodic in x with period
  // `period_mm` (the circumference where u is measured), a whole number of cells around it,
  // no border along the seam, and the strand closing across it (x beyond the period wraps;
  // no segment spans half the period). Toolpath::derived gets wrap_period_mm, cells_around,
  // cell_around_mm (the adjusted cell), cell_around_requested_mm and wrap_fit (a sentence);
  // footprint_mm / size_mm start with the period. Impossible requests throw InputError
  // "<name>.wrap = full: ..." naming the limit (docs/wrapping.md). nullptr: cannot wrap
  // (every shipped design can).
  slicer::Toolpath (*generate_wrapped)(const nlohmann::json& values, double period_mm) = nullptr;

  // The toolpath from values already checked by resolve_params, one layer at a time (the
  // record, with `parameters` = values, is complete before the first layer); checks the
  // rules that tie parameters together and throws InputError listing every violation. A stack
  // estimated above kMaxToolpathSegments is refused before it is made; asking for the last
  // layer throws if the real count exceeds it.
  std::unique_ptr<slicer::LayerSource> (*layers)(const nlohmann::json& values);
};

const std::vector<GeneratorSpec>& generators();
// nullptr when there is no generator of that name.
const GeneratorSpec* find_generator(const std::string& name);

}  // namespace strand::patterns
