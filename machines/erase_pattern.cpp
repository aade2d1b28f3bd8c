// Writing the erase sweeps (Scribit thesis: M109 to temperature, G4 dwell per disc step).
#include "machines/erase_pattern.h"

#include <cmath>

#include "machines/gcode_format.h"
#include "machines/pen_emitter.h"
#include "machines/plotter_kinematics.h"
#include "slicer/input_error.h"
#include "slicer/params.h"

namespace strand::machines {

std::string emit_erase_gcode(const MachineProfile& m, const slicer::Vec2& lo, const slicer::Vec2& hi,
                             const std::vector<std::string>& header) {
  const EraseSetup& e = m.plotter.pen.erase;
  if (!m.plotter.enabled || e.disc_diameter_mm <= 0.0) {
    throw InputError("erase: machine " + m.name + " has no erase disc (pen.erase.disc_diameter_mm)");
  }
  std::string out;
  const auto line = [&](const std::string& s) { out += s + "\n"; };
  const auto xy = [&](const slicer::Vec2& marker) {
    if (const auto why = unreachable_reason(m.plotter, marker)) {
      throw InputError("erase: marker position (" + slicer::short_number(std::round(marker.x())) + ", " +
                       slicer::short_number(std::round(marker.y())) + ") mm cannot be reached: " + *why);
    }
    const slicer::Vec2 a = to_axes(m.plotter.setup, marker);
    return " X" + fmt_fixed(a.x(), kPenAxisDecimals) + " Y" + fmt_fixed(a.y(), kPenAxisDecimals);
  };
  for (const auto& h : header) line(h.empty() ? ";" : "; " + h);
  for (const auto& s : m.start_gcode) line(s);
  line("G21");
  line("G90");
  line("G92" + xy(m.plotter.setup.home_mm) + " ; pen parked at the home mark");
  const double d = e.disc_diameter_mm;
  const int rows = std::max(1, static_cast<int>(std::ceil((hi.y() - lo.y()) / d)));
  const int steps = std::max(1, static_cast<int>(std::ceil((hi.x() - lo.x()) / d)));
  const std::string dwell = "G4 P" + fmt_fixed(e.dwell_s * 1000.0, 0);
  for (int r = 0; r < rows; ++r) {
    const double y = lo.y() + (r + 0.5) * d;
    const bool forward = r % 2 == 0;
    const auto disc_x = [&](int k) { return forward ? lo.x() + k * (hi.x() - lo.x()) / steps
                                                    : hi.x() - k * (hi.x() - lo.x()) / steps; };
    line("G0" + xy(slicer::Vec2(disc_x(0), y) - e.offset_mm) + " F" + fmt_feed(m.limits.travel_feed_mm_per_min));
    line("M109 S" + fmt_fixed(e.temperature_c, 0) + " ; heat the disc and wait");
    for (int k = 1; k <= steps; ++k) {
      line("G1" + xy(slicer::Vec2(disc_x(k), y) - e.offset_mm) + " F" + fmt_feed(e.feed_mm_per_min));
      line(dwell);
    }
  }
  line("M104 S0 ; disc heater off");
  line("G0" + xy(m.plotter.setup.home_mm) + " F" + fmt_feed(m.limits.travel_feed_mm_per_min));
  for (const auto& s : m.end_gcode) line(s);
  return out;
}

}  // namespace strand::machines
