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

// Sunrise project data named in the profile: an object template's name is a plain
// identifier of at most 64 characters; a frame path is "/" and such names joined by "/"
// ("/Nozzle", "/Cell/NozzleTip"), at most 200 characters. Both go into the program as string
// literals. Throw InputError naming `key` otherwise.
void require_sunrise_name(const std::string& key, const std::string& value);
void require_sunrise_frame_path(const std::string& key, const std::string& value);

// RAPID (ABB): an identifier starts with a letter, then letters, digits and _, at most 32
// characters, and is not a RAPID reserved word (compared without case). Throws InputError
// naming `key` otherwise.
bool is_rapid_identifier(std::string_view name);
void require_rapid_identifier(const std::string& key, const std::string& value);
// A RAPID module name for an output base name: invalid characters become _, an `M` is put
// before a leading digit or _, a reserved word gets `M_` before it, cut to 32 characters.
std::string rapid_module_name(const std::string& base_name);
// A RAPID string literal (with its quotes): printable ASCII as is with `"` and `\` doubled,
// every other byte as a `\hh` escape; at most 80 characters of the value (longer text is cut
// and ends in "...").
std::string rapid_string_literal(std::string_view text);

// URScript: a function name for an output base name ([A-Za-z_][A-Za-z0-9_]*, at most 63
// characters, not a URScript keyword or a built-in function the program calls).
std::string urscript_function_name(const std::string& base_name);
bool is_urscript_keyword(std::string_view name);
// A URScript string literal (with its quotes): printable ASCII only, `"`, `\` and anything
// else (line terminators included) become `?` (URScript has no escapes to rely on).
std::string urscript_string_literal(std::string_view text);

// KRL keywords and the names KSS reserves for its own programs, upper case; a module or
// sub-program name must not be one of them.
bool is_krl_keyword(std::string_view name);

}  // namespace strand::machines
