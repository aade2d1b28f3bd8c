// Text that goes into a robot program (KUKA Sunrise Java, KUKA KRL, URScript, ABB RAPID) from
// outside Strand: output names, profile strings and header comments. Each language gets its own
// rule, because each has its own way of being broken out of: a quote or a backslash in a
// string literal, a line terminator in a comment, and in Java a `\u` escape, which javac
// replaces before it even splits the text into tokens (inside comments and strings too).
// Identifiers are checked (a value that is not one is refused, naming its key); literals and
// comments are escaped so that the text they carry stays text.
#pragma once

#include <string>
#include <string_view>

namespace strand::machines {

// A Java string literal (with its quotes) whose value is `text` exactly: printable ASCII as
// is, `\` and `"` escaped, control characters as octal escapes, every other character as a
// \uXXXX escape of its UTF-16 units (none of which can end the literal). Throws InputError
// naming `key` when `text` is not valid UTF-8.
std::string java_string_literal(std::string_view text, const std::string& key);

// One `//` comment line's text for Java: printable ASCII only (a backslash is doubled so that
// no `\u` escape can form; anything else, line terminators included, becomes `?`).
std::string java_comment_text(std::string_view text);

// One `;` comment's text for KRL (and RAPID's `!`, URScript's `#`): printable ASCII only,
// anything else, line terminators included, becomes `?`.
std::string program_comment_text(std::string_view text);

// True for [A-Za-z_][A-Za-z0-9_]* of at most `max_length` characters.
bool is_plain_identifier(std::string_view text, std::size_t max_length);

// Throws InputError "KEY = "VALUE": must be a Java identifier ..." unless `value` is a plain
// identifier of at most 64 characters that is not a Java keyword or literal.
void require_java_identifier(const std::string& key, const std::string& value);

// KRL keywords and the names KSS reserves for its own programs, upper case; a module or
// sub-program name must not be one of them.
bool is_krl_keyword(std::string_view name);

}  // namespace strand::machines
