// The CSS Syntax Level 3 tokenizer under the style sheet parser of svg_css.cpp: the token
// kinds and the tokens of one sheet or style attribute.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace strand::slicer::css {

enum class Tok {
  Whitespace,
  Ident,
  Function,
  AtKeyword,
  Hash,
  String,
  BadString,
  Url,
  BadUrl,
  Delim,
  Numeric,
  Cdo,
  Cdc,
  Colon,
  Semicolon,
  Comma,
  LBracket,
  RBracket,
  LParen,
  RParen,
  LBrace,
  RBrace,
  Eof
};

struct Token {
  Tok type = Tok::Eof;
  std::string value;     // ident, function, at-keyword and hash names with escapes resolved
  std::string_view src;  // the source text of the token
  char delim = 0;
};

// The tokens of `text` (CSS Syntax Level 3, section 4), up to but not including Eof. Tokens
// point into `text` (Token::src), which must outlive them.
std::vector<Token> tokenize(std::string_view text);

}  // namespace strand::slicer::css
