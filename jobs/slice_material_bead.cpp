// Centre beads for layers with material and no deposit (jobs/slice_material_bead.h).
#include "jobs/slice_material_bead.h"

#include <Eigen/Eigenvalues>

namespace strand::jobs {

namespace {

// The ring's long axis: the principal direction of its vertices.
slicer::Vec2 long_axis(const slicer::Ring& ring) {
  slicer::Vec2 mean = slicer::Vec2::Zero();
  for (const auto& p : ring) mean += p;
  mean /= static_cast<double>(ring.size());
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (const auto& p : ring) cov += (p - mean) * (p - mean).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(cov);
  return eig.eigenvectors().col(1);  // eigenvalues ascending: the largest spread
}

}  // namespace

std::vector<slicer::Stroke> material_beads(const slicer::Region& region, double nozzle_mm,
                                           double layer_height_mm) {
  std::vector<slicer::Stroke> out;
  for (const slicer::RegionPart& shrunk : slicer::offset_region(region, -nozzle_mm / 4.0)) {
    const slicer::Ring& ring = shrunk.outer;
    if (ring.size() < 2) continue;
    const slicer::Vec2 axis = long_axis(ring);
    std::size_t lo = 0, hi = 0;
    for (std::size_t i = 1; i < ring.size(); ++i) {
      if (ring[i].dot(axis) < ring[lo].dot(axis)) lo = i;
      if (ring[i].dot(axis) > ring[hi].dot(axis)) hi = i;
    }
    slicer::Stroke s;
    s.start_mm = ring[lo];
    s.width_mm = nozzle_mm;
    s.height_mm = layer_height_mm;
    for (std::size_t i = lo; i != hi;) {
      i = (i + 1) % ring.size();
      s.segments.push_back(slicer::line_to(ring[i], slicer::Feature::Wall));
    }
    if (!s.segments.empty()) out.push_back(std::move(s));
  }
  return out;
}

}  // namespace strand::jobs
