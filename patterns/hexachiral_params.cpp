// Hexachiral parameters: the thesis' defaults (core 2.055 mm) on the shared chiral table.
#include "patterns/hexachiral.h"

namespace strand::patterns {

const slicer::ParamTable& hexachiral_table() {
  static const slicer::ParamTable kTable = chiral_table("hexachiral", 2.055, 10, 4);
  return kTable;
}

ChiralParams hexachiral_params_from(const nlohmann::json& values) {
  return chiral_params_from(ChiralKind::Hexa, "hexachiral", values);
}

}  // namespace strand::patterns
