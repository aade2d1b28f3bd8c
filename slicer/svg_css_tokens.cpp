// The CSS tokenizer (CSS Syntax Level 3, section 4) used for style sheets and style attributes.
#include "slicer/svg_css_tokens.h"

#include <algorithm>
#include <cctype>
#include <utility>

namespace strand::slicer::css {

namespace {

bool is_name_start(unsigned char c) { return std::isalpha(c) || c == '_' || c >= 0x80; }
bool is_name(unsigned char c) { return is_name_start(c) || std::isdigit(c) || c == '-'; }

// CSS Syntax Level 3, section 4 (tokenization), without the preprocessing of NUL and CR:
// they are kept as they are and never form a name.
class Tokenizer {
 public:
  explicit Tokenizer(std::string_view s) : s_(s) {}

  std::vector<Token> all() {
    std::vector<Token> out;
    for (Token t = next(); t.type != Tok::Eof; t = next()) out.push_back(std::move(t));
    return out;
  }

 private:
  std::string_view s_;
  std::size_t i_ = 0;

  unsigned char at(std::size_t k) const { return k < s_.size() ? s_[k] : 0; }
  bool valid_escape(std::size_t k) const {
    return at(k) == '\\' && k + 1 < s_.size() && at(k + 1) != '\n';
  }
  bool starts_ident(std::size_t k) const {
    if (at(k) == '-') return is_name_start(at(k + 1)) || at(k + 1) == '-' || valid_escape(k + 1);
    return is_name_start(at(k)) || valid_escape(k);
  }
  bool starts_number(std::size_t k) const {
    std::size_t j = k;
    if (at(j) == '+' || at(j) == '-') ++j;
    if (std::isdigit(at(j))) return true;
    return at(j) == '.' && std::isdigit(at(j + 1));
  }
  // After the backslash: up to 6 hex digits and one white space, or the next character.
  void escape(std::string& out) {
    if (i_ >= s_.size()) return;
    if (std::isxdigit(at(i_))) {
      unsigned long cp = 0;
      for (int n = 0; n < 6 && std::isxdigit(at(i_)); ++n, ++i_)
        cp = cp * 16 + static_cast<unsigned long>(
                           std::isdigit(at(i_)) ? at(i_) - '0' : std::tolower(at(i_)) - 'a' + 10);
      if (std::isspace(at(i_))) ++i_;
      if (cp == 0 || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) cp = 0xFFFD;
      // UTF-8 of the code point
      if (cp < 0x80) {
        out += static_cast<char>(cp);
      } else if (cp < 0x800) {
        out += static_cast<char>(0xC0 | (cp >> 6));
        out += static_cast<char>(0x80 | (cp & 0x3F));
      } else if (cp < 0x10000) {
        out += static_cast<char>(0xE0 | (cp >> 12));
        out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
        out += static_cast<char>(0x80 | (cp & 0x3F));
      } else {
        out += static_cast<char>(0xF0 | (cp >> 18));
        out += static_cast<char>(0x80 | ((cp >> 12) & 0x3F));
        out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
        out += static_cast<char>(0x80 | (cp & 0x3F));
      }
      return;
    }
    out += s_[i_++];
  }
  std::string name() {
    std::string out;
    while (i_ < s_.size()) {
      if (is_name(at(i_))) {
        out += s_[i_++];
      } else if (valid_escape(i_)) {
        ++i_;
        escape(out);
      } else {
        break;
      }
    }
    return out;
  }
  void comments() {
    while (at(i_) == '/' && at(i_ + 1) == '*') {
      const auto end = s_.find("*/", i_ + 2);
      i_ = end == std::string_view::npos ? s_.size() : end + 2;
    }
  }
  Token string_token(char quote) {
    Token t{Tok::String, {}, {}, 0};
    ++i_;
    while (i_ < s_.size()) {
      const char c = s_[i_];
      if (c == quote) {
        ++i_;
        return t;
      }
      if (c == '\n') {  // a newline ends the string badly; it is not consumed
        t.type = Tok::BadString;
        return t;
      }
      if (c == '\\') {
        ++i_;
        if (at(i_) == '\n') {
          ++i_;
        } else {
          escape(t.value);
        }
        continue;
      }
      t.value += c;
      ++i_;
    }
    return t;
  }
  void numeric() {
    if (at(i_) == '+' || at(i_) == '-') ++i_;
    while (std::isdigit(at(i_))) ++i_;
    if (at(i_) == '.' && std::isdigit(at(i_ + 1))) {
      i_ += 2;
      while (std::isdigit(at(i_))) ++i_;
    }
    if ((at(i_) == 'e' || at(i_) == 'E') &&
        (std::isdigit(at(i_ + 1)) ||
         ((at(i_ + 1) == '+' || at(i_ + 1) == '-') && std::isdigit(at(i_ + 2))))) {
      i_ += 2;
      while (std::isdigit(at(i_))) ++i_;
    }
    if (starts_ident(i_)) {
      name();
    } else if (at(i_) == '%') {
      ++i_;
    }
  }
  // url( without quotes: up to ')' ; a quote, '(' or bad escape makes it a bad url
  void url(Token& t) {
    while (std::isspace(at(i_))) ++i_;
    while (i_ < s_.size()) {
      const char c = s_[i_++];
      if (c == ')') return;
      if (c == '"' || c == '\'' || c == '(' || (c == '\\' && !valid_escape(i_ - 1)))
        t.type = Tok::BadUrl;
      if (c == '\\' && i_ < s_.size()) ++i_;
    }
  }

  Token next() {
    comments();
    const std::size_t start = i_;
    Token t = raw();
    t.src = s_.substr(start, i_ - start);
    return t;
  }
  Token raw() {
    if (i_ >= s_.size()) return {};
    const unsigned char c = at(i_);
    const auto simple = [&](Tok type) {
      ++i_;
      return Token{type, {}, {}, static_cast<char>(c)};
    };
    if (std::isspace(c)) {
      while (std::isspace(at(i_))) ++i_;
      return {Tok::Whitespace, {}, {}, 0};
    }
    if (c == '"' || c == '\'') return string_token(static_cast<char>(c));
    if (c == '#' && (is_name(at(i_ + 1)) || valid_escape(i_ + 1))) {
      ++i_;
      return {Tok::Hash, name(), {}, 0};
    }
    if (starts_number(i_)) {
      numeric();
      return {Tok::Numeric, {}, {}, 0};
    }
    if (c == '<' && s_.substr(i_, 4) == "<!--") {
      i_ += 4;
      return {Tok::Cdo, {}, {}, 0};
    }
    if (c == '-' && s_.substr(i_, 3) == "-->") {
      i_ += 3;
      return {Tok::Cdc, {}, {}, 0};
    }
    if (starts_ident(i_)) {
      Token t{Tok::Ident, name(), {}, 0};
      if (at(i_) == '(') {
        ++i_;
        std::string lower = t.value;
        std::transform(lower.begin(), lower.end(), lower.begin(),
                       [](unsigned char ch) { return std::tolower(ch); });
        if (lower == "url") {
          std::size_t k = i_;
          while (std::isspace(at(k))) ++k;
          if (at(k) != '"' && at(k) != '\'') {
            t.type = Tok::Url;
            url(t);
            return t;
          }
        }
        t.type = Tok::Function;
      }
      return t;
    }
    if (c == '@' && starts_ident(i_ + 1)) {
      ++i_;
      return {Tok::AtKeyword, name(), {}, 0};
    }
    switch (c) {
      case ':':
        return simple(Tok::Colon);
      case ';':
        return simple(Tok::Semicolon);
      case ',':
        return simple(Tok::Comma);
      case '[':
        return simple(Tok::LBracket);
      case ']':
        return simple(Tok::RBracket);
      case '(':
        return simple(Tok::LParen);
      case ')':
        return simple(Tok::RParen);
      case '{':
        return simple(Tok::LBrace);
      case '}':
        return simple(Tok::RBrace);
      default:
        break;
    }
    if (c == '\\') {  // a backslash that starts no escape is a delimiter
      ++i_;
      return {Tok::Delim, {}, {}, '\\'};
    }
    return simple(Tok::Delim);
  }
};

}  // namespace

std::vector<Token> tokenize(std::string_view text) { return Tokenizer(text).all(); }

}  // namespace strand::slicer::css
