// Internal to mesh pose planning (mesh_pose_planner.cpp): the path of a placed toolpath on a
// mesh's offset surfaces as targets, its points before their orientation is known, each one
// checked against the nozzle cone. Not for use outside postprocess/plan/.
#pragma once

#include <string>
#include <vector>

#include "postprocess/plan/mesh_pose_planner.h"

namespace strand::post::mesh_detail {

// One point of the path, before its orientation is known.
struct Target {
  slicer::Vec2 uv = slicer::Vec2::Zero();
  double offset = 0.0;
  bool extrude = false;
  bool lifted = false;  // above its layer's offset (a travel backed off the substrate)
  slicer::Feature feature = slicer::Feature::Infill;
  double speed = 0.0;
  int layer = 0;
  slicer::SurfaceFrame frame;
};

// Where target `t` is, for messages: its pattern point, nozzle tip and layer.
std::string where(const Target& t);

// The path: deposits and travels on the offset surfaces, every point's cone checked.
class PathBuilder {
 public:
  PathBuilder(const slicer::MeshSubstrate& s, const machines::RobotCell& c,
              const PosePlanOptions& o)
      : s_(s), c_(c), o_(o) {}

  // The targets of every stroke of `t`, layer by layer, with the travels between them.
  std::vector<Target> run(const slicer::Toolpath& t);

  // The target `t` raised by `by` mm along its normal (a restart backs off there).
  Target lifted(const Target& t, double by) const;

 private:
  double speed_of(slicer::Feature f) const;
  void travel_to(const slicer::Vec2& uv, double offset);
  void check_cone(const Target& t) const;
  void push(const slicer::Vec2& uv, double offset, bool extrude, slicer::Feature f, double speed);

  const slicer::MeshSubstrate& s_;
  const machines::RobotCell& c_;
  const PosePlanOptions& o_;
  std::vector<Target> out_;
  slicer::Vec2 uv_ = slicer::Vec2::Zero();
  double off_ = 0.0, layer_offset_ = 0.0;
  slicer::Feature feature_ = slicer::Feature::Infill;
  int layer_ = 0;
};

}  // namespace strand::post::mesh_detail
