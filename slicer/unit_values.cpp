// Numbers with units, lists and sizes, paper names and choices, read into a table's unit.
#include "slicer/unit_values.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <system_error>

namespace strand::slicer {

namespace {

// A unit as written, and its size in its dimension's base unit (mm, mm/min, deg, px) as
// multiplier * 10^exponent; rad is the one irrational factor (flag `radian`).
struct UnitName {
  std::string_view text;
  Dimension dimension;
  int multiplier;
  int exponent;
  bool radian = false;
};

// Longest names first where one is a prefix of another ("mm/min" before "mm/s", "mm", "m").
constexpr UnitName kUnits[] = {
    {"mm/min", Dimension::Speed, 1, 0},
    {"mm/s", Dimension::Speed, 6, 1},
    {"\xC2\xB5m", Dimension::Length, 1, -3},  // µm, the micro sign
    {"\xCE\xBCm", Dimension::Length, 1, -3},  // μm, the Greek mu
    {"deg", Dimension::Angle, 1, 0},
    {"rad", Dimension::Angle, 1, 0, true},
    {"\xC2\xB0", Dimension::Angle, 1, 0},  // °
    {"mm", Dimension::Length, 1, 0},
    {"cm", Dimension::Length, 1, 1},
    {"um", Dimension::Length, 1, -3},
    {"in", Dimension::Length, 254, -1},
    {"px", Dimension::Pixels, 1, 0},
    {"m", Dimension::Length, 1, 3},
};

const UnitName* find_unit(std::string_view text) {
  for (const auto& u : kUnits) {
    if (u.text == text) return &u;
  }
  return nullptr;
}

struct Paper {
  std::string_view name;
  double width_mm, height_mm;  // portrait
};

constexpr Paper kPapers[] = {
    {"A0", 841, 1189},      {"A1", 594, 841},       {"A2", 420, 594},
    {"A3", 297, 420},       {"A4", 210, 297},       {"A5", 148, 210},
    {"A6", 105, 148},       {"letter", 215.9, 279.4}, {"legal", 215.9, 355.6},
    {"tabloid", 279.4, 431.8},
};

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

bool is_space(char c) { return c == ' ' || c == '\t'; }
bool is_digit(char c) { return c >= '0' && c <= '9'; }

// A number as written: sign, the mantissa's digits without the point, and the power of ten
// they are scaled by ("-8.4e-1" -> negative, "84", -2).
struct Decimal {
  bool negative = false;
  std::string digits;
  long exponent = 0;
};

// Reads a decimal number at `at`; false (and `at` unchanged) if none starts there. An 'e'
// not followed by digits is left for the unit.
bool read_decimal(std::string_view s, std::size_t& at, Decimal& d) {
  std::size_t i = at;
  d = Decimal{};
  if (i < s.size() && (s[i] == '+' || s[i] == '-')) d.negative = s[i++] == '-';
  std::size_t mantissa_digits = 0;
  for (; i < s.size() && is_digit(s[i]); ++i, ++mantissa_digits) d.digits += s[i];
  if (i < s.size() && s[i] == '.') {
    for (++i; i < s.size() && is_digit(s[i]); ++i, ++mantissa_digits, --d.exponent) d.digits += s[i];
  }
  if (mantissa_digits == 0) return false;
  if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
    std::size_t j = i + 1;
    bool minus = false;
    if (j < s.size() && (s[j] == '+' || s[j] == '-')) minus = s[j++] == '-';
    if (j < s.size() && is_digit(s[j])) {
      long e = 0;
      while (j < s.size() && is_digit(s[j])) {
        e = std::min(e * 10 + (s[j] - '0'), 1'000'000L);  // far past any double
        ++j;
      }
      d.exponent += minus ? -e : e;
      i = j;
    }
  }
  at = i;
  return true;
}

// d * multiplier * 10^exponent as the nearest double: the digits are multiplied exactly
// and converted once.
std::optional<double> to_double(Decimal d, int multiplier, int exponent) {
  if (multiplier != 1) {
    int carry = 0;
    for (auto it = d.digits.rbegin(); it != d.digits.rend(); ++it) {
      const int v = (*it - '0') * multiplier + carry;
      *it = static_cast<char>('0' + v % 10);
      carry = v / 10;
    }
    while (carry > 0) {
      d.digits.insert(d.digits.begin(), static_cast<char>('0' + carry % 10));
      carry /= 10;
    }
  }
  const std::string text = (d.negative ? "-" : "") + d.digits + "e" +
                           std::to_string(d.exponent + exponent);
  double v = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec == std::errc::result_out_of_range) {
    // Underflow is a zero; overflow is no number a table accepts.
    const bool tiny = d.exponent + exponent < 0;
    if (!tiny) return std::nullopt;
    return d.negative ? -0.0 : 0.0;
  }
  if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

bool is_separator(std::string_view s, std::size_t at, char separator) {
  if (at >= s.size()) return false;
  if (s[at] == separator) return true;
  if (separator == 'x') return s[at] == 'X' || s.substr(at).starts_with("\xC3\x97");  // ×
  return false;
}

std::size_t separator_length(std::string_view s, std::size_t at) {
  return s.substr(at).starts_with("\xC3\x97") ? 2 : 1;
}

bool boundary(std::string_view s, std::size_t at, char separator) {
  return at >= s.size() || is_space(s[at]) || is_separator(s, at, separator);
}

// One element: a number, spaces, an optional unit. `unit` is left empty when none is
// written; an unknown unit is returned as its text with `known` null.
struct Element {
  Decimal number;
  std::string unit;
  const UnitName* known = nullptr;
};

bool read_element(std::string_view s, std::size_t& at, char separator, Element& e) {
  while (at < s.size() && is_space(s[at])) ++at;
  if (!read_decimal(s, at, e.number)) return false;
  while (at < s.size() && is_space(s[at])) ++at;
  if (at >= s.size() || is_separator(s, at, separator)) return true;
  for (const auto& u : kUnits) {
    if (s.substr(at).starts_with(u.text) && boundary(s, at + u.text.size(), separator)) {
      e.unit = std::string(u.text);
      e.known = &u;
      at += u.text.size();
      return true;
    }
  }
  // Not a unit of ours: everything up to a space or separator, so the message can say no.
  // Text that cannot start a unit ("1,5", "2;") is no number at all.
  const unsigned char first = static_cast<unsigned char>(s[at]);
  if (!std::isalpha(first) && first < 0x80 && first != '"' && first != '\'') return false;
  const std::size_t start = at;
  while (!boundary(s, at, separator)) ++at;
  e.unit = std::string(s.substr(start, at - start));
  return true;
}

struct Target {
  std::optional<Dimension> dimension;
  const UnitName* unit = nullptr;  // the table unit among ours
};

Target target_of(std::string_view table_unit) {
  Target t;
  t.dimension = dimension_of(table_unit);
  t.unit = find_unit(table_unit);
  return t;
}

// The element's value in the table's unit, or the problem.
std::optional<double> convert(const Element& e, std::string_view table_unit, const Target& t,
                              std::string& problem) {
  if (e.unit.empty() || e.unit == table_unit) {
    auto v = to_double(e.number, 1, 0);
    if (!v) problem = "must be a number";
    return v;
  }
  if (!e.known || !t.unit || e.known->dimension != t.unit->dimension) {
    problem = "expected " + expected_units(table_unit);
    return std::nullopt;
  }
  std::optional<double> base;
  if (e.known->radian) {
    const auto rad = to_double(e.number, 1, 0);
    if (rad) {
      constexpr long double kDegPerRad = 180.0L / 3.141592653589793238462643383279502884L;
      base = static_cast<double>(static_cast<long double>(*rad) * kDegPerRad);
    }
  } else {
    base = to_double(e.number, e.known->multiplier, e.known->exponent);
  }
  if (!base) {
    problem = "must be a number";
    return std::nullopt;
  }
  if (t.unit->multiplier == 1 && t.unit->exponent == 0) return base;
  // A table unit that is not its dimension's base (none today): one rounded division.
  const double v =
      *base / (t.unit->multiplier * std::pow(10.0, static_cast<double>(t.unit->exponent)));
  if (!std::isfinite(v)) {
    problem = "must be a number";
    return std::nullopt;
  }
  return v;
}

}  // namespace

std::optional<Dimension> dimension_of(std::string_view table_unit) {
  if (table_unit.empty()) return Dimension::None;
  if (const UnitName* u = find_unit(table_unit)) return u->dimension;
  return std::nullopt;
}

std::string expected_units(std::string_view table_unit) {
  const auto d = dimension_of(table_unit);
  if (!d) return "a plain number or " + std::string(table_unit);
  switch (*d) {
    case Dimension::None: return "a plain number (no unit)";
    case Dimension::Length: return "a length (mm, cm, m, um, in)";
    case Dimension::Speed: return "a speed (mm/min, mm/s)";
    case Dimension::Angle: return "an angle (deg, rad)";
    case Dimension::Pixels: return "pixels (px)";
  }
  return "";
}

UnitValues parse_quantities(std::string_view text, std::string_view table_unit, char separator) {
  UnitValues r;
  std::vector<Element> elements;
  std::size_t at = 0;
  while (true) {
    Element e;
    if (!read_element(text, at, separator, e)) {
      r.malformed = true;
      return r;
    }
    elements.push_back(std::move(e));
    while (at < text.size() && is_space(text[at])) ++at;
    if (at >= text.size()) break;
    if (separator == 0 || !is_separator(text, at, separator)) {
      r.malformed = true;
      return r;
    }
    at += separator_length(text, at);
  }
  // One unit after the last number applies to every number before it written without one.
  const std::string& last = elements.back().unit;
  for (auto& e : elements) {
    if (!e.unit.empty()) continue;
    if (last.empty()) continue;
    e.unit = last;
    e.known = elements.back().known;
  }
  if (last.empty()) {
    for (const auto& e : elements) {
      if (!e.unit.empty()) {
        r.unit_problem = "give the unit after every number, or once after the last";
        return r;
      }
    }
  }
  const Target t = target_of(table_unit);
  for (const auto& e : elements) {
    std::string problem;
    const auto v = convert(e, table_unit, t, problem);
    if (!v) {
      if (problem == "must be a number") {
        r.malformed = true;
      } else {
        r.unit_problem = problem;
      }
      r.values.clear();
      return r;
    }
    r.values.push_back(*v);
  }
  return r;
}

UnitValues parse_quantity(std::string_view text, std::string_view table_unit) {
  return parse_quantities(text, table_unit, 0);
}

std::optional<std::array<double, 2>> paper_size_mm(std::string_view text) {
  std::string s = lower(text);
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string::npos) return std::nullopt;
  s = s.substr(b, s.find_last_not_of(" \t") - b + 1);
  bool landscape = false;
  for (const std::string_view orientation : {"landscape", "portrait"}) {
    if (s.size() > orientation.size() && s.ends_with(orientation)) {
      std::string rest = s.substr(0, s.size() - orientation.size());
      const char sep = rest.back();
      if (sep != ' ' && sep != '-' && sep != '_' && sep != '\t') continue;
      while (!rest.empty() && (rest.back() == ' ' || rest.back() == '\t')) rest.pop_back();
      if (!rest.empty() && (rest.back() == '-' || rest.back() == '_')) rest.pop_back();
      while (!rest.empty() && (rest.back() == ' ' || rest.back() == '\t')) rest.pop_back();
      s = rest;
      landscape = orientation == "landscape";
      break;
    }
  }
  for (const auto& p : kPapers) {
    if (lower(p.name) == s) {
      if (landscape) return std::array<double, 2>{p.height_mm, p.width_mm};
      return std::array<double, 2>{p.width_mm, p.height_mm};
    }
  }
  return std::nullopt;
}

std::string paper_names() {
  std::string out;
  for (const auto& p : kPapers) out += (out.empty() ? "" : ", ") + std::string(p.name);
  return out;
}

bool looks_like_name(std::string_view text) {
  for (const char c : text) {
    if (is_space(c)) continue;
    return std::isalpha(static_cast<unsigned char>(c)) != 0;
  }
  return false;
}

std::optional<std::string> match_choice(std::string_view text,
                                        const std::vector<std::string>& choices) {
  const std::string t = lower(text);
  for (const auto& c : choices) {
    if (lower(c) == t) return c;
  }
  return std::nullopt;
}

}  // namespace strand::slicer
