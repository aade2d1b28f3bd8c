// Planning a robot job's start and end for produce_curved.
#include "postprocess/plan/robot_transit_plan.h"

#include "slicer/input_error.h"

namespace strand::post {

// The program's start and end planned and checked clear of the nozzle (robot_transit.h); a
// start or end that cannot be is refused with the plan's line.
machines::TransitPlan plan_robot_transit(const slicer::PoseProgram& p, const machines::MachineProfile& m,
                                         const machines::TransitWorkpiece& workpiece,
                                         nlohmann::json& robot) {
  machines::TransitPlan plan = machines::plan_transit(m.robot, p, workpiece);
  if (!plan.ok) throw InputError(plan.problem);
  robot["transit"] = machines::transit_json(plan);
  return plan;
}

// The thickness the layers printed add to the workpiece: the last layer's tip offset.
double printed_mm(const slicer::PoseProgram& p) {
  return p.layers.empty() ? 0.0 : p.layers.back().offset_mm;
}

std::string transit_summary(const machines::TransitPlan& plan) {
  return "  outside laps   " + machines::transit_text(plan) + "\n";
}

}  // namespace strand::post
