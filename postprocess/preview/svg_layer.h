// Top view of one layer as SVG (viewBox in mm, y up): deposits coloured by feature, travels
// dashed, crossings in red circles, touches in orange, a scale bar; deterministic text.
#pragma once

#include <string>
#include <vector>

#include "postprocess/inspect/crossings.h"
#include "slicer/motion.h"

namespace strand::post {

struct LayerMarks {
  std::vector<Contact> crossings;  // drawn as red circles
  std::vector<Contact> touches;    // drawn as orange circles
};

// SVG text of layer `layer` (index into program.layers; -1 = moves before the first layer).
// Arcs are drawn as chords within `arc_tolerance_mm`.
std::string layer_svg(const slicer::MotionProgram& program, int layer, const LayerMarks& marks,
                      double arc_tolerance_mm);

}  // namespace strand::post
