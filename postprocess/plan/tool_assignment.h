// Which printhead prints what (issue 33): by feature (`--tools node=1,ligament=0`) or cycled
// per layer (`--tools layers=0,1`), applied to each layer's strokes before planning.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "slicer/toolpath.h"

namespace strand::post {

struct ToolAssignment {
  std::map<slicer::Feature, int> by_feature;  // features not listed keep their stroke's tool
  std::vector<int> by_layer;                  // layer k: by_layer[k % size]
  bool empty() const { return by_feature.empty() && by_layer.empty(); }
  int highest() const;  // the highest tool index named, -1 when empty
};

// Parses "node=1,ligament=0" or "layers=0,1" (the --tools flag), and {"by_feature": {...}}
// or {"by_layer": [...]} (a job file's "tools"). InputError naming `what` and the allowed
// forms; tools are 0 to 15, features as ;FEATURE: writes them.
ToolAssignment tool_assignment_from_text(const std::string& text, const std::string& what);
ToolAssignment tool_assignment_from_json(const nlohmann::json& j, const std::string& what);

// The layer's strokes with their tools: a stroke whose segments change tool is cut there
// (each piece keeps its segments), then the strokes are grouped by tool, `current` (the tool
// the machine holds) first, the others in ascending order, each group in its first order,
// so a layer changes tool as few times as it can.
std::vector<slicer::Stroke> assign_tools(const std::vector<slicer::Stroke>& strokes, const ToolAssignment& a,
                                         int layer_index, int current);

}  // namespace strand::post
