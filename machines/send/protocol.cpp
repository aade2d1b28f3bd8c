// Serial protocol words: command extraction, checksums, reply classification.
#include "machines/send/protocol.h"

#include <algorithm>
#include <cctype>

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
    if (std::tolower(static_cast<unsigned char>(s[i])) != std::tolower(static_cast<unsigned char>(prefix[i]))) return false;
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
  return !rest.empty() && (std::isdigit(static_cast<unsigned char>(rest[0])) || rest[0] == '-' || rest[0] == '.');
}

long number_after(std::string_view s) {
  std::size_t i = 0;
  while (i < s.size() && !std::isdigit(static_cast<unsigned char>(s[i]))) ++i;
  long n = 0;
  while (i < s.size() && std::isdigit(static_cast<unsigned char>(s[i]))) n = n * 10 + (s[i++] - '0');
  return n;
}

}  // namespace

std::vector<Command> commands_of(std::string_view gcode, const std::string& origin) {
  if (gcode.find('\0') != std::string_view::npos) throw InputError(origin + ": not a G-code file (binary data)");
  std::vector<Command> out;
  int line = 0;
  while (!gcode.empty()) {
    const auto nl = gcode.find('\n');
    const std::string_view raw = gcode.substr(0, nl);
    ++line;
    std::string c = strip_comments(raw);
    if (!c.empty()) {
      if (!looks_like_gcode(c)) {
        throw InputError(origin + ": line " + std::to_string(line) + ": \"" + std::string(trim(raw)).substr(0, 40) +
                         "\" is not G-code (a command starts with a letter and a number, such as G1 or M280)");
      }
      if (out.size() >= kMaxSendLines) throw InputError(origin + ": more than " + std::to_string(kMaxSendLines) + " commands");
      out.push_back({line, std::move(c)});
    }
    if (nl == std::string_view::npos) break;
    gcode.remove_prefix(nl + 1);
  }
  if (out.empty()) throw InputError(origin + ": no G-code commands in the file");
  return out;
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
