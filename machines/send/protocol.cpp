// Serial protocol words: command extraction, checksums, reply classification.
#include "machines/send/protocol.h"

#include <algorithm>
#include <cctype>
#include <limits>

#include "slicer/input_error.h"

namespace strand::machines {

namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

// Comments: ';' to the end of the line, and '(' ... ')' (RS-274, GRBL).
std::string strip_comments(std::string_view line) {
  std::string out;
  int depth = 0;
  for (char c : line) {
    if (depth == 0 && c == ';') break;
    if (c == '(') ++depth;
    if (depth == 0) out += c;
    if (c == ')' && depth > 0) --depth;
  }
  return std::string(trim(out));
}

bool starts_with_ci(std::string_view s, std::string_view prefix) {
  if (s.size() < prefix.size()) return false;
  for (std::size_t i = 0; i < prefix.size(); ++i) {
    if (std::tolower(static_cast<unsigned char>(s[i])) !=
        std::tolower(static_cast<unsigned char>(prefix[i])))
      return false;
  }
  return true;
}

bool contains_ci(std::string_view s, std::string_view what) {
  for (std::size_t i = 0; i + what.size() <= s.size(); ++i) {
    if (starts_with_ci(s.substr(i), what)) return true;
  }
  return false;
}

// A G-code command starts with a word letter and a number ("G1", "M280", "T0", "N5"), or is
// a GRBL system command ("$H", "$X") or a lone realtime character.
bool looks_like_gcode(std::string_view c) {
  if (c[0] == '$' || c[0] == '%') return true;
  if (!std::isalpha(static_cast<unsigned char>(c[0]))) return false;
  const std::string_view rest = trim(c.substr(1));
  return !rest.empty() &&
         (std::isdigit(static_cast<unsigned char>(rest[0])) || rest[0] == '-' || rest[0] == '.');
}

long number_after(std::string_view s) {
  std::size_t i = 0;
  while (i < s.size() && !std::isdigit(static_cast<unsigned char>(s[i]))) ++i;
  // Saturates instead of overflowing: a firmware that names a line past any the file has
  // (a garbled "Resend: 888…") is answered as a resend of a line never sent.
  constexpr long kMax = std::numeric_limits<long>::max();
  long n = 0;
  for (; i < s.size() && std::isdigit(static_cast<unsigned char>(s[i])); ++i) {
    const int digit = s[i] - '0';
    n = n > (kMax - digit) / 10 ? kMax : n * 10 + digit;
  }
  return n;
}

// The next line of `rest` without its end, which is LF, CRLF or a lone CR; `rest` moves past it.
std::string_view next_line(std::string_view& rest) {
  const auto end = rest.find_first_of("\r\n");
  const std::string_view line = rest.substr(0, end);
  if (end == std::string_view::npos) {
    rest = {};
  } else {
    rest.remove_prefix(
        end + (rest[end] == '\r' && end + 1 < rest.size() && rest[end + 1] == '\n' ? 2 : 1));
  }
  return line;
}

// A file's own serial framing, "N12 G1 X5*57" -> "G1 X5": the line number word in front and
// the checksum at the end (only after a line number, as the protocol frames them).
std::string_view without_framing(std::string_view c) {
  if (c.size() < 2 || (c[0] != 'N' && c[0] != 'n') ||
      !std::isdigit(static_cast<unsigned char>(c[1])))
    return c;
  std::size_t i = 1;
  while (i < c.size() && std::isdigit(static_cast<unsigned char>(c[i]))) ++i;
  c = trim(c.substr(i));
  const auto star = c.rfind('*');
  if (star != std::string_view::npos && star + 1 < c.size() &&
      std::all_of(c.begin() + static_cast<long>(star) + 1, c.end(),
                  [](char ch) { return std::isdigit(static_cast<unsigned char>(ch)); })) {
    c = trim(c.substr(0, star));
  }
  return c;
}

std::string hex_byte(unsigned char u) {
  static const char* const kHex = "0123456789abcdef";
  return std::string("0x") + kHex[u >> 4] + kHex[u & 15];
}

}  // namespace

std::vector<Command> commands_of(std::string_view gcode, const std::string& origin) {
  if (gcode.find('\0') != std::string_view::npos)
    throw InputError(origin + ": not a G-code file (binary data)");
  std::vector<Command> out;
  int line = 0;
  const auto refuse = [&](std::string_view raw, const std::string& why) {
    std::string shown;
    for (char ch : trim(raw).substr(0, 40))
      shown += static_cast<unsigned char>(ch) < 0x20 || ch == 0x7f ? '?' : ch;
    throw InputError(origin + ": line " + std::to_string(line) + ": \"" + shown + "\" " + why);
  };
  while (!gcode.empty()) {
    const std::string_view raw = next_line(gcode);
    ++line;
    const std::string stripped = strip_comments(raw);
    const std::string_view c = without_framing(stripped);
    if (c.empty()) continue;
    if (!looks_like_gcode(c))
      refuse(raw,
             "is not G-code (a command starts with a letter and a number, such as G1 or M280)");
    for (char ch : c) {
      const auto u = static_cast<unsigned char>(ch);
      if ((u < 0x20 && ch != '\t') || u == 0x7f) {
        refuse(raw, "holds the control character " + hex_byte(u) +
                        " inside a command (it would reach the controller)");
      }
      if (ch == '*')
        refuse(raw, "holds a '*' inside a command ('*' starts the checksum on the serial line)");
    }
    if (out.size() >= kMaxSendLines)
      throw InputError(origin + ": more than " + std::to_string(kMaxSendLines) + " commands");
    out.push_back({line, std::string(c)});
  }
  if (out.empty()) throw InputError(origin + ": no G-code commands in the file");
  return out;
}

bool sets_line_number(std::string_view command) {
  const std::string_view c = trim(command);
  if (c.empty() || (c[0] != 'M' && c[0] != 'm')) return false;
  std::string_view rest = trim(c.substr(1));
  long code = 0;
  std::size_t i = 0;
  while (i < rest.size() && i < 9 && std::isdigit(static_cast<unsigned char>(rest[i])))
    code = code * 10 + (rest[i++] - '0');
  if (i == 0 || code != 110) return false;
  return i == rest.size() || (!std::isdigit(static_cast<unsigned char>(rest[i])) && rest[i] != '.');
}

void refuse_grbl_realtime_characters(const std::vector<Command>& commands,
                                     const std::string& origin) {
  for (const auto& c : commands) {
    for (char ch : c.text) {
      const auto u = static_cast<unsigned char>(ch);
      const char* what = ch == '?'   ? "'?' (status report)"
                         : ch == '!' ? "'!' (feed hold)"
                         : ch == '~' ? "'~' (cycle start)"
                                     : nullptr;
      if (!what && u < 0x80) continue;
      const std::string name =
          what ? std::string(what) : "the byte " + hex_byte(u) + " (a real-time override)";
      throw InputError(origin + ": line " + std::to_string(c.file_line) + ": " + name +
                       " inside a command: GRBL acts on it at once wherever it appears");
    }
  }
}

int checksum(std::string_view text) {
  int cs = 0;
  for (char c : text) cs ^= static_cast<unsigned char>(c);
  return cs & 0xff;
}

std::string numbered(long n, std::string_view command) {
  const std::string body = "N" + std::to_string(n) + " " + std::string(command);
  return body + "*" + std::to_string(checksum(body));
}

Reply parse_reply(std::string_view raw, Firmware firmware) {
  Reply r;
  const std::string_view s = trim(raw);
  r.text = std::string(s);
  if (starts_with_ci(s, "ok")) {
    r.kind = ReplyKind::Ok;
  } else if (starts_with_ci(s, "resend:") || starts_with_ci(s, "rs ")) {
    r.kind = ReplyKind::Resend;
    r.line = number_after(s);
  } else if (s.starts_with("!!")) {
    r.kind = ReplyKind::Error;  // Klipper: "!! Move out of range: ...", "!! Shutdown"
  } else if (contains_ci(s, "busy:")) {
    r.kind = ReplyKind::Busy;
  } else if (starts_with_ci(s, "error")) {
    // Marlin and RRF report transmission errors, then ask for a resend
    const bool line_error = contains_ci(s, "checksum") || contains_ci(s, "line number") ||
                            contains_ci(s, "last line") || contains_ci(s, "no line");
    r.kind = line_error && firmware != Firmware::Grbl ? ReplyKind::LineError : ReplyKind::Error;
  } else if (starts_with_ci(s, "alarm")) {
    r.kind = ReplyKind::Alarm;
  } else if (firmware == Firmware::Grbl && s.size() > 1 && s.front() == '<') {
    r.kind = ReplyKind::Status;
    r.idle = starts_with_ci(s.substr(1), "idle");
  } else if (s == "start" || starts_with_ci(s, "grbl ")) {
    r.kind = ReplyKind::Restart;
  }
  return r;
}

}  // namespace strand::machines
