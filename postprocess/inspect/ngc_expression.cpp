// Recursive descent over one line; depth bounded, so hostile nesting cannot exhaust the stack.
#include "postprocess/inspect/ngc_expression.h"

#include <charconv>
#include <cmath>

#include "slicer/params.h"
#include "slicer/units.h"

namespace strand::post {

namespace {

// LinuxCNC compares with this tolerance (EQ, NE, GE, LE).
constexpr double kEqualTolerance = 1e-4;

bool is_alpha(char c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z'); }
char lower(char c) { return c >= 'A' && c <= 'Z' ? static_cast<char>(c + 32) : c; }

std::string num(double v) { return slicer::short_number(v); }

class Parser {
 public:
  Parser(std::string_view text, std::size_t& pos, const NgcScope& scope)
      : t_(text), pos_(pos), scope_(scope) {}

  double real_value() {
    Depth d(*this);
    skip();
    if (pos_ >= t_.size()) throw NgcError("a value is missing at the end of the line");
    const char c = t_[pos_];
    if (c == '[') return bracketed();
    if (c == '#') {
      ++pos_;
      const NgcParameterRef ref = parameter_ref();
      return value_of(ref);
    }
    if (c == '-' || c == '+') {
      ++pos_;
      const double v = real_value();
      return c == '-' ? -v : v;
    }
    if (is_alpha(c)) return function();
    return number();
  }

  NgcParameterRef parameter_ref() {
    Depth d(*this);
    skip();
    NgcParameterRef ref;
    if (pos_ < t_.size() && t_[pos_] == '<') {
      const std::size_t close = t_.find('>', pos_);
      if (close == std::string_view::npos) throw NgcError("'>' missing after #<");
      for (std::size_t i = pos_ + 1; i < close; ++i) {
        if (t_[i] != ' ' && t_[i] != '\t') ref.name += lower(t_[i]);
      }
      if (ref.name.empty()) throw NgcError("empty parameter name #<>");
      pos_ = close + 1;
      return ref;
    }
    const double v = real_value();  // #1, #[1+1], ##2
    if (!(v >= 1 && v <= kMaxNgcNumberedParameter) || v != std::floor(v))
      throw NgcError("parameter #" + num(v) + ": must be a whole number in [1, " +
                     std::to_string(kMaxNgcNumberedParameter) + "]");
    ref.index = static_cast<int>(v);
    return ref;
  }

  double value_of(const NgcParameterRef& ref) const {
    if (ref.index > 0) return scope_.numbered(ref.index);
    if (auto v = scope_.named(ref.name)) return *v;
    if (ref.name[0] == '_') throw NgcUnsupported("parameter #<" + ref.name + ">");
    throw NgcError("parameter #<" + ref.name + "> is used before it is set");
  }

 private:
  // Counts nesting; throws past kMaxNgcDepth.
  struct Depth {
    explicit Depth(Parser& p) : p_(p) {
      if (++p_.depth_ > kMaxNgcDepth)
        throw NgcError("expression nested deeper than " + std::to_string(kMaxNgcDepth));
    }
    ~Depth() { --p_.depth_; }
    Parser& p_;
  };

  void skip() {
    while (pos_ < t_.size() && (t_[pos_] == ' ' || t_[pos_] == '\t' || t_[pos_] == '\r')) ++pos_;
  }

  void expect(char c) {
    skip();
    if (pos_ >= t_.size() || t_[pos_] != c)
      throw NgcError(std::string("'") + c + "' expected" + where());
    ++pos_;
  }

  std::string where() const {
    return pos_ >= t_.size() ? " at the end of the line"
                             : " before '" + std::string(t_.substr(pos_, 12)) + "'";
  }

  double number() {
    skip();
    double v = 0.0;
    const auto r = std::from_chars(t_.data() + pos_, t_.data() + t_.size(), v);
    if (r.ec != std::errc() || (pos_ < t_.size() && is_alpha(t_[pos_])))
      throw NgcError("a number expected" + where());
    // from_chars reads "1e5", "inf" and "nan": G-code has no exponents and no infinities.
    for (const char* p = t_.data() + pos_; p < r.ptr; ++p) {
      if (!((*p >= '0' && *p <= '9') || *p == '.'))
        throw NgcError("malformed number '" + std::string(t_.data() + pos_, r.ptr) + "'");
    }
    pos_ = static_cast<std::size_t>(r.ptr - t_.data());
    return v;
  }

  std::string word() {
    skip();
    std::string w;
    while (pos_ < t_.size() && is_alpha(t_[pos_]) && w.size() < 8) w += lower(t_[pos_++]);
    return w;
  }

  double bracketed() {
    expect('[');
    const double v = binary(0);
    expect(']');
    return v;
  }

  double function() {
    const std::size_t start = pos_;
    const std::string f = word();
    if (f == "exists") {
      expect('[');
      expect('#');
      const NgcParameterRef ref = parameter_ref();
      expect(']');
      return ref.index > 0 || scope_.named(ref.name) ? 1.0 : 0.0;
    }
    if (f == "atan") {
      const double y = bracketed();
      expect('/');
      const double x = bracketed();
      return slicer::rad_to_deg(std::atan2(y, x));
    }
    static const char* kUnary[] = {"abs", "acos", "asin",  "cos", "exp",  "fix",
                                   "fup", "ln",   "round", "sin", "sqrt", "tan"};
    bool known = false;
    for (const char* u : kUnary) known = known || f == u;
    if (!known) {
      pos_ = start;
      throw NgcError("unknown function or word '" + f + "'" + where());
    }
    const double a = bracketed();
    if (f == "abs") return std::abs(a);
    if (f == "acos" || f == "asin") {
      if (a < -1.0 || a > 1.0) throw NgcError(f + "[" + num(a) + "]: outside [-1, 1]");
      return slicer::rad_to_deg(f == "acos" ? std::acos(a) : std::asin(a));
    }
    if (f == "cos") return std::cos(slicer::deg_to_rad(a));
    if (f == "sin") return std::sin(slicer::deg_to_rad(a));
    if (f == "tan") return std::tan(slicer::deg_to_rad(a));
    if (f == "exp") return finite(std::exp(a), "exp[" + num(a) + "]");
    if (f == "fix") return std::floor(a);
    if (f == "fup") return std::ceil(a);
    if (f == "round") return std::round(a);
    if (f == "ln") {
      if (!(a > 0)) throw NgcError("ln[" + num(a) + "]: needs a value > 0");
      return std::log(a);
    }
    if (!(a >= 0)) throw NgcError("sqrt[" + num(a) + "]: needs a value >= 0");
    return std::sqrt(a);
  }

  static double finite(double v, const std::string& what) {
    if (!std::isfinite(v)) throw NgcError(what + " is not a finite number");
    return v;
  }

  // Operator at pos_ and its precedence (4 = power ... 0 = logical); -1 when none.
  int peek_operator(std::string& op) {
    skip();
    if (pos_ >= t_.size()) return -1;
    const char c = t_[pos_];
    if (c == '*' && pos_ + 1 < t_.size() && t_[pos_ + 1] == '*') return op = "**", 4;
    if (c == '*' || c == '/') return op = std::string(1, c), 3;
    if (c == '+' || c == '-') return op = std::string(1, c), 2;
    if (!is_alpha(c)) return -1;
    std::size_t end = pos_;
    std::string w;
    while (end < t_.size() && is_alpha(t_[end]) && w.size() < 8) w += lower(t_[end++]);
    op = w;
    if (w == "power") return 4;
    if (w == "mod") return 3;
    if (w == "eq" || w == "ne" || w == "gt" || w == "ge" || w == "lt" || w == "le") return 1;
    if (w == "and" || w == "or" || w == "xor") return 0;
    return -1;
  }

  // Precedence climbing: left to right within a group.
  double binary(int min_level) {
    Depth d(*this);
    double left = real_value();
    while (true) {
      std::string op;
      const int level = peek_operator(op);
      if (level < min_level) return left;
      pos_ += op.size();
      const double right = binary(level + 1);
      left = apply(op, left, right);
    }
  }

  static double apply(const std::string& op, double a, double b) {
    const std::string what = "[" + num(a) + " " + op + " " + num(b) + "]";
    if (op == "+") return finite(a + b, what);
    if (op == "-") return finite(a - b, what);
    if (op == "*") return finite(a * b, what);
    if (op == "/") {
      if (b == 0.0) throw NgcError("division by zero " + what);
      return finite(a / b, what);
    }
    if (op == "mod") {
      if (b == 0.0) throw NgcError("division by zero " + what);
      double m = std::fmod(a, b);
      if (m < 0.0) m += std::abs(b);
      return m;
    }
    if (op == "**" || op == "power") {
      if (a < 0 && b != std::floor(b))
        throw NgcError("negative base to a fractional power " + what);
      if (a == 0 && b < 0) throw NgcError("division by zero " + what);
      return finite(std::pow(a, b), what);
    }
    const bool eq = std::abs(a - b) < kEqualTolerance;
    if (op == "eq") return eq;
    if (op == "ne") return !eq;
    if (op == "gt") return a > b && !eq;
    if (op == "ge") return a > b || eq;
    if (op == "lt") return a < b && !eq;
    if (op == "le") return a < b || eq;
    if (op == "and") return a != 0.0 && b != 0.0;
    if (op == "or") return a != 0.0 || b != 0.0;
    return (a != 0.0) != (b != 0.0);  // xor
  }

  std::string_view t_;
  std::size_t& pos_;
  const NgcScope& scope_;
  int depth_ = 0;
};

}  // namespace

double ngc_real_value(std::string_view text, std::size_t& pos, const NgcScope& scope) {
  return Parser(text, pos, scope).real_value();
}

NgcParameterRef ngc_parameter_ref(std::string_view text, std::size_t& pos, const NgcScope& scope) {
  return Parser(text, pos, scope).parameter_ref();
}

double ngc_evaluate(std::string_view text, const NgcScope& scope) {
  std::size_t pos = 0;
  const double v = ngc_real_value(text, pos, scope);
  while (pos < text.size() && (text[pos] == ' ' || text[pos] == '\t')) ++pos;
  if (pos != text.size())
    throw NgcError("unexpected '" + std::string(text.substr(pos, 12)) + "' after the value");
  return v;
}

}  // namespace strand::post
