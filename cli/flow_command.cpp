// `strand flow`: pneumatic syringe flow model both ways (pressure -> flow -> speed, and
// speed -> flow -> pressure) for a bead of given section.
#include <cmath>
#include <iostream>
#include <memory>
#include <optional>

#include "machines/gcode_format.h"
#include "postprocess/plan/flow_model.h"
#include "cli/param_flags.h"
#include "cli/commands.h"
#include "slicer/input_error.h"
#include "slicer/params.h"
#include "slicer/toolpath.h"

namespace strand::cli {

namespace {

struct FlowArgs {
  std::optional<double> pressure_bar, viscosity_pa_s, k_pa_sn, n, speed_mm_per_min;
  std::optional<double> bead_width_mm, bead_height_mm;
  double nozzle_mm = 0.0;
  double nozzle_length_mm = 0.0;
};

void positive(const char* key, std::optional<double> v, const char* unit,
              std::vector<std::string>& problems) {
  if (v && !(*v > 0.0 && std::isfinite(*v))) {
    problems.push_back(std::string("flow.") + key + " = " + slicer::short_number(*v) +
                       ": must be a finite number > 0 (" + unit + ")");
  }
}

post::Rheology rheology(const FlowArgs& a, std::vector<std::string>& problems) {
  post::Rheology ink;
  const bool newtonian = a.viscosity_pa_s.has_value();
  const bool power = a.k_pa_sn.has_value() || a.n.has_value();
  if (newtonian == power) {
    problems.push_back("flow.viscosity-pa-s: give --viscosity-pa-s (Newtonian) or --k-pa-sn with --n (power law), exactly one");
    return ink;
  }
  if (power && !(a.k_pa_sn && a.n)) problems.push_back("flow.n: a power-law ink needs both --k-pa-sn and --n");
  if (a.n && !(*a.n > 0.0 && *a.n <= 2.0)) problems.push_back("flow.n = " + slicer::short_number(*a.n) + ": must be in (0, 2] (shear thinning < 1)");
  ink.power_law = power;
  ink.viscosity_pa_s = a.viscosity_pa_s.value_or(1.0);
  ink.k_pa_sn = a.k_pa_sn.value_or(1.0);
  ink.n = a.n.value_or(1.0);
  return ink;
}

int run_flow(const FlowArgs& a) {
  std::vector<std::string> problems;
  positive("nozzle-mm", a.nozzle_mm, "mm", problems);
  positive("nozzle-length-mm", a.nozzle_length_mm, "mm", problems);
  positive("pressure-bar", a.pressure_bar, "bar", problems);
  positive("viscosity-pa-s", a.viscosity_pa_s, "Pa.s", problems);
  positive("k-pa-sn", a.k_pa_sn, "Pa.s^n", problems);
  positive("speed", a.speed_mm_per_min, "mm/min", problems);
  positive("bead-width", a.bead_width_mm, "mm", problems);
  positive("bead-height", a.bead_height_mm, "mm", problems);
  if (!a.pressure_bar && !a.speed_mm_per_min) problems.push_back("flow.pressure-bar: give --pressure-bar (-> speed) and/or --speed (-> pressure)");
  const post::Rheology ink = rheology(a, problems);
  const double w = a.bead_width_mm.value_or(a.nozzle_mm);
  const double h = a.bead_height_mm.value_or(0.88 * a.nozzle_mm);
  if (problems.empty() && h > w) {
    problems.push_back("flow.bead-height = " + slicer::short_number(h) + ": must be <= bead width " +
                       slicer::short_number(w) + " (a squashed bead is not taller than wide) (mm)");
  }
  if (!problems.empty()) throw InputError(problems);

  const post::Nozzle nozzle{a.nozzle_mm / 2.0, a.nozzle_length_mm};
  const double area = slicer::bead_area_mm2(w, h);
  using machines::fmt_fixed;
  std::cout << "ink      " << (ink.power_law ? "power law K " + slicer::short_number(ink.k_pa_sn) + " Pa.s^n, n " + slicer::short_number(ink.n)
                                               : "Newtonian mu " + slicer::short_number(ink.viscosity_pa_s) + " Pa.s") << "\n";
  std::cout << "nozzle   d " << slicer::short_number(a.nozzle_mm) << " mm, L " << slicer::short_number(a.nozzle_length_mm) << " mm\n";
  std::cout << "bead     " << slicer::short_number(w) << " x " << slicer::short_number(h) << " mm, stadium section " << fmt_fixed(area, 4) << " mm2\n";
  if (a.pressure_bar) {
    const double q = post::flow_mm3_per_s(ink, nozzle, *a.pressure_bar * post::kPaPerBar);
    std::cout << "pressure " << slicer::short_number(*a.pressure_bar) << " bar -> flow " << fmt_fixed(q, 4) << " mm3/s -> speed "
              << fmt_fixed(post::speed_mm_per_min(q, area), 1) << " mm/min\n";
  }
  if (a.speed_mm_per_min) {
    const double q = post::flow_for_speed_mm3_per_s(*a.speed_mm_per_min, area);
    const double p = post::pressure_pa_for(ink, nozzle, q);
    std::cout << "speed    " << slicer::short_number(*a.speed_mm_per_min) << " mm/min -> flow " << fmt_fixed(q, 4) << " mm3/s -> pressure "
              << fmt_fixed(p / post::kPaPerBar, 4) << " bar\n";
  }
  std::cout << "model    fully developed laminar flow in the nozzle only (no syringe, entrance, slip or yield stress)\n";
  return 0;
}

}  // namespace

void add_flow_command(CLI::App& app, Action& action) {
  CLI::App* sub = app.add_subcommand("flow", "pneumatic syringe flow: pressure <-> print speed (Hagen-Poiseuille, power law)");
  auto a = std::make_shared<FlowArgs>();
  sub->add_option("--pressure-bar", a->pressure_bar, "pressure drop over the nozzle [bar] -> flow and speed");
  add_quantity_option(sub, "--speed", a->speed_mm_per_min, "mm/min", "wanted print speed [mm/min] -> flow and pressure");
  sub->add_option("--viscosity-pa-s", a->viscosity_pa_s, "Newtonian viscosity mu [Pa.s]");
  sub->add_option("--k-pa-sn", a->k_pa_sn, "power-law consistency K [Pa.s^n]");
  sub->add_option("--n", a->n, "power-law index n (< 1 shear thinning)");
  add_quantity_option(sub, "--nozzle-mm", a->nozzle_mm, "mm", "nozzle inner diameter [mm]")->required();
  add_quantity_option(sub, "--nozzle-length-mm", a->nozzle_length_mm, "mm", "nozzle (needle) length [mm]")->required();
  add_quantity_option(sub, "--bead-width", a->bead_width_mm, "mm", "bead width [mm] (default nozzle)");
  add_quantity_option(sub, "--bead-height,--layer-height", a->bead_height_mm, "mm", "bead height [mm] (default 0.88 * nozzle)");
  sub->callback([&action, a] { action = [a] { return run_flow(*a); }; });
}

}  // namespace strand::cli
