// Recursive-descent parsers for SVG transform lists, number lists, lengths and
// colours, and the number grammar of the attribute scanner (svg_scanner.h).
#include "slicer/svg_syntax.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>

#include "slicer/input_error.h"
#include "slicer/svg_scanner.h"
#include "slicer/units.h"

namespace strand::slicer {

namespace {

constexpr double kPxPerInch = 96.0;

}  // namespace

// number ::= sign? (digits ('.' digits?)? | '.' digits) exponent?
std::optional<double> SvgScanner::number() {
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
std::optional<bool> SvgScanner::flag() {
  skip_comma_space();
  if (peek() != '0' && peek() != '1') return std::nullopt;
  return take() == '1';
}

Affine parse_transform(std::string_view text) {
  SvgScanner sc(text);
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
  SvgScanner sc(text);
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
  SvgScanner sc(text);
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
    SvgScanner sc(text.substr(0, text.size() - suffix));
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