// Arcs as G2/G3 or chords, and deposits cut below EXTRUDE_MAXLENGTH.
#include "machines/deposit_pieces.h"

#include <algorithm>
#include <cmath>

#include "machines/move_split.h"
#include "slicer/units.h"

namespace strand::machines {

using slicer::Move;
using slicer::Vec2;
using slicer::Vec3;

namespace {

// Chord error used only if an arc reaches the emitter of a machine without G2/G3 (the
// planner normally segments them with the user's tolerance), mm.
constexpr double kFallbackChordMm = 0.01;
// XYZ and IJ are written with 3 decimals.
constexpr double kWrittenResolutionMm = 1e-3;
// Largest difference between the written start and end radius of a G2/G3 (firmware draws
// the start radius and ends on the target, so this is the deviation it leaves), mm.
constexpr double kArcRadiusMismatchMm = 2e-3;

Vec2 rounded(const Vec2& v) {
  return {std::round(v.x() / kWrittenResolutionMm) * kWrittenResolutionMm,
          std::round(v.y() / kWrittenResolutionMm) * kWrittenResolutionMm};
}

// G2/G3 only where the firmware will draw what the rounded numbers say: ends that round to
// the same point make a full circle (right only for an arc of more than half a turn), and
// the rounded centre must lie as far from both rounded ends as the arc's radius implies.
bool arc_writable(const Vec3& at, const Move& mv) {
  const Vec2 from = at.head<2>(), to = mv.end_mm.head<2>();
  const Vec2 s = rounded(from), e = rounded(to), c = s + rounded(mv.center_mm - from);
  if ((e - s).norm() < 0.5 * kWrittenResolutionMm) {
    return std::abs(slicer::arc_sweep(mv.center_mm, from, to, mv.ccw)) > slicer::kPi;
  }
  return std::abs((e - c).norm() - (s - c).norm()) <= kArcRadiusMismatchMm;
}

}  // namespace

PiecePlan piece_plan(const Vec3& from, const Move& mv, const MachineProfile& m, bool limit_e) {
  int n = 1;
  const bool chords = mv.is_arc && (!m.arcs || !arc_writable(from, mv));
  if (chords) {
    const double r = (from.head<2>() - mv.center_mm).norm();
    const double sweep = std::abs(slicer::arc_sweep(mv.center_mm, from.head<2>(), mv.end_mm.head<2>(), mv.ccw));
    const double tol = std::min(kFallbackChordMm, r);
    n = std::max(1, static_cast<int>(std::ceil(sweep / (2 * std::acos(1 - tol / r)))));
  }
  if (limit_e) {
    const double e = mv.volume_mm3 / m.deposition.mm3_per_e;
    n = std::max(n, static_cast<int>(std::ceil(e / m.deposition.extrude_max_length - 1e-9)));
  }
  return {n, chords};
}

std::vector<Move> deposit_pieces(const Vec3& from, const Move& mv, const PiecePlan& plan) {
  if (plan.n == 1) {
    Move line = mv;
    line.is_arc = mv.is_arc && !plan.chords;
    return {line};
  }
  std::vector<double> cuts;
  for (int i = 1; i < plan.n; ++i) cuts.push_back(static_cast<double>(i) / plan.n);
  auto out = split_move(from, mv, cuts);
  if (plan.chords) {
    for (auto& piece : out) piece.is_arc = false;
  }
  return out;
}

}  // namespace strand::machines
