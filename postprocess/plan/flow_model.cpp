// Hagen-Poiseuille and its power-law form, in SI inside (m, Pa, m^3/s).
#include "postprocess/plan/flow_model.h"

#include <cmath>

#include "slicer/units.h"

namespace strand::post {

namespace {

constexpr double kM3PerMm3 = 1e-9;
constexpr double kMPerMm = 1e-3;

}  // namespace

double flow_mm3_per_s(const Rheology& ink, const Nozzle& nz, double dp_pa) {
  const double r = nz.radius_mm * kMPerMm;
  const double l = nz.length_mm * kMPerMm;
  double q_m3 = 0.0;
  if (!ink.power_law) {
    q_m3 = slicer::kPi * std::pow(r, 4) * dp_pa / (8.0 * ink.viscosity_pa_s * l);
  } else {
    const double n = ink.n;
    q_m3 = slicer::kPi * n * std::pow(r, 3) / (3.0 * n + 1.0) *
           std::pow(r * dp_pa / (2.0 * ink.k_pa_sn * l), 1.0 / n);
  }
  return q_m3 / kM3PerMm3;
}

double pressure_pa_for(const Rheology& ink, const Nozzle& nz, double q_mm3_per_s) {
  const double r = nz.radius_mm * kMPerMm;
  const double l = nz.length_mm * kMPerMm;
  const double q = q_mm3_per_s * kM3PerMm3;
  if (!ink.power_law) return 8.0 * ink.viscosity_pa_s * l * q / (slicer::kPi * std::pow(r, 4));
  const double n = ink.n;
  return 2.0 * ink.k_pa_sn * l / r *
         std::pow(q * (3.0 * n + 1.0) / (slicer::kPi * n * std::pow(r, 3)), n);
}

double speed_mm_per_min(double q_mm3_per_s, double area_mm2) {
  return slicer::mm_per_s_to_mm_per_min(q_mm3_per_s / area_mm2);
}

double flow_for_speed_mm3_per_s(double speed_mm_per_min, double area_mm2) {
  return slicer::mm_per_min_to_mm_per_s(speed_mm_per_min) * area_mm2;
}

}  // namespace strand::post
