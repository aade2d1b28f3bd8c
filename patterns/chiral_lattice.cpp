// Chiral lattice geometry: nodes, tangent ligaments, pass radii, border and clearances.
#include "patterns/chiral_lattice.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "slicer/units.h"

namespace strand::patterns {

using slicer::Vec2;

namespace {

Vec2 rotate(const Vec2& v, double rad) {
  const double c = std::cos(rad), s = std::sin(rad);
  return {c * v.x() - s * v.y(), s * v.x() + c * v.y()};
}

void centre(ChiralLattice& l) {
  Vec2 lo = l.nodes.front(), hi = l.nodes.front();
  for (const Vec2& p : l.nodes) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const Vec2 mid = (lo + hi) / 2;
  for (Vec2& p : l.nodes) p -= mid;
}

// Boundary of a (cols + 1) x (rows + 1) index grid, counter-clockwise from (0, 0).
std::vector<int> grid_boundary(int cols, int rows) {
  auto id = [&](int i, int j) { return j * (cols + 1) + i; };
  std::vector<int> b;
  for (int i = 0; i <= cols; ++i) b.push_back(id(i, 0));
  for (int j = 1; j <= rows; ++j) b.push_back(id(cols, j));
  for (int i = cols - 1; i >= 0; --i) b.push_back(id(i, rows));
  for (int j = rows - 1; j >= 1; --j) b.push_back(id(0, j));
  return b;
}

double segment_distance(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  if (slicer::segment_contact(a, b, c, d, 0.0) == slicer::Contact::Crossing) return 0.0;
  return std::min({slicer::point_segment_distance(a, c, d), slicer::point_segment_distance(b, c, d),
                   slicer::point_segment_distance(c, a, b),
                   slicer::point_segment_distance(d, a, b)});
}

}  // namespace

ChiralLattice tetrachiral_lattice(int cols, int rows, double cell_mm) {
  ChiralLattice l;
  l.cell_mm = cell_mm;
  auto id = [&](int i, int j) { return j * (cols + 1) + i; };
  for (int j = 0; j <= rows; ++j) {
    for (int i = 0; i <= cols; ++i) {
      l.nodes.emplace_back(i * cell_mm, j * cell_mm);
      if (i > 0) l.ligaments.emplace_back(id(i - 1, j), id(i, j));
      if (j > 0) l.ligaments.emplace_back(id(i, j - 1), id(i, j));
    }
  }
  l.boundary = grid_boundary(cols, rows);
  centre(l);
  return l;
}

namespace {

// Row-major ring lattice: `shift(j)` is row j's offset in cells, `neighbours_below(i, j)`
// the column indices (unwrapped, may leave [0, around)) of row j - 1's neighbours of (i, j).
template <class Shift, class Below>
ChiralLattice ring(int around, int rows, double cell_mm, double row_mm, Shift shift,
                   Below neighbours_below) {
  ChiralLattice l;
  l.cell_mm = cell_mm;
  l.period_mm = around * cell_mm;
  auto id = [&](int i, int j) { return j * around + i; };
  auto link = [&](int from_col, int from_row, int to) {  // from_col unwrapped
    const int wrapped = ((from_col % around) + around) % around;
    l.ligaments.emplace_back(id(wrapped, from_row), to);
    l.wraps.push_back(-(from_col - wrapped) / around);
  };
  for (int j = 0; j <= rows; ++j) {
    for (int i = 0; i < around; ++i) {
      const double x = (i + 0.5 + shift(j)) * cell_mm - l.period_mm / 2;
      l.nodes.emplace_back(x, (j - rows / 2.0) * row_mm);
      link(i - 1, j, id(i, j));
      if (j > 0) {
        for (int k : neighbours_below(i, j)) link(k, j - 1, id(i, j));
      }
    }
  }
  return l;
}

}  // namespace

ChiralLattice tetrachiral_ring(int around, int rows, double cell_mm) {
  return ring(around, rows, cell_mm, cell_mm, [](int) { return 0.0; },
              [](int i, int) { return std::vector<int>{i}; });
}

ChiralLattice hexachiral_ring(int around, int rows, double cell_mm) {
  // as hexachiral_lattice: below an odd row the neighbours are i, i + 1, below an even one
  // i - 1, i; rows shifted by a quarter cell either way keep the seam between nodes
  return ring(around, rows, cell_mm, cell_mm * std::sin(slicer::deg_to_rad(60.0)),
              [](int j) { return j % 2 == 0 ? -0.25 : 0.25; },
              [](int i, int j) {
                const int shift = (j - 1) % 2 == 0 ? 0 : -1;
                return std::vector<int>{i + shift, i + shift + 1};
              });
}

std::pair<Vec2, Vec2> ligament_nodes(const ChiralLattice& l, std::size_t k) {
  const auto [a, b] = l.ligaments[k];
  const int wrap = l.wraps.empty() ? 0 : l.wraps[k];
  return {l.nodes[static_cast<std::size_t>(a)],
          l.nodes[static_cast<std::size_t>(b)] + Vec2(wrap * l.period_mm, 0.0)};
}

ChiralLattice hexachiral_lattice(int cols, int rows, double cell_mm) {
  ChiralLattice l;
  l.cell_mm = cell_mm;
  const double row_mm = cell_mm * std::sin(slicer::deg_to_rad(60.0));
  auto id = [&](int i, int j) { return j * (cols + 1) + i; };
  for (int j = 0; j <= rows; ++j) {
    for (int i = 0; i <= cols; ++i) {
      l.nodes.emplace_back((i + 0.5 * (j % 2)) * cell_mm, j * row_mm);
      if (i > 0) l.ligaments.emplace_back(id(i - 1, j), id(i, j));
      if (j == 0) continue;
      // row j - 1 neighbours: even row below reaches i and i + 1, odd row below i - 1 and i
      const int shift = (j - 1) % 2 == 0 ? 0 : -1;
      for (int k : {i + shift, i + shift + 1}) {
        if (k >= 0 && k <= cols) l.ligaments.emplace_back(id(k, j - 1), id(i, j));
      }
    }
  }
  l.boundary = grid_boundary(cols, rows);
  centre(l);
  return l;
}

NodeRings node_rings(double core_mm, double nozzle_mm, double layer_height_mm, int passes) {
  NodeRings r;
  for (int k = 0; k < passes; ++k)
    r.pass_mm.push_back(core_mm / 2 + nozzle_mm / 2 + k * layer_height_mm);
  r.middle_mm = core_mm / 2 + nozzle_mm / 2 + (passes - 1) / 2.0 * layer_height_mm;
  r.attach_mm = r.pass_mm.back() + layer_height_mm;
  r.frame_mm = r.attach_mm + layer_height_mm;
  r.ring_width_mm = (passes - 1) * layer_height_mm + nozzle_mm;
  return r;
}

double ligament_angle_rad(double cell_mm, double radius_mm) {
  return std::asin(std::min(1.0, 2.0 * radius_mm / cell_mm));
}

std::pair<Vec2, Vec2> ligament_tangent(const Vec2& a, const Vec2& b, double radius_mm) {
  const Vec2 u = (b - a).normalized();
  const double alpha = ligament_angle_rad((b - a).norm(), radius_mm);
  const Vec2 ta = a + radius_mm * rotate(u, alpha - slicer::kPi / 2);
  return {ta, a + b - ta};  // point symmetry about the midpoint
}

std::vector<Vec2> border_polygon(const ChiralLattice& lattice, double offset_mm) {
  const auto& b = lattice.boundary;
  const std::size_t n = b.size();
  std::vector<Vec2> out;
  for (std::size_t k = 0; k < n; ++k) {
    const Vec2& p = lattice.nodes[static_cast<std::size_t>(b[(k + n - 1) % n])];
    const Vec2& v = lattice.nodes[static_cast<std::size_t>(b[k])];
    const Vec2& q = lattice.nodes[static_cast<std::size_t>(b[(k + 1) % n])];
    const Vec2 e1 = (v - p).normalized(), e2 = (q - v).normalized();
    const Vec2 n1(e1.y(), -e1.x()), n2(e2.y(), -e2.x());  // outward for a ccw cycle
    out.push_back(v + offset_mm * (n1 + n2) / (1.0 + n1.dot(n2)));
  }
  return out;
}

Clearance lattice_clearance(const ChiralLattice& lattice, const NodeRings& rings) {
  Clearance c{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  std::vector<std::pair<Vec2, Vec2>> segs;
  for (std::size_t k = 0; k < lattice.ligaments.size(); ++k) {
    const auto [pa, pb] = ligament_nodes(lattice, k);
    segs.push_back(ligament_tangent(pa, pb, rings.attach_mm));
  }
  for (std::size_t i = 0; i < segs.size(); ++i) {
    const auto [a, b] = lattice.ligaments[i];
    for (int n = 0; n < static_cast<int>(lattice.nodes.size()); ++n) {
      if (n == a || n == b) continue;
      const double dist = slicer::point_segment_distance(lattice.nodes[static_cast<std::size_t>(n)],
                                                         segs[i].first, segs[i].second);
      c.node_mm = std::min(c.node_mm, dist - rings.pass_mm.back());
    }
    for (std::size_t j = i + 1; j < segs.size(); ++j) {
      const auto [p, q] = lattice.ligaments[j];
      if (p == a || p == b || q == a || q == b) continue;
      c.ligament_mm = std::min(c.ligament_mm, segment_distance(segs[i].first, segs[i].second,
                                                               segs[j].first, segs[j].second));
    }
  }
  return c;
}

double min_cell_mm(ChiralLattice (*make)(int, int, double), const NodeRings& rings,
                   double nozzle_mm) {
  auto ok = [&](double cell) {
    // the ligament (length sqrt(l^2 - 4 R^2)) must be at least one bead long
    if (cell * cell - 4.0 * rings.attach_mm * rings.attach_mm < nozzle_mm * nozzle_mm) return false;
    const Clearance c = lattice_clearance(make(3, 3, cell), rings);
    return c.node_mm >= nozzle_mm && c.ligament_mm >= nozzle_mm;
  };
  double lo = 2.0 * rings.attach_mm, hi = lo + nozzle_mm;
  while (!ok(hi) && hi < 1e4) lo = hi, hi *= 2.0;
  while (hi - lo > 0.005) {
    const double mid = (lo + hi) / 2;
    (ok(mid) ? hi : lo) = mid;
  }
  return std::ceil(hi * 100.0 - 1e-9) / 100.0;
}

}  // namespace strand::patterns
