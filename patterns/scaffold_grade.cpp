// Graded gaps: the grade's value along its axis and the filament positions it gives.
#include "patterns/scaffold_grade.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace strand::patterns {

double GapGrade::at(double fraction) const {
  if (gaps_mm.empty()) return 0.0;
  const double f = std::clamp(fraction, 0.0, 1.0);
  if (linear) return gaps_mm.front() + f * (gaps_mm.back() - gaps_mm.front());
  const auto zones = gaps_mm.size();
  const auto zone = std::min(zones - 1, static_cast<std::size_t>(f * static_cast<double>(zones)));
  return gaps_mm[zone];
}

double GapGrade::mean_mm() const {
  if (gaps_mm.empty()) return 0.0;
  return std::accumulate(gaps_mm.begin(), gaps_mm.end(), 0.0) / static_cast<double>(gaps_mm.size());
}

std::vector<double> graded_centres_mm(const GapGrade& grade, double nozzle_mm, double length_mm) {
  std::vector<double> centres = {nozzle_mm / 2};
  // The side grows by at least a nozzle per filament: stop once it is past the length.
  while (centres.size() < 2 || centres.back() + nozzle_mm / 2 < length_mm) {
    const double c = centres.back();
    centres.push_back(c + nozzle_mm + grade.at((c + nozzle_mm / 2) / length_mm));
  }
  const double over = centres.back() + nozzle_mm / 2 - length_mm;
  const double under = length_mm - (centres[centres.size() - 2] + nozzle_mm / 2);
  if (centres.size() > 2 && under <= over) centres.pop_back();
  return centres;
}

std::vector<double> graded_offsets_mm(const GapGrade& grade, double nozzle_mm, double n_axis,
                                      double side_mm, double length_mm, double reach_mm) {
  // t runs along the normal, signed to grow along the axis; a line at t crosses the centre
  // line at t / |n_axis| from the footprint's middle.
  const double a = std::abs(n_axis);
  const double d = nozzle_mm;
  const double t0 = -a * side_mm / 2 + d / 2;
  std::vector<double> t;
  for (double at = t0; at <= reach_mm + 1e-9;) {
    t.push_back(at);
    const double gap_start = (at + d / 2) / a + side_mm / 2;  // from the low edge
    at += d + grade.at(gap_start / length_mm);
  }
  for (double at = t0 - d - grade.at(0.0); at >= -reach_mm - 1e-9; at -= d + grade.at(0.0)) t.push_back(at);
  std::vector<double> offsets;
  for (double v : t) offsets.push_back(n_axis > 0 ? v : -v);
  std::sort(offsets.begin(), offsets.end());
  return offsets;
}

}  // namespace strand::patterns
