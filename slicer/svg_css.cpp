// CSS rules read from the tokens of svg_css_tokens.h (the parts a style sheet in a drawing
// needs), selectors and their specificity (Selectors Level 3), and right-to-left matching on
// pugixml.
#include "slicer/svg_css.h"

#include <algorithm>
#include <cctype>
#include <pugixml.hpp>
#include <tuple>

#include "slicer/input_error.h"
#include "slicer/svg_css_tokens.h"

namespace strand::slicer {

namespace {

using css::Tok;
using css::Token;

Tok closing(Tok open) {
  return open == Tok::LBrace ? Tok::RBrace : open == Tok::LBracket ? Tok::RBracket : Tok::RParen;
}
bool opens(Tok t) {
  return t == Tok::LBrace || t == Tok::LBracket || t == Tok::LParen || t == Tok::Function;
}

// Index just past the block or function opened at tokens[k] (the end if never closed).
std::size_t skip_block(const std::vector<Token>& tokens, std::size_t k) {
  std::vector<Tok> stack{closing(tokens[k].type == Tok::Function ? Tok::LParen : tokens[k].type)};
  for (++k; k < tokens.size() && !stack.empty(); ++k) {
    const Tok t = tokens[k].type;
    if (t == stack.back()) {
      stack.pop_back();
    } else if (opens(t)) {
      stack.push_back(closing(t == Tok::Function ? Tok::LParen : t));
    }
  }
  return k;
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char ch) { return std::tolower(ch); });
  return s;
}

// Tokens [b, e) as text: white space collapsed to one space, trimmed.
std::string text_of(const std::vector<Token>& tokens, std::size_t b, std::size_t e) {
  while (b < e && tokens[b].type == Tok::Whitespace) ++b;
  while (e > b && tokens[e - 1].type == Tok::Whitespace) --e;
  std::string out;
  for (std::size_t k = b; k < e; ++k)
    out += tokens[k].type == Tok::Whitespace ? std::string_view(" ") : tokens[k].src;
  return out;
}

// One declaration from tokens [b, e): `name : value [! important]`; false if malformed.
bool declaration(const std::vector<Token>& tokens, std::size_t b, std::size_t e,
                 CssDeclaration& d) {
  while (b < e && tokens[b].type == Tok::Whitespace) ++b;
  if (b >= e || tokens[b].type != Tok::Ident) return false;
  d.property = lower(tokens[b].value);
  std::size_t k = b + 1;
  while (k < e && tokens[k].type == Tok::Whitespace) ++k;
  if (k >= e || tokens[k].type != Tok::Colon) return false;
  ++k;
  while (e > k && tokens[e - 1].type == Tok::Whitespace) --e;
  if (e > k && tokens[e - 1].type == Tok::Ident && lower(tokens[e - 1].value) == "important") {
    std::size_t j = e - 1;
    while (j > k && tokens[j - 1].type == Tok::Whitespace) --j;
    if (j > k && tokens[j - 1].type == Tok::Delim && tokens[j - 1].delim == '!') {
      d.important = true;
      e = j - 1;
    }
  }
  d.value = text_of(tokens, k, e);
  return !d.value.empty();
}

std::vector<CssDeclaration> declarations(const std::vector<Token>& tokens, std::size_t b,
                                         std::size_t e) {
  std::vector<CssDeclaration> out;
  std::size_t start = b;
  for (std::size_t k = b; k <= e;) {
    if (k == e || tokens[k].type == Tok::Semicolon) {
      CssDeclaration d;
      if (declaration(tokens, start, k, d)) out.push_back(std::move(d));
      start = ++k;
    } else if (opens(tokens[k].type)) {
      k = std::min(skip_block(tokens, k), e);
    } else {
      ++k;
    }
  }
  return out;
}

// A selector from tokens [b, e); false for a syntax error or a kind not supported.
bool selector(const std::vector<Token>& tokens, std::size_t b, std::size_t e, CssRule& r) {
  while (b < e && tokens[b].type == Tok::Whitespace) ++b;
  while (e > b && tokens[e - 1].type == Tok::Whitespace) --e;
  if (b >= e) return false;
  CssCompound cur;
  bool have = false;  // cur holds something
  char pending = ' ';
  for (std::size_t k = b; k < e; ++k) {
    const Token& t = tokens[k];
    const bool combinator = t.type == Tok::Whitespace || (t.type == Tok::Delim && t.delim == '>');
    if (combinator) {
      // white space around '>' belongs to it
      char comb = t.type == Tok::Whitespace ? ' ' : '>';
      while (k + 1 < e && (tokens[k + 1].type == Tok::Whitespace ||
                           (tokens[k + 1].type == Tok::Delim && tokens[k + 1].delim == '>'))) {
        ++k;
        if (tokens[k].type == Tok::Delim) {
          if (comb == '>') return false;  // "a > > b"
          comb = '>';
        }
      }
      if (!have) return false;
      cur.combinator = pending;
      r.chain.push_back(std::move(cur));
      cur = CssCompound{};
      have = false;
      pending = comb;
      if (r.chain.size() >= kMaxCssChain) return false;
      continue;
    }
    if (t.type == Tok::Ident || (t.type == Tok::Delim && t.delim == '*')) {
      if (have) return false;  // a type selector comes first in its compound
      if (k + 1 < e && tokens[k + 1].type == Tok::Delim && tokens[k + 1].delim == '|')
        return false;  // namespaces
      cur.type = t.type == Tok::Ident ? t.value : "*";
      if (t.type == Tok::Ident) ++r.specificity[2];
    } else if (t.type == Tok::Hash) {
      cur.id = t.value;  // two ids in one compound: the later one (never both match)
      ++r.specificity[0];
      if (!cur.id.empty() && std::isdigit(static_cast<unsigned char>(cur.id[0]))) return false;
    } else if (t.type == Tok::Delim && t.delim == '.' && k + 1 < e &&
               tokens[k + 1].type == Tok::Ident) {
      cur.classes.push_back(tokens[++k].value);
      ++r.specificity[1];
    } else {
      return false;  // ':' pseudo classes, '[' attributes, '+' '~' siblings, '|' namespaces
    }
    have = true;
  }
  if (!have) return false;
  cur.combinator = pending;
  r.chain.push_back(std::move(cur));
  return r.chain.size() <= kMaxCssChain;
}

void rules(const std::vector<Token>& tokens, StyleSheet& sheet) {
  for (std::size_t k = 0; k < tokens.size();) {
    const Token& t = tokens[k];
    if (t.type == Tok::Whitespace || t.type == Tok::Cdo || t.type == Tok::Cdc) {
      ++k;
      continue;
    }
    if (t.type == Tok::AtKeyword) {
      const std::string name = lower(t.value);
      while (k < tokens.size() && tokens[k].type != Tok::Semicolon &&
             tokens[k].type != Tok::LBrace) {
        k = opens(tokens[k].type) ? skip_block(tokens, k) : k + 1;
      }
      if (k < tokens.size()) k = tokens[k].type == Tok::LBrace ? skip_block(tokens, k) : k + 1;
      // @charset and @namespace change nothing a drawing needs; every other one is counted
      if (name == "charset" || name == "namespace") continue;
      const bool known = name == "import" || name == "media" || name == "font-face" ||
                         name == "supports" || name == "keyframes" || name == "page";
      ++sheet.skipped[known ? "CSS @" + name : std::string("CSS at-rule")];
      continue;
    }
    // qualified rule: a prelude up to '{', then the block
    const std::size_t prelude = k;
    while (k < tokens.size() && tokens[k].type != Tok::LBrace) {
      k = opens(tokens[k].type) ? skip_block(tokens, k) : k + 1;
    }
    if (k >= tokens.size()) {
      ++sheet.skipped["CSS rule without a block"];
      break;
    }
    const std::size_t block_end = skip_block(tokens, k);
    const std::size_t body_end = block_end - (tokens[block_end - 1].type == Tok::RBrace ? 1 : 0);
    auto decls =
        std::make_shared<const std::vector<CssDeclaration>>(declarations(tokens, k + 1, body_end));
    // the selector list, split at commas outside brackets
    std::size_t start = prelude;
    for (std::size_t j = prelude; j <= k;) {
      if (j == k || tokens[j].type == Tok::Comma) {
        CssRule r;
        if (sheet.rules.size() >= kMaxCssRules) {
          ++sheet.skipped["CSS rule beyond " + std::to_string(kMaxCssRules)];
        } else if (selector(tokens, start, j, r)) {
          r.order = sheet.rules.size();
          r.declarations = decls;
          sheet.rules.push_back(std::move(r));
        } else {
          ++sheet.skipped["CSS selector"];
        }
        start = ++j;
      } else {
        j = opens(tokens[j].type) ? std::min(skip_block(tokens, j), k) : j + 1;
      }
    }
    k = block_end;
  }
}

bool has_class(const pugi::xml_node& n, std::string_view cls) {
  std::string_view list = n.attribute("class").value();
  while (!list.empty()) {
    std::size_t b = 0;
    while (b < list.size() && std::isspace(static_cast<unsigned char>(list[b]))) ++b;
    std::size_t e = b;
    while (e < list.size() && !std::isspace(static_cast<unsigned char>(list[e]))) ++e;
    if (list.substr(b, e - b) == cls) return true;
    list.remove_prefix(e);
  }
  return false;
}

std::string_view local_name_of(const pugi::xml_node& n) {
  std::string_view name = n.name();
  const auto colon = name.find(':');
  return colon == std::string_view::npos ? name : name.substr(colon + 1);
}

std::vector<std::string> class_list(const pugi::xml_node& n) {
  std::vector<std::string> out;
  std::string cur;
  for (const char* p = n.attribute("class").value();; ++p) {
    if (*p == '\0' || std::isspace(static_cast<unsigned char>(*p))) {
      if (!cur.empty()) out.push_back(cur);
      cur.clear();
      if (*p == '\0') break;
    } else {
      cur += *p;
    }
  }
  return out;
}

}  // namespace

void parse_css(std::string_view text, StyleSheet& sheet) {
  if (sheet.bytes + text.size() > kMaxCssBytes) {
    ++sheet.skipped["CSS sheet beyond " + std::to_string(kMaxCssBytes >> 20) + " MiB"];
    return;
  }
  sheet.bytes += text.size();
  rules(css::tokenize(text), sheet);
}

std::vector<CssDeclaration> parse_css_declarations(std::string_view text) {
  const std::vector<Token> tokens = css::tokenize(text);
  return declarations(tokens, 0, tokens.size());
}

CssCascade::CssCascade(const StyleSheet& sheet) : sheet_(&sheet) {
  for (std::size_t k = 0; k < sheet.rules.size(); ++k) {
    const CssCompound& subject = sheet.rules[k].chain.back();
    if (!subject.id.empty()) {
      by_id_[subject.id].push_back(k);
    } else if (!subject.classes.empty()) {
      by_class_[subject.classes.front()].push_back(k);
    } else if (!subject.type.empty() && subject.type != "*") {
      by_type_[subject.type].push_back(k);
    } else {
      universal_.push_back(k);
    }
  }
}

namespace {

struct Matcher {
  const CssRule& rule;
  std::size_t& steps;

  bool compound(const CssCompound& c, const pugi::xml_node& n) {
    if (++steps > kMaxCssMatchSteps) {
      throw InputError("the drawing's CSS selectors need more than " +
                       std::to_string(kMaxCssMatchSteps) +
                       " element tests (the limit for one drawing)");
    }
    if (!c.type.empty() && c.type != "*" && local_name_of(n) != c.type) return false;
    if (!c.id.empty() && c.id != n.attribute("id").value()) return false;
    return std::all_of(c.classes.begin(), c.classes.end(),
                       [&](const std::string& k) { return has_class(n, k); });
  }
  // compound k at element n, and every compound left of it at its ancestors
  bool from(std::size_t k, const pugi::xml_node& n) {
    if (!compound(rule.chain[k], n)) return false;
    if (k == 0) return true;
    pugi::xml_node p = n.parent();
    if (rule.chain[k].combinator == '>') return p.type() == pugi::node_element && from(k - 1, p);
    for (; p.type() == pugi::node_element; p = p.parent()) {
      if (from(k - 1, p)) return true;
    }
    return false;
  }
};

}  // namespace

CssMatch CssCascade::matching(const pugi::xml_node& n) const {
  CssMatch out;
  if (sheet_->rules.empty()) return out;
  std::vector<std::size_t> candidates = universal_;
  const auto add = [&](const std::map<std::string, std::vector<std::size_t>>& index,
                       const std::string& key) {
    const auto found = index.find(key);
    if (found != index.end())
      candidates.insert(candidates.end(), found->second.begin(), found->second.end());
  };
  if (const auto id = n.attribute("id")) add(by_id_, id.value());
  std::vector<std::string> classes = class_list(n);
  std::sort(classes.begin(), classes.end());
  classes.erase(std::unique(classes.begin(), classes.end()), classes.end());
  for (const auto& c : classes) add(by_class_, c);
  add(by_type_, std::string(local_name_of(n)));
  std::vector<const CssRule*> matched;
  for (std::size_t k : candidates) {
    const CssRule& r = sheet_->rules[k];
    if (Matcher{r, steps_}.from(r.chain.size() - 1, n)) matched.push_back(&r);
  }
  std::sort(matched.begin(), matched.end(), [](const CssRule* a, const CssRule* b) {
    return std::tie(a->specificity, a->order) < std::tie(b->specificity, b->order);
  });
  for (const CssRule* r : matched) {
    for (const auto& d : *r->declarations) (d.important ? out.important : out.normal).push_back(&d);
  }
  return out;
}

}  // namespace strand::slicer