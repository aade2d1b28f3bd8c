// Shared checks for lattice generators, read back from the emitted G-code the way a
// reviewer would: no crossing, one strand per layer, size and centring as reported, and
// unjoined filaments a nozzle apart.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <utility>

#include "postprocess/inspect/gcode_parser.h"
#include "slicer/params.h"
#include "slicer/toolpath.h"

namespace strand::testing {

struct EmittedPart {
  slicer::Toolpath toolpath;
  post::ParsedGcode parsed;
  std::string gcode;
};

// Generates from `given` (checked against `table`), plans and emits for the delta, parses back.
EmittedPart emit_on_delta(const slicer::ParamTable& table,
                          slicer::Toolpath (*make)(const nlohmann::json&), const nlohmann::json& given);

// The InputError message emit_on_delta throws for `given`, or "" when it is accepted.
std::string input_error_of(const slicer::ParamTable& table,
                           slicer::Toolpath (*make)(const nlohmann::json&), const nlohmann::json& given);

// Centre-line bounds of the deposits of one layer {min, max}.
std::pair<slicer::Vec2, slicer::Vec2> deposit_bounds(const slicer::MotionProgram& p, int layer);

// Smallest centre-line distance between deposits of one layer that do not share an end
// point: below the nozzle diameter, two beads that are not joined would overlap.
double min_gap_between_unjoined(const slicer::MotionProgram& p, int layer);

// No crossing; as many strands per layer as derived "strands_per_layer" says, and exactly one;
// layer 0 spans derived "footprint_mm" within 0.01 mm, centred on (0, 0); unjoined filaments
// a nozzle apart.
void expect_sound_lattice(const EmittedPart& e, const std::string& what);

}  // namespace strand::testing
