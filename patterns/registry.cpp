// The list of generators; add one line per design.
#include "patterns/registry.h"

#include "patterns/scaffold.h"

namespace strand::patterns {

const std::vector<GeneratorSpec>& generators() {
  static const std::vector<GeneratorSpec> kGenerators = {
      {"scaffold", "log-pile scaffold: one serpentine per layer, rotated by --angles",
       &scaffold_table, &scaffold_from_values},
  };
  return kGenerators;
}

const GeneratorSpec* find_generator(const std::string& name) {
  for (const auto& g : generators()) {
    if (g.name == name) return &g;
  }
  return nullptr;
}

}  // namespace strand::patterns
