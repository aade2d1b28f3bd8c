// Log-pile scaffold wrapped round a cylinder (`--wrap full`). Layers at 90 deg lay lines
// along the axis, a whole number of them round the circumference, in one serpentine whose
// U-turns lie beyond the two ends; layers at 0 deg lay one continuous helix whose lead is
// the pitch, so neighbouring turns lie a pitch apart like the flat filaments, with no U-turn
// and no seam (closed rings would need a step where the strand meets itself). Each layer
// starts where the previous one ended, through a short link at the cylinder's ends.
#include <cmath>

#include "patterns/scaffold.h"
#include "patterns/wrap_fit.h"
#include "slicer/input_error.h"
#include "slicer/params.h"

namespace strand::patterns {

using slicer::Feature;
using slicer::Stroke;
using slicer::Vec2;

namespace {

// A helix turn is drawn as this many segments, so no segment spans half the period and each
// maps round the cylinder without ambiguity.
constexpr int kHelixSegmentsPerTurn = 4;

struct Ring {
  double period_mm = 0.0;
  int lines = 0;               // axial lines round the circumference
  double line_pitch_mm = 0.0;  // period / lines
  double axial_half_mm = 0.0;  // axial lines and U-turns run to +-this (footprint + overhang)
  double helix_half_mm = 0.0;  // the helix runs between +-this: the outer filament centres
  double pitch_mm = 0.0;       // helix lead, along the axis
  int helix_turns = 0;
};

double wrapped(double x, double period) { return x - period * std::floor(x / period + 0.5); }

void add_line(Stroke& s, const Vec2& to, Feature f) {
  if ((to - s.end_mm()).norm() > 1e-9) s.segments.push_back(slicer::line_to(to, f));
}

// One helix from the end of the axis `at` is nearer to, towards the other end, x increasing.
void add_helix(Stroke& s, const Ring& r) {
  const bool from_top = s.end_mm().y() > 0;
  const double dir = from_top ? -1.0 : 1.0;
  const Vec2 start(s.end_mm().x(), -dir * r.helix_half_mm);
  add_line(s, start, Feature::Link);
  const int steps = r.helix_turns * kHelixSegmentsPerTurn;
  for (int k = 1; k <= steps; ++k) {
    const double f = static_cast<double>(k) / kHelixSegmentsPerTurn;  // turns so far
    s.segments.push_back(
        slicer::line_to(start + Vec2(f * r.period_mm, dir * f * r.pitch_mm), Feature::Infill));
  }
}

// The serpentine of axial lines from the line nearest the stroke's end, x increasing.
void add_axial(Stroke& s, const Ring& r) {
  const Vec2 at = s.end_mm();
  const double side = at.y() > 0 ? 1.0 : -1.0;
  const double half = r.period_mm / 2;
  const double k = std::round((at.x() + half) / r.line_pitch_mm - 0.5);
  const double x0 = -half + (k + 0.5) * r.line_pitch_mm;
  add_line(s, Vec2(x0, side * r.axial_half_mm), Feature::Link);
  double y = side * r.axial_half_mm;
  for (int j = 0; j < r.lines; ++j) {
    const double x = x0 + j * r.line_pitch_mm;
    if (j > 0) add_line(s, Vec2(x, y), Feature::Infill);  // U-turn beyond the end
    y = -y;
    add_line(s, Vec2(x, y), Feature::Infill);
  }
}

bool is_axial(double angle_deg) { return std::abs(std::remainder(angle_deg - 90.0, 180.0)) < 1e-9; }

void check_angles(const ScaffoldParams& p) {
  if (p.grade.axis != GradeAxis::None || p.stagger || !p.schedule.empty()) {
    throw InputError(std::string("scaffold.") + (p.stagger ? "stagger" : p.schedule.empty() ? "grade" : "schedule") +
                     ": with --wrap full the scaffold keeps one gap, one cycle and no stagger "
                     "(graded, staggered and scheduled piles are flat)");
  }
  for (double a : p.angles_deg) {
    if (!is_axial(a) && std::abs(std::remainder(a, 180.0)) >= 1e-9) {
      throw InputError(slicer::problem(
          "scaffold", "angles", p.angles_deg,
          "with --wrap full each angle must be 0 (one helix round the cylinder) or 90 "
          "(lines along its axis), mod 180",
          "deg"));
    }
  }
}

void add_ring_report(nlohmann::json& d, const Ring& r, const WrapFit& fit) {
  d["porosity_formula"] =
      "1 - (filament length inside the footprint * bead area) / (circumference * length * "
      "height)";
  d["axial_lines"] = r.lines;
  d["axial_line_pitch_mm"] = r.line_pitch_mm;
  d["helix_turns"] = r.helix_turns;
  d["helix_lead_mm"] = r.pitch_mm;
  d["strands_per_layer"] = 1;
  add_wrap_report(d, fit, "pitch of the lines along the axis");
}

}  // namespace

slicer::Toolpath generate_scaffold_wrapped(const ScaffoldParams& p, double period_mm) {
  check_angles(p);
  const WrapFit fit = fit_around("scaffold", period_mm, p.pitch_mm,
                                 {3, 1, 5000, p.nozzle_mm, "lines along the axis"});
  const ScaffoldGeometry g = scaffold_geometry(p);
  Ring r{period_mm,
         fit.cells,
         fit.cell_mm,
         g.depth_mm / 2 + p.overhang_mm,
         (g.filaments_y - 1) * p.pitch_mm / 2,
         p.pitch_mm,
         g.filaments_y - 1};
  slicer::Toolpath t;
  t.generator = "scaffold";
  // the first layer starts at the bottom end, where its own path begins (no link)
  Vec2 at(-period_mm / 2 + r.line_pitch_mm / 2,
          is_axial(p.angles_deg.front()) ? -r.axial_half_mm : -r.helix_half_mm);
  double inside_mm = 0.0;
  nlohmann::json per_layer = nlohmann::json::array();
  for (int k = 0; k < p.layers; ++k) {
    const bool axial = is_axial(p.angles_deg[static_cast<std::size_t>(k) % p.angles_deg.size()]);
    Stroke s;
    s.start_mm = Vec2(wrapped(at.x(), period_mm), at.y());  // the same point, in one period
    if (axial) {
      add_axial(s, r);
    } else {
      add_helix(s, r);
    }
    s.width_mm = p.nozzle_mm;
    s.height_mm = p.layer_height_mm;
    at = s.end_mm();
    inside_mm += axial ? r.lines * g.depth_mm : r.helix_turns * std::hypot(period_mm, p.pitch_mm);
    if (k < static_cast<int>(p.angles_deg.size()))
      per_layer.push_back(axial ? r.lines : g.filaments_y);
    t.layers.push_back({(k + 1) * p.layer_height_mm, p.layer_height_mm, {std::move(s)}});
  }
  t.derived = scaffold_report(p, g, period_mm, per_layer, inside_mm);
  add_ring_report(t.derived, r, fit);
  return t;
}

}  // namespace strand::patterns
