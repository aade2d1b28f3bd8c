// Chiral layer strand. Ligaments are internal tangents of the attach circles; a node visit
// enters at one edge end and leaves at the angularly adjacent one, drawing a serpentine of
// concentric passes inside that sector (the sector of another visit never overlaps it).
// A non-crossing Euler circuit over ligaments and frame edges (chiral_border) gives the
// strand.
#include "patterns/chiral_strand.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "patterns/chiral_border.h"
#include "patterns/euler_circuit.h"
#include "slicer/units.h"

namespace strand::patterns {

using slicer::Feature;
using slicer::Segment;
using slicer::Vec2;

namespace {

EdgePath oriented(const EdgePath& e, bool forward) {
  if (forward) return e;
  EdgePath r;
  r.pts.assign(e.pts.rbegin(), e.pts.rend());
  r.feats.assign(e.feats.rbegin(), e.feats.rend());
  return r;
}

struct Built {
  PlaneGraph graph;
  std::vector<EdgePath> paths;
  std::vector<std::vector<double>> end_angles;  // per vertex
  int grip_edge = -1;
  Vec2 mark = Vec2::Zero();
};

void add_edge(Built& b, int from, int to, double a_from, double a_to, EdgePath path) {
  b.graph.add_edge(from, to, a_from, a_to);
  b.end_angles[static_cast<std::size_t>(from)].push_back(a_from);
  b.end_angles[static_cast<std::size_t>(to)].push_back(a_to);
  b.paths.push_back(std::move(path));
}

Built build_graph(const ChiralLattice& l, const NodeRings& rings, const StrandSpec& spec) {
  Built b;
  const int n = static_cast<int>(l.nodes.size());
  b.graph.vertex_count = n;
  b.end_angles.resize(static_cast<std::size_t>(n));
  for (std::size_t k = 0; k < l.ligaments.size(); ++k) {
    const auto [pa, pc] = ligament_nodes(l, k);
    const auto [ta, tc] = ligament_tangent(pa, pc, rings.attach_mm);
    EdgePath path;
    path.pts.push_back(ta);
    path.add(tc, Feature::Ligament);
    path.wrap = l.wraps.empty() ? 0 : l.wraps[k];
    add_edge(b, l.ligaments[k].first, l.ligaments[k].second, slicer::angle_of(pa, ta),
             slicer::angle_of(pc, tc), std::move(path));
  }
  ChiralFrame frame =
      l.period_mm > 0 ? chiral_ring_frame(l, rings, b.end_angles, spec.nozzle_mm, spec.grip_mm)
                      : chiral_frame(l, rings, b.end_angles, spec.nozzle_mm, spec.grip_mm);
  if (frame.grip_edge >= 0) b.grip_edge = static_cast<int>(b.paths.size()) + frame.grip_edge;
  b.mark = frame.mark;
  for (FrameEdge& e : frame.edges)
    add_edge(b, e.from, e.to, e.angle_from_rad, e.angle_to_rad, std::move(e.path));
  return b;
}

// Signed sweep of the visit from `in` to `out`: through the sector holding no other end.
double visit_sweep(const std::vector<double>& angles, double in, double out) {
  const double gap = slicer::wrap_period(out - in, slicer::kTwoPi);
  if (angles.size() == 2) return gap <= slicer::kPi ? gap : gap - slicer::kTwoPi;
  for (double a : angles) {
    const double x = slicer::wrap_period(a - in, slicer::kTwoPi);
    if (x > 1e-12 && x < gap - 1e-12) return gap - slicer::kTwoPi;
  }
  return gap;
}

struct Visit {
  int vertex = 0;
  double in_rad = 0, sweep_rad = 0, extend_rad = 0;
};

// Visits of the circuit: where each arrives, its sector, and how far its inner passes may
// reach back beyond the entry into the empty gap there: up to the next end when that end
// is an exit, half way when it is another visit's entry.
std::vector<Visit> visits_of(const Built& b, const NodeRings& rings,
                             const std::vector<CircuitStep>& steps) {
  const auto& g = b.graph;
  std::vector<Visit> visits;
  std::vector<std::vector<double>> entries(b.end_angles.size());
  for (std::size_t i = 0; i < steps.size(); ++i) {
    const auto e = static_cast<std::size_t>(steps[i].edge);
    const auto ne = static_cast<std::size_t>(steps[(i + 1) % steps.size()].edge);
    Visit v;
    v.vertex = steps[i].forward ? g.edge_to[e] : g.edge_from[e];
    v.in_rad = steps[i].forward ? g.angle_to_rad[e] : g.angle_from_rad[e];
    const double out =
        steps[(i + 1) % steps.size()].forward ? g.angle_from_rad[ne] : g.angle_to_rad[ne];
    v.sweep_rad = visit_sweep(b.end_angles[static_cast<std::size_t>(v.vertex)], v.in_rad, out);
    entries[static_cast<std::size_t>(v.vertex)].push_back(v.in_rad);
    visits.push_back(v);
  }
  const double h = rings.attach_mm - rings.pass_mm.back();
  for (Visit& v : visits) {
    const double back = v.sweep_rad >= 0 ? -1.0 : 1.0;
    double gap = slicer::kTwoPi, next = v.in_rad;
    for (double a : b.end_angles[static_cast<std::size_t>(v.vertex)]) {
      const double dist = slicer::wrap_period(back * (a - v.in_rad), slicer::kTwoPi);
      if (dist > 1e-12 && dist < gap) gap = dist, next = a;
    }
    const auto& ins = entries[static_cast<std::size_t>(v.vertex)];
    const bool shared = std::find(ins.begin(), ins.end(), next) != ins.end();
    const double margin = std::min(h / rings.pass_mm.front(), gap / 4);
    v.extend_rad = std::max(0.0, shared ? (gap - margin) / 2 : gap - margin);
  }
  return visits;
}

// Rotates a closed stroke so it starts (and ends) at `mark`, a joint of its segments. On a
// ring the stroke may close one or more periods away; the pieces moved to the end are
// shifted by that displacement, so the stroke stays continuous.
void start_at(slicer::Stroke& s, const Vec2& mark) {
  const Vec2 closing = s.end_mm() - s.start_mm;
  for (std::size_t k = 0; k < s.segments.size(); ++k) {
    if ((s.segments[k].end_mm - mark).norm() > 1e-9) continue;
    for (std::size_t i = 0; i <= k; ++i) {
      s.segments[i].end_mm += closing;
      s.segments[i].center_mm += closing;
    }
    std::rotate(s.segments.begin(), s.segments.begin() + static_cast<long>(k + 1),
                s.segments.end());
    s.start_mm = mark;
    return;
  }
}

// The strand of one circuit. Walking it, `at` counts the periods (ring lattices) between
// where the strand is and the stored position of the node it reached, so every edge and
// node visit is drawn where the strand is: a ring strand runs on past the seam.
slicer::Stroke assemble(const Built& b, const ChiralLattice& l, const NodeRings& rings,
                        std::vector<CircuitStep> steps) {
  auto it = std::find_if(steps.begin(), steps.end(),
                         [&](const CircuitStep& s) { return s.edge == b.grip_edge; });
  const bool has_grip = it != steps.end();
  if (has_grip) std::rotate(steps.begin(), it, steps.end());
  const std::vector<Visit> visits = visits_of(b, rings, steps);
  slicer::Stroke s;
  int at = 0;
  for (std::size_t i = 0; i < steps.size(); ++i) {
    const EdgePath& e = b.paths[static_cast<std::size_t>(steps[i].edge)];
    const Vec2 shift((steps[i].forward ? at : at - e.wrap) * l.period_mm, 0.0);
    at += steps[i].forward ? e.wrap : -e.wrap;
    const EdgePath p = oriented(e, steps[i].forward);
    if (i == 0) s.start_mm = p.pts.front() + shift;
    for (std::size_t k = 0; k < p.feats.size(); ++k)
      s.segments.push_back(slicer::line_to(p.pts[k + 1] + shift, p.feats[k]));
    const Visit& v = visits[i];
    const Vec2 centre = l.nodes[static_cast<std::size_t>(v.vertex)] + Vec2(at * l.period_mm, 0.0);
    for (const Segment& seg : node_hairpin(centre, rings, v.in_rad, v.sweep_rad, v.extend_rad)) {
      s.segments.push_back(seg);
    }
  }
  if (has_grip) {
    const int wrap = b.paths[static_cast<std::size_t>(b.grip_edge)].wrap;
    start_at(s, b.mark + Vec2((steps[0].forward ? 0 : -wrap) * l.period_mm, 0.0));
  }
  return s;
}

}  // namespace

std::vector<Segment> node_hairpin(const Vec2& c, const NodeRings& rings, double entry_rad,
                                  double sweep_rad, double extend_rad) {
  const auto& rho = rings.pass_mm;
  const int passes = static_cast<int>(rho.size());
  const double sign = sweep_rad >= 0 ? 1.0 : -1.0;
  const double h = rings.attach_mm - rho.back();
  const double margin = sign * std::min(h / rho.front(), std::abs(sweep_rad) / 4);
  const double exit_rad = entry_rad + sweep_rad;
  std::vector<Segment> out;
  out.push_back(slicer::line_to(c + rho.back() * slicer::unit_vector(entry_rad), Feature::Node));
  for (int j = passes - 1; j >= 0; --j) {
    const int leg = passes - 1 - j;  // 0 = outermost; even legs run towards the exit
    const double back =
        passes > 1 && extend_rad > 0 ? -sign * extend_rad : margin;  // inner legs turn here
    const double end = j == 0 ? exit_rad : (leg % 2 == 0 ? exit_rad - margin : entry_rad + back);
    const bool ccw = (leg % 2 == 0) == (sign > 0);
    out.push_back(
        slicer::arc_to(c + rho[static_cast<std::size_t>(j)] * slicer::unit_vector(end), c, ccw, Feature::Node));
    if (j > 0)
      out.push_back(
          slicer::line_to(c + rho[static_cast<std::size_t>(j - 1)] * slicer::unit_vector(end), Feature::Node));
  }
  out.push_back(slicer::line_to(c + rings.attach_mm * slicer::unit_vector(exit_rad), Feature::Node));
  return out;
}

std::vector<slicer::Stroke> chiral_layer(const ChiralLattice& lattice, const NodeRings& rings,
                                         const StrandSpec& spec) {
  const Built b = build_graph(lattice, rings, spec);
  std::vector<slicer::Stroke> strokes;
  for (auto& circuit : noncrossing_circuits(b.graph)) {
    slicer::Stroke s = assemble(b, lattice, rings, std::move(circuit));
    s.width_mm = spec.nozzle_mm;
    s.height_mm = spec.layer_height_mm;
    strokes.push_back(std::move(s));
  }
  return strokes;
}

}  // namespace strand::patterns
