// Distance, volume, strand and naive time sums over a MotionProgram.
#include "postprocess/plan/estimate.h"

#include <algorithm>
#include <cmath>

#include "postprocess/plan/motion_time.h"
#include "slicer/units.h"

namespace strand::post {

using slicer::MoveKind;

double move_length(const slicer::Vec3& from, const slicer::Move& mv) {
  if (!mv.is_arc) return (mv.end_mm - from).norm();
  const slicer::Vec2 a = from.head<2>();
  const double r = (a - mv.center_mm).norm();
  const double xy = r * std::abs(slicer::arc_sweep(mv.center_mm, a, mv.end_mm.head<2>(), mv.ccw));
  return std::hypot(xy, mv.end_mm.z() - from.z());
}

struct EstimateStream::Impl {
  explicit Impl(const machines::MachineProfile* m) {
    if (m) {
      time_options = time_options_for(*m);
      timer = std::make_unique<TrapezoidTimer>(time_options);
    }
  }

  void add(const slicer::MotionProgram& p) {
    if (!started && !p.moves.empty()) {  // layers before the first move may be empty
      at = p.start_mm;
      started = true;
    }
    for (std::size_t i = e.layers.size(); i < p.layers.size(); ++i) {
      e.layers.push_back({static_cast<int>(i), p.layers[i].z_mm});
    }
    for (const auto& mv : p.moves) add_move(p, mv);
    if (timer) timer->add(p);
  }

  void add_move(const slicer::MotionProgram& p, const slicer::Move& mv) {
    LayerEstimate* le = mv.layer >= 0 && mv.layer < static_cast<int>(e.layers.size())
                            ? &e.layers[static_cast<std::size_t>(mv.layer)]
                            : nullptr;
    if (mv.layer != last_layer) depositing = false;  // a new layer starts a new strand
    last_layer = mv.layer;
    if (mv.kind == MoveKind::Dwell) {
      e.time_naive_s += slicer::dwell_seconds(p, mv);
      if (le) le->time_naive_s += slicer::dwell_seconds(p, mv);
      return;
    }
    if (mv.kind == MoveKind::Raw) return;
    if (last_tool >= 0 && mv.tool != last_tool) ++e.tool_changes;
    last_tool = mv.tool;
    const double len = move_length(at, mv);
    const double t = mv.feed_mm_per_min > 0 ? len / slicer::mm_per_min_to_mm_per_s(mv.feed_mm_per_min) : 0.0;
    e.time_naive_s += t;
    if (mv.kind == MoveKind::Deposit) {
      e.deposit_length_mm += len;
      e.volume_mm3 += mv.volume_mm3;
      const auto k = static_cast<std::size_t>(std::max<int>(mv.tool, 0));
      while (e.tools.size() <= k) e.tools.push_back({static_cast<int>(e.tools.size())});
      ToolEstimate& te = e.tools[k];
      if (!depositing) ++te.strands;
      te.deposit_length_mm += len;
      te.volume_mm3 += mv.volume_mm3;
      te.time_naive_s += t;
      if (le) {
        if (!depositing) ++le->strands;
        le->deposit_length_mm += len;
        le->volume_mm3 += mv.volume_mm3;
        le->time_naive_s += t;
      }
      depositing = true;
    } else {
      if (len > 0) depositing = false;
      e.travel_length_mm += len;
      if (le) {
        le->travel_length_mm += len;
        le->time_naive_s += t;
      }
    }
    at = mv.end_mm;
  }

  Estimate finish() {
    if (!timer) return std::move(e);
    const MotionTime t = timer->finish();
    e.time_trapezoid_s = t.total_s;
    for (std::size_t i = 0; i < e.layers.size(); ++i) {
      auto& l = e.layers[i];
      l.time_trapezoid_s = i < t.layer_s.size() ? t.layer_s[i] : 0.0;
      l.time_naive_s += l.strands * time_options.strand_start_dwell_s;
      e.time_naive_s += l.strands * time_options.strand_start_dwell_s;
    }
    return std::move(e);
  }

  Estimate e;
  slicer::Vec3 at = slicer::Vec3::Zero();
  bool started = false;
  bool depositing = false;
  int last_layer = -2;
  int last_tool = -1;
  TimeOptions time_options;
  std::unique_ptr<TrapezoidTimer> timer;
};

EstimateStream::EstimateStream(const machines::MachineProfile* m) : impl_(std::make_unique<Impl>(m)) {}
EstimateStream::~EstimateStream() = default;
void EstimateStream::add(const slicer::MotionProgram& piece) { impl_->add(piece); }
Estimate EstimateStream::finish() { return impl_->finish(); }

Estimate estimate(const slicer::MotionProgram& p) {
  EstimateStream s(nullptr);
  s.add(p);
  return s.finish();
}

Estimate estimate(const slicer::MotionProgram& p, const machines::MachineProfile& m) {
  EstimateStream s(&m);
  s.add(p);
  return s.finish();
}

}  // namespace strand::post
