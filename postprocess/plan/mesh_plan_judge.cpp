// Mesh pose planning's last step: every row of the plan read back against the mesh as
// `strand check` reads the CSV (same digits, same rule, slicer/mesh_row_rule), so the planner
// refuses a job the check would reject.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "machines/gcode_format.h"
#include "postprocess/plan/mesh_pose_planner.h"
#include "slicer/input_error.h"
#include "slicer/mesh_row_rule.h"

namespace strand::post {

using slicer::PosePoint;

namespace {

// The CSV's digits for contact points and normals (machines/pose_csv.h).
double csv_digits(double v, double scale) { return std::round(v * scale) / scale; }

}  // namespace

void judge_mesh_plan(const slicer::MeshSubstrate& s, MeshPlan& plan) {
  std::vector<PosePoint> rows = plan.program.points;
  std::vector<slicer::MeshRowReading> at;
  at.reserve(rows.size());
  for (PosePoint& p : rows) {
    p.contact_mm = p.contact_mm.unaryExpr([](double v) { return csv_digits(v, 1e4); });
    p.normal = p.normal.unaryExpr([](double v) { return csv_digits(v, 1e9); });
    at.push_back(slicer::read_mesh_row(s, p.contact_mm, p.normal));
  }
  std::vector<double> offsets;
  for (const auto& l : plan.program.layers) offsets.push_back(l.offset_mm);
  const slicer::MeshRowJudgement j = slicer::judge_mesh_rows(rows, at, offsets);
  plan.worst_offset_mm = j.worst_deposit_mm;
  plan.worst_offset_row = j.worst_deposit_row;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (!rows[i].extrude || offsets.empty()) continue;
    const auto k = static_cast<std::size_t>(std::clamp(rows[i].layer, 0, int(offsets.size()) - 1));
    plan.max_raise_mm = std::max(plan.max_raise_mm, at[i].along_mm - offsets[k]);
  }
  if (j.ok()) return;
  const slicer::MeshRowFault* first = nullptr;
  for (const auto* list : {&j.normals, &j.off_surface})
    for (const auto& f : *list)
      if (!first || f.row < first->row) first = &f;
  const PosePoint& p = rows[first->row];
  throw InputError("substrate.mesh = " + s.source() + ": strand check would reject row " +
                   std::to_string(first->row) + " (layer " + std::to_string(p.layer) +
                   ", contact (" + machines::fmt_fixed(p.contact_mm.x(), 3) + ", " +
                   machines::fmt_fixed(p.contact_mm.y(), 3) + ", " +
                   machines::fmt_fixed(p.contact_mm.z(), 3) +
                   ") mm in the mesh's frame): " + first->what +
                   "; the mesh is too coarse or too concave there for the layer: refine it or "
                   "use a smaller pattern");
}

}  // namespace strand::post
