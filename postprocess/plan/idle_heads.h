// Idle printheads against the print (issue 33). The heads of a machine ride one carriage:
// while head A deposits, every other head B travels with it, its tip at A's tip plus
// (offset B - offset A) and held idle_lift_mm higher. A tip that comes down to the beads
// already laid under it (this layer's so far and the earlier layers') drags through the
// print. The planner refuses such a job (throw_if_idle_head_drags); `strand check` counts the
// places (check_stream.h). Beads are kept in a uniform grid of cells, each with the highest
// bead top in it, so a query looks at a cell's beads only when they reach the tip's height.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <unordered_map>
#include <vector>

#include "machines/profile.h"
#include "slicer/motion.h"

namespace strand::post {

// One place where an idle head's tip meets the print (the first of a move, per idle head).
struct IdleHeadHit {
  int layer = 0;
  int tool = 0;         // the idle head
  int active_tool = 0;  // the head depositing
  slicer::Vec3 tip_mm = slicer::Vec3::Zero();  // the idle tip where it meets the beads (bed frame)
  double bead_top_mm = 0.0;                    // the top of the bead (or substrate) it meets
  bool substrate = false;                      // it meets the substrate under the print (--onto)
  std::size_t move = 0;                        // index of the deposit move of the active head
  int line = 0;                                // its G-code line, when known
};

class IdleHeadCheck {
 public:
  // Clearance the idle tip keeps above bead tops: 0.1 mm (the uncertainty of a tip height
  // measured with a calibration print), at most half the layer height, so that a tip level
  // with the depositing one is never flagged over the layer below (where that one runs).
  static constexpr double kClearanceMm = 0.1;
  static constexpr std::size_t kMaxHits = 20;  // hits kept; all are counted
  // Beyond this many beads, while the print only rises, the beads no idle tip can come down
  // to again (below the lowest tip height of the layer begun, less the clearance) are
  // dropped at each new layer: memory stays about a few layers', not the file's.
  static constexpr std::size_t kKeepBeads = 1u << 20;

  // The machine's heads: their offsets, idle lifts and nozzles. Active only with two heads
  // or more at different places.
  // `keep_beads`: kKeepBeads but in tests.
  explicit IdleHeadCheck(const machines::MachineProfile& machine, std::size_t keep_beads = kKeepBeads);
  bool active() const { return active_; }
  std::size_t beads_held() const { return beads_.size(); }

  // The next move in program order. `from_tip`/`to_tip`: where the depositing head's tip goes
  // (bed frame); `layer_height_mm` 0 when unknown. Only Deposit moves are judged and kept;
  // arcs must already be flattened into chords (add one call per chord).
  void add(const slicer::Vec3& from_tip, const slicer::Vec3& to_tip, const slicer::Move& mv,
           double layer_height_mm, std::size_t move, int line);
  // The same for a program's move from `from` (arcs flattened into chords within
  // `arc_tolerance_mm`), each point shifted by `to_tip` (from the move's frame to its tip).
  void add_move(const slicer::Vec3& from, const slicer::Move& mv, const slicer::Vec3& to_tip,
                double layer_height_mm, std::size_t move, int line, double arc_tolerance_mm);

  // A substrate under the print (--onto): its top z at a bed point (x, y), or -infinity off
  // it. The idle tips are then held clear of it as of the beads.
  void set_ground(std::function<double(const slicer::Vec2&)> top_z) { ground_ = std::move(top_z); }

  const std::vector<IdleHeadHit>& hits() const { return hits_; }
  std::size_t hit_count() const { return hit_count_; }

 private:
  struct Bead {
    slicer::Vec2 a, b;
    float half_width;
    double top;
  };
  struct Cell {
    double max_top = -1e30;
    std::vector<std::uint32_t> beads;
  };
  std::int64_t key(std::int64_t i, std::int64_t j) const { return (i << 32) ^ (j & 0xffffffff); }
  std::int64_t cell_of(double v) const;
  // The highest bead top within `reach` (+ each bead's half width) of the segment p-q that
  // reaches `floor` or above; `floor` - 1 when none.
  double highest_near(const slicer::Vec2& p, const slicer::Vec2& q, double reach, double floor,
                      slicer::Vec2& where) const;
  void insert(const slicer::Vec2& a, const slicer::Vec2& b, double width, double top);
  void drop_below(double floor);

  struct Head {
    slicer::Vec3 offset;
    double lift = 0.0, tip_radius = 0.0;
  };
  std::vector<Head> heads_;
  bool active_ = false;
  double cell_mm_ = 2.0;
  double max_half_width_ = 0.0;
  bool rising_ = true;  // every bead so far at or above the ones before (tops in program order)
  double last_top_ = -1e30;
  double lowest_rel_ = 0.0;  // the lowest idle tip relative to the depositing one (z offsets, lifts)
  int layer_ = -2;           // the layer of the last deposit
  std::size_t kept_after_drop_ = 0, keep_beads_ = kKeepBeads;
  std::vector<Bead> beads_;
  std::unordered_map<std::int64_t, Cell> cells_;
  std::vector<IdleHeadHit> hits_;
  std::size_t hit_count_ = 0;
  std::function<double(const slicer::Vec2&)> ground_;
};

// The planner's use: a planned program's moves in the carriage frame (each head's tip at the
// carriage plus its offset), fed to `check` in order from `start_mm`; throws InputError at the
// first idle head that would drag, naming the heads, the layer and the remedy.
void throw_if_idle_head_drags(IdleHeadCheck& check, const slicer::MotionProgram& piece,
                              const machines::MachineProfile& machine, double arc_tolerance_mm);

}  // namespace strand::post
