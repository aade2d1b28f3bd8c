// Substrate parameters, declared once for the CLI (--substrate, --substrate-radius,
// --substrate-length, --wrap, --arc-length-at, --substrate-mesh) and for job files
// ("substrate": {"type", "radius", "length", "wrap", "arc-length-at", "mesh"}): every
// generator accepts them. A cylinder needs radius and length; a mesh (a robot-held substrate
// of any shape, slicer/mesh_substrate.h) needs the mesh file.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "slicer/cylinder_surface.h"
#include "slicer/params.h"

namespace strand::slicer {

// How a flat pattern goes onto a closed substrate.
enum class Wrap {
  Patch,  // the flat specimen laid on the surface as it is (must fit the circumference)
  Full,   // the design made periodic: a whole number of cells around, no seam defect
};
std::string to_string(Wrap w);

struct SubstrateSpec {
  std::string type = "cylinder";
  double radius_mm = 0.0;
  double length_mm = 0.0;
  Wrap wrap = Wrap::Patch;
  ArcLengthAt arc_length_at = ArcLengthAt::Surface;
  // What drives a robot cell's extruder: "time", "volumetric", or empty for the machine
  // profile's extruder.e_per_mm (--extrusion).
  std::string extrusion;
  std::string mesh_path;  // type "mesh": the substrate mesh file (workpiece frame, mm)
  // Where a relative mesh_path is found (the job's folder); empty: the current directory.
  // Files and reports name the mesh by mesh_path, as written.
  std::string mesh_folder;

  // mesh_path as a path from the current directory: the file to read.
  std::string mesh_file() const {
    const bool absolute = !mesh_path.empty() && mesh_path.front() == '/';
    return mesh_folder.empty() || absolute ? mesh_path : mesh_folder + "/" + mesh_path;
  }

  bool operator==(const SubstrateSpec&) const = default;
};

// Keys as in the job's "substrate" object; messages read "substrate.radius = 0: must be > 0 (mm)".
const ParamTable& substrate_table();
// The command-line flag (without dashes) of a table key: radius -> substrate-radius,
// type -> substrate, mesh -> substrate-mesh, wrap -> wrap.
std::string substrate_flag(const std::string& key);

// Checks `given` (an object with the table's keys, as a job's "substrate" or the CLI flags
// gathered under the table keys). nullopt when nothing was given (planar job). Throws
// InputError naming every problem, including a radius or length without a type.
std::optional<SubstrateSpec> substrate_from(const nlohmann::json& given);

// The cylinder a job prints on; `layer_height_mm` places deposition arc lengths at the bead
// centre (half a layer under the nozzle tip). With wrap full every layer keeps the first
// layer's angles, so the lattice closes on itself on every layer.
CylinderSpec cylinder_spec(const SubstrateSpec& s, double layer_height_mm);

}  // namespace strand::slicer
