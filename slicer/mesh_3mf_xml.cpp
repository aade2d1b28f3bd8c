// The XML tokenizer that follows lib3mf's reader, one character at a time (see mesh_3mf_xml.h).
#include "slicer/mesh_3mf_xml.h"

#include <stdexcept>

namespace strand::slicer {

namespace {

bool space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }
bool kept(const std::string& local, const std::string& prefix) {
  return local == "id" || local == "objectid" || local == "path" || local == "Type" ||
         local == "Target" || local == "requiredextensions" || local == "xmlns" ||
         prefix == "xmlns";
}
// "p:name" -> "name" and "p"; false for two colons (lib3mf refuses them).
bool local_name(const std::string& qualified, std::string& local, bool& prefixed,
                std::string& prefix) {
  const auto colon = qualified.find(':');
  if (colon != std::string::npos && qualified.find(':', colon + 1) != std::string::npos)
    return false;
  prefixed = colon != std::string::npos;
  local = prefixed ? qualified.substr(colon + 1) : qualified;
  prefix = prefixed ? qualified.substr(0, colon) : std::string();
  return true;
}

}  // namespace

void XmlTokens::append(std::string& s, char c, std::size_t cap) {
  if (c == '\0') state_ = State::Broken;  // lib3mf: a name may not hold a zero byte
  if (s.size() < cap)
    s.push_back(c);
  else
    long_ = true;
}

void XmlTokens::begin_element() {
  std::string local, prefix;
  bool prefixed = false;
  if (!local_name(name_, local, prefixed, prefix)) {
    state_ = State::Broken;
    return;
  }
  if (root_name_end_ == static_cast<std::size_t>(-1)) root_name_end_ = offset_;
  element_ = long_ ? std::string() : local;
  element_prefix_ = long_ ? std::string() : prefix;
  attrs_.clear();
}

void XmlTokens::finish_attr() {
  std::string local, prefix;
  bool prefixed = false;
  if (!local_name(attr_name_, local, prefixed, prefix)) {
    state_ = State::Broken;
    return;
  }
  if (in_pi_) return;
  const bool keep = kept(local, prefix);
  if (keep || prefixed) {
    if (attrs_.size() >= kMaxKeptAttrs) throw std::length_error("attributes");
    attrs_.push_back({prefixed, local,
                      !keep ? std::string() : value_long_ ? std::string(1, '\x01') : value_,
                      prefix});
  }
}

void XmlTokens::finish_start(bool self_closing) {
  if (!in_pi_) sink_.start(element_, element_prefix_, attrs_, self_closing);
  in_pi_ = false;
  state_ = State::Text;
}

void XmlTokens::step(char c) {
  switch (state_) {
    case State::Text:
      if (c == '<') {
        name_.clear();
        long_ = false;
        state_ = State::Name;
      }
      return;
    case State::Name:
      if (space(c)) {
        if (name_.empty()) {
          state_ = State::Broken;
          return;
        }
        begin_element();
        if (state_ != State::Broken) state_ = State::Attrs;
      } else if (c == '?') {
        state_ = name_.empty() ? State::PiName : State::Broken;
      } else if (c == '>') {
        begin_element();
        if (state_ != State::Broken) finish_start(false);
      } else if (c == '/') {
        if (name_.empty()) {
          ends_ = 0;
          state_ = State::EndName;
        } else {
          begin_element();
          if (state_ != State::Broken) state_ = State::CloseElement;
        }
      } else {
        append(name_, c, kMaxName);
        if (name_ == "!--") {
          comment_ = 0;
          state_ = State::Comment;
        }
      }
      return;
    case State::Comment: {  // ends at the first "-->", as lib3mf's parseComment
      static constexpr char kEnd[3] = {'-', '-', '>'};
      if (c == kEnd[comment_]) {
        if (comment_ == 2)
          state_ = State::Text;
        else
          ++comment_;
      } else if (c != '-') {
        comment_ = 0;
      }
      return;
    }
    case State::PiName:
      if (space(c)) {
        if (name_.empty())
          state_ = State::Broken;
        else
          in_pi_ = true, attrs_.clear(), state_ = State::Attrs;
      } else if (c == '/') {
        state_ = State::Broken;
      } else if (c == '?') {
        state_ = name_.empty() ? State::Broken : State::ClosePi;
      } else {
        append(name_, c, kMaxName);
      }
      return;
    case State::EndName:
      if (c == '/' || c == '?' || (c == '>' && ends_ == 0)) {
        state_ = State::Broken;
      } else if (c == '>') {
        sink_.end();
        state_ = State::Text;
      } else {
        ++ends_;
      }
      return;
    case State::Attrs:
      if (space(c)) return;
      if (c == '>') {
        // A processing instruction closed by '>' or '/>' alone leaves lib3mf's reader in
        // a state this tokenizer does not model: refused.
        if (in_pi_)
          state_ = State::Broken;
        else
          finish_start(false);
      } else if (c == '/') {
        state_ = in_pi_ ? State::Broken : State::CloseElement;
      } else if (c == '?') {
        state_ = in_pi_ ? State::ClosePi : State::Broken;
      } else if (c == '"' || c == '\'') {
        state_ = State::Broken;
      } else {
        attr_name_.clear();
        long_ = false;
        if (c == '=') {
          value_spaced_ = false;
          state_ = State::ValueStart;
        } else {
          append(attr_name_, c, kMaxName);
          state_ = State::AttrName;
        }
      }
      return;
    case State::AttrName:
      if (space(c)) {
        state_ = State::AttrNameSpaced;
      } else if (c == '"' || c == '\'') {
        state_ = State::Broken;
      } else if (c == '=') {
        value_spaced_ = false;
        state_ = State::ValueStart;
      } else {
        append(attr_name_, c, kMaxName);
      }
      return;
    case State::AttrNameSpaced:
      if (space(c)) return;
      if (c == '=') {
        value_spaced_ = false;
        state_ = State::ValueStart;
      } else {
        state_ = State::Broken;
      }
      return;
    case State::ValueStart:
      if (space(c)) {
        value_spaced_ = true;
      } else if (c == '"' || c == '\'') {
        quote_ = c;
        value_.clear();
        value_long_ = false;
        state_ = State::Value;
      } else if (value_spaced_) {
        state_ = State::Broken;
      }
      return;
    case State::Value:
      if (c == quote_) {
        finish_attr();
        if (state_ != State::Broken) state_ = State::Attrs;
      } else if (value_.size() < kMaxValue) {
        value_.push_back(c);
      } else {
        value_long_ = true;
      }
      return;
    case State::CloseElement:
      if (c == '>')
        finish_start(true);
      else
        state_ = State::Broken;
      return;
    case State::ClosePi:
      if (c == '>')
        in_pi_ = false, state_ = State::Text;
      else
        state_ = State::Broken;
      return;
    case State::Broken:
      return;
  }
}

}  // namespace strand::slicer
