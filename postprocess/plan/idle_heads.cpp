// Idle printheads against the beads under them: a grid of bead segments, each cell with its
// highest top, queried along each idle tip's path.
#include "postprocess/plan/idle_heads.h"

#include <algorithm>
#include <cmath>

#include "machines/gcode_format.h"
#include "postprocess/plan/arc_segmentation.h"
#include "slicer/input_error.h"

namespace strand::post {

using slicer::MoveKind;
using slicer::Vec2;
using slicer::Vec3;

namespace {

double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// The point of segment a-b nearest to p.
Vec2 nearest_on(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 d = b - a;
  const double n = d.squaredNorm();
  if (n <= 0) return a;
  return a + std::clamp((p - a).dot(d) / n, 0.0, 1.0) * d;
}

// The distance between segments p-q and a-b, and the point of p-q where it is reached.
double segment_distance(const Vec2& p, const Vec2& q, const Vec2& a, const Vec2& b, Vec2& at) {
  const Vec2 r = q - p, s = b - a;
  const double den = cross(r, s);
  if (std::abs(den) > 1e-12) {
    const double t = cross(a - p, s) / den, u = cross(a - p, r) / den;
    if (t >= 0 && t <= 1 && u >= 0 && u <= 1) {
      at = p + t * r;
      return 0.0;
    }
  }
  double best = (p - nearest_on(p, a, b)).norm();
  at = p;
  if (const double d = (q - nearest_on(q, a, b)).norm(); d < best) best = d, at = q;
  for (const Vec2& e : {a, b}) {
    const Vec2 n = nearest_on(e, p, q);
    if (const double d = (e - n).norm(); d < best) best = d, at = n;
  }
  return best;
}

std::string head_name(const machines::MachineProfile& m, int tool) {
  const std::string t = "T" + std::to_string(tool);
  if (tool < 0 || tool >= static_cast<int>(m.tools.size()) || m.tools[static_cast<std::size_t>(tool)].name.empty()) return t;
  return m.tools[static_cast<std::size_t>(tool)].name + " (" + t + ")";
}

// "passes 0.050 mm above the beads", "reaches 2.000 mm into the substrate".
std::string clearance_text(const IdleHeadHit& hit) {
  const double above = hit.tip_mm.z() - hit.bead_top_mm;
  const std::string what = hit.substrate ? "the substrate" : "the beads";
  if (above < 0) return "reaches " + machines::fmt_xyz(-above) + " mm into " + what;
  return "passes " + machines::fmt_xyz(above) + " mm above " + what;
}

}  // namespace

IdleHeadCheck::IdleHeadCheck(const machines::MachineProfile& m, std::size_t keep_beads) : keep_beads_(keep_beads) {
  for (const auto& t : m.tools) heads_.push_back({t.offset_mm, t.idle_lift_mm, t.nozzle_mm / 2});
  for (const Head& h : heads_) active_ = active_ || (h.offset - heads_.front().offset).norm() > 1e-9;
  bool first = true;
  for (const Head& a : heads_) {
    for (const Head& b : heads_) {
      if ((b.offset - a.offset).norm() <= 1e-9) continue;
      const double rel = b.offset.z() - a.offset.z() + b.lift;
      lowest_rel_ = first ? rel : std::min(lowest_rel_, rel);
      first = false;
    }
  }
}

void IdleHeadCheck::drop_below(double floor) {
  std::vector<Bead> kept;
  for (const Bead& b : beads_) {
    if (b.top >= floor) kept.push_back(b);
  }
  beads_.clear();
  cells_.clear();
  max_half_width_ = 0.0;
  for (const Bead& b : kept) insert(b.a, b.b, 2.0 * b.half_width, b.top);
  kept_after_drop_ = beads_.size();
}

std::int64_t IdleHeadCheck::cell_of(double v) const {
  return static_cast<std::int64_t>(std::floor(std::clamp(v / cell_mm_, -1e9, 1e9)));
}

void IdleHeadCheck::insert(const Vec2& a, const Vec2& b, double width, double top) {
  const auto index = static_cast<std::uint32_t>(beads_.size());
  beads_.push_back({a, b, static_cast<float>(width / 2), top});
  max_half_width_ = std::max(max_half_width_, width / 2);
  rising_ = rising_ && top >= last_top_ - 1e-6;
  last_top_ = std::max(last_top_, top);
  const double pad = width / 2;
  // The cells of the segment's box: a bead is short or straight along x or y (a serpentine's
  // rows, a ring's chords), so its box holds few cells more than the bead crosses.
  for (std::int64_t i = cell_of(std::min(a.x(), b.x()) - pad); i <= cell_of(std::max(a.x(), b.x()) + pad); ++i) {
    for (std::int64_t j = cell_of(std::min(a.y(), b.y()) - pad); j <= cell_of(std::max(a.y(), b.y()) + pad); ++j) {
      const Vec2 lo(static_cast<double>(i) * cell_mm_, static_cast<double>(j) * cell_mm_);
      const Vec2 centre = lo + Vec2(cell_mm_ / 2, cell_mm_ / 2);
      // Skip cells of a diagonal's box that the bead does not come near.
      if (slicer::point_segment_distance(centre, a, b) > pad + cell_mm_ * 0.7072) continue;
      Cell& c = cells_[key(i, j)];
      c.max_top = std::max(c.max_top, top);
      c.beads.push_back(index);
    }
  }
}

double IdleHeadCheck::highest_near(const Vec2& p, const Vec2& q, double reach, double floor, Vec2& where) const {
  const double pad = reach + max_half_width_;
  double best = floor - 1;
  for (std::int64_t i = cell_of(std::min(p.x(), q.x()) - pad); i <= cell_of(std::max(p.x(), q.x()) + pad); ++i) {
    for (std::int64_t j = cell_of(std::min(p.y(), q.y()) - pad); j <= cell_of(std::max(p.y(), q.y()) + pad); ++j) {
      const auto it = cells_.find(key(i, j));
      if (it == cells_.end() || it->second.max_top < floor) continue;
      const auto& list = it->second.beads;
      // Newest first: in a print that only rises the beads below `floor` come last.
      for (auto k = list.rbegin(); k != list.rend(); ++k) {
        const Bead& b = beads_[*k];
        if (b.top < floor || b.top <= best) {
          if (rising_ && b.top < floor) break;
          continue;
        }
        Vec2 at;
        if (segment_distance(p, q, b.a, b.b, at) < reach + b.half_width) {
          best = b.top;
          where = at;
        }
      }
    }
  }
  return best;
}

void IdleHeadCheck::add(const Vec3& from, const Vec3& to, const slicer::Move& mv, double layer_height_mm,
                        std::size_t move, int line) {
  if (!active_ || mv.kind != MoveKind::Deposit) return;
  const int a = mv.tool;
  const Vec3 own = a >= 0 && a < static_cast<int>(heads_.size()) ? heads_[static_cast<std::size_t>(a)].offset : Vec3::Zero();
  const double clearance = layer_height_mm > 0 ? std::min(kClearanceMm, layer_height_mm / 2) : kClearanceMm;
  if (mv.layer != layer_) {  // a new layer: in a rising print the beads far below can go
    layer_ = mv.layer;
    const double lowest = std::min(from.z(), to.z());
    if (rising_ && lowest >= last_top_ - 1e-6 && beads_.size() > std::max(keep_beads_, 2 * kept_after_drop_))
      drop_below(lowest + lowest_rel_ - kClearanceMm - 1e-6);
  }
  for (std::size_t k = 0; k < heads_.size(); ++k) {
    if (static_cast<int>(k) == a) continue;
    const Head& h = heads_[k];
    const Vec3 d = h.offset - own;
    if (d.norm() <= 1e-9) continue;  // one nozzle fed by several extruders
    const double tip_z = std::min(from.z(), to.z()) + d.z() + h.lift;
    const Vec2 p = from.head<2>() + d.head<2>(), q = to.head<2>() + d.head<2>();
    const double radius = h.tip_radius > 0 ? h.tip_radius : mv.width_mm / 2;
    Vec2 where = p;
    double top = highest_near(p, q, radius, tip_z - clearance, where);
    bool ground = false;
    if (ground_) {  // the substrate under the tip's path: its ends and middle (moves are short)
      for (const Vec2& g : {p, Vec2((p + q) / 2), q}) {
        const double z = ground_(g);
        if (z >= tip_z - clearance && z > top) top = z, where = g, ground = true;
      }
    }
    if (top < tip_z - clearance) continue;
    if (hits_.size() < kMaxHits)
      hits_.push_back({mv.layer, static_cast<int>(k), a, Vec3(where.x(), where.y(), tip_z), top, ground, move, line});
    ++hit_count_;
  }
  insert(from.head<2>(), to.head<2>(), mv.width_mm, std::max(from.z(), to.z()));
}

void IdleHeadCheck::add_move(const Vec3& from, const slicer::Move& mv, const Vec3& to_tip, double layer_height_mm,
                             std::size_t move, int line, double arc_tolerance_mm) {
  if (!active_ || mv.kind != MoveKind::Deposit) return;
  if (!mv.is_arc) {
    add(from + to_tip, mv.end_mm + to_tip, mv, layer_height_mm, move, line);
    return;
  }
  Vec3 at = from;
  for (const Vec2& c : segment_arc(from.head<2>(), mv.center_mm, mv.end_mm.head<2>(), mv.ccw, arc_tolerance_mm)) {
    const Vec3 to(c.x(), c.y(), mv.end_mm.z());
    add(at + to_tip, to + to_tip, mv, layer_height_mm, move, line);
    at = to;
  }
}

void throw_if_idle_head_drags(IdleHeadCheck& check, const slicer::MotionProgram& piece,
                              const machines::MachineProfile& m, double arc_tolerance_mm) {
  if (!check.active()) return;
  Vec3 at = piece.start_mm;
  for (std::size_t i = 0; i < piece.moves.size(); ++i) {
    const slicer::Move& mv = piece.moves[i];
    if (mv.kind != MoveKind::Travel && mv.kind != MoveKind::Deposit) continue;
    const Vec3 o = machines::tool_offset(m, mv.tool);
    const double h = mv.layer >= 0 && mv.layer < static_cast<int>(piece.layers.size())
                         ? piece.layers[static_cast<std::size_t>(mv.layer)].height_mm : 0.0;
    check.add_move(at, mv, o, h, i, 0, arc_tolerance_mm);
    at = mv.end_mm;
    if (check.hit_count() == 0) continue;
    const IdleHeadHit& hit = check.hits().front();
    const std::string idle = head_name(m, hit.tool);
    const Vec3 d = machines::tool_offset(m, hit.tool) - o;
    throw InputError("tools: " + idle + " would drag through the print: idle while " + head_name(m, hit.active_tool) +
                     " deposits layer " + std::to_string(hit.layer) + ", its tip (" + machines::fmt_xyz(d.x()) + ", " +
                     machines::fmt_xyz(d.y()) + ") mm from that nozzle " + clearance_text(hit) + " at (" +
                     machines::fmt_xyz(hit.tip_mm.x()) + ", " + machines::fmt_xyz(hit.tip_mm.y()) +
                     ") mm; give tools[" + std::to_string(hit.tool) + "].idle_lift_mm in machine " + m.name +
                     " (how high an idle head is held, 0 to 100 mm), " +
                     (hit.substrate ? std::string("or a substrate that stays lower under the idle head")
                                    : std::string("or print a part narrower than the heads' offset, placed so the idle "
                                                  "head stays outside it")));
  }
}

}  // namespace strand::post
