// Pneumatic syringe flow: volumetric flow through a cylindrical nozzle from the applied
// pressure and the ink's rheology, the print speed that flow sustains for a bead, and the
// reverse (pressure for a wanted speed). Fully developed laminar flow, no wall slip, no
// entrance losses or yield stress.
#pragma once

namespace strand::post {

// Newtonian ink (mu) or power-law ink (tau = K * shear_rate^n; n < 1 shear thinning).
struct Rheology {
  bool power_law = false;
  double viscosity_pa_s = 1.0;   // Newtonian mu
  double k_pa_sn = 1.0;          // power-law consistency K, Pa.s^n
  double n = 1.0;                // power-law index
};

struct Nozzle {
  double radius_mm = 0.25;
  double length_mm = 10.0;
};

// Volumetric flow for a pressure drop over the nozzle, mm3/s.
// Newtonian (Hagen-Poiseuille): Q = pi r^4 dP / (8 mu L).
// Power law: Q = (pi n r^3 / (3n + 1)) (r dP / (2 K L))^(1/n).
double flow_mm3_per_s(const Rheology& ink, const Nozzle& nozzle, double pressure_pa);
// The inverse: pressure drop that gives flow q_mm3_per_s, Pa.
double pressure_pa_for(const Rheology& ink, const Nozzle& nozzle, double q_mm3_per_s);

// Bead speed that deposits flow q into a bead of section area_mm2: v = Q / A, mm/min.
double speed_mm_per_min(double q_mm3_per_s, double area_mm2);
// Flow needed for a bead of section area_mm2 at speed v, mm3/s.
double flow_for_speed_mm3_per_s(double speed_mm_per_min, double area_mm2);

constexpr double kPaPerBar = 1e5;

}  // namespace strand::post
