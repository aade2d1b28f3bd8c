// Pen up/down from plotter commands: the profile's servo values when given, else the
// conventions of the programs that write these files; Z-lift drawings read by their heights
// (parse_drawing, declared in gcode_parser.h).
#include "postprocess/inspect/pen_reading.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>

#include "postprocess/inspect/gcode_parser.h"
#include "slicer/params.h"

namespace strand::post {

namespace {

// Without a profile. M300 S: the MakerBot Unicorn convention (Inkscape's Unicorn extension
// and the Arduino plotters that read it): S30 or S40 down, S50 up. M280 S: Makelangelo's
// Marlin polargraph, S40 down and S90 up (Strand's own plotters: S30 and S90).
constexpr double kM300DownBelow = 45.0;
constexpr double kM280DownBelow = 65.0;

bool nearer_down(const PenReading& r, double s) {
  return std::abs(s - *r.down_value) < std::abs(s - *r.up_value);
}

bool from_profile(const PenReading& r) { return r.down_value && r.up_value; }

}  // namespace

namespace {

// "M62 P0 ; open" -> (62, 0); nullopt for anything but M62-M65.
std::optional<std::pair<int, std::optional<double>>> output_command(const std::string& line) {
  int m = 0;
  if (line.size() < 3 || (line[0] != 'M' && line[0] != 'm')) return std::nullopt;
  const auto r = std::from_chars(line.data() + 1, line.data() + line.size(), m);
  if (r.ec != std::errc() || m < 62 || m > 65) return std::nullopt;
  std::optional<double> p;
  const std::size_t at = line.find_first_of("Pp");
  const std::size_t semi = line.find(';');
  if (at != std::string::npos && at < semi) {
    double v = 0;
    if (std::from_chars(line.data() + at + 1, line.data() + line.size(), v).ec == std::errc())
      p = v;
  }
  return std::pair{m, p};
}

}  // namespace

PenReading pen_reading_from(const machines::MachineProfile& m) {
  PenReading r;
  const auto& d = m.deposition;
  if (d.model == machines::DepositionModel::Valve && !d.on_gcode.empty() && !d.off_gcode.empty()) {
    const auto on = output_command(d.on_gcode.front());
    const auto off = output_command(d.off_gcode.front());
    if (on && off && on->first != off->first) {
      r.valve_on_m = on->first;
      r.valve_off_m = off->first;
      r.valve_p = on->second;
    }
  }
  if (!m.plotter.enabled) return r;
  const machines::PenSetup& pen = m.plotter.pen;
  r.machine = m.name;
  if (pen.lift == machines::PenLift::Servo) {
    r.down_value = pen.down_value;
    r.up_value = pen.up_value;
    if (m.firmware != machines::Firmware::Grbl) r.servo_index = pen.servo_index;
  } else if (pen.lift == machines::PenLift::Z) {
    r.z_down_max_mm = (pen.z_down_mm + pen.z_up_mm) / 2.0;
  }
  return r;
}

std::optional<bool> pen_down_by_command(const PenReading& r, int m, std::optional<double> s,
                                        std::optional<double> p) {
  switch (m) {
    case 300:  // Marlin's M300 S<frequency> P<duration> is a beep; plotters send M300 S alone
      if (!s || p) return std::nullopt;
      return from_profile(r) ? nearer_down(r, *s) : *s < kM300DownBelow;
    case 280:
      if (!s) return std::nullopt;
      if (r.servo_index >= 0 && p && *p != r.servo_index) return std::nullopt;
      return from_profile(r) ? nearer_down(r, *s) : *s < kM280DownBelow;
    case 3:
    case 4:  // GRBL spindle (or laser) output driving the pen: on is down, S0 is off
      if (from_profile(r) && s) return nearer_down(r, *s);
      return !s || *s != 0.0;
    case 5:
      return false;
    default:
      return std::nullopt;
  }
}

std::string pen_convention(const PenReading& r, int m) {
  const std::string command = m == 300 ? "M300 S" : m == 280 ? "M280 S" : "M3/M5";
  if (from_profile(r)) {
    return "pen read from " + command + " with machine " + r.machine + "'s values (down " +
           slicer::short_number(*r.down_value) + ", up " + slicer::short_number(*r.up_value) + ")";
  }
  switch (m) {
    case 300:
      return "pen read from M300 S by the Unicorn plotter convention (S30 or S40 down, S50 up; "
             "below 45 is down): give --machine for other values";
    case 280:
      return "pen read from M280 S by Makelangelo's convention (S40 down, S90 up; below 65 is "
             "down): give --machine for other values";
    default:
      return "pen read from M3/M5 as a GRBL spindle: M3 down, M5 or M3 S0 up";
  }
}

std::optional<PenByZ> pen_by_z(const ParsedGcode& first, const PenReading& pen, double low,
                               double high) {
  if (first.has_e || first.pen_commands > 0 || pen.z_down_max_mm) return std::nullopt;
  if (!(high - low > kPenLiftMinMm)) return std::nullopt;  // one drawing height: nothing to lift
  PenByZ by_z{pen, {}};
  by_z.pen.z_down_max_mm = low + kPenLiftMinMm;
  by_z.note = {0, "pen read from Z: drawing moves above z " +
                      slicer::short_number(*by_z.pen.z_down_max_mm) +
                      " mm (the lowest drawing z + " + slicer::short_number(kPenLiftMinMm) +
                      " mm) are pen-up travels"};
  return by_z;
}

ParsedGcode parse_drawing(std::string_view text, const PenReading& pen) {
  ParsedGcode first = parse_gcode(text, pen);
  double low = std::numeric_limits<double>::infinity(), high = -low;
  for (const slicer::Move& m : first.program.moves) {
    if (m.kind != slicer::MoveKind::Deposit) continue;
    low = std::min(low, m.end_mm.z());
    high = std::max(high, m.end_mm.z());
  }
  const auto by_z = pen_by_z(first, pen, low, high);
  if (!by_z) return first;
  ParsedGcode second = parse_gcode(text, by_z->pen);
  second.notes.push_back(by_z->note);
  return second;
}

}  // namespace strand::post
