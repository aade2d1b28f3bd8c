// Line-level pieces of the G-code reader (gcode_text.h), each linear in the line's length.
#include "postprocess/inspect/gcode_text.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>

namespace strand::post::gcode {

using slicer::Feature;

namespace {

// M-codes whose argument is free text ("M117 Open the valve", Marlin's "M0 Set flow 1.25",
// RepRapFirmware's M291 P"message" S2), not address words.
bool takes_text(const Words& w) {
  if (w.count != 1 || w.letter[0] != 'M') return false;
  const double m = w.value[0];
  return m == 117 || m == 118 || m == 23 || m == 28 || m == 30 || m == 32 || m == 0 || m == 1 || m == 291;
}

}  // namespace

bool is_letter(char c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z'); }

Words split_words(std::string_view code) {
  Words w;
  std::size_t i = 0;
  while (i < code.size() && w.count < 16) {
    const char c = code[i];
    if (c == ';' || c == '(') break;
    if (!is_letter(c)) {
      ++i;
      continue;
    }
    std::size_t j = i + 1;
    while (j < code.size() && code[j] == ' ') ++j;
    const std::size_t k = j < code.size() && code[j] == '+' ? j + 1 : j;
    double v = 0.0;
    const auto res = std::from_chars(code.data() + k, code.data() + code.size(), v);
    if (res.ec != std::errc()) {
      const bool bare = k >= code.size() || (is_letter(code[k]) && k > i + 1) || code[k] == ';';
      if (!bare && w.count > 0 && w.letter[0] == 'G') w.bad_number = true;
      i = bare ? i + 1 : code.find(' ', k);  // a malformed word is skipped whole
      continue;
    }
    if (!std::isfinite(v)) {  // nan, inf: never used as a coordinate
      w.bad_number = true;
      i = static_cast<std::size_t>(res.ptr - code.data());
      continue;
    }
    w.letter[w.count] = static_cast<char>(c & ~0x20);
    w.value[w.count] = v;
    ++w.count;
    i = static_cast<std::size_t>(res.ptr - code.data());
    if (takes_text(w)) break;
  }
  return w;
}

bool starts_with(std::string_view s, std::string_view p) { return s.substr(0, p.size()) == p; }

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\r' || s.back() == '\t'))
    s.remove_suffix(1);
  return s;
}

Feature feature_from_comment(std::string_view name, Feature fallback) {
  static const char* kNames[] = {"infill", "wall",  "ligament", "node",
                                 "grip",   "frame", "link",     "pen"};
  for (const char* n : kNames) {
    if (name == n) return slicer::feature_from_string(n);
  }
  return fallback;
}

Feature feature_from_role(std::string_view role) {
  auto has = [role](std::string_view w) { return role.find(w) != std::string_view::npos; };
  return has("WALL") || has("erimeter") ? Feature::Wall : Feature::Infill;
}

std::string o_text(const std::string& name) {
  const bool numeric = !name.empty() && name.find_first_not_of("0123456789") == std::string::npos;
  return numeric ? "o" + name : "o<" + name + ">";
}

std::optional<OWord> o_word(std::string_view s) {
  std::size_t i = 0;
  if (i < s.size() && (s[i] == 'N' || s[i] == 'n')) {  // a line number first
    ++i;
    while (i < s.size() && ((s[i] >= '0' && s[i] <= '9') || s[i] == ' ' || s[i] == '\t')) ++i;
  }
  if (i >= s.size() || (s[i] != 'O' && s[i] != 'o')) return std::nullopt;
  ++i;
  OWord o;
  if (i < s.size() && s[i] == '<') {
    const std::size_t close = s.find('>', i);
    if (close == std::string_view::npos) return std::nullopt;
    for (std::size_t k = i + 1; k < close; ++k)
      if (s[k] != ' ' && s[k] != '\t') o.name += static_cast<char>(std::tolower(s[k]));
    i = close + 1;
  } else {
    while (i < s.size() && s[i] >= '0' && s[i] <= '9') o.name += s[i++];
    if (o.name.empty()) return std::nullopt;
    o.name.erase(0, std::min(o.name.find_first_not_of('0'), o.name.size() - 1));  // o010 = o10
  }
  while (i < s.size() && (s[i] == ' ' || s[i] == '\t')) ++i;
  while (i < s.size() && is_letter(s[i]) && o.keyword.size() < 10)
    o.keyword += static_cast<char>(std::tolower(s[i++]));
  o.args = i;
  return o;
}

std::string strip_comments(std::string_view s) {
  std::string out;
  bool paren = false;
  for (char c : s) {
    if (paren) {
      paren = c != ')';
      continue;
    }
    if (c == ';') break;
    if (c == '(') {
      paren = true;
      continue;
    }
    out += c;
  }
  return out;
}

// A line that needs the RS274NGC reader: parameters or expressions in its code, and not a
// vendor's extended command ("EXCLUDE_OBJECT_DEFINE ... POLYGON=[[..]]", "M117 [text]",
// RepRapFirmware's "G1 X{move.axes[0].max}", read as before: a malformed number).
bool is_ngc_line(std::string_view s) {
  if (s.size() >= 2 && is_letter(s[0]) && (is_letter(s[1]) || s[1] == '_')) return false;
  if (!is_letter(s[0]) && s[0] != '#' && s[0] != '/') return false;  // not code: JSON, text
  if (s[0] == 'M' || s[0] == 'm') {
    int m = 0;
    std::from_chars(s.data() + 1, s.data() + s.size(), m);
    if (m == 117 || m == 118 || m == 23 || m == 28 || m == 30 || m == 32) return false;
  }
  int paren = 0;
  for (char c : s) {
    if (c == ';' || c == '{') return false;  // RepRapFirmware's {expressions} are not RS274NGC
    if (c == '(') ++paren;
    if (c == ')' && paren > 0) --paren;
    if (paren == 0 && (c == '#' || c == '[')) return true;
  }
  return false;
}

}  // namespace strand::post::gcode
