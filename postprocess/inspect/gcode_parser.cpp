// Single-pass G-code reader with std::from_chars; linear in the file size. This half reads
// lines, comments, G/M words, moves and arcs; gcode_ngc_program.cpp runs RS274NGC programs.
#include "postprocess/inspect/gcode_parser.h"

#include <algorithm>
#include <charconv>
#include <cmath>

#include "postprocess/inspect/gcode_reader.h"
#include "postprocess/plan/arc_segmentation.h"
#include "slicer/input_error.h"
#include "slicer/params.h"
#include "slicer/units.h"

namespace strand::post {

namespace gcode {

Reader::Reader(std::string_view text, const PenReading& pen) : text_(text), pen_(pen) {
  has_markers_ = text.find(";LAYER") != std::string_view::npos;
  has_e_ = scan_has_e(text);
  out_.has_e = has_e_;
}

Reader::Reader(const GcodeScan& scan, const PenReading& pen) : pen_(pen) {
  has_markers_ = scan.has_markers;
  has_e_ = scan.has_e;
  out_.has_e = has_e_;
}

ParsedGcode Reader::run() {
  if (has_o_words(text_)) {
    out_ = run_indexed();  // it hands the reading back whole
  } else {
    run_streaming();
  }
  return finish();
}

void Reader::feed(std::string_view raw_line) {
  if (stopped_) return;
  line(trim(raw_line), ++fed_lines_);
}

void Reader::flush() {
  if (!sink_) return;
  (*sink_)(out_, first_move_);
  first_move_ += out_.program.moves.size();
  out_.program.moves.clear();
  out_.program.texts.clear();
  out_.program.dwells_s.clear();
  out_.move_lines.clear();
  out_.arc_lines.clear();
  out_.a_deg.clear();
  out_.e_step.clear();
}

ParsedGcode Reader::finish() {
  ParsedGcode& out = out_;
  if (spindle_line_ && plunge_line_ && !has_e_) {
    out.issues.push_back(
        {plunge_line_, "milling program: the spindle turns (M" + std::to_string(spindle_m_) + " S" +
                           slicer::short_number(spindle_s_) + " at line " +
                           std::to_string(spindle_line_) + ") and the tool cuts " +
                           slicer::short_number(-plunge_z_) + " mm below the work surface (line " +
                           std::to_string(plunge_line_) +
                           "): a subtractive program, not a deposition or drawing toolpath"});
  }
  flush();
  return std::move(out);
}

bool Reader::line_has_o_word(std::string_view raw_line) {
  const std::string_view l = trim(raw_line);
  return !l.empty() && (l[0] == 'O' || l[0] == 'o' || l[0] == 'N' || l[0] == 'n') && o_word(l);
}

bool Reader::has_o_words(std::string_view t) {
  for (std::size_t pos = 0; pos < t.size();) {
    std::size_t nl = t.find('\n', pos);
    if (nl == std::string_view::npos) nl = t.size();
    if (line_has_o_word(t.substr(pos, nl - pos))) return true;
    pos = nl + 1;
  }
  return false;
}

void Reader::run_streaming() {
  if (!sink_) {
    // One move per line at most: reserving avoids re-copying a million moves while growing.
    const auto lines = static_cast<std::size_t>(std::count(text_.begin(), text_.end(), '\n')) + 1;
    out_.program.moves.reserve(lines);
    out_.move_lines.reserve(lines);
  }
  std::size_t pos = 0;
  while (pos <= text_.size()) {
    const std::size_t nl = text_.find('\n', pos);
    const std::size_t end = nl == std::string_view::npos ? text_.size() : nl;
    feed(text_.substr(pos, end - pos));
    if (nl == std::string_view::npos || stopped_) break;
    pos = nl + 1;
  }
}

void Reader::words(const Words& w, std::string_view s, int n) {
  if (w.bad_number)
    out_.issues.push_back({n, "non-finite or malformed number in '" +
                                  std::string(s.substr(0, kQuotedLineBytes)) +
                                  (s.size() > kQuotedLineBytes ? "...'" : "'")});
  if (w.count == 0) return;
  const char cmd = w.letter[0];
  // G and M numbers are small; a huge one ("G1e12") names no command and would not fit int.
  if (!(w.value[0] >= 0.0 && w.value[0] < kMaxCommandNumber)) return;
  const int code = static_cast<int>(w.value[0]);
  if (cmd == 'G') g_code(code, w, n);
  if (cmd == 'M') m_code(code, w, n);
  // T<n>: printhead n from here on (Marlin, RepRapFirmware, Klipper; PrusaSlicer's files).
  if (cmd == 'T' && w.count == 1 && code <= 63 && w.value[0] == code) tool_ = static_cast<std::int16_t>(code);
}

bool Reader::line_has_e(std::string_view l) {
  if (l.empty() || l[0] != 'G') return false;
  const std::size_t semi = l.find(';');
  for (std::size_t i = l.find('E'); i != std::string_view::npos && i < semi; i = l.find('E', i + 1)) {
    if (l[i - 1] != ' ' && l[i - 1] != '\t') continue;
    double v = 0;
    auto r = std::from_chars(l.data() + i + 1, l.data() + l.size(), v);
    if (r.ec == std::errc() && v != 0.0) return true;
  }
  return false;
}

bool Reader::scan_has_e(std::string_view t) {
  for (std::size_t pos = 0; pos <= t.size();) {
    std::size_t nl = t.find('\n', pos);
    if (nl == std::string_view::npos) nl = t.size();
    if (line_has_e(t.substr(pos, nl - pos))) return true;
    pos = nl + 1;
  }
  return false;
}

void Reader::line(std::string_view s, int n) {
  if (s.empty() || stopped_) return;
  if (s.front() == ';') {
    comment(s.substr(1), n);
    return;
  }
  if (is_ngc_line(s)) {
    ngc_line(s, n);
    return;
  }
  words(split_words(s), s, n);
}

void Reader::new_layer(std::optional<double> z) {
  flush();  // every layer before this one is final now
  out_.program.layers.push_back({z.value_or(pos_.z()), 0.0});
  layer_z_known_ = z.has_value();
  layer_ = static_cast<int>(out_.program.layers.size()) - 1;
  marker_pending_ = true;
}

void Reader::m_code(int code, const Words& w, int n) {
  if (code == 82) relative_e_ = false;
  if (code == 83) relative_e_ = true;
  if (code == 3 || code == 4) {
    const auto s = w.get('S');
    if (s && *s > kSpindleMinRpm && !spindle_line_)
      spindle_line_ = n, spindle_s_ = *s, spindle_m_ = code;
  }
  if (has_e_) return;
  if (pen_.valve_on_m && (code == *pen_.valve_on_m || code == *pen_.valve_off_m)) {
    const auto p = w.get('P');
    if (!pen_.valve_p || (p && *p == *pen_.valve_p)) valve_open_ = code == *pen_.valve_on_m;
    return;
  }  // an extruder's M300 is a beep, its M3 a spindle or laser
  const std::optional<bool> down = pen_down_by_command(pen_, code, w.get('S'), w.get('P'));
  if (!down) return;
  if (out_.pen_commands++ == 0) out_.notes.push_back({n, pen_convention(pen_, code)});
  out_.pen_servo = out_.pen_servo || code == 300 || code == 280;
  pen_down_ = *down;
}

bool Reader::draws(int code, const Vec3& target) const {
  if (code == 0 || (target.head<2>() - pos_.head<2>()).norm() == 0.0) return false;
  if (pen_.valve_on_m) return valve_open_;
  if (pen_down_) return *pen_down_;
  return !pen_.z_down_max_mm || target.z() <= *pen_.z_down_max_mm;
}

void Reader::g_code(int code, const Words& w, int n) {
  switch (code) {
    case 0:
    case 1:
    case 2:
    case 3:
      motion(code, w, n);
      break;
    case 4:
      dwell(w, n);
      break;
    case 20:
      scale_ = slicer::kMmPerInch;
      if (!out_.inches) out_.notes.push_back({n, "inch units (G20): coordinates converted to mm"});
      out_.inches = true;
      break;
    case 21:
      scale_ = 1.0;
      break;
    case 90:
      relative_ = false;
      relative_e_ = false;
      break;  // Marlin: G90 resets E mode too
    case 91:
      relative_ = true;
      relative_e_ = true;
      break;
    case 92:
      if (auto e = w.get('E')) e_ = *e;
      if (auto a = w.get('A')) a_ = *a;
      for (int a = 0; a < 3; ++a) {
        if (auto v = w.get("XYZ"[a])) pos_[a] = *v * scale_;
      }
      break;
    default:
      break;
  }
}

void Reader::dwell(const Words& w, int n) {
  double seconds = 0.0;
  if (auto s = w.get('S')) seconds = *s;
  if (auto p = w.get('P')) seconds = *p / 1000.0;
  slicer::push_dwell(out_.program, seconds, pos_, layer_);
  ++moves_read_;
  out_.move_lines.push_back(n);  // one line per move, dwells included
  if (has_a_) out_.a_deg.push_back(a_);
  if (has_a_ || sink_) out_.e_step.push_back(0.0);
}

void Reader::motion(int code, const Words& w, int n) {
  if (auto f = w.get('F')) feed_ = *f * scale_;
  Vec3 target = pos_;
  bool moved = false;
  for (int a = 0; a < 3; ++a) {
    if (auto v = w.get("XYZ"[a])) {
      target[a] = relative_ ? pos_[a] + *v * scale_ : *v * scale_;
      moved = true;
    }
  }
  moved = rotary(w) || moved;
  if (spindle_line_ && code != 0 && target.z() < -kPlungeMm && !plunge_line_)
    plunge_line_ = n, plunge_z_ = target.z();
  double de = 0.0;
  if (auto e = w.get('E')) {
    de = relative_e_ ? *e : *e - e_;
    e_ = relative_e_ ? e_ + *e : *e;
  }
  if (!moved) return;  // E-only moves (prime, retract) carry no geometry
  Move mv;
  mv.end_mm = target;
  mv.feed_mm_per_min = feed_;
  mv.feature = feature_;
  mv.tool = tool_;
  mv.width_mm = width_;
  mv.kind = (has_e_ ? de > 0.0 : draws(code, target)) ? MoveKind::Deposit : MoveKind::Travel;
  if (code == 2 || code == 3) arc(mv, code, w, n);
  if (tool_ >= 0 && static_cast<std::size_t>(tool_) < tool_offsets_.size()) {
    const Vec2 o = tool_offsets_[static_cast<std::size_t>(tool_)];
    mv.end_mm.x() += o.x();
    mv.end_mm.y() += o.y();
    mv.center_mm += o;
  }
  if (!has_markers_ && mv.kind == MoveKind::Deposit &&
      (layer_ < 0 || std::abs(target.z() - out_.program.layers.back().z_mm) > 1e-6)) {
    new_layer(target.z());
  }
  if (mv.kind == MoveKind::Deposit && layer_ >= 0 && !layer_z_known_) {
    out_.program.layers.back().z_mm = target.z();  // Cura: no ;Z:, the z comes after ;LAYER:
    layer_z_known_ = true;
  }
  mv.layer = layer_;
  out_.program.moves.push_back(std::move(mv));
  out_.move_lines.push_back(n);
  if (has_a_) out_.a_deg.push_back(a_);
  if (has_a_ || sink_) out_.e_step.push_back(de);
  if (++moves_read_ == 1) out_.program.start_mm = pos_;
  pos_ = target;
  marker_pending_ = false;
}

bool Reader::rotary(const Words& w) {
  const auto a = w.get('A');
  if (!a) return false;
  if (!has_a_) {
    out_.a_deg.assign(out_.program.moves.size(), a_);
    if (!sink_) out_.e_step.assign(out_.program.moves.size(), 0.0);  // a piece has its steps
  }
  has_a_ = true;
  a_ = relative_ ? a_ + *a : *a;
  return true;
}

void Reader::arc(Move& mv, int code, const Words& w, int n) {
  out_.arc_lines.push_back(n);
  mv.is_arc = true;
  mv.ccw = code == 3;
  const auto i = w.get('I'), j = w.get('J'), r = w.get('R');
  if (i || j) {
    mv.center_mm = pos_.head<2>() + slicer::Vec2(i.value_or(0) * scale_, j.value_or(0) * scale_);
    bound_arc(mv, n);
    return;
  }
  if (r) {  // radius form: centre on the perpendicular bisector, sign picks the short way
    const slicer::Vec2 a = pos_.head<2>(), b = mv.end_mm.head<2>();
    const double rad = std::abs(*r) * scale_;
    const slicer::Vec2 mid = (a + b) / 2, d = b - a;
    const double half = d.norm() / 2;
    const double h = std::sqrt(std::max(0.0, rad * rad - half * half));
    slicer::Vec2 perp(-d.y(), d.x());
    if (perp.norm() > 0) perp.normalize();
    const bool left = (mv.ccw == (*r > 0));
    mv.center_mm = mid + (left ? h : -h) * perp;
    bound_arc(mv, n);
    return;
  }
  out_.issues.push_back({n, "arc without I/J or R: read as a straight move"});
  mv.is_arc = false;
}

void Reader::bound_arc(Move& mv, int n) {
  const slicer::Vec2 from = pos_.head<2>(), to = mv.end_mm.head<2>();
  const double r = (from - mv.center_mm).norm();
  if (!(r >= kMinArcRadiusMm && r <= kMaxArcRadiusMm)) {
    out_.issues.push_back({n, "arc radius " + slicer::short_number(r) + " mm outside [" +
                                  slicer::short_number(kMinArcRadiusMm) + ", " +
                                  slicer::short_number(kMaxArcRadiusMm) +
                                  "] mm: read as a straight move"});
    mv.is_arc = false;
    return;
  }
  const double sweep = slicer::arc_sweep(mv.center_mm, from, to, mv.ccw);
  arc_chords_ += chords_needed(r, sweep, kMinFlattenToleranceMm);
  if (arc_chords_ > kMaxArcChords) {
    out_.issues.push_back({n, "arcs of this file would flatten into more than " +
                                  slicer::short_number(kMaxArcChords) +
                                  " chords: read as a straight move"});
    mv.is_arc = false;
  }
}

}  // namespace gcode

ParsedGcode parse_gcode(std::string_view text, const PenReading& pen) {
  return gcode::Reader(text, pen).run();
}

ParsedGcode parse_gcode_layers(std::string_view text, const PenReading& pen,
                               const PieceSink& sink) {
  gcode::Reader reader(text, pen);
  reader.set_sink(&sink);
  return reader.run();
}

ParsedGcode parse_gcode_layers(const LineSource& lines, const GcodeScan& scan,
                               const PenReading& pen, const PieceSink& sink) {
  gcode::Reader reader(scan, pen);
  reader.set_sink(&sink);
  lines([&reader](std::string_view l) { reader.feed(l); });
  return reader.finish();
}

void GcodeScan::add_line(std::string_view l) {
  if (head.size() < kHeadBytes) {
    head.append(l.substr(0, kHeadBytes - head.size()));
    if (head.size() < kHeadBytes) head += '\n';
  }
  has_markers = has_markers || l.find(";LAYER") != std::string_view::npos;
  rotary = rotary || l.find(";ROTARY_AXIS:") != std::string_view::npos;
  has_e = has_e || gcode::Reader::line_has_e(l);
  has_o_words = has_o_words || gcode::Reader::line_has_o_word(l);
}

GcodeScan scan_gcode(std::string_view text) {
  GcodeScan scan;
  for (std::size_t pos = 0; pos <= text.size();) {
    std::size_t nl = text.find('\n', pos);
    if (nl == std::string_view::npos) nl = text.size();
    scan.add_line(text.substr(pos, nl - pos));
    pos = nl + 1;
  }
  return scan;
}

}  // namespace strand::post
