// RS274NGC values as LinuxCNC and Planet CNC read them: numbers, parameters (`#1`, `#<name>`,
// `##1`), `[...]` expressions with the binary operators (precedence high to low: `**`/POWER;
// `*`, `/`, MOD; `+`, `-`; EQ NE GT GE LT LE; AND OR XOR; left to right within a group) and the
// functions ABS ACOS ASIN ATAN[a]/[b] COS EXP FIX FUP LN ROUND SIN SQRT TAN EXISTS (angles in
// degrees). Spaces and tabs are ignored, names are case-insensitive. Errors (division by zero,
// LN of 0, an unset parameter, a malformed expression) throw NgcError; what the reader cannot
// know (probe results, HAL pins) throws NgcUnsupported. Work is linear in the text: nesting is
// bounded by kMaxNgcDepth.
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace strand::post {

inline constexpr int kMaxNgcDepth = 64;                // nested brackets and indirections
inline constexpr int kMaxNgcNumberedParameter = 5602;  // LinuxCNC's #1 .. #5602

struct NgcError : std::runtime_error {
  using std::runtime_error::runtime_error;
};
struct NgcUnsupported : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Where parameter values come from. `name` is lower-case without spaces.
class NgcScope {
 public:
  virtual ~NgcScope() = default;
  // Unset numbered parameters read 0 (RS274NGC); the scope throws NgcUnsupported for system
  // parameters it cannot know.
  virtual double numbered(int index) const = 0;
  // nullopt: not set (an error, or false for EXISTS).
  virtual std::optional<double> named(const std::string& name) const = 0;
};

// Reads one real value at text[pos] (a number, a parameter, `[expression]`, a function, with
// an optional sign) and advances pos past it.
double ngc_real_value(std::string_view text, std::size_t& pos, const NgcScope& scope);

// A parameter reference at text[pos] (after its '#'): the numbered index or the lower-case name.
struct NgcParameterRef {
  int index = 0;     // > 0 for #n
  std::string name;  // for #<name>
};
NgcParameterRef ngc_parameter_ref(std::string_view text, std::size_t& pos, const NgcScope& scope);

// The whole text as one real value (tests and the fuzzer): trailing text is an error.
double ngc_evaluate(std::string_view text, const NgcScope& scope);

// A scope with no parameters set (positions 0).
class NgcEmptyScope : public NgcScope {
 public:
  double numbered(int) const override { return 0.0; }
  std::optional<double> named(const std::string&) const override { return std::nullopt; }
};

}  // namespace strand::post
