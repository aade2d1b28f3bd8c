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
           "curved substrate to print on (a cylinder held by a robot or on a rotary axis, or a "
           "mesh held by a robot); default none = flat",
           {},
           false,
           {},
           false,
           nullptr,
           "none",
           {"cylinder", "mesh"}},
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
          {"mesh", ParamType::Text, "",
           "substrate mesh held by the robot (OBJ, STL, PLY, OFF, glTF, 3MF; mm, its coordinates "
           "are the workpiece frame on the flange); required with --substrate mesh"},
          {"extrusion",
           ParamType::Text,
           "",
           "what drives the robot cell's extruder: time (E = v_ext x each lap's duration, as the "
           "thesis' screw) or volumetric (the beads' volume through deposition.mm3_per_e); default "
           "the profile's extruder.e_per_mm",
           {},
           false,
           {},
           false,
           nullptr,
           "profile",
           {"time", "volumetric"}},
      }};
  return kTable;
}

std::string substrate_flag(const std::string& key) {
  if (key == "type") return "substrate";
  if (key == "radius" || key == "length" || key == "mesh") return "substrate-" + key;
  return key;
}

std::optional<SubstrateSpec> substrate_from(const nlohmann::json& given) {
  if (given.is_null() || (given.is_object() && given.empty())) return std::nullopt;
  const nlohmann::json v = resolve_params(substrate_table(), given);
  std::vector<std::string> problems;
  if (!v.contains("type")) {
    problems.push_back(
        "substrate.type: missing (required with a radius, length, wrap, arc-length-at or mesh: "
        "cylinder or mesh)");
  }
  const bool mesh = v.value("type", "") == "mesh";
  if (mesh) {
    if (!v.contains("mesh") || v.at("mesh").get<std::string>().empty())
      problems.push_back("substrate.mesh: missing (required for a mesh substrate: the mesh file)");
    for (const char* key : {"radius", "length"}) {
      if (v.contains(key))
        problems.push_back(std::string("substrate.") + key +
                           ": only for a cylinder (a mesh substrate has its own size)");
    }
    if (v.at("wrap") == "full")
      problems.push_back("substrate.wrap = full: only for a cylinder (a mesh is a patch)");
  } else {
    for (const char* key : {"radius", "length"}) {
      if (!v.contains(key))
        problems.push_back(std::string("substrate.") + key +
                           ": missing (required for a cylinder, > 0 mm)");
    }
    if (v.contains("mesh"))
      problems.push_back("substrate.mesh: only with --substrate mesh (type mesh)");
  }
  if (!problems.empty()) throw InputError(problems);
  SubstrateSpec s;
  s.type = v.at("type").get<std::string>();
  if (mesh) {
    s.mesh_path = v.at("mesh").get<std::string>();
  } else {
    s.radius_mm = v.at("radius").get<double>();
    s.length_mm = v.at("length").get<double>();
  }
  s.wrap = v.at("wrap") == "full" ? Wrap::Full : Wrap::Patch;
  s.arc_length_at =
      v.at("arc-length-at") == "deposition" ? ArcLengthAt::Deposition : ArcLengthAt::Surface;
  if (v.contains("extrusion")) s.extrusion = v.at("extrusion").get<std::string>();
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
