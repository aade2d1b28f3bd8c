// Splits the tail of each strand at the valve-close point.
#include "postprocess/plan/valve_lag.h"

#include <vector>

#include "machines/move_split.h"
#include "slicer/units.h"

namespace strand::post {

using slicer::Move;
using slicer::MoveKind;

namespace {

double seconds(const slicer::Vec3& from, const Move& mv) {
  const double v = slicer::mm_per_min_to_mm_per_s(mv.feed_mm_per_min);
  return v > 0 ? machines::path_length(from, mv) / v : 0.0;
}

// Moves [first, last) are one strand; `starts[i]` is where move i begins.
void lag_strand(slicer::LargeVector<Move>& out, const slicer::LargeVector<Move>& in,
                const std::vector<slicer::Vec3>& starts, std::size_t first, std::size_t last,
                double lag_s) {
  double total = 0.0;
  for (std::size_t i = first; i < last; ++i) total += seconds(starts[i], in[i]);
  if (total <= lag_s) {
    out.insert(out.end(), in.begin() + static_cast<long>(first), in.begin() + static_cast<long>(last));
    return;
  }
  double remaining = lag_s;  // seconds of motion left after the close point
  std::size_t cut = last;
  double cut_t = 0.0;        // fraction of move `cut` before the close point
  while (cut > first) {
    const double s = seconds(starts[cut - 1], in[cut - 1]);
    --cut;
    if (s >= remaining) {
      cut_t = (s - remaining) / s;
      break;
    }
    remaining -= s;
  }
  for (std::size_t i = first; i < last; ++i) {
    if (i < cut) {
      out.push_back(in[i]);
    } else if (i == cut && cut_t > 1e-9) {
      auto pieces = machines::split_move(starts[i], in[i], {cut_t});
      pieces[1].coast = true;
      out.push_back(pieces[0]);
      out.push_back(pieces[1]);
    } else {
      out.push_back(in[i]);
      out.back().coast = true;
    }
  }
}

}  // namespace

void apply_valve_lag(slicer::MotionProgram& p, double lag_s) {
  std::vector<slicer::Vec3> starts;
  slicer::Vec3 at = p.start_mm;
  for (const auto& mv : p.moves) {
    starts.push_back(at);
    if (mv.kind == MoveKind::Travel || mv.kind == MoveKind::Deposit) at = mv.end_mm;
  }
  slicer::LargeVector<Move> out;
  out.reserve(p.moves.size() + p.moves.size() / 8);
  std::size_t i = 0;
  while (i < p.moves.size()) {
    if (p.moves[i].kind != MoveKind::Deposit) {
      out.push_back(p.moves[i++]);
      continue;
    }
    std::size_t j = i;
    while (j < p.moves.size() && p.moves[j].kind == MoveKind::Deposit) ++j;
    lag_strand(out, p.moves, starts, i, j, lag_s);
    i = j;
  }
  p.moves = std::move(out);
}

}  // namespace strand::post
