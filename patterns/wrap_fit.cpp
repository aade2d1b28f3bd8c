// Whole cells around a circumference: nearest count, adjusted cell, and the limits.
#include "patterns/wrap_fit.h"

#include <algorithm>
#include <cmath>

#include "slicer/input_error.h"
#include "slicer/params.h"

namespace strand::patterns {

namespace {

std::string mm(double v) { return slicer::short_number(std::round(v * 1000.0) / 1000.0) + " mm"; }

std::string count_text(const WrapRule& rule) {
  std::string t = "at least " + std::to_string(rule.min_cells) + " cells around";
  if (!rule.count_why.empty()) t += " (" + rule.count_why + ")";
  return t;
}

}  // namespace

WrapFit fit_around(const std::string& table, double period_mm, double cell_mm,
                   const WrapRule& rule) {
  const std::string head = table + ".wrap = full: ";
  if (!std::isfinite(period_mm) || period_mm <= 0.0) {
    throw InputError(head + "the circumference must be > 0 mm (got " +
                     slicer::short_number(period_mm) + ")");
  }
  const double ratio = period_mm / cell_mm;
  if (!std::isfinite(ratio) || ratio > 10.0 * rule.max_cells) {
    throw InputError(head + "a " + mm(period_mm) + " circumference at a " + mm(cell_mm) +
                     " cell needs more than " + std::to_string(rule.max_cells) +
                     " cells around (the limit)");
  }
  int n = std::max(rule.min_cells, rule.step * static_cast<int>(std::lround(ratio / rule.step)));
  while (n - rule.step >= rule.min_cells && period_mm / n < rule.min_cell_mm) n -= rule.step;
  while (period_mm / n > rule.max_cell_mm && n <= rule.max_cells) n += rule.step;
  if (period_mm / n < rule.min_cell_mm && period_mm / (n - rule.step) > rule.max_cell_mm &&
      n > rule.min_cells) {
    throw InputError(head + "a " + mm(period_mm) + " circumference holds no whole number of " +
                     "cells" + (rule.count_why.empty() ? "" : " (" + rule.count_why + ")") +
                     " between " + mm(rule.min_cell_mm) + " and " + mm(rule.max_cell_mm) +
                     "; change the circumference or the cell");
  }
  if (period_mm / n < rule.min_cell_mm) {
    throw InputError(head + "a " + mm(period_mm) +
                     " circumference is too small: " + count_text(rule) + " of at least " +
                     mm(rule.min_cell_mm) + " need " + mm(rule.min_cells * rule.min_cell_mm));
  }
  if (n > rule.max_cells) {
    throw InputError(head + "a " + mm(period_mm) + " circumference at a " + mm(cell_mm) +
                     " cell needs " + std::to_string(n) + " cells around, at most " +
                     std::to_string(rule.max_cells) + " allowed");
  }
  return {period_mm, n, period_mm / n, cell_mm};
}

void add_wrap_report(nlohmann::json& derived, const WrapFit& fit, const std::string& what) {
  derived["wrap_period_mm"] = fit.period_mm;
  derived["cells_around"] = fit.cells;
  derived["cell_around_mm"] = fit.cell_mm;
  derived["cell_around_requested_mm"] = fit.requested_cell_mm;
  derived["wrap_fit"] = what + " adjusted from " + slicer::short_number(fit.requested_cell_mm) +
                        " to " + slicer::short_number(std::round(fit.cell_mm * 1e4) / 1e4) +
                        " mm so " + std::to_string(fit.cells) +
                        " cells close round the circumference";
}

}  // namespace strand::patterns
