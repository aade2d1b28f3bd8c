// Recursive-descent parser and evaluator for sweep constraints.
#include "jobs/sweep_constraint.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>

#include "slicer/input_error.h"

namespace strand::jobs {

struct Constraint::Node {
  char kind = 'n';  // 'n' number, 'v' variable, '+', '-', '*', '/', 'u' (unary minus)
  double number = 0.0;
  std::string name;
  std::shared_ptr<const Node> a, b;
};

namespace {

using NodePtr = std::shared_ptr<const Constraint::Node>;

class Parser {
 public:
  // Bounds that keep parsing, evaluating and freeing the tree shallow (no stack overflow).
  static constexpr std::size_t kMaxLength = 500;
  static constexpr int kMaxDepth = 32;

  Parser(const std::string& text, const std::string& where) : s_(text), where_(where) {}

  Constraint parse() {
    if (s_.size() > kMaxLength) fail("longer than " + std::to_string(kMaxLength) + " characters");
    Constraint c;
    c.text = s_;
    c.lhs = expr();
    c.op = comparison();
    c.rhs = expr();
    skip_space();
    if (i_ != s_.size()) fail("unexpected '" + s_.substr(i_) + "'");
    std::sort(names_.begin(), names_.end());
    names_.erase(std::unique(names_.begin(), names_.end()), names_.end());
    c.names = names_;
    return c;
  }

 private:
  [[noreturn]] void fail(const std::string& why) const {
    const std::string shown = s_.size() > 80 ? s_.substr(0, 77) + "..." : s_;
    throw InputError(where_ + " = \"" + shown + "\": " + why +
                     " (write e.g. \"gap >= nozzle\"; operators + - * / ( ) and < <= > >= == !=)");
  }
  void skip_space() {
    while (i_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[i_]))) ++i_;
  }
  bool eat(char c) {
    skip_space();
    if (i_ < s_.size() && s_[i_] == c) {
      ++i_;
      return true;
    }
    return false;
  }
  std::string comparison() {
    skip_space();
    for (const char* op : {"<=", ">=", "==", "!=", "<", ">"}) {
      if (s_.compare(i_, std::char_traits<char>::length(op), op) == 0) {
        i_ += std::char_traits<char>::length(op);
        return op;
      }
    }
    fail("expected a comparison (< <= > >= == !=)");
  }
  NodePtr make(char kind, NodePtr a, NodePtr b) {
    auto n = std::make_shared<Constraint::Node>();
    n->kind = kind;
    n->a = std::move(a);
    n->b = std::move(b);
    return n;
  }
  NodePtr expr() {
    NodePtr left = term();
    for (;;) {
      if (eat('+')) {
        left = make('+', left, term());
      } else if (eat('-')) {
        left = make('-', left, term());
      } else {
        return left;
      }
    }
  }
  NodePtr term() {
    NodePtr left = factor();
    for (;;) {
      if (eat('*')) {
        left = make('*', left, factor());
      } else if (eat('/')) {
        left = make('/', left, factor());
      } else {
        return left;
      }
    }
  }
  NodePtr factor() {
    if (++depth_ > kMaxDepth) fail("nested deeper than " + std::to_string(kMaxDepth) + " levels");
    NodePtr n = primary();
    --depth_;
    return n;
  }
  NodePtr primary() {
    if (eat('(')) {
      NodePtr inner = expr();
      if (!eat(')')) fail("missing ')'");
      return inner;
    }
    if (eat('-')) return make('u', factor(), nullptr);
    skip_space();
    if (i_ >= s_.size()) fail("expression ends early");
    auto n = std::make_shared<Constraint::Node>();
    const char c = s_[i_];
    if (std::isalpha(static_cast<unsigned char>(c))) {
      const std::size_t start = i_;
      while (i_ < s_.size() && (std::isalnum(static_cast<unsigned char>(s_[i_])) || s_[i_] == '-' || s_[i_] == '_')) ++i_;
      n->kind = 'v';
      n->name = s_.substr(start, i_ - start);
      names_.push_back(n->name);
      return n;
    }
    const auto [end, ec] = std::from_chars(s_.data() + i_, s_.data() + s_.size(), n->number);
    if (ec != std::errc() || !std::isfinite(n->number)) fail("expected a number or a parameter at '" + s_.substr(i_) + "'");
    i_ = static_cast<std::size_t>(end - s_.data());
    return n;
  }

  const std::string& s_;
  const std::string& where_;
  std::size_t i_ = 0;
  int depth_ = 0;
  std::vector<std::string> names_;
};

double eval(const Constraint::Node& n, const std::map<std::string, double>& v) {
  switch (n.kind) {
    case 'n': return n.number;
    case 'v': return v.at(n.name);
    case 'u': return -eval(*n.a, v);
    case '+': return eval(*n.a, v) + eval(*n.b, v);
    case '-': return eval(*n.a, v) - eval(*n.b, v);
    case '*': return eval(*n.a, v) * eval(*n.b, v);
    default: return eval(*n.a, v) / eval(*n.b, v);
  }
}

}  // namespace

Constraint parse_constraint(const std::string& text, const std::string& where) {
  return Parser(text, where).parse();
}

bool holds(const Constraint& c, const std::map<std::string, double>& values) {
  // Relative slack: values from ranges carry rounding error in the last bits.
  constexpr double kRelativeSlack = 1e-9;
  const double a = eval(*c.lhs, values);
  const double b = eval(*c.rhs, values);
  const double slack = kRelativeSlack * std::max({1.0, std::abs(a), std::abs(b)});
  if (c.op == "<") return a < b - slack;
  if (c.op == "<=") return a <= b + slack;
  if (c.op == ">") return a > b + slack;
  if (c.op == ">=") return a >= b - slack;
  if (c.op == "==") return std::abs(a - b) <= slack;
  return std::abs(a - b) > slack;
}

}  // namespace strand::jobs
