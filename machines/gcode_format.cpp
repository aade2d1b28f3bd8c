// Number formatting: rounds to an integer count of 10^-decimals and writes its digits; values
// too large for that (or non-finite) go through std::to_chars of the rounded double, which
// gives the same text wherever both apply.
#include "machines/gcode_format.h"

#include <charconv>
#include <cmath>
#include <cstdint>

namespace strand::machines {

namespace {

constexpr double kPow10[] = {1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9};
constexpr std::uint64_t kPow10Int[] = {1,      10,      100,      1000,      10000,
                                       100000, 1000000, 10000000, 100000000, 1000000000};
// Below this many units the double nearest k / 10^d prints back as exactly k (2^52 > 4.5e15).
constexpr double kExactUnits = 1e15;

std::size_t put_digits(char* out, std::uint64_t u, int min_digits) {
  char rev[24];
  int n = 0;
  do {
    rev[n++] = static_cast<char>('0' + u % 10);
    u /= 10;
  } while (u > 0 || n < min_digits);
  for (int i = 0; i < n; ++i) out[i] = rev[n - 1 - i];
  return static_cast<std::size_t>(n);
}

}  // namespace

std::size_t fixed_chars(char* out, double v, int decimals) {
  const bool table = decimals >= 0 && decimals <= 9;
  const double scale = table ? kPow10[decimals] : std::pow(10.0, decimals);
  const double k = std::round(v * scale);
  if (!table || !(std::abs(k) < kExactUnits)) {
    double r = k / scale;
    if (r == 0.0) r = 0.0;  // turns -0 into +0
    return static_cast<std::size_t>(
        std::to_chars(out, out + kFixedCharsMax, r, std::chars_format::fixed, decimals).ptr - out);
  }
  const auto units = static_cast<std::int64_t>(k);
  std::uint64_t u = units < 0 ? static_cast<std::uint64_t>(-units) : static_cast<std::uint64_t>(units);
  std::size_t n = 0;
  if (units < 0) out[n++] = '-';
  const std::uint64_t p = kPow10Int[decimals];
  n += put_digits(out + n, u / p, 1);
  if (decimals > 0) {
    out[n++] = '.';
    n += put_digits(out + n, u % p, decimals);
  }
  return n;
}

std::string fmt_fixed(double v, int decimals) {
  char buf[kFixedCharsMax];
  return std::string(buf, fixed_chars(buf, v, decimals));
}

std::string comment_text(std::string text, bool parentheses) {
  for (char& c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 0x20 || u == 0x7f) c = ' ';
    if (!parentheses && c == '(') c = '[';
    if (!parentheses && c == ')') c = ']';
  }
  return text;
}

// The nearest honest PrusaSlicer role (docs/checking-gcode.md has the table and the why):
// nothing is called "Top", "Overhang" or "External" unless it is. A link lies outside the
// part and is sacrificial, as a skirt (PrusaSlicer's draft shield repeats it every layer).
std::string viewer_role(slicer::Feature f) {
  switch (f) {
    case slicer::Feature::Infill: return "Solid infill";
    case slicer::Feature::Wall: return "Perimeter";
    case slicer::Feature::Ligament: return "Internal infill";
    case slicer::Feature::Node:
      return "Perimeter";
    case slicer::Feature::Grip:
      return "Solid infill";
    case slicer::Feature::Frame:
      return "External perimeter";
    case slicer::Feature::Link: return "Skirt/Brim";
    case slicer::Feature::Pen: return "Perimeter";
  }
  return "Custom";
}

std::string replace_all(std::string s, const std::string& from, const std::string& to) {
  for (std::size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size())) {
    s.replace(at, from.size(), to);
  }
  return s;
}

}  // namespace strand::machines
