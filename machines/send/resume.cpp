// Modal state of a G-code file up to a line, and the commands that restore it or make the
// machine safe.
#include "machines/send/resume.h"

#include <cctype>
#include <cstdlib>
#include <map>

#include "machines/gcode_format.h"
#include "machines/pen_emitter.h"

namespace strand::machines {

namespace {

// Word letter -> value of a command ("G1 X5 Y-2.5" -> G:1 X:5 Y:-2.5); first of each letter.
std::map<char, double> words(const std::string& c) {
  std::map<char, double> w;
  for (std::size_t i = 0; i < c.size();) {
    const char letter = static_cast<char>(std::toupper(static_cast<unsigned char>(c[i])));
    if (!std::isalpha(static_cast<unsigned char>(c[i]))) {
      ++i;
      continue;
    }
    char* end = nullptr;
    const double v = std::strtod(c.c_str() + i + 1, &end);
    const std::size_t used = static_cast<std::size_t>(end - (c.c_str() + i + 1));
    if (used > 0 && !w.count(letter)) w[letter] = v;
    i += 1 + used;
  }
  return w;
}

// Which state a command sets, or "" when it is no tool-state command.
std::string family(const std::map<char, double>& w, const std::string& text, const MachineProfile& m) {
  for (const auto& on : m.deposition.on_gcode) {
    if (text == on) return "valve";
  }
  for (const auto& off : m.deposition.off_gcode) {
    if (text == off) return "valve";
  }
  if (w.count('T') && !w.count('G') && !w.count('M')) return "tool";
  if (!w.count('M')) return "";
  const int code = static_cast<int>(w.at('M'));
  if (code == 3 || code == 4 || code == 5) return "spindle";
  if (code == 280) return "servo " + std::to_string(w.count('P') ? static_cast<int>(w.at('P')) : 0);
  if (code == 106 || code == 107) return "fan";
  return "";
}

void move(ModalState& s, const std::map<char, double>& w) {
  const auto axis = [&](char k, std::optional<double>& v) {
    if (!w.count(k)) return;
    v = (s.relative || (k == 'E' && s.relative_e.value_or(false))) ? v.value_or(0.0) + w.at(k) : w.at(k);
  };
  axis('X', s.x);
  axis('Y', s.y);
  axis('Z', s.z);
  axis('E', s.e);
  if (w.count('F')) s.f = w.at('F');
}

}  // namespace

ModalState modal_state_before(const std::vector<Command>& commands, int file_line, const MachineProfile& m) {
  ModalState s;
  std::map<std::string, std::string> tools;  // family -> last command
  std::vector<std::string> order;            // families in order of first use
  for (const auto& c : commands) {
    if (c.file_line >= file_line) break;
    const auto w = words(c.text);
    const int g = w.count('G') ? static_cast<int>(w.at('G')) : -1;
    if (g == 20 || g == 21) s.inches = g == 20;
    if (g == 90 || g == 91) s.relative = g == 91;
    if (g >= 0 && g <= 3) move(s, w);
    if (g == 92) {
      for (char k : {'X', 'Y', 'Z', 'E'}) {
        if (!w.count(k)) continue;
        (k == 'X' ? s.x : k == 'Y' ? s.y : k == 'Z' ? s.z : s.e) = w.at(k);
      }
    }
    if (w.count('M') && (w.at('M') == 82 || w.at('M') == 83)) s.relative_e = w.at('M') == 83;
    const std::string f = family(w, c.text, m);
    if (f.empty()) continue;
    if (!tools.count(f)) order.push_back(f);
    tools[f] = c.text;
  }
  for (const auto& f : order) s.tool_state.push_back(tools.at(f));
  return s;
}

std::vector<std::string> safe_state_gcode(const MachineProfile& m, const ModalState&) {
  if (m.plotter.enabled) {
    if (m.plotter.pen.lift == PenLift::Drum) return {"M400"};  // the drum's rest angle depends on the marker
    return {pen_lift_command(m, true)};
  }
  if (m.deposition.model == DepositionModel::Valve) return m.deposition.off_gcode;
  return {};
}

std::vector<std::string> resume_preamble(const MachineProfile& m, const ModalState& s) {
  std::vector<std::string> out = {s.inches ? "G20" : "G21", "G90"};
  if (s.relative_e) out.push_back(*s.relative_e ? "M83" : "M82");
  for (const auto& c : safe_state_gcode(m, s)) out.push_back(c);
  const bool pen_z = m.plotter.enabled && m.plotter.pen.lift != PenLift::Servo;  // Z is the pen (or drum)
  const std::string travel = " F" + fmt_feed(m.limits.travel_feed_mm_per_min);
  if (s.z && !m.plotter.enabled) out.push_back("G0 Z" + fmt_fixed(*s.z + m.travel_lift_mm, 3) + travel);
  if (s.x && s.y) out.push_back("G0 X" + fmt_fixed(*s.x, 3) + " Y" + fmt_fixed(*s.y, 3) + travel);
  if (s.z && (!m.plotter.enabled || (pen_z && m.plotter.pen.lift == PenLift::Z))) out.push_back("G0 Z" + fmt_fixed(*s.z, 3));
  if (s.e) out.push_back("G92 E" + fmt_fixed(*s.e, 5));
  if (s.f) out.push_back((m.firmware == Firmware::Grbl ? "F" : "G1 F") + fmt_feed(*s.f));
  for (const auto& t : s.tool_state) out.push_back(t);
  if (s.relative) out.push_back("G91");
  return out;
}

}  // namespace strand::machines
