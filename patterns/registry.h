// The generators the CLI and job files can run, by name.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "slicer/params.h"
#include "slicer/toolpath.h"

namespace strand::patterns {

// Most segments (plus strokes) one generated specimen may have: about 4 million moves, a few
// hundred MB through planning and emission; larger stacks are refused before they are built.
inline constexpr std::size_t kMaxToolpathSegments = 4'000'000;

struct GeneratorSpec {
  std::string name;     // CLI sub-command and job "generator"
  std::string summary;  // one line for --help
  const slicer::ParamTable& (*table)();
  // Builds the toolpath from values already checked by resolve_params; checks the rules
  // that tie parameters together and throws InputError listing every violation.
  slicer::Toolpath (*generate)(const nlohmann::json& values);
  // For `--wrap full` on a cylinder: the same design made periodic in x with period
  // `period_mm` (the circumference where u is measured), a whole number of cells around it,
  // no border along the seam, and the strand closing across it (x beyond the period wraps).
  // The adjusted cell size goes into Toolpath::derived. nullptr: the design cannot wrap.
  slicer::Toolpath (*generate_wrapped)(const nlohmann::json& values, double period_mm) = nullptr;
};

const std::vector<GeneratorSpec>& generators();
// nullptr when there is no generator of that name.
const GeneratorSpec* find_generator(const std::string& name);

}  // namespace strand::patterns
