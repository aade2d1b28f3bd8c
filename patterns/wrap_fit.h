// Fitting a lattice round a cylinder for `--wrap full`: a whole number of cells around the
// circumference (the period of u), the cell adjusted to fit, and the figures every wrapped
// design reports in Toolpath::derived.
#pragma once

#include <limits>
#include <nlohmann/json.hpp>
#include <string>

namespace strand::patterns {

// What a design allows around the circumference.
struct WrapRule {
  int min_cells = 3;         // fewest cells around
  int step = 1;              // the count must be a multiple of this (2: even)
  int max_cells = 500;       // bound on work, as the flat designs bound their cols
  double min_cell_mm = 0.0;  // smallest valid cell after fitting
  std::string count_why;     // why the count is constrained, shown in messages
  double max_cell_mm = std::numeric_limits<double>::infinity();  // largest valid cell
};

struct WrapFit {
  double period_mm = 0.0;          // circumference where u is measured
  int cells = 0;                   // cells around
  double cell_mm = 0.0;            // period / cells: the adjusted cell (or pitch)
  double requested_cell_mm = 0.0;  // what the parameters asked for
};

// The multiple of rule.step nearest period / cell, rounded down instead when that cell would
// be smaller than rule.min_cell_mm, up when larger than rule.max_cell_mm. Throws InputError
// "<table>.wrap = full: ..." naming the limit when no count in [min_cells, max_cells] fits,
// or the period is not positive.
WrapFit fit_around(const std::string& table, double period_mm, double cell_mm,
                   const WrapRule& rule);

// Adds wrap_period_mm, cells_around, cell_around_mm (adjusted), cell_around_requested_mm and
// wrap_fit (one sentence: `what` the cell is, and that it was adjusted to fit).
void add_wrap_report(nlohmann::json& derived, const WrapFit& fit, const std::string& what);

}  // namespace strand::patterns
