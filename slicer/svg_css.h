// CSS in SVG: style sheets (<style>, <?xml-stylesheet href="#id"?>) and style attributes read
// with a tokenizer that follows CSS Syntax Level 3, selectors of the kinds SVG drawings use
// (type, class, id, universal, descendant, child, grouping) with their specificity, and the
// matching of rules against elements. What is not supported is counted, never fetched.
#pragma once

#include <array>
#include <cstddef>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace pugi {
class xml_node;
}

namespace strand::slicer {

// Bounds on the style sheets of one drawing (docs/limits.md). Sheets past the byte bound and
// rules past the rule bound are skipped and counted; a match needing more steps than the
// step bound throws InputError.
inline constexpr std::size_t kMaxCssBytes = std::size_t{1} << 20;  // all sheets together
inline constexpr std::size_t kMaxCssRules = 10'000;           // selectors, each of a group counted
inline constexpr std::size_t kMaxCssChain = 32;               // compound selectors in one selector
inline constexpr std::size_t kMaxCssMatchSteps = 20'000'000;  // compound tests per drawing

struct CssDeclaration {
  std::string property;  // lower case: "fill", "font-size"
  std::string value;     // white space collapsed, !important removed: "#000", "12px"
  bool important = false;

  bool operator==(const CssDeclaration&) const = default;
};

// One compound selector: `rect.st2#a`; an empty type (or "*") matches any element.
struct CssCompound {
  std::string type;
  std::string id;
  std::vector<std::string> classes;
  char combinator = ' ';  // relation to the compound on its left: ' ' descendant, '>' child

  bool operator==(const CssCompound&) const = default;
};

struct CssRule {
  std::vector<CssCompound> chain;    // leftmost first; the last one is the subject
  std::array<int, 3> specificity{};  // ids, classes, types
  std::size_t order = 0;             // position among all rules of the drawing
  std::shared_ptr<const std::vector<CssDeclaration>> declarations;  // shared by a group
};

struct StyleSheet {
  std::vector<CssRule> rules;
  std::size_t bytes = 0;               // sheet text read so far
  std::map<std::string, int> skipped;  // "CSS @import": what was not applied, counted
};

// Appends the rules of `text` to `sheet` (order continues). Unsupported selectors (pseudo
// classes, attributes, siblings, namespaces) and at-rules (@import is never fetched, @media,
// @font-face, ...) are counted in sheet.skipped; a sheet past kMaxCssBytes is skipped whole.
void parse_css(std::string_view text, StyleSheet& sheet);

// The declarations of a style attribute or a rule block, in order.
std::vector<CssDeclaration> parse_css_declarations(std::string_view text);

// Sheet declarations that apply to one element, each list in cascade order (a later one
// wins). The full cascade is: presentation attributes, `normal`, the style attribute,
// `important`, the style attribute's !important declarations.
struct CssMatch {
  std::vector<const CssDeclaration*> normal, important;
};

// Rules indexed by their subject's id, class and type. Matching counts compound tests
// against kMaxCssMatchSteps and throws InputError beyond it.
class CssCascade {
 public:
  explicit CssCascade(const StyleSheet& sheet);
  CssMatch matching(const pugi::xml_node& n) const;

 private:
  const StyleSheet* sheet_;
  std::map<std::string, std::vector<std::size_t>> by_id_, by_class_, by_type_;
  std::vector<std::size_t> universal_;
  mutable std::size_t steps_ = 0;
};

}  // namespace strand::slicer
