// Tetrachiral parameters: the thesis' defaults (core 1.87 mm) on the shared chiral table.
#include "patterns/tetrachiral.h"

namespace strand::patterns {

const slicer::ParamTable& tetrachiral_table() {
  static const slicer::ParamTable kTable = chiral_table("tetrachiral", 1.87, 6, 2);
  return kTable;
}

ChiralParams tetrachiral_params_from(const nlohmann::json& values) {
  return chiral_params_from(ChiralKind::Tetra, "tetrachiral", values);
}

}  // namespace strand::patterns
