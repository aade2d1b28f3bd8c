// `where` constraints of a sweep: small comparisons such as "gap >= nozzle" or
// "pitch - nozzle >= 0.5 * nozzle", parsed once (no eval) and tested per point.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace strand::jobs {

// Grammar: constraint := expr OP expr, OP one of < <= > >= == !=;
// expr := term (("+" | "-") term)*; term := factor (("*" | "/") factor)*;
// factor := number | name | "(" expr ")" | "-" factor.
// Names are parameter keys (letters, digits, "-", "_"; they start with a letter), so a
// subtraction needs spaces around "-": "gap - nozzle", whereas "layer-height" is one name.
// Comparisons allow a relative slack of 1e-9 so range values such as 0.8 + 2 * 0.4 compare
// as written.
struct Constraint {
  struct Node;
  std::string text;
  std::string op;
  std::shared_ptr<const Node> lhs, rhs;
  std::vector<std::string> names;  // parameters used, sorted, unique
};

// Throws InputError naming `where` ("sweep.where[0]") for a syntax error.
Constraint parse_constraint(const std::string& text, const std::string& where);

// True when the point satisfies the constraint. `values` must hold every name in c.names.
bool holds(const Constraint& c, const std::map<std::string, double>& values);

}  // namespace strand::jobs
