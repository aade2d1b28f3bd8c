// Single-pass G-code reader with std::from_chars; linear in the file size.
#include "postprocess/inspect/gcode_parser.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <map>
#include <optional>
#include <unordered_map>

#include "postprocess/inspect/ngc_expression.h"
#include "postprocess/plan/arc_segmentation.h"
#include "slicer/input_error.h"
#include "slicer/params.h"
#include "slicer/units.h"

namespace strand::post {

using slicer::Feature;
using slicer::Move;
using slicer::MoveKind;
using slicer::Vec3;

namespace {

struct Words {
  char letter[16];
  double value[16];
  int count = 0;
  bool bad_number = false;
  std::optional<double> get(char c) const {
    for (int i = 0; i < count; ++i) {
      if (letter[i] == c) return value[i];
    }
    return std::nullopt;
  }
};

constexpr double kMaxCommandNumber = 1e6;

bool is_letter(char c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z'); }

// M-codes whose argument is free text ("M117 Open the valve"), not address words.
bool takes_text(const Words& w) {
  if (w.count != 1 || w.letter[0] != 'M') return false;
  const double m = w.value[0];
  return m == 117 || m == 118 || m == 23 || m == 28 || m == 30 || m == 32;
}

// Splits "G1 X1.5 Y-2 E0.1" into letter/number words; stops at ';' or '('. A word whose
// number is nan/inf, or a G word followed by something that is not a number, sets
// bad_number; a bare letter ("G28 X Y") is a flag word and is skipped.
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

// Another slicer's ;TYPE: role (Cura "WALL-OUTER", "FILL"; PrusaSlicer "Perimeter",
// "Solid infill") as the nearest feature, so previews colour walls and fills apart. Every
// role that is not a wall (fills, gap fill, skirt, support, wipe tower) reads as infill:
// FDM rules let such moves cross. Strand's own files follow with ;FEATURE:, which wins.
Feature feature_from_role(std::string_view role) {
  auto has = [role](std::string_view w) { return role.find(w) != std::string_view::npos; };
  return has("WALL") || has("erimeter") ? Feature::Wall : Feature::Infill;
}

// A milling program: the spindle turns faster than any pen servo or laser value (S > this,
// rpm) and a cutting move goes below the work surface (z < -kPlungeMm).
constexpr double kSpindleMinRpm = 1000.0;
constexpr double kPlungeMm = 0.05;

// O-word programs may repeat lines (loops, calls) this many times beyond the file's own
// lines, and read this many bytes beyond its size: then the loop is called unbounded.
constexpr std::size_t kMaxRepeatedLines = 1'000'000;
constexpr std::size_t kMaxRepeatedBytes = 64u << 20;
constexpr int kMaxCallDepth = 64;
constexpr std::size_t kMaxNamedParameters = 10'000;

// "o100 while [...]" / "o<name> call [1]": the O-word's name, keyword and where its
// arguments start; nullopt when the line is no O-word.
struct OWord {
  std::string name;
  std::string keyword;  // lower-case; empty for a bare program number ("O1000")
  std::size_t args = 0;
};

// How the file writes the O-word: o100 or o<name>.
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

// Comments out: "(...)" anywhere and ';' to the end.
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

class Reader {
 public:
  Reader(std::string_view text, const PenReading& pen) : text_(text), pen_(pen) {
    has_markers_ = text.find(";LAYER") != std::string_view::npos;
    has_e_ = scan_has_e(text);
    out_.has_e = has_e_;
  }

  ParsedGcode run() {
    ParsedGcode out = has_o_words(text_) ? run_indexed() : run_streaming();
    if (spindle_line_ && plunge_line_ && !has_e_) {
      out.issues.push_back(
          {plunge_line_, "milling program: the spindle turns (M" + std::to_string(spindle_m_) +
                             " S" + slicer::short_number(spindle_s_) + " at line " +
                             std::to_string(spindle_line_) + ") and the tool cuts " +
                             slicer::short_number(-plunge_z_) +
                             " mm below the work surface (line " + std::to_string(plunge_line_) +
                             "): a subtractive program, not a deposition or drawing toolpath"});
    }
    return out;
  }

 private:
  static bool has_o_words(std::string_view t) {
    for (std::size_t pos = 0; pos < t.size();) {
      std::size_t nl = t.find('\n', pos);
      if (nl == std::string_view::npos) nl = t.size();
      const std::string_view l = trim(t.substr(pos, nl - pos));
      if (!l.empty() && (l[0] == 'O' || l[0] == 'o' || l[0] == 'N' || l[0] == 'n') && o_word(l))
        return true;
      pos = nl + 1;
    }
    return false;
  }

  ParsedGcode run_streaming() {
    // One move per line at most: reserving avoids re-copying a million moves while growing.
    const auto lines = static_cast<std::size_t>(std::count(text_.begin(), text_.end(), '\n')) + 1;
    out_.program.moves.reserve(lines);
    out_.move_lines.reserve(lines);
    std::size_t pos = 0;
    int line_no = 0;
    while (pos <= text_.size()) {
      const std::size_t nl = text_.find('\n', pos);
      const std::size_t end = nl == std::string_view::npos ? text_.size() : nl;
      ++line_no;
      line(trim(text_.substr(pos, end - pos)), line_no);
      if (nl == std::string_view::npos || stopped_) break;
      pos = nl + 1;
    }
    return std::move(out_);
  }

  // O-word programs: lines by index, blocks matched first, then run with a program counter.
  ParsedGcode run_indexed() {
    for (std::size_t pos = 0; pos <= text_.size();) {
      std::size_t nl = text_.find('\n', pos);
      if (nl == std::string_view::npos) nl = text_.size();
      lines_.push_back(trim(text_.substr(pos, nl - pos)));
      pos = nl + 1;
    }
    match_blocks();
    const std::size_t line_budget = lines_.size() + kMaxRepeatedLines;
    const std::size_t byte_budget = text_.size() + kMaxRepeatedBytes;
    std::size_t lines_run = 0, bytes_run = 0;
    for (std::size_t pc = 0; pc < lines_.size() && !stopped_;) {
      lines_run += 1;
      bytes_run += lines_[pc].size();
      if (lines_run > line_budget || bytes_run > byte_budget) {
        throw InputError("line " + std::to_string(loop_line_) +
                         ": this O-word loop or call repeats past " +
                         std::to_string(kMaxRepeatedLines) + " lines or " +
                         std::to_string(kMaxRepeatedBytes >> 20) + " MiB of the file (unbounded?)");
      }
      const auto o = o_words_.find(pc);
      if (o == o_words_.end()) {
        line(lines_[pc], static_cast<int>(pc) + 1);
        ++pc;
      } else {
        pc = o_step(pc, o->second);
      }
    }
    return std::move(out_);
  }

  [[noreturn]] void bad(std::size_t index, const std::string& what) const {
    throw InputError("line " + std::to_string(index + 1) + ": " + what + " in '" +
                     std::string(lines_[index].substr(0, 80)) + "'");
  }

  // Pairs every O-word block: sub/endsub, if/elseif/else/endif, while/endwhile,
  // do/while, repeat/endrepeat; break and continue point at their loop.
  void match_blocks() {
    std::vector<std::size_t> open;
    for (std::size_t i = 0; i < lines_.size(); ++i) {
      const std::string_view l = lines_[i];
      if (l.empty() || !(l[0] == 'O' || l[0] == 'o' || l[0] == 'N' || l[0] == 'n')) continue;
      auto o = o_word(l);
      if (!o) continue;
      const std::string& k = o->keyword;
      const auto top_is = [&](std::initializer_list<const char*> kinds) {
        if (open.empty() || o_words_[open.back()].name != o->name) return false;
        for (const char* kind : kinds)
          if (o_words_[open.back()].keyword == kind) return true;
        return false;
      };
      if (k == "while" && top_is({"do"})) {
        o->keyword = "do-while";
        end_[open.back()] = i, partner_[i] = open.back();
        open.pop_back();
      } else if (k == "sub" || k == "if" || k == "while" || k == "do" || k == "repeat") {
        if (k == "sub") subs_[o->name] = i;
        open.push_back(i);
      } else if (k == "elseif" || k == "else") {
        if (!top_is({"if"}))
          bad(i, o_text(o->name) + " " + k + " without its " + o_text(o->name) + " if");
        branches_[open.back()].push_back(i);
        partner_[i] = open.back();
      } else if (k == "endsub" || k == "endif" || k == "endwhile" || k == "endrepeat") {
        const std::string opener = k.substr(3);
        if (!top_is({opener.c_str()}))
          bad(i, o_text(o->name) + " " + k + " without its " + o_text(o->name) + " " + opener);
        end_[open.back()] = i, partner_[i] = open.back();
        for (std::size_t b : branches_[open.back()]) end_[b] = i;
        open.pop_back();
      } else if (k == "break" || k == "continue") {
        auto loop = std::find_if(open.rbegin(), open.rend(), [&](std::size_t j) {
          const auto& w = o_words_[j];
          return w.name == o->name &&
                 (w.keyword == "while" || w.keyword == "do" || w.keyword == "repeat");
        });
        if (loop == open.rend()) bad(i, o_text(o->name) + " " + k + " outside its loop");
        partner_[i] = *loop;
      } else if (k != "call" && k != "return" && !k.empty()) {
        bad(i, "unknown O-word keyword '" + k + "'");
      }
      o_words_[i] = std::move(*o);
    }
    if (!open.empty()) {
      const auto& o = o_words_[open.back()];
      bad(open.back(), o_text(o.name) + " " + o.keyword + " is never closed");
    }
  }

  double condition(std::size_t index) {
    const OWord& o = o_words_[index];
    const std::string code = strip_comments(lines_[index].substr(o.args));
    try {
      std::size_t pos = 0;
      return ngc_real_value(code, pos, scope_);
    } catch (const NgcError& e) {
      bad(index, e.what());
    } catch (const NgcUnsupported& e) {
      unsupported(static_cast<int>(index) + 1, e.what());
      return 0.0;
    }
  }

  // Runs one O-word line; returns the next line index.
  std::size_t o_step(std::size_t pc, const OWord& o) {
    const std::string& k = o.keyword;
    if (k == "sub") return end_.at(pc) + 1;
    if (k == "endsub" || k == "return") return return_from(pc, o);
    if (k == "call") return call(pc, o);
    if (k == "if") {
      if (condition(pc) != 0.0) return pc + 1;
      for (std::size_t b : branches_[pc]) {
        if (stopped_) return lines_.size();
        if (o_words_[b].keyword == "else" || condition(b) != 0.0) return b + 1;
      }
      return end_.at(pc) + 1;
    }
    if (k == "elseif" || k == "else") return end_.at(pc) + 1;  // the branch above ran
    if (k == "while") return condition(pc) != 0.0 ? pc + 1 : end_.at(pc) + 1;
    if (k == "endwhile") {
      loop_line_ = partner_.at(pc) + 1;
      return partner_.at(pc);
    }
    if (k == "do-while") {
      if (condition(pc) == 0.0) return pc + 1;
      loop_line_ = partner_.at(pc) + 1;
      return partner_.at(pc) + 1;
    }
    if (k == "repeat") {
      const double n = condition(pc);
      repeats_[pc] = n >= 1 ? static_cast<long long>(std::min(n, 1e15)) : 0;
      return repeats_[pc] > 0 ? pc + 1 : end_.at(pc) + 1;
    }
    if (k == "endrepeat") {
      const std::size_t r = partner_.at(pc);
      if (--repeats_[r] <= 0) return pc + 1;
      loop_line_ = r + 1;
      return r + 1;
    }
    if (k == "break") return end_.at(partner_.at(pc)) + 1;
    if (k == "continue") {
      const std::size_t loop = partner_.at(pc);
      loop_line_ = loop + 1;
      return o_words_[loop].keyword == "while" ? loop : end_.at(loop);
    }
    return pc + 1;  // "do", "endif", a program number
  }

  struct CallFrame {
    std::size_t return_to = 0;
    std::unordered_map<int, double> numbered;
    std::map<std::string, double> named;
  };

  std::size_t call(std::size_t pc, const OWord& o) {
    const auto sub = subs_.find(o.name);
    if (sub == subs_.end()) {
      unsupported(static_cast<int>(pc) + 1,
                  "O-word call of " + o_text(o.name) + ", a subroutine not defined in this file");
      return lines_.size();
    }
    if (calls_.size() >= static_cast<std::size_t>(kMaxCallDepth))
      bad(pc, "subroutine calls nested deeper than " + std::to_string(kMaxCallDepth));
    std::vector<double> args;
    const std::string code = strip_comments(lines_[pc].substr(o.args));
    try {
      for (std::size_t pos = 0; pos < code.size() && args.size() < 30;) {
        if (code[pos] == ' ' || code[pos] == '\t') {
          ++pos;
          continue;
        }
        args.push_back(ngc_real_value(code, pos, scope_));
      }
    } catch (const NgcError& e) {
      bad(pc, e.what());
    } catch (const NgcUnsupported& e) {
      unsupported(static_cast<int>(pc) + 1, e.what());
      return lines_.size();
    }
    CallFrame f{pc + 1, numbered_, {}};
    for (const auto& [name, v] : named_)
      if (name[0] != '_') f.named.emplace(name, v);
    calls_.push_back(std::move(f));
    for (int i = 1; i <= 30; ++i) numbered_.erase(i);
    for (std::size_t i = 0; i < args.size(); ++i) numbered_[static_cast<int>(i) + 1] = args[i];
    loop_line_ = pc + 1;
    return sub->second + 1;
  }

  std::size_t return_from(std::size_t pc, const OWord& o) {
    if (calls_.empty()) return pc + 1;  // ran into a definition's end: nothing to return to
    std::optional<double> value;
    if (strip_comments(lines_[pc].substr(o.args)).find('[') != std::string::npos)
      value = condition(pc);
    CallFrame f = std::move(calls_.back());
    calls_.pop_back();
    // Locals (#1-#30 and names without '_') come back; globals keep what the call set.
    for (int i = 1; i <= 30; ++i) {
      numbered_.erase(i);
      if (auto it = f.numbered.find(i); it != f.numbered.end()) numbered_[i] = it->second;
    }
    for (auto it = named_.begin(); it != named_.end();)
      it = it->first[0] == '_' ? std::next(it) : named_.erase(it);
    named_.insert(f.named.begin(), f.named.end());
    if (value) named_["_value"] = *value;
    named_["_value_returned"] = value ? 1.0 : 0.0;
    return f.return_to;
  }

  void unsupported(int n, const std::string& what) {
    if (stopped_) return;
    out_.issues.push_back({n, "unsupported: " + what + " at line " + std::to_string(n) +
                                  "; the rest of the file is not read"});
    stopped_ = true;
  }

  // Parameters and positions for expressions (positions in the file's units).
  class Scope : public NgcScope {
   public:
    explicit Scope(const Reader& r) : r_(r) {}
    double numbered(int i) const override {
      if (i >= 5420 && i <= 5423) return i == 5423 ? r_.a_ : r_.pos_[i - 5420] / r_.scale_;
      const auto it = r_.numbered_.find(i);
      if (it != r_.numbered_.end()) return it->second;
      if (i >= 5000) throw NgcUnsupported("system parameter #" + std::to_string(i));
      return 0.0;
    }
    std::optional<double> named(const std::string& n) const override {
      if (n == "_x" || n == "_y" || n == "_z") return r_.pos_[n[1] - 'x'] / r_.scale_;
      if (n == "_a") return r_.a_;
      if (n == "_metric") return r_.scale_ == 1.0 ? 1.0 : 0.0;
      if (n == "_imperial") return r_.scale_ == 1.0 ? 0.0 : 1.0;
      const auto it = r_.named_.find(n);
      if (it != r_.named_.end()) return it->second;
      return std::nullopt;
    }

   private:
    const Reader& r_;
  };

  // A line with parameters or expressions: words evaluated, then the assignments made (all
  // reads on a line see the values from before it, as RS274NGC says).
  void ngc_line(std::string_view s, int n) {
    const std::string code = strip_comments(s);
    Words w;
    std::vector<std::pair<NgcParameterRef, double>> sets;
    try {
      for (std::size_t pos = 0; pos < code.size();) {
        const char c = code[pos];
        if (c == ' ' || c == '\t' || c == '\r' || (c == '/' && pos == 0) || c == '%') {
          ++pos;
        } else if (c == '#') {
          ++pos;
          NgcParameterRef ref = ngc_parameter_ref(code, pos, scope_);
          while (pos < code.size() && (code[pos] == ' ' || code[pos] == '\t')) ++pos;
          if (pos >= code.size() || code[pos] != '=')
            throw NgcError("'=' expected after the parameter (an assignment)");
          ++pos;
          const double v = ngc_real_value(code, pos, scope_);
          sets.emplace_back(std::move(ref), v);
        } else if (is_letter(c)) {
          ++pos;
          const double v = ngc_real_value(code, pos, scope_);
          const char letter = static_cast<char>(c & ~0x20);
          if (letter != 'N' && w.count < 16) {
            w.letter[w.count] = letter;
            w.value[w.count] = v;
            ++w.count;
          }
        } else {
          throw NgcError(std::string("unexpected '") + c + "'");
        }
      }
    } catch (const NgcError& e) {
      throw InputError("line " + std::to_string(n) + ": " + e.what() + " in '" +
                       std::string(s.substr(0, 80)) + "'");
    } catch (const NgcUnsupported& e) {
      unsupported(n, e.what());
      return;
    }
    for (auto& [ref, v] : sets) {
      if (ref.index > 0) {
        if (ref.index >= 5000)
          throw InputError("line " + std::to_string(n) + ": #" + std::to_string(ref.index) +
                           " is a system parameter: it cannot be set");
        numbered_[ref.index] = v;
      } else {
        if (scope_.named(ref.name) &&
            (ref.name == "_x" || ref.name == "_y" || ref.name == "_z" || ref.name == "_a" ||
             ref.name == "_metric" || ref.name == "_imperial")) {
          throw InputError("line " + std::to_string(n) + ": #<" + ref.name +
                           "> is read-only (the machine's state)");
        }
        if (named_.size() >= kMaxNamedParameters && !named_.count(ref.name))
          throw InputError("line " + std::to_string(n) + ": more than " +
                           std::to_string(kMaxNamedParameters) + " named parameters");
        named_[ref.name] = v;
      }
    }
    words(w, s, n);
  }

  void words(const Words& w, std::string_view s, int n) {
    if (w.bad_number)
      out_.issues.push_back({n, "non-finite or malformed number in '" + std::string(s) + "'"});
    if (w.count == 0) return;
    const char cmd = w.letter[0];
    // G and M numbers are small; a huge one ("G1e12") names no command and would not fit int.
    if (!(w.value[0] >= 0.0 && w.value[0] < kMaxCommandNumber)) return;
    const int code = static_cast<int>(w.value[0]);
    if (cmd == 'G') g_code(code, w, n);
    if (cmd == 'M') m_code(code, w, n);
  }

  // Files whose moves carry E words (other than E0 everywhere) use E to tell deposits.
  static bool scan_has_e(std::string_view t) {
    for (std::size_t i = t.find('E'); i != std::string_view::npos; i = t.find('E', i + 1)) {
      if (i == 0 || (t[i - 1] != ' ' && t[i - 1] != '\t')) continue;
      const std::size_t ls = t.rfind('\n', i) + 1;
      const std::size_t semi = t.find(';', ls);
      if (semi != std::string_view::npos && semi < i) continue;
      if (t[ls] != 'G') continue;
      double v = 0;
      auto r = std::from_chars(t.data() + i + 1, t.data() + t.size(), v);
      if (r.ec == std::errc() && v != 0.0) return true;
    }
    return false;
  }

  void line(std::string_view s, int n) {
    if (s.empty() || stopped_) return;
    if (s.front() == ';') {
      comment(s.substr(1), n);
      return;
    }
    if (is_ngc_line(s)) {
      ngc_line(s, n);
      return;
    }
    words(split_words(s), s, n);
  }

  void comment(std::string_view c, int) {
    if (starts_with(c, "LAYER_CHANGE")) {
      new_layer(std::nullopt);
    } else if (starts_with(c, "LAYER:")) {
      if (!marker_pending_) new_layer(std::nullopt);
      marker_pending_ = false;
    } else if (starts_with(c, "Z:") && !out_.program.layers.empty()) {
      double z = 0;
      std::from_chars(c.data() + 2, c.data() + c.size(), z);
      out_.program.layers.back().z_mm = z;
      layer_z_known_ = true;
    } else if (starts_with(c, "HEIGHT:") && !out_.program.layers.empty()) {
      double h = 0;
      std::from_chars(c.data() + 7, c.data() + c.size(), h);
      out_.program.layers.back().height_mm = h;
    } else if (starts_with(c, "TYPE:")) {
      feature_ = feature_from_role(c.substr(5));
    } else if (starts_with(c, "FEATURE:")) {
      feature_ = feature_from_comment(trim(c.substr(8)), feature_);
    } else if (starts_with(c, "WIDTH:")) {
      std::from_chars(c.data() + 6, c.data() + c.size(), width_);
    } else if (starts_with(c, "PEN:")) {  // Strand's pen G-code: pen k from here on
      int k = 0;
      const auto r = std::from_chars(c.data() + 4, c.data() + c.size(), k);
      if (r.ec == std::errc() && k >= 1 && k <= kMaxPens) tool_ = static_cast<std::int16_t>(k - 1);
    } else {
      pen_colour(trim(c));
    }
  }

  // "pen 2 colour: #d40000", a header line of Strand's pen G-code: pen 2 draws in that colour.
  void pen_colour(std::string_view c) {
    if (!starts_with(c, "pen ")) return;
    int k = 0;
    const auto r = std::from_chars(c.data() + 4, c.data() + c.size(), k);
    if (r.ec != std::errc() || k < 1 || k > kMaxPens) return;
    const std::string_view rest = c.substr(static_cast<std::size_t>(r.ptr - c.data()));
    if (!starts_with(rest, " colour: #") || rest.size() != 16) return;
    const std::string_view hex = rest.substr(10);
    if (hex.find_first_not_of("0123456789abcdefABCDEF") != std::string_view::npos) return;
    auto& colours = out_.pen_colours;
    if (colours.size() < static_cast<std::size_t>(k)) colours.resize(static_cast<std::size_t>(k));
    colours[static_cast<std::size_t>(k - 1)] = "#" + std::string(hex);
  }

  void new_layer(std::optional<double> z) {
    out_.program.layers.push_back({z.value_or(pos_.z()), 0.0});
    layer_z_known_ = z.has_value();
    layer_ = static_cast<int>(out_.program.layers.size()) - 1;
    marker_pending_ = true;
  }

  void m_code(int code, const Words& w, int n) {
    if (code == 82) relative_e_ = false;
    if (code == 83) relative_e_ = true;
    if (code == 3 || code == 4) {
      const auto s = w.get('S');
      if (s && *s > kSpindleMinRpm && !spindle_line_)
        spindle_line_ = n, spindle_s_ = *s, spindle_m_ = code;
    }
    if (has_e_) return;
    if (pen_.valve_on_m && (code == *pen_.valve_on_m || code == *pen_.valve_off_m)) {
      const auto p = w.get('P');
      if (!pen_.valve_p || (p && *p == *pen_.valve_p)) valve_open_ = code == *pen_.valve_on_m;
      return;
    }  // an extruder's M300 is a beep, its M3 a spindle or laser
    const std::optional<bool> down = pen_down_by_command(pen_, code, w.get('S'), w.get('P'));
    if (!down) return;
    if (out_.pen_commands++ == 0) out_.notes.push_back({n, pen_convention(pen_, code)});
    out_.pen_servo = out_.pen_servo || code == 300 || code == 280;
    pen_down_ = *down;
  }

  // Without E a G1/G2/G3 in XY draws, unless the file lifts its pen: by command, or by z
  // above the pen-down height when the reading gives one.
  bool draws(int code, const Vec3& target) const {
    if (code == 0 || (target.head<2>() - pos_.head<2>()).norm() == 0.0) return false;
    if (pen_.valve_on_m) return valve_open_;
    if (pen_down_) return *pen_down_;
    return !pen_.z_down_max_mm || target.z() <= *pen_.z_down_max_mm;
  }

  void g_code(int code, const Words& w, int n) {
    switch (code) {
      case 0:
      case 1:
      case 2:
      case 3:
        motion(code, w, n);
        break;
      case 4:
        dwell(w, n);
        break;
      case 20:
        scale_ = slicer::kMmPerInch;
        if (!out_.inches)
          out_.notes.push_back({n, "inch units (G20): coordinates converted to mm"});
        out_.inches = true;
        break;
      case 21:
        scale_ = 1.0;
        break;
      case 90:
        relative_ = false;
        relative_e_ = false;
        break;  // Marlin: G90 resets E mode too
      case 91:
        relative_ = true;
        relative_e_ = true;
        break;
      case 92:
        if (auto e = w.get('E')) e_ = *e;
        if (auto a = w.get('A')) a_ = *a;
        for (int a = 0; a < 3; ++a) {
          if (auto v = w.get("XYZ"[a])) pos_[a] = *v * scale_;
        }
        break;
      default:
        break;
    }
  }

  void dwell(const Words& w, int n) {
    double seconds = 0.0;
    if (auto s = w.get('S')) seconds = *s;
    if (auto p = w.get('P')) seconds = *p / 1000.0;
    slicer::push_dwell(out_.program, seconds, pos_, layer_);
    out_.move_lines.push_back(n);  // one line per move, dwells included
    if (has_a_) out_.a_deg.push_back(a_), out_.e_step.push_back(0.0);
  }

  void motion(int code, const Words& w, int n) {
    if (auto f = w.get('F')) feed_ = *f * scale_;
    Vec3 target = pos_;
    bool moved = false;
    for (int a = 0; a < 3; ++a) {
      if (auto v = w.get("XYZ"[a])) {
        target[a] = relative_ ? pos_[a] + *v * scale_ : *v * scale_;
        moved = true;
      }
    }
    moved = rotary(w) || moved;
    if (spindle_line_ && code != 0 && target.z() < -kPlungeMm && !plunge_line_)
      plunge_line_ = n, plunge_z_ = target.z();
    double de = 0.0;
    if (auto e = w.get('E')) {
      de = relative_e_ ? *e : *e - e_;
      e_ = relative_e_ ? e_ + *e : *e;
    }
    if (!moved) return;  // E-only moves (prime, retract) carry no geometry
    Move mv;
    mv.end_mm = target;
    mv.feed_mm_per_min = feed_;
    mv.feature = feature_;
    mv.tool = tool_;
    mv.width_mm = width_;
    mv.kind = (has_e_ ? de > 0.0 : draws(code, target)) ? MoveKind::Deposit : MoveKind::Travel;
    if (code == 2 || code == 3) arc(mv, code, w, n);
    if (!has_markers_ && mv.kind == MoveKind::Deposit &&
        (layer_ < 0 || std::abs(target.z() - out_.program.layers.back().z_mm) > 1e-6)) {
      new_layer(target.z());
    }
    if (mv.kind == MoveKind::Deposit && layer_ >= 0 && !layer_z_known_) {
      out_.program.layers.back().z_mm = target.z();  // Cura: no ;Z:, the z comes after ;LAYER:
      layer_z_known_ = true;
    }
    mv.layer = layer_;
    out_.program.moves.push_back(std::move(mv));
    out_.move_lines.push_back(n);
    if (has_a_) out_.a_deg.push_back(a_), out_.e_step.push_back(de);
    if (out_.program.moves.size() == 1) out_.program.start_mm = pos_;
    pos_ = target;
    marker_pending_ = false;
  }

  // Reads an A word (rotary axis, degrees); true when there is one. Moves before the first
  // A word were at the old A.
  bool rotary(const Words& w) {
    const auto a = w.get('A');
    if (!a) return false;
    if (!has_a_) {
      out_.a_deg.assign(out_.program.moves.size(), a_);
      out_.e_step.assign(out_.program.moves.size(), 0.0);
    }
    has_a_ = true;
    a_ = relative_ ? a_ + *a : *a;
    return true;
  }

  void arc(Move& mv, int code, const Words& w, int n) {
    out_.arc_lines.push_back(n);
    mv.is_arc = true;
    mv.ccw = code == 3;
    const auto i = w.get('I'), j = w.get('J'), r = w.get('R');
    if (i || j) {
      mv.center_mm = pos_.head<2>() + slicer::Vec2(i.value_or(0) * scale_, j.value_or(0) * scale_);
      bound_arc(mv, n);
      return;
    }
    if (r) {  // radius form: centre on the perpendicular bisector, sign picks the short way
      const slicer::Vec2 a = pos_.head<2>(), b = mv.end_mm.head<2>();
      const double rad = std::abs(*r) * scale_;
      const slicer::Vec2 mid = (a + b) / 2, d = b - a;
      const double half = d.norm() / 2;
      const double h = std::sqrt(std::max(0.0, rad * rad - half * half));
      slicer::Vec2 perp(-d.y(), d.x());
      if (perp.norm() > 0) perp.normalize();
      const bool left = (mv.ccw == (*r > 0));
      mv.center_mm = mid + (left ? h : -h) * perp;
      bound_arc(mv, n);
      return;
    }
    out_.issues.push_back({n, "arc without I/J or R: read as a straight move"});
    mv.is_arc = false;
  }

  // Keeps every later flattening finite: absurd radii become straight moves, and the chord
  // count of all arcs at the finest tolerance stays within kMaxArcChords.
  void bound_arc(Move& mv, int n) {
    const slicer::Vec2 from = pos_.head<2>(), to = mv.end_mm.head<2>();
    const double r = (from - mv.center_mm).norm();
    if (!(r >= kMinArcRadiusMm && r <= kMaxArcRadiusMm)) {
      out_.issues.push_back({n, "arc radius " + slicer::short_number(r) + " mm outside [" +
                                    slicer::short_number(kMinArcRadiusMm) + ", " +
                                    slicer::short_number(kMaxArcRadiusMm) +
                                    "] mm: read as a straight move"});
      mv.is_arc = false;
      return;
    }
    const double sweep = slicer::arc_sweep(mv.center_mm, from, to, mv.ccw);
    arc_chords_ += chords_needed(r, sweep, kMinFlattenToleranceMm);
    if (arc_chords_ > kMaxArcChords) {
      out_.issues.push_back({n, "arcs of this file would flatten into more than " +
                                    slicer::short_number(kMaxArcChords) +
                                    " chords: read as a straight move"});
      mv.is_arc = false;
    }
  }

  std::string_view text_;
  const PenReading& pen_;
  ParsedGcode out_;
  Vec3 pos_ = Vec3::Zero();
  double e_ = 0.0;
  double a_ = 0.0;      // rotary axis position, degrees
  bool has_a_ = false;  // an A word was read: a_deg is kept parallel to the moves
  double feed_ = 0.0;
  double scale_ = 1.0;
  double width_ = 0.0;
  double arc_chords_ = 0.0;
  bool relative_ = false;
  bool relative_e_ = false;
  bool has_markers_ = false;
  bool has_e_ = false;
  bool marker_pending_ = false;
  bool layer_z_known_ = false;  // the current layer's z came from ;Z: or a deposit
  int layer_ = -1;
  std::optional<bool> pen_down_;  // unset until the file's first pen command
  bool valve_open_ = false;       // valve outputs read (pen_.valve_on_m): the output is on
  int spindle_line_ = 0, spindle_m_ = 0, plunge_line_ = 0;  // milling: M3/M4 S, cut below z 0
  double spindle_s_ = 0.0, plunge_z_ = 0.0;
  // RS274NGC: parameters, O-word blocks (by line index), calls and repeat counters.
  std::unordered_map<int, double> numbered_;
  std::map<std::string, double> named_;
  Scope scope_{*this};
  std::vector<std::string_view> lines_;
  std::unordered_map<std::size_t, OWord> o_words_;
  std::unordered_map<std::size_t, std::size_t> end_, partner_;
  std::unordered_map<std::size_t, std::vector<std::size_t>> branches_;
  std::map<std::string, std::size_t> subs_;
  std::unordered_map<std::size_t, long long> repeats_;
  std::vector<CallFrame> calls_;
  std::size_t loop_line_ = 0;  // the loop or call that repeated lines last (1-based)
  bool stopped_ = false;       // an unsupported construct: the rest is not read
  Feature feature_ = Feature::Infill;
  std::int16_t tool_ = 0;  // pen (;PEN:k) drawing from here on, 0-based
};

}  // namespace

ParsedGcode parse_gcode(std::string_view text, const PenReading& pen) {
  return Reader(text, pen).run();
}

}  // namespace strand::post
