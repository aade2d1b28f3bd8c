// The substrate table and its conversion to a cylinder.
#include "slicer/substrate_params.h"

#include "slicer/input_error.h"

namespace strand::slicer {

std::string to_string(Wrap w) { return w == Wrap::Patch ? "patch" : "full"; }

const ParamTable& substrate_table() {
  static const ParamTable kTable = {
      "substrate",
      {
          {"type",
           ParamType::Text,
           "",
           "curved substrate to print on (a cylinder held by a robot or on a rotary axis); default "
           "none = flat",
           {},
           false,
           {},
           false,
           nullptr,
           "none",
           {"cylinder"}},
          {"radius", ParamType::Number, "mm", "cylinder radius; required with --substrate", 0.0,
           true, 10000.0},
          {"length", ParamType::Number, "mm",
           "cylinder length along its axis; required with --substrate", 0.0, true, 10000.0},
          {"wrap",
           ParamType::Text,
           "",
           "patch: lay the flat specimen on the cylinder; full: a whole number of cells around, "
           "closing on itself",
           {},
           false,
           {},
           false,
           "patch",
           "",
           {"patch", "full"}},
          {"arc-length-at",
           ParamType::Text,
           "",
           "measure the pattern's x around the cylinder at the substrate (surface) or at each "
           "layer's bead centre (deposition)",
           {},
           false,
           {},
           false,
           "surface",
           "",
           {"surface", "deposition"}},
      }};
  return kTable;
}

std::string substrate_flag(const std::string& key) {
  if (key == "type") return "substrate";
  if (key == "radius" || key == "length") return "substrate-" + key;
  return key;
}

std::optional<SubstrateSpec> substrate_from(const nlohmann::json& given) {
  if (given.is_null() || (given.is_object() && given.empty())) return std::nullopt;
  const nlohmann::json v = resolve_params(substrate_table(), given);
  std::vector<std::string> problems;
  if (!v.contains("type")) {
    problems.push_back(
        "substrate.type: missing (required with a radius, length, wrap or arc-length-at: "
        "cylinder)");
  }
  for (const char* key : {"radius", "length"}) {
    if (!v.contains(key))
      problems.push_back(std::string("substrate.") + key +
                         ": missing (required for a cylinder, > 0 mm)");
  }
  if (!problems.empty()) throw InputError(problems);
  SubstrateSpec s;
  s.type = v.at("type").get<std::string>();
  s.radius_mm = v.at("radius").get<double>();
  s.length_mm = v.at("length").get<double>();
  s.wrap = v.at("wrap") == "full" ? Wrap::Full : Wrap::Patch;
  s.arc_length_at =
      v.at("arc-length-at") == "deposition" ? ArcLengthAt::Deposition : ArcLengthAt::Surface;
  return s;
}

CylinderSpec cylinder_spec(const SubstrateSpec& s, double layer_height_mm) {
  CylinderSpec c;
  c.radius_mm = s.radius_mm;
  c.length_mm = s.length_mm;
  c.arc_length_at = s.arc_length_at;
  c.bead_inset_mm = layer_height_mm / 2.0;
  // A lattice that closes around the cylinder keeps its cells' angles on every layer, so
  // deposition arc lengths are measured once, at the first layer's bead centre.
  if (s.wrap == Wrap::Full && s.arc_length_at == ArcLengthAt::Deposition) {
    c.fixed_measure_offset_mm = layer_height_mm;
  }
  return c;
}

}  // namespace strand::slicer
