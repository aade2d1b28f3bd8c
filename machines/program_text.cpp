// Escaping and checking the outside text of robot programs.
#include "machines/program_text.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <iterator>
#include <optional>

#include "slicer/input_error.h"

namespace strand::machines {

namespace {

bool printable_ascii(unsigned char c) { return c >= 0x20 && c <= 0x7e; }

// The next code point of UTF-8 `s` at `i` (advanced past it), or nullopt for a malformed,
// overlong or surrogate sequence.
std::optional<char32_t> next_code_point(std::string_view s, std::size_t& i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned char b0 = byte(i);
  int extra = 0;
  char32_t cp = 0;
  if (b0 < 0x80) {
    ++i;
    return b0;
  } else if ((b0 & 0xe0) == 0xc0) {
    extra = 1, cp = b0 & 0x1f;
  } else if ((b0 & 0xf0) == 0xe0) {
    extra = 2, cp = b0 & 0x0f;
  } else if ((b0 & 0xf8) == 0xf0) {
    extra = 3, cp = b0 & 0x07;
  } else {
    return std::nullopt;
  }
  if (i + static_cast<std::size_t>(extra) >= s.size()) return std::nullopt;
  for (int k = 1; k <= extra; ++k) {
    const unsigned char b = byte(i + static_cast<std::size_t>(k));
    if ((b & 0xc0) != 0x80) return std::nullopt;
    cp = (cp << 6) | (b & 0x3f);
  }
  static constexpr std::array<char32_t, 4> kMin = {0, 0x80, 0x800, 0x10000};
  if (cp < kMin[static_cast<std::size_t>(extra)] || cp > 0x10ffff || (cp >= 0xd800 && cp <= 0xdfff))
    return std::nullopt;
  i += static_cast<std::size_t>(extra) + 1;
  return cp;
}

std::string hex4(unsigned v) {
  static const char* const kDigits = "0123456789abcdef";
  std::string out = "\\u";
  for (int shift = 12; shift >= 0; shift -= 4) out += kDigits[(v >> shift) & 0xf];
  return out;
}

// Printable ASCII of `text`, anything else as '?', for quoting a bad value in a message.
std::string shown(std::string_view text) {
  std::string out;
  for (char c : text.substr(0, 80)) out += printable_ascii(static_cast<unsigned char>(c)) ? c : '?';
  if (text.size() > 80) out += "...";
  return out;
}

}  // namespace

std::string java_string_literal(std::string_view text, const std::string& key) {
  std::string out = "\"";
  for (std::size_t i = 0; i < text.size();) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (c == '\\' || c == '"') {
      out += '\\';
      out += static_cast<char>(c);
      ++i;
    } else if (printable_ascii(c)) {
      out += static_cast<char>(c);
      ++i;
    } else if (c < 0x80) {
      // Control characters (CR and LF would end the literal): an octal escape.
      out += '\\';
      out += static_cast<char>('0' + ((c >> 6) & 7));
      out += static_cast<char>('0' + ((c >> 3) & 7));
      out += static_cast<char>('0' + (c & 7));
      ++i;
    } else {
      const auto cp = next_code_point(text, i);
      if (!cp) {
        throw InputError(key + " = \"" + shown(text) +
                         "\": not valid UTF-8 (a name written into the Java program)");
      }
      if (*cp >= 0x10000) {
        const char32_t v = *cp - 0x10000;
        out += hex4(0xd800 + static_cast<unsigned>(v >> 10));
        out += hex4(0xdc00 + static_cast<unsigned>(v & 0x3ff));
      } else {
        out += hex4(static_cast<unsigned>(*cp));
      }
    }
  }
  return out + "\"";
}

std::string java_comment_text(std::string_view text) {
  std::string out;
  for (char c : text) {
    if (c == '\\') {
      out += "\\\\";
    } else {
      out += printable_ascii(static_cast<unsigned char>(c)) ? c : '?';
    }
  }
  return out;
}

std::string program_comment_text(std::string_view text) {
  std::string out;
  for (char c : text) out += printable_ascii(static_cast<unsigned char>(c)) ? c : '?';
  return out;
}

bool is_plain_identifier(std::string_view text, std::size_t max_length) {
  if (text.empty() || text.size() > max_length) return false;
  const auto letter = [](char c) {
    return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || c == '_';
  };
  if (!letter(text[0])) return false;
  return std::all_of(text.begin(), text.end(),
                     [&](char c) { return letter(c) || (c >= '0' && c <= '9'); });
}

void require_sunrise_name(const std::string& key, const std::string& value) {
  if (!is_plain_identifier(value, 64)) {
    throw InputError(key + " = \"" + shown(value) +
                     "\": must be a Sunrise object name (letters, digits and _, not starting "
                     "with a digit, at most 64 characters)");
  }
}

void require_sunrise_frame_path(const std::string& key, const std::string& value) {
  bool ok = value.size() >= 2 && value.size() <= 200 && value.front() == '/';
  for (std::size_t at = 1; ok && at <= value.size();) {
    const std::size_t slash = std::min(value.find('/', at), value.size());
    ok = is_plain_identifier(std::string_view(value).substr(at, slash - at), 64);
    at = slash + 1;
  }
  if (!ok) {
    throw InputError(key + " = \"" + shown(value) +
                     "\": must be a frame path such as \"/Nozzle\" or \"/Cell/Nozzle\" "
                     "(names of letters, digits and _ after each /)");
  }
}

void require_java_identifier(const std::string& key, const std::string& value) {
  static const std::string_view kReserved[] = {
      "abstract", "assert", "boolean",    "break",     "byte",       "case",      "catch",
      "char",     "class",  "const",      "continue",  "default",    "do",        "double",
      "else",     "enum",   "extends",    "final",     "finally",    "float",     "for",
      "goto",     "if",     "implements", "import",    "instanceof", "int",       "interface",
      "long",     "native", "new",        "package",   "private",    "protected", "public",
      "return",   "short",  "static",     "strictfp",  "super",      "switch",    "synchronized",
      "this",     "throw",  "throws",     "transient", "try",        "void",      "volatile",
      "while",    "true",   "false",      "null"};
  const bool reserved = std::find(std::begin(kReserved), std::end(kReserved),
                                  std::string_view(value)) != std::end(kReserved);
  if (!is_plain_identifier(value, 64) || reserved) {
    throw InputError(key + " = \"" + shown(value) +
                     "\": must be a Java identifier (letters, digits and _, not starting with a "
                     "digit, at most 64 characters, not a Java keyword)");
  }
}

namespace {

std::string upper_case(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

constexpr std::size_t kMaxRapidName = 32;
constexpr std::size_t kMaxRapidString = 80;
constexpr std::size_t kMaxUrName = 63;

bool is_rapid_reserved(std::string_view name) {
  // RAPID reserved words, and the names the module itself uses for its data.
  static const std::string_view kReserved[] = {
      "ALIAS",     "AND",     "BACKWARD",  "CASE",    "CONNECT",  "CONST",    "DEFAULT",
      "DIV",       "DO",      "ELSE",      "ELSEIF",  "ENDFOR",   "ENDFUNC",  "ENDIF",
      "ENDMODULE", "ENDPROC", "ENDRECORD", "ENDTEST", "ENDTRAP",  "ENDWHILE", "ERROR",
      "EXIT",      "FALSE",   "FOR",       "FROM",    "FUNC",     "GOTO",     "IF",
      "INOUT",     "LOCAL",   "MOD",       "MODULE",  "NOSTEPIN", "NOT",      "NOVIEW",
      "OR",        "PERS",    "PROC",      "RAISE",   "READONLY", "RECORD",   "RETRY",
      "RETURN",    "STEP",    "SYSMODULE", "TEST",    "THEN",     "TO",       "TRAP",
      "TRUE",      "TRYNEXT", "UNDO",      "VAR",     "VIEWONLY", "WHILE",    "WITH",
      "XOR",       "MAIN",    "TOOL0",     "WOBJ0",   "LOAD0",    "FINE",     "STRANDZONE"};
  const std::string upper = upper_case(name);
  if (upper.rfind("STRANDV", 0) == 0 || upper.rfind("STRANDLAP", 0) == 0) return true;
  return std::find(std::begin(kReserved), std::end(kReserved), std::string_view(upper)) !=
         std::end(kReserved);
}

}  // namespace

bool is_rapid_identifier(std::string_view name) {
  if (!is_plain_identifier(name, kMaxRapidName) || name[0] == '_') return false;
  return !is_rapid_reserved(name);
}

void require_rapid_identifier(const std::string& key, const std::string& value) {
  if (!is_rapid_identifier(value)) {
    throw InputError(key + " = \"" + shown(value) +
                     "\": must be a RAPID identifier (a letter, then letters, digits and _, at "
                     "most 32 characters, not a RAPID reserved word)");
  }
}

std::string rapid_module_name(const std::string& base) {
  std::string out;
  for (char c : base.substr(0, 4 * kMaxRapidName)) {
    const bool ok = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9');
    out += ok ? c : '_';
  }
  if (out.empty() || !std::isalpha(static_cast<unsigned char>(out[0]))) out = "M" + out;
  out = out.substr(0, kMaxRapidName);
  if (!is_rapid_identifier(out)) out = ("M_" + out).substr(0, kMaxRapidName);
  return out;
}

std::string rapid_string_literal(std::string_view text) {
  static const char* const kHex = "0123456789ABCDEF";
  std::string out = "\"";
  std::size_t shown_chars = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (shown_chars == kMaxRapidString - 3) {
      out += "...";
      break;
    }
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (c == '"') {
      out += "\"\"";
    } else if (c == '\\') {
      out += "\\\\";
    } else if (printable_ascii(c)) {
      out += static_cast<char>(c);
    } else {
      out += '\\';
      out += kHex[c >> 4];
      out += kHex[c & 15];
    }
    ++shown_chars;
  }
  return out + "\"";
}

bool is_urscript_keyword(std::string_view name) {
  static const std::string_view kKeywords[] = {"and",
                                               "or",
                                               "xor",
                                               "not",
                                               "def",
                                               "end",
                                               "if",
                                               "elif",
                                               "else",
                                               "while",
                                               "for",
                                               "return",
                                               "thread",
                                               "run",
                                               "join",
                                               "kill",
                                               "halt",
                                               "True",
                                               "False",
                                               "global",
                                               "local",
                                               "break",
                                               "continue",
                                               "sec",
                                               "pass",
                                               "enter_critical",
                                               "exit_critical",
                                               "movel",
                                               "movej",
                                               "set_tcp",
                                               "set_payload",
                                               "textmsg",
                                               "sync",
                                               "sleep",
                                               "p",
                                               "set_standard_digital_out",
                                               "get_standard_digital_in",
                                               "strand_wait_ready"};
  return std::find(std::begin(kKeywords), std::end(kKeywords), name) != std::end(kKeywords);
}

std::string urscript_function_name(const std::string& base) {
  std::string out;
  for (char c : base.substr(0, 4 * kMaxUrName)) {
    const bool ok = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9');
    out += ok ? c : '_';
  }
  if (out.empty() || std::isdigit(static_cast<unsigned char>(out[0]))) out = "p" + out;
  out = out.substr(0, kMaxUrName);
  if (is_urscript_keyword(out)) out = ("strand_" + out).substr(0, kMaxUrName);
  return out;
}

std::string urscript_string_literal(std::string_view text) {
  std::string out = "\"";
  for (char c : text.substr(0, 200)) {
    const unsigned char u = static_cast<unsigned char>(c);
    out += printable_ascii(u) && c != '"' && c != '\\' ? c : '?';
  }
  return out + "\"";
}

bool is_krl_keyword(std::string_view name) {
  static const std::string_view kKeywords[] = {
      "AND",    "ANIN",   "ANOUT",    "B_AND",     "B_EXOR",   "B_NOT",     "B_OR",      "BOOL",
      "BRAKE",  "C_DIS",  "C_ORI",    "C_PTP",     "C_VEL",    "CASE",      "CAST_FROM", "CAST_TO",
      "CHAR",   "CIRC",   "CIRC_REL", "CONFIRM",   "CONTINUE", "DEF",       "DEFAULT",   "DEFDAT",
      "DEFFCT", "DELAY",  "DECL",     "DIGIN",     "DISTANCE", "DO",        "ELSE",      "END",
      "ENDDAT", "ENDFCT", "ENDFOR",   "ENDIF",     "ENDLOOP",  "ENDSWITCH", "ENDWHILE",  "EXIT",
      "EXOR",   "EXT",    "EXTFCT",   "FALSE",     "FOR",      "GLOBAL",    "GOTO",      "HALT",
      "IF",     "IMPORT", "INT",      "INTERRUPT", "LIN",      "LIN_REL",   "LOOP",      "NOT",
      "OR",     "PTP",    "PTP_REL",  "PUBLIC",    "REAL",     "TRUE"};
  std::string upper(name);
  for (char& c : upper) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return std::find(std::begin(kKeywords), std::end(kKeywords), std::string_view(upper)) !=
         std::end(kKeywords);
}

}  // namespace strand::machines
