// A robot job's start and end (machines/robot_transit.h) as produce_curved uses them: planned
// and refused in one line, the report's object, the summary line.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "machines/profile.h"
#include "machines/robot_transit.h"
#include "slicer/pose_program.h"

namespace strand::post {

machines::TransitPlan plan_robot_transit(const slicer::PoseProgram& p,
                                         const machines::MachineProfile& m,
                                         const machines::TransitWorkpiece& workpiece,
                                         nlohmann::json& robot);
double printed_mm(const slicer::PoseProgram& p);
std::string transit_summary(const machines::TransitPlan& plan);

}  // namespace strand::post
