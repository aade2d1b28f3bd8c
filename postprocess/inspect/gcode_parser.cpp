// Single-pass G-code reader with std::from_chars; linear in the file size.
#include "postprocess/inspect/gcode_parser.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <optional>

#include "postprocess/plan/arc_segmentation.h"
#include "slicer/params.h"
#include "slicer/units.h"

namespace strand::post {

using slicer::Feature;
using slicer::Move;
using slicer::MoveKind;
using slicer::Vec3;

namespace {

struct Words {
  char letter[16];
  double value[16];
  int count = 0;
  bool bad_number = false;
  std::optional<double> get(char c) const {
    for (int i = 0; i < count; ++i) {
      if (letter[i] == c) return value[i];
    }
    return std::nullopt;
  }
};

bool is_letter(char c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z'); }

// M-codes whose argument is free text ("M117 Open the valve"), not address words.
bool takes_text(const Words& w) {
  if (w.count != 1 || w.letter[0] != 'M') return false;
  const double m = w.value[0];
  return m == 117 || m == 118 || m == 23 || m == 28 || m == 30 || m == 32;
}

// Splits "G1 X1.5 Y-2 E0.1" into letter/number words; stops at ';' or '('. A word whose
// number is nan/inf, or a G word followed by something that is not a number, sets
// bad_number; a bare letter ("G28 X Y") is a flag word and is skipped.
Words split_words(std::string_view code) {
  Words w;
  std::size_t i = 0;
  while (i < code.size() && w.count < 16) {
    const char c = code[i];
    if (c == ';' || c == '(') break;
    if (!is_letter(c)) {
      ++i;
      continue;
    }
    std::size_t j = i + 1;
    while (j < code.size() && code[j] == ' ') ++j;
    const std::size_t k = j < code.size() && code[j] == '+' ? j + 1 : j;
    double v = 0.0;
    const auto res = std::from_chars(code.data() + k, code.data() + code.size(), v);
    if (res.ec != std::errc()) {
      const bool bare = k >= code.size() || (is_letter(code[k]) && k > i + 1) || code[k] == ';';
      if (!bare && w.count > 0 && w.letter[0] == 'G') w.bad_number = true;
      i = bare ? i + 1 : code.find(' ', k);  // a malformed word is skipped whole
      continue;
    }
    if (!std::isfinite(v)) {  // nan, inf: never used as a coordinate
      w.bad_number = true;
      i = static_cast<std::size_t>(res.ptr - code.data());
      continue;
    }
    w.letter[w.count] = static_cast<char>(c & ~0x20);
    w.value[w.count] = v;
    ++w.count;
    i = static_cast<std::size_t>(res.ptr - code.data());
    if (takes_text(w)) break;
  }
  return w;
}

bool starts_with(std::string_view s, std::string_view p) { return s.substr(0, p.size()) == p; }

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\r' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

Feature feature_from_comment(std::string_view name, Feature fallback) {
  static const char* kNames[] = {"infill", "wall", "ligament", "node", "grip", "frame", "link", "pen"};
  for (const char* n : kNames) {
    if (name == n) return slicer::feature_from_string(n);
  }
  return fallback;
}

// Another slicer's ;TYPE: role (Cura "WALL-OUTER", "FILL"; PrusaSlicer "Perimeter",
// "Solid infill") as the nearest feature, so previews colour walls and fills apart.
Feature feature_from_role(std::string_view role, Feature fallback) {
  auto has = [role](std::string_view w) { return role.find(w) != std::string_view::npos; };
  if (has("WALL") || has("erimeter")) return Feature::Wall;
  if (has("FILL") || has("SKIN") || has("nfill") || has("Bridge")) return Feature::Infill;
  return fallback;
}

class Reader {
 public:
  explicit Reader(std::string_view text) : text_(text) {
    has_markers_ = text.find(";LAYER") != std::string_view::npos;
    has_e_ = scan_has_e(text);
    out_.has_e = has_e_;
  }

  ParsedGcode run() {
    // One move per line at most: reserving avoids re-copying a million moves while growing.
    const auto lines = static_cast<std::size_t>(std::count(text_.begin(), text_.end(), '\n')) + 1;
    out_.program.moves.reserve(lines);
    out_.move_lines.reserve(lines);
    std::size_t pos = 0;
    int line_no = 0;
    while (pos <= text_.size()) {
      const std::size_t nl = text_.find('\n', pos);
      const std::size_t end = nl == std::string_view::npos ? text_.size() : nl;
      ++line_no;
      line(trim(text_.substr(pos, end - pos)), line_no);
      if (nl == std::string_view::npos) break;
      pos = nl + 1;
    }
    return std::move(out_);
  }

 private:
  // Files whose moves carry E words (other than E0 everywhere) use E to tell deposits.
  static bool scan_has_e(std::string_view t) {
    for (std::size_t i = t.find('E'); i != std::string_view::npos; i = t.find('E', i + 1)) {
      if (i == 0 || (t[i - 1] != ' ' && t[i - 1] != '\t')) continue;
      const std::size_t ls = t.rfind('\n', i) + 1;
      const std::size_t semi = t.find(';', ls);
      if (semi != std::string_view::npos && semi < i) continue;
      if (t[ls] != 'G') continue;
      double v = 0;
      auto r = std::from_chars(t.data() + i + 1, t.data() + t.size(), v);
      if (r.ec == std::errc() && v != 0.0) return true;
    }
    return false;
  }

  void line(std::string_view s, int n) {
    if (s.empty()) return;
    if (s.front() == ';') {
      comment(s.substr(1), n);
      return;
    }
    const Words w = split_words(s);
    if (w.bad_number) out_.issues.push_back({n, "non-finite or malformed number in '" + std::string(s) + "'"});
    if (w.count == 0) return;
    const char cmd = w.letter[0];
    const int code = static_cast<int>(w.value[0]);
    if (cmd == 'G') g_code(code, w, n);
    if (cmd == 'M') m_code(code);
  }

  void comment(std::string_view c, int) {
    if (starts_with(c, "LAYER_CHANGE")) {
      new_layer(std::nullopt);
    } else if (starts_with(c, "LAYER:")) {
      if (!marker_pending_) new_layer(std::nullopt);
      marker_pending_ = false;
    } else if (starts_with(c, "Z:") && !out_.program.layers.empty()) {
      double z = 0;
      std::from_chars(c.data() + 2, c.data() + c.size(), z);
      out_.program.layers.back().z_mm = z;
      layer_z_known_ = true;
    } else if (starts_with(c, "HEIGHT:") && !out_.program.layers.empty()) {
      double h = 0;
      std::from_chars(c.data() + 7, c.data() + c.size(), h);
      out_.program.layers.back().height_mm = h;
    } else if (starts_with(c, "TYPE:")) {
      feature_ = feature_from_role(c.substr(5), feature_);
    } else if (starts_with(c, "FEATURE:")) {
      feature_ = feature_from_comment(trim(c.substr(8)), feature_);
    } else if (starts_with(c, "WIDTH:")) {
      std::from_chars(c.data() + 6, c.data() + c.size(), width_);
    }
  }

  void new_layer(std::optional<double> z) {
    out_.program.layers.push_back({z.value_or(pos_.z()), 0.0});
    layer_z_known_ = z.has_value();
    layer_ = static_cast<int>(out_.program.layers.size()) - 1;
    marker_pending_ = true;
  }

  void m_code(int code) {
    if (code == 82) relative_e_ = false;
    if (code == 83) relative_e_ = true;
  }

  void g_code(int code, const Words& w, int n) {
    switch (code) {
      case 0: case 1: case 2: case 3: motion(code, w, n); break;
      case 4: dwell(w, n); break;
      case 20:
        scale_ = slicer::kMmPerInch;
        if (!out_.inches) out_.issues.push_back({n, "inch units (G20): coordinates converted to mm"});
        out_.inches = true;
        break;
      case 21: scale_ = 1.0; break;
      case 90: relative_ = false; relative_e_ = false; break;  // Marlin: G90 resets E mode too
      case 91: relative_ = true; relative_e_ = true; break;
      case 92:
        if (auto e = w.get('E')) e_ = *e;
        if (auto a = w.get('A')) a_ = *a;
        for (int a = 0; a < 3; ++a) {
          if (auto v = w.get("XYZ"[a])) pos_[a] = *v * scale_;
        }
        break;
      default: break;
    }
  }

  void dwell(const Words& w, int n) {
    double seconds = 0.0;
    if (auto s = w.get('S')) seconds = *s;
    if (auto p = w.get('P')) seconds = *p / 1000.0;
    slicer::push_dwell(out_.program, seconds, pos_, layer_);
    out_.move_lines.push_back(n);  // one line per move, dwells included
    if (has_a_) out_.a_deg.push_back(a_);
  }

  void motion(int code, const Words& w, int n) {
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
    mv.width_mm = width_;
    const bool xy_moves = (target.head<2>() - pos_.head<2>()).norm() > 0.0;
    mv.kind = (has_e_ ? de > 0.0 : (code != 0 && xy_moves)) ? MoveKind::Deposit : MoveKind::Travel;
    if (code == 2 || code == 3) arc(mv, code, w, n);
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
    if (out_.program.moves.size() == 1) out_.program.start_mm = pos_;
    pos_ = target;
    marker_pending_ = false;
  }

  // Reads an A word (rotary axis, degrees); true when there is one. Moves before the first
  // A word were at the old A.
  bool rotary(const Words& w) {
    const auto a = w.get('A');
    if (!a) return false;
    if (!has_a_) out_.a_deg.assign(out_.program.moves.size(), a_);
    has_a_ = true;
    a_ = relative_ ? a_ + *a : *a;
    return true;
  }

  void arc(Move& mv, int code, const Words& w, int n) {
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

  // Keeps every later flattening finite: absurd radii become straight moves, and the chord
  // count of all arcs at the finest tolerance stays within kMaxArcChords.
  void bound_arc(Move& mv, int n) {
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

  std::string_view text_;
  ParsedGcode out_;
  Vec3 pos_ = Vec3::Zero();
  double e_ = 0.0;
  double a_ = 0.0;      // rotary axis position, degrees
  bool has_a_ = false;  // an A word was read: a_deg is kept parallel to the moves
  double feed_ = 0.0;
  double scale_ = 1.0;
  double width_ = 0.0;
  double arc_chords_ = 0.0;
  bool relative_ = false;
  bool relative_e_ = false;
  bool has_markers_ = false;
  bool has_e_ = false;
  bool marker_pending_ = false;
  bool layer_z_known_ = false;  // the current layer's z came from ;Z: or a deposit
  int layer_ = -1;
  Feature feature_ = Feature::Infill;
};

}  // namespace

ParsedGcode parse_gcode(std::string_view text) { return Reader(text).run(); }

}  // namespace strand::post
