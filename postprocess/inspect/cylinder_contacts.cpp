// Seam-cut segments in a flat MotionProgram, searched with the planar contact finder.
#include "postprocess/inspect/cylinder_contacts.h"

#include <cmath>

namespace strand::post {

namespace {

// Flattens strands into [0, period) x v: `base_` is the multiple of the period subtracted
// from the unwrapped u of the current piece.
class Builder {
 public:
  explicit Builder(double period) : period_(period) {}

  void strand(const std::vector<CylinderStrandPoint>& pts, int layer) {
    if (pts.size() < 2) return;
    layer_ = layer;
    base_ = period_ * std::floor(pts[0].uv_mm.x() / period_);
    push(slicer::MoveKind::Travel, pts[0].uv_mm.x() - base_, pts[0].uv_mm.y(), pts[0].source);
    u_ = pts[0].uv_mm.x();
    v_ = pts[0].uv_mm.y();
    for (std::size_t i = 1; i < pts.size(); ++i) deposit_to(pts[i].uv_mm, pts[i].source);
  }

  slicer::MotionProgram program;
  std::vector<std::size_t> sources;  // per move

 private:
  // Deposits to `target` (unwrapped u), cut at every seam crossed on the way.
  void deposit_to(const slicer::Vec2& target, std::size_t source) {
    const double du = target.x() - u_, dv = target.y() - v_;
    const int dir = du > 0 ? 1 : -1;
    while (du != 0.0) {
      const double seam = dir > 0 ? base_ + period_ : base_;
      if (dir > 0 ? target.x() <= seam : target.x() >= seam) break;
      const double v = v_ + (seam - u_) / du * dv;
      push(slicer::MoveKind::Deposit, seam - base_, v, source);
      base_ += dir * period_;
      push(slicer::MoveKind::Travel, seam - base_, v, source);
    }
    push(slicer::MoveKind::Deposit, target.x() - base_, target.y(), source);
    u_ = target.x();
    v_ = target.y();
  }

  void push(slicer::MoveKind kind, double u, double v, std::size_t source) {
    slicer::Move mv;
    mv.kind = kind;
    mv.end_mm = slicer::Vec3(u, v, 0.0);
    mv.layer = layer_;
    program.moves.push_back(mv);
    sources.push_back(source);
  }

  double period_;
  double base_ = 0.0, u_ = 0.0, v_ = 0.0;
  int layer_ = 0;
};

}  // namespace

ContactReport find_cylinder_contacts(const std::vector<CylinderLayer>& layers, double touch_mm) {
  ContactReport out;
  for (const auto& layer : layers) {
    if (!(layer.circumference_mm > 0)) continue;
    Builder b(layer.circumference_mm);
    for (const auto& s : layer.strands) b.strand(s, layer.layer);
    if (b.program.moves.empty()) continue;
    b.program.start_mm = b.program.moves.front().end_mm;
    ContactReport r = find_contacts(b.program, 1.0, touch_mm);
    for (auto* list : {&r.crossings, &r.touches}) {
      for (auto& c : *list) c.move_a = b.sources[c.move_a], c.move_b = b.sources[c.move_b];
    }
    out.crossings.insert(out.crossings.end(), r.crossings.begin(), r.crossings.end());
    out.touches.insert(out.touches.end(), r.touches.begin(), r.touches.end());
  }
  return out;
}

}  // namespace strand::post
