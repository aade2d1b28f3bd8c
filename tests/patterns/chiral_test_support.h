// Shared checks for the chiral generators: random valid parameter sets, and the
// properties read back from the emitted G-code (crossings, strands, size).
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <string>

#include "machines/profile.h"
#include "postprocess/inspect/crossings.h"
#include "postprocess/plan/estimate.h"
#include "postprocess/inspect/gcode_parser.h"
#include "patterns/registry.h"
#include "postprocess/plan/produce.h"
#include "slicer/input_error.h"
#include "slicer/params.h"
#include "tests/support/gcode_view.h"
#include "tests/support/wrap_checks.h"

namespace strand::patterns::chiral_testing {

struct Emitted {
  slicer::Toolpath toolpath;
  post::ParsedGcode parsed;
};

inline Emitted emit(const slicer::ParamTable& table,
                    slicer::Toolpath (*make)(const nlohmann::json&), const nlohmann::json& given) {
  Emitted e;
  e.toolpath = make(slicer::resolve_params(table, given));
  const auto m = machines::load_profile("deltawasp-2040-clay");
  const auto gcode =
      post::produce(e.toolpath, m, post::plan_options_from(e.toolpath, 0.01), "x.gcode").gcode;
  e.parsed = post::parse_gcode(gcode);
  return e;
}

// A random parameter set: nozzle, layer height, passes, core and grip drawn first, then a
// cell between the generator's limit and three times it, and a lattice that fits the delta.
inline nlohmann::json random_params(std::mt19937& rng, double (*min_cell)(const nlohmann::json&)) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double d = 0.2 + 0.6 * unit(rng);
  nlohmann::json p = {{"nozzle", d},
                      {"layer-height", d * (0.5 + 0.5 * unit(rng))},
                      {"node-core", 0.05 + 2.95 * unit(rng)},
                      {"node-passes", std::vector<int>{1, 3, 3, 5}[rng() % 4]},
                      {"grip", unit(rng) < 0.2 ? 0.0 : 2 * d + 8 * unit(rng)},
                      {"layers", 2}};
  const double lo = min_cell(p);
  p["cell"] = std::round((lo + 2 * lo * unit(rng)) * 100.0) / 100.0 + 0.01;
  const double cell = p["cell"].get<double>();
  const int max_cells = std::max(2, static_cast<int>(70.0 / cell));
  p["cols"] = 2 + static_cast<int>(rng() % static_cast<unsigned>(std::min(6, max_cells) - 1));
  p["rows"] = 2 + static_cast<int>(rng() % static_cast<unsigned>(std::min(8, max_cells) - 1));
  return p;
}

// Zero crossings, one strand per layer, and deposits spanning the reported size.
inline void expect_sound(const Emitted& e) {
  const auto c = post::find_contacts(e.parsed.program, 0.01, 1e-3);
  EXPECT_TRUE(c.crossings.empty())
      << c.crossings.size() << " crossings, first at " << c.crossings.front().at_mm.transpose();
  const auto est = post::estimate(e.parsed.program);
  ASSERT_EQ(est.layers.size(), e.toolpath.layers.size());
  for (const auto& l : est.layers) EXPECT_EQ(l.strands, 1) << "layer " << l.layer;
  double lo[2] = {1e9, 1e9}, hi[2] = {-1e9, -1e9};
  for (const auto& s : testing::deposit_segments(e.parsed.program)) {
    for (const auto& p : {s.a, s.b}) {
      for (int k = 0; k < 2; ++k) lo[k] = std::min(lo[k], p[k]), hi[k] = std::max(hi[k], p[k]);
    }
  }
  const auto& size = e.toolpath.derived.at("size_mm");
  const double d = e.toolpath.parameters.at("nozzle").get<double>();
  for (int k = 0; k < 2; ++k)
    EXPECT_NEAR(hi[k] - lo[k] + d, size[k].get<double>(), 0.01) << "axis " << k;
}

// A random `--wrap full` case: random_params plus a circumference of 2 to 12 cells (so some
// fit only after rounding down, a few not at all). Returns {values, period_mm}.
inline std::pair<nlohmann::json, double> random_wrap(std::mt19937& rng,
                                                     double (*min_cell)(const nlohmann::json&)) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  nlohmann::json p = random_params(rng, min_cell);
  p["rows"] = 2 + static_cast<int>(rng() % 4);
  return {p, p["cell"].get<double>() * (2.0 + 10.0 * unit(rng))};
}

// Thirty random sleeves of chiral generator `name`: each is sound on the cylinder with a
// multiple of `step` cells round it, each cell at least the smallest valid one; where the
// circumference is under `min_cells` smallest cells, an InputError instead. At least 20 made.
inline void expect_random_sleeves(const char* name, double (*min_cell)(const nlohmann::json&),
                                  int min_cells, int step, unsigned seed) {
  const auto* g = find_generator(name);
  std::mt19937 rng(seed);
  int made = 0;
  for (int i = 0; i < 30; ++i) {
    const auto [given, period] = random_wrap(rng, min_cell);
    SCOPED_TRACE(given.dump() + " period " + std::to_string(period));
    slicer::Toolpath t;
    try {
      t = g->generate_wrapped(slicer::resolve_params(g->table(), given), period);
    } catch (const InputError& e) {
      EXPECT_LT(period, min_cells * min_cell(given) + 1e-9) << e.what();
      continue;
    }
    ++made;
    testing::expect_sound_wrap(t, period);
    EXPECT_EQ(t.derived.at("cells_around").get<int>() % step, 0);
    EXPECT_GE(t.derived.at("cells_around").get<int>(), min_cells);
    EXPECT_GE(t.derived.at("cell_around_mm").get<double>(), min_cell(given) - 1e-9);
  }
  EXPECT_GE(made, 20);
}

}  // namespace strand::patterns::chiral_testing
