// Modal state of a G-code file up to a line, and the commands that restore it or make the
// machine safe.
#include "machines/send/resume.h"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "machines/gcode_format.h"
#include "machines/pen_emitter.h"

namespace strand::machines {

namespace {

// The words of one block: every G and M code (x10, so G59.1 is 591), and the first value of
// each other letter ("G1 X5 Y-2.5" -> g {10}, X 5, Y -2.5). Numbers are read without
// exponents: "X1E5" is X 1 and E 5, as firmware reads it.
struct Block {
  std::vector<int> g, m;
  std::map<char, double> w;
  bool has_g(int code10) const { return std::find(g.begin(), g.end(), code10) != g.end(); }
};

constexpr double kLargestWord = 1e12;

Block block_of(const std::string& c) {
  Block b;
  for (std::size_t i = 0; i < c.size();) {
    const char letter = static_cast<char>(std::toupper(static_cast<unsigned char>(c[i])));
    ++i;
    if (!std::isalpha(static_cast<unsigned char>(letter))) continue;
    std::size_t j = i;
    const bool negative = j < c.size() && c[j] == '-';
    if (j < c.size() && (c[j] == '-' || c[j] == '+')) ++j;
    double v = 0.0, scale = 1.0;
    bool digits = false, point = false;
    for (; j < c.size() && j - i < 40; ++j) {
      if (c[j] == '.' && !point) {
        point = true;
      } else if (std::isdigit(static_cast<unsigned char>(c[j]))) {
        digits = true;
        if (point) {
          scale /= 10.0;
          v += (c[j] - '0') * scale;
        } else {
          v = v * 10.0 + (c[j] - '0');
        }
      } else {
        break;
      }
    }
    if (!digits) continue;
    // No firmware has a word this large; bounding it keeps every integer conversion below
    // defined (a 40-digit "P555..." once overflowed a long).
    v = std::min(v, kLargestWord);
    if (negative) v = -v;
    i = j;
    // A code past any firmware's numbering is kept as an unknown code (-1): it sets no state.
    const int code10 = std::abs(v) < 100000.0 ? static_cast<int>(std::lround(v * 10)) : -1;
    if (letter == 'G') {
      b.g.push_back(code10);
    } else if (letter == 'M') {
      b.m.push_back(code10);
    } else if (!b.w.count(letter)) {
      b.w[letter] = v;
    }
  }
  return b;
}

std::string strip_comment(const std::string& c) {
  std::string s = c.substr(0, c.find(';'));
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.pop_back();
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.erase(0, 1);
  return s;
}

std::string index_word(const Block& b, char letter) {
  return b.w.count(letter) ? std::to_string(static_cast<long>(b.w.at(letter))) : "default";
}

// The states an M code sets ("pin P6", "fan 0"), empty for codes that set none.
std::vector<std::string> families_of_m(int code10, const Block& b) {
  switch (code10) {
    case 30:
    case 40:
    case 50:
      return {"spindle"};
    case 70:
    case 80:
    case 90:
      return {"coolant"};  // tracked as mist and flood, below
    case 420:
      return {"pin " + index_word(b, 'P')};  // Marlin / RRF M42 P<pin> S<value>
    case 620:
    case 630:
    case 640:
    case 650:
      return {"output " + index_word(b, 'P')};  // M62-M65
    case 1040:
    case 1090:
      return {"hotend " + index_word(b, 'T')};
    case 1060:
    case 1070:
      return {"fan " + index_word(b, 'P')};
    case 1400:
    case 1900:
      return {"bed"};
    case 1410:
    case 1910:
      return {"chamber"};
    case 2800:
      return {"servo " + index_word(b, 'P')};
    case 3020:
      return b.w.empty() ? std::vector<std::string>{}
                         : std::vector<std::string>{"cold extrusion"};  // M302 S0
    default:
      return {};
  }
}

// What to replay for M code `code10` of a block: the line itself, or (when the block also
// moves) just the M word with its S/P/T words, so replaying it moves nothing.
std::string replay_text(int code10, const Block& b, const std::string& text) {
  const bool moves = std::any_of(b.g.begin(), b.g.end(), [](int g) { return g >= 0 && g <= 30; });
  if (!moves && b.m.size() == 1) return text;
  std::string out = "M" + std::to_string(code10 / 10);
  for (char k : {'P', 'T', 'S'}) {
    if (!b.w.count(k)) continue;
    const double v = b.w.at(k);
    out += std::string(" ") + k +
           (v == std::round(v) ? std::to_string(std::lround(v)) : fmt_fixed(v, 3));
  }
  return out;
}

void move(ModalState& s, const Block& b) {
  const auto axis = [&](char k, std::optional<double>& v) {
    if (!b.w.count(k)) return;
    const bool rel = s.relative || (k == 'E' && s.relative_e.value_or(false));
    v = rel ? v.value_or(0.0) + b.w.at(k) : b.w.at(k);
  };
  axis('X', s.x);
  axis('Y', s.y);
  axis('Z', s.z);
  axis('E', s.e);
  for (char k : {'A', 'B', 'C'}) {
    if (!b.w.count(k)) continue;
    s.rotary[k] = s.relative ? (s.rotary.count(k) ? s.rotary[k] : 0.0) + b.w.at(k) : b.w.at(k);
  }
  if (b.w.count('F')) s.f = b.w.at('F');
}

}  // namespace

ModalState modal_state_before(const std::vector<Command>& commands, int file_line,
                              const MachineProfile& m) {
  ModalState s;
  std::map<std::string, std::string> tools;  // family -> last command
  std::vector<std::string> order;            // families in order of first use
  std::map<std::string, std::string> modes;  // "plane", "offset" -> G word
  std::vector<std::string> mode_order;
  bool mist = false, flood = false;  // coolant: M7, M8, M9 (both off)
  std::vector<std::string> valve;    // the profile's valve commands without comments
  for (const auto& list : {m.deposition.on_gcode, m.deposition.off_gcode}) {
    for (const auto& c : list) {
      const std::string t = strip_comment(c);
      const Block b = block_of(t);
      // waits (M400, G4) and moves in the valve sequence set no state
      if (!t.empty() && b.g.empty() &&
          !(b.m.size() == 1 && (b.m[0] == 4000 || b.m[0] == 0 || b.m[0] == 10)))
        valve.push_back(t);
    }
  }
  const auto set_tool = [&](const std::string& f, const std::string& text) {
    if (!tools.count(f)) order.push_back(f);
    tools[f] = text;
  };
  const auto set_mode = [&](const std::string& group, const std::string& word) {
    if (!modes.count(group)) mode_order.push_back(group);
    modes[group] = word;
  };
  for (const auto& c : commands) {
    if (c.file_line >= file_line) break;
    const Block b = block_of(c.text);
    for (int g : b.g) {
      if (g == 200 || g == 210) s.inches = g == 200;
      if (g == 900 || g == 910) {
        s.relative = g == 910;
        if (s.relative_e) s.relative_e = s.relative;  // Marlin: G90/G91 set E's mode too
      }
      if (g == 930 || g == 940) s.inverse_time = g == 930;
      if (g == 170 || g == 180 || g == 190) set_mode("plane", "G" + std::to_string(g / 10));
      if (g >= 540 && g <= 593)
        set_mode("offset",
                 "G" + std::to_string(g / 10) + (g % 10 ? "." + std::to_string(g % 10) : ""));
    }
    const bool machine_coords = b.has_g(530);  // G53: a move in machine coordinates
    if (b.has_g(0) || b.has_g(10) || b.has_g(20) || b.has_g(30)) {
      if (machine_coords) {
        for (char k : {'X', 'Y', 'Z'}) {
          if (b.w.count(k)) (k == 'X' ? s.x : k == 'Y' ? s.y : s.z).reset();
        }
      } else {
        move(s, b);
      }
    } else if (b.w.count('F') && b.g.empty() && b.m.empty()) {
      s.f = b.w.at('F');  // GRBL "F1200" alone
    }
    if (b.has_g(280)) {  // homing: where the homed axes are is the firmware's business
      const bool all = !b.w.count('X') && !b.w.count('Y') && !b.w.count('Z');
      if (all || b.w.count('X')) s.x.reset();
      if (all || b.w.count('Y')) s.y.reset();
      if (all || b.w.count('Z')) s.z.reset();
    }
    if (b.has_g(920)) {
      for (char k : {'X', 'Y', 'Z', 'E'}) {
        if (!b.w.count(k)) continue;
        (k == 'X' ? s.x : k == 'Y' ? s.y : k == 'Z' ? s.z : s.e) = b.w.at(k);
      }
      for (char k : {'A', 'B', 'C'}) {
        if (b.w.count(k)) s.rotary[k] = b.w.at(k);
      }
    }
    for (int code : b.m) {
      if (code == 820 || code == 830) s.relative_e = code == 830;
      if (code == 70 || code == 90) mist = code == 70;
      if (code == 80 || code == 90) flood = code == 80;
      for (const auto& f : families_of_m(code, b)) set_tool(f, replay_text(code, b, c.text));
    }
    if (std::find(valve.begin(), valve.end(), c.text) != valve.end() && b.g.empty() &&
        (b.m.empty() || families_of_m(b.m[0], b).empty())) {
      set_tool("valve", c.text);  // a valve command of the profile that is no known output
    }
    if (b.w.count('T') && b.g.empty() && b.m.empty()) set_tool("tool", c.text);
  }
  for (const auto& g : mode_order) s.modes.push_back(modes.at(g));
  for (const auto& f : order) {
    std::vector<std::string> texts = {tools.at(f)};
    if (f == "coolant") {  // M9 turns both off, so the last command alone may not say it
      texts.clear();
      if (mist) texts.push_back("M7");
      if (flood) texts.push_back("M8");
      if (texts.empty()) texts.push_back("M9");
    }
    for (const auto& t : texts) {
      if (std::find(s.tool_state.begin(), s.tool_state.end(), t) == s.tool_state.end())
        s.tool_state.push_back(t);
    }
  }
  return s;
}

std::vector<std::string> safe_state_gcode(const MachineProfile& m, const ModalState&) {
  if (m.plotter.enabled) {
    if (m.plotter.pen.lift == PenLift::Drum)
      return {"M400"};  // the drum's rest angle depends on the marker
    return {pen_lift_command(m, true)};
  }
  if (m.deposition.model == DepositionModel::Valve) return m.deposition.off_gcode;
  return {};
}

std::vector<std::string> resume_preamble(const MachineProfile& m, const ModalState& s) {
  // positions are in the file's units; the profile's feeds and lift are mm
  const double unit = s.inches ? 25.4 : 1.0;
  std::vector<std::string> out = {s.inches ? "G20" : "G21", "G90"};
  if (s.inverse_time) out.push_back("G94");  // the travels below give mm/min (in/min) feeds
  for (const auto& mode : s.modes) out.push_back(mode);
  if (s.relative_e && m.firmware != Firmware::Grbl) out.push_back(*s.relative_e ? "M83" : "M82");
  for (const auto& c : safe_state_gcode(m, s)) out.push_back(c);
  const bool pen_z =
      m.plotter.enabled && m.plotter.pen.lift != PenLift::Servo;  // Z is the pen (or drum)
  const std::string travel = " F" + fmt_feed(m.limits.travel_feed_mm_per_min / unit);
  if (s.z && !m.plotter.enabled)
    out.push_back("G0 Z" + fmt_fixed(*s.z + m.travel_lift_mm / unit, 3) + travel);
  if (s.x || s.y) {
    out.push_back("G0" + (s.x ? " X" + fmt_fixed(*s.x, 3) : "") +
                  (s.y ? " Y" + fmt_fixed(*s.y, 3) : "") + travel);
  }
  if (s.z && (!m.plotter.enabled || (pen_z && m.plotter.pen.lift == PenLift::Z)))
    out.push_back("G0 Z" + fmt_fixed(*s.z, 3));
  if (s.e) out.push_back("G92 E" + fmt_fixed(*s.e, 5));
  for (const auto& [axis, v] : s.rotary)
    out.push_back(std::string("G92 ") + axis + fmt_fixed(v, 3));
  if (s.f && !s.inverse_time.value_or(false))
    out.push_back((m.firmware == Firmware::Grbl ? "F" : "G1 F") + fmt_feed(*s.f));
  for (const auto& t : s.tool_state) out.push_back(t);
  if (s.inverse_time.value_or(false)) out.push_back("G93");
  if (s.relative) out.push_back("G91");
  return out;
}

}  // namespace strand::machines
