// The cursor the SVG attribute parsers share: spaces, commas, numbers and arc flags as the
// SVG 1.1 grammar spells them (used by svg_syntax.cpp and svg_path_data.cpp).
#pragma once

#include <cctype>
#include <cstddef>
#include <optional>
#include <string_view>

namespace strand::slicer {

// Cursor over attribute text with the SVG number grammar (number() and flag() are defined
// in svg_syntax.cpp).
class SvgScanner {
 public:
  explicit SvgScanner(std::string_view s) : s_(s) {}
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
  std::optional<double> number();
  // flag ::= '0' | '1' (arc flags may be packed without separators)
  std::optional<bool> flag();

 private:
  std::string_view s_;
  std::size_t i_ = 0;
};

}  // namespace strand::slicer
