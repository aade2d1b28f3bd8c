// Recursive-descent parsers for SVG path data, transform lists, number lists, lengths and
// colours.
#include "slicer/svg_syntax.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>

#include "slicer/input_error.h"
#include "slicer/units.h"

namespace strand::slicer {

namespace {

constexpr double kPxPerInch = 96.0;

// Cursor over attribute text with the SVG number grammar.
class Scanner {
 public:
  explicit Scanner(std::string_view s) : s_(s) {}
  void skip_space() {
    while (i_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[i_]))) ++i_;
  }
  void skip_comma_space() {
    skip_space();
    if (i_ < s_.size() && s_[i_] == ',') ++i_;
    skip_space();
  }
  bool done() {
    skip_space();
    return i_ >= s_.size();
  }
  char peek() const { return i_ < s_.size() ? s_[i_] : '\0'; }
  char take() { return s_[i_++]; }
  std::size_t pos() const { return i_; }
  std::string_view rest() const { return s_.substr(i_); }

  // number ::= sign? (digits ('.' digits?)? | '.' digits) exponent?
  std::optional<double> number() {
    skip_space();
    std::size_t j = i_;
    if (j < s_.size() && (s_[j] == '+' || s_[j] == '-')) ++j;
    const std::size_t mantissa = j;
    while (j < s_.size() && std::isdigit(static_cast<unsigned char>(s_[j]))) ++j;
    if (j < s_.size() && s_[j] == '.') {
      ++j;
      while (j < s_.size() && std::isdigit(static_cast<unsigned char>(s_[j]))) ++j;
    }
    if (j == mantissa || (j == mantissa + 1 && s_[mantissa] == '.')) return std::nullopt;
    if (j < s_.size() && (s_[j] == 'e' || s_[j] == 'E')) {
      std::size_t k = j + 1;
      if (k < s_.size() && (s_[k] == '+' || s_[k] == '-')) ++k;
      if (k < s_.size() && std::isdigit(static_cast<unsigned char>(s_[k]))) {
        while (k < s_.size() && std::isdigit(static_cast<unsigned char>(s_[k]))) ++k;
        j = k;
      }
    }
    const std::size_t b = (s_[i_] == '+') ? i_ + 1 : i_;
    double v = 0.0;
    const auto r = std::from_chars(s_.data() + b, s_.data() + j, v);
    if (r.ec != std::errc() || !std::isfinite(v)) return std::nullopt;
    i_ = j;
    return v;
  }
  // flag ::= '0' | '1' (arc flags may be packed without separators)
  std::optional<bool> flag() {
    skip_comma_space();
    if (peek() != '0' && peek() != '1') return std::nullopt;
    return take() == '1';
  }

 private:
  std::string_view s_;
  std::size_t i_ = 0;
};

int arg_count(char upper) {
  switch (upper) {
    case 'M':
    case 'L':
    case 'T':
      return 2;
    case 'H':
    case 'V':
      return 1;
    case 'C':
      return 6;
    case 'S':
    case 'Q':
      return 4;
    case 'A':
      return 7;
    default:
      return 0;
  }
}

// State of the path interpreter: current point, sub-path start, last control points.
struct PathBuilder {
  std::vector<SubPath> out;
  std::size_t max_pieces = 0;
  std::size_t pieces = 0;  // pieces and sub-paths stored so far

  void count() {
    if (++pieces > max_pieces) {
      throw InputError("path data has more than " + std::to_string(max_pieces) + " curve pieces");
    }
  }
  Vec2 cur = Vec2::Zero();
  Vec2 last_cubic_ctrl = Vec2::Zero();
  Vec2 last_quad_ctrl = Vec2::Zero();
  char prev = ' ';

  SubPath& current() {
    if (out.empty() || out.back().closed) {
      const Vec2 start = out.empty() ? Vec2::Zero() : out.back().start;
      count();
      out.push_back({start, {}, false});
    }
    return out.back();
  }
  void move_to(const Vec2& p) {
    if (!out.empty() && out.back().pieces.empty()) out.pop_back();
    count();
    out.push_back({p, {}, false});
    cur = p;
  }
  void line_to(const Vec2& p) {
    CurvePiece c;
    c.p[0] = p;
    add(c);
    cur = p;
  }
  void add(const CurvePiece& c) {
    SubPath& s = current();
    count();
    s.pieces.push_back(c);
  }
  void cubic_to(const Vec2& c1, const Vec2& c2, const Vec2& p) {
    CurvePiece c;
    c.kind = CurveKind::Cubic;
    c.p[0] = c1;
    c.p[1] = c2;
    c.p[2] = p;
    add(c);
    last_cubic_ctrl = c2;
    cur = p;
  }
  void quad_to(const Vec2& q, const Vec2& p) {
    const Vec2 from = cur;
    cubic_to(from + 2.0 / 3.0 * (q - from), p + 2.0 / 3.0 * (q - p), p);
    last_quad_ctrl = q;
  }
  void close() {
    SubPath& s = current();
    if ((cur - s.start).norm() > 0.0) line_to(s.start);
    s.closed = true;
    cur = s.start;
  }

  void apply(char cmd, const double* a) {
    const bool rel = std::islower(static_cast<unsigned char>(cmd));
    const char up = static_cast<char>(std::toupper(static_cast<unsigned char>(cmd)));
    const Vec2 base = rel ? cur : Vec2::Zero();
    const auto pt = [&](int i) -> Vec2 { return Vec2(a[i], a[i + 1]) + base; };
    const bool prev_cubic = prev == 'C' || prev == 'S';
    const bool prev_quad = prev == 'Q' || prev == 'T';
    switch (up) {
      case 'M':
        move_to(pt(0));
        break;
      case 'L':
        line_to(pt(0));
        break;
      case 'H':
        line_to(Vec2(a[0] + (rel ? cur.x() : 0.0), cur.y()));
        break;
      case 'V':
        line_to(Vec2(cur.x(), a[0] + (rel ? cur.y() : 0.0)));
        break;
      case 'C':
        cubic_to(pt(0), pt(2), pt(4));
        break;
      case 'S':
        cubic_to(prev_cubic ? 2 * cur - last_cubic_ctrl : cur, pt(0), pt(2));
        break;
      case 'Q':
        quad_to(pt(0), pt(2));
        break;
      case 'T':
        quad_to(prev_quad ? 2 * cur - last_quad_ctrl : cur, pt(0));
        break;
      case 'A': {
        const Vec2 to = pt(5);
        if ((to - cur).norm() == 0.0) break;  // SVG: an arc to the current point is omitted
        add(arc_piece(cur, a[0], a[1], a[2], a[3] != 0, a[4] != 0, to));
        cur = to;
        break;
      }
      default:
        break;
    }
    prev = up;
  }
};

bool read_args(Scanner& sc, char up, double* a) {
  const int n = arg_count(up);
  for (int i = 0; i < n; ++i) {
    if (up == 'A' && (i == 3 || i == 4)) {
      const auto f = sc.flag();
      if (!f) return false;
      a[i] = *f ? 1.0 : 0.0;
    } else {
      if (i > 0) sc.skip_comma_space();
      const auto v = sc.number();
      if (!v) return false;
      a[i] = *v;
    }
  }
  return true;
}

}  // namespace

CurvePiece arc_piece(const Vec2& from, double rx, double ry, double phi_deg, bool large_arc,
                     bool sweep, const Vec2& to) {
  rx = std::abs(rx);
  ry = std::abs(ry);
  CurvePiece line;
  line.p[0] = to;
  if (rx == 0.0 || ry == 0.0) return line;
  // SVG 1.1 implementation notes F.6.5: endpoint to centre parameterisation.
  const double phi = deg_to_rad(phi_deg);
  const double c = std::cos(phi), s = std::sin(phi);
  const Vec2 h = (from - to) / 2.0;
  const Vec2 p1(c * h.x() + s * h.y(), -s * h.x() + c * h.y());
  const double lambda = p1.x() * p1.x() / (rx * rx) + p1.y() * p1.y() / (ry * ry);
  if (lambda > 1.0) {
    rx *= std::sqrt(lambda);
    ry *= std::sqrt(lambda);
  }
  const double num = rx * rx * ry * ry - rx * rx * p1.y() * p1.y() - ry * ry * p1.x() * p1.x();
  const double den = rx * rx * p1.y() * p1.y() + ry * ry * p1.x() * p1.x();
  double k = std::sqrt(std::max(0.0, num / den));
  if (large_arc == sweep) k = -k;
  const Vec2 cp(k * rx * p1.y() / ry, -k * ry * p1.x() / rx);
  const Vec2 mid = (from + to) / 2.0;
  CurvePiece arc;
  arc.kind = CurveKind::Arc;
  arc.center = Vec2(c * cp.x() - s * cp.y(), s * cp.x() + c * cp.y()) + mid;
  arc.axes << c * rx, -s * ry, s * rx, c * ry;
  const Vec2 u((p1.x() - cp.x()) / rx, (p1.y() - cp.y()) / ry);
  const Vec2 v((-p1.x() - cp.x()) / rx, (-p1.y() - cp.y()) / ry);
  arc.t0_rad = std::atan2(u.y(), u.x());
  double dt = std::atan2(v.y(), v.x()) - arc.t0_rad;
  if (sweep && dt < 0) dt += kTwoPi;
  if (!sweep && dt > 0) dt -= kTwoPi;
  arc.sweep_rad = dt;
  return arc;
}

std::vector<SubPath> parse_path_data(std::string_view d, std::string* error,
                                     std::size_t max_pieces) {
  Scanner sc(d);
  PathBuilder b;
  b.max_pieces = max_pieces;
  char cmd = '\0';
  double a[7];
  while (!sc.done()) {
    if (std::isalpha(static_cast<unsigned char>(sc.peek()))) {
      cmd = sc.take();
      const char up = static_cast<char>(std::toupper(static_cast<unsigned char>(cmd)));
      if (std::string_view("MLHVCSQTAZ").find(up) == std::string_view::npos ||
          (b.out.empty() && up != 'M')) {
        if (error)
          *error =
              "unexpected '" + std::string(1, cmd) + "' at offset " + std::to_string(sc.pos() - 1);
        break;
      }
      if (up == 'Z') {
        b.close();
        b.prev = 'Z';
        continue;
      }
    } else if (cmd == '\0' || cmd == 'Z' || cmd == 'z') {
      if (error) *error = "number without a command at offset " + std::to_string(sc.pos());
      break;
    }
    const char up = static_cast<char>(std::toupper(static_cast<unsigned char>(cmd)));
    if (!read_args(sc, up, a)) {
      if (error)
        *error =
            "bad arguments for '" + std::string(1, cmd) + "' at offset " + std::to_string(sc.pos());
      break;
    }
    b.apply(cmd, a);
    if (up == 'M') cmd = (cmd == 'm') ? 'l' : 'L';  // implicit repeats after a move are lines
    sc.skip_comma_space();
  }
  if (!b.out.empty() && b.out.back().pieces.empty()) b.out.pop_back();
  return b.out;
}

Affine parse_transform(std::string_view text) {
  Scanner sc(text);
  Affine total;
  while (!sc.done()) {
    std::string name;
    while (std::isalpha(static_cast<unsigned char>(sc.peek()))) name += sc.take();
    sc.skip_space();
    if (name.empty() || sc.peek() != '(') {
      throw InputError("transform = \"" + std::string(text) +
                       "\": expected a function like translate(x y)");
    }
    sc.take();
    std::vector<double> v;
    for (sc.skip_space(); sc.peek() != ')';) {
      const auto x = sc.number();
      if (!x)
        throw InputError("transform = \"" + std::string(text) + "\": bad number in " + name + "()");
      v.push_back(*x);
      sc.skip_comma_space();
    }
    sc.take();
    const std::size_t n = v.size();
    Affine m;
    const auto bad = [&] {
      return InputError("transform = \"" + std::string(text) + "\": wrong argument count for " +
                        name + "()");
    };
    if (name == "matrix") {
      if (n != 6) throw bad();
      m.linear << v[0], v[2], v[1], v[3];
      m.offset = Vec2(v[4], v[5]);
    } else if (name == "translate") {
      if (n < 1 || n > 2) throw bad();
      m.offset = Vec2(v[0], n == 2 ? v[1] : 0.0);
    } else if (name == "scale") {
      if (n < 1 || n > 2) throw bad();
      m.linear << v[0], 0, 0, (n == 2 ? v[1] : v[0]);
    } else if (name == "rotate") {
      if (n != 1 && n != 3) throw bad();
      const double r = deg_to_rad(v[0]);
      m.linear << std::cos(r), -std::sin(r), std::sin(r), std::cos(r);
      if (n == 3) m.offset = Vec2(v[1], v[2]) - m.linear * Vec2(v[1], v[2]);
    } else if (name == "skewX" || name == "skewY") {
      if (n != 1) throw bad();
      const double t = std::tan(deg_to_rad(v[0]));
      m.linear << 1, (name == "skewX" ? t : 0), (name == "skewY" ? t : 0), 1;
    } else {
      throw InputError("transform = \"" + std::string(text) + "\": unknown function " + name +
                       "()");
    }
    total = compose(total, m);  // later functions apply first to points
    sc.skip_comma_space();
  }
  return total;
}

std::vector<double> parse_number_list(std::string_view text, std::size_t max_count) {
  Scanner sc(text);
  std::vector<double> out;
  while (!sc.done()) {
    if (out.size() >= max_count) {
      throw InputError("points = \"" + std::string(text.substr(0, 40)) + "...\": more than " +
                       std::to_string(max_count) + " numbers");
    }
    const auto v = sc.number();
    if (!v)
      throw InputError("points = \"" + std::string(text.substr(0, 40)) +
                       "\": not a list of numbers");
    out.push_back(*v);
    sc.skip_comma_space();
  }
  return out;
}

double parse_length_px(std::string_view text, const std::string& what) {
  Scanner sc(text);
  const auto v = sc.number();
  if (!v) throw InputError(what + " = \"" + std::string(text) + "\": not a length");
  std::string unit(sc.rest());
  while (!unit.empty() && std::isspace(static_cast<unsigned char>(unit.back()))) unit.pop_back();
  const double in = kPxPerInch;
  if (unit.empty() || unit == "px") return *v;
  if (unit == "mm") return *v * in / kMmPerInch;
  if (unit == "cm") return *v * in / kMmPerInch * 10.0;
  if (unit == "in") return *v * in;
  if (unit == "pt") return *v * in / 72.0;
  if (unit == "pc") return *v * in / 6.0;
  throw InputError(what + " = \"" + std::string(text) + "\": unknown unit '" + unit +
                   "' (use px, mm, cm, in, pt, pc, em, ex or %)");
}

namespace {

double resolve_finite(std::string_view text, LengthAxis axis, const LengthBasis& basis,
                      const std::string& what);

}  // namespace

double resolve_length_px(std::string_view text, LengthAxis axis, const LengthBasis& basis,
                         const std::string& what) {
  const double v = resolve_finite(text, axis, basis, what);
  if (!std::isfinite(v))
    throw InputError(what + " = \"" + std::string(text) + "\": not a finite length");
  return v;
}

namespace {

double resolve_finite(std::string_view text, LengthAxis axis, const LengthBasis& basis,
                      const std::string& what) {
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back())))
    text.remove_suffix(1);
  const auto number = [&](std::size_t suffix) {
    Scanner sc(text.substr(0, text.size() - suffix));
    const auto v = sc.number();
    if (!v || !sc.done()) throw InputError(what + " = \"" + std::string(text) + "\": not a length");
    return *v;
  };
  const auto ends = [&](std::string_view unit) {
    return text.size() > unit.size() && text.substr(text.size() - unit.size()) == unit;
  };
  if (ends("%")) {
    const Vec2& v = basis.viewport;
    const double full = axis == LengthAxis::X   ? v.x()
                        : axis == LengthAxis::Y ? v.y()
                                                : std::sqrt((v.x() * v.x() + v.y() * v.y()) / 2.0);
    return number(1) * full / 100.0;
  }
  if (ends("em")) return number(2) * basis.font_size_px;
  if (ends("ex")) return number(2) * basis.font_size_px / 2.0;
  return parse_length_px(text, what);
}

}  // namespace

std::string normalise_color(std::string_view text) {
  static const std::map<std::string, std::string> kNamed = {
      {"black", "#000000"},   {"white", "#ffffff"},  {"red", "#ff0000"},    {"green", "#008000"},
      {"lime", "#00ff00"},    {"blue", "#0000ff"},   {"yellow", "#ffff00"}, {"cyan", "#00ffff"},
      {"magenta", "#ff00ff"}, {"orange", "#ffa500"}, {"purple", "#800080"}, {"gray", "#808080"},
      {"grey", "#808080"},    {"brown", "#a52a2a"},  {"navy", "#000080"},   {"pink", "#ffc0cb"}};
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.front())))
    text.remove_prefix(1);
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back())))
    text.remove_suffix(1);
  std::string s(text);
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char ch) { return std::tolower(ch); });
  if (kNamed.count(s)) return kNamed.at(s);
  const auto hex = [](const std::string& h) {
    return std::all_of(h.begin(), h.end(), [](unsigned char ch) { return std::isxdigit(ch); });
  };
  if (s.size() == 4 && s[0] == '#' && hex(s.substr(1))) {
    return std::string("#") + s[1] + s[1] + s[2] + s[2] + s[3] + s[3];
  }
  if (s.rfind("rgb(", 0) == 0 && s.back() == ')') {
    std::vector<double> v;
    try {
      v = parse_number_list(s.substr(4, s.size() - 5), 3);
    } catch (const InputError&) {
      return s;  // rgb() with percentages or too many numbers: kept as text
    }
    if (v.size() == 3) {
      char buf[8];
      const auto ch = [](double x) { return static_cast<int>(std::clamp(x, 0.0, 255.0)); };
      std::snprintf(buf, sizeof buf, "#%02x%02x%02x", ch(v[0]), ch(v[1]), ch(v[2]));
      return buf;
    }
  }
  return s;
}

}  // namespace strand::slicer
