// Number formatting with std::to_chars (locale-independent, shortest code path).
#include "machines/gcode_format.h"

#include <charconv>
#include <cmath>

namespace strand::machines {

std::string fmt_fixed(double v, int decimals) {
  const double scale = std::pow(10.0, decimals);
  double r = std::round(v * scale) / scale;
  if (r == 0.0) r = 0.0;  // turns -0 into +0
  char buf[64];
  auto res = std::to_chars(buf, buf + sizeof buf, r, std::chars_format::fixed, decimals);
  return std::string(buf, res.ptr);
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

}  // namespace strand::machines
