// The RS274NGC half of the G-code reader: O-word blocks matched and run with a program
// counter (bounded repetition), subroutine calls with their local parameters, and lines with
// parameters or [expressions] evaluated before their words are read.
#include <algorithm>

#include "postprocess/inspect/gcode_reader.h"
#include "slicer/input_error.h"

namespace strand::post::gcode {

ParsedGcode Reader::run_indexed() {
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

void Reader::bad(std::size_t index, const std::string& what) const {
  throw InputError("line " + std::to_string(index + 1) + ": " + what + " in '" +
                   std::string(lines_[index].substr(0, 80)) + "'");
}

void Reader::match_blocks() {
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

double Reader::condition(std::size_t index) {
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

std::size_t Reader::o_step(std::size_t pc, const OWord& o) {
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

std::size_t Reader::call(std::size_t pc, const OWord& o) {
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

std::size_t Reader::return_from(std::size_t pc, const OWord& o) {
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

void Reader::unsupported(int n, const std::string& what) {
  if (stopped_) return;
  out_.issues.push_back({n, "unsupported: " + what + " at line " + std::to_string(n) +
                                "; the rest of the file is not read"});
  stopped_ = true;
}

void Reader::ngc_line(std::string_view s, int n) {
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

}  // namespace strand::post::gcode
