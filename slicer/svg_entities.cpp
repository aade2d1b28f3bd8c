// Expanding internal-subset entities: a small scanner over the prolog (the DOCTYPE and its
// internal subset) and over the body's markup (tags, quoted attribute values, comments, CDATA
// sections, processing instructions), charging the expansion budget before each append.
#include "slicer/svg_entities.h"

#include <algorithm>
#include <cctype>
#include <map>
#include <vector>

#include "slicer/input_error.h"

namespace strand::slicer {

namespace {

constexpr std::size_t npos = std::string_view::npos;

struct Entity {
  std::string_view name;
  std::string_view value;  // replacement text as declared, references inside unexpanded
  bool external = false;   // SYSTEM or PUBLIC: never loaded (no file or network access)
};

// An entity's expansion in one context, kept for its later references.
struct Expansion {
  std::string text;
  std::size_t cost = 0;  // budget the expansion charged (bytes plus nested references)
  int external = 0;      // external references inside it
  int height = 1;        // reference levels it spans, itself included
};
using EntityMap = std::map<std::string_view, Entity, std::less<>>;

bool name_start(unsigned char c) { return std::isalpha(c) || c == '_' || c == ':' || c >= 0x80; }
bool name_char(unsigned char c) { return name_start(c) || std::isdigit(c) || c == '-' || c == '.'; }

// Length of the XML Name starting at s[i] (0 when none starts there).
std::size_t name_length(std::string_view s, std::size_t i) {
  if (i >= s.size() || !name_start(static_cast<unsigned char>(s[i]))) return 0;
  std::size_t j = i + 1;
  while (j < s.size() && name_char(static_cast<unsigned char>(s[j]))) ++j;
  return j - i;
}

std::size_t skip_space(std::string_view s, std::size_t i) {
  while (i < s.size() && std::isspace(static_cast<unsigned char>(s[i]))) ++i;
  return i;
}

bool at(std::string_view s, std::size_t i, std::string_view what) {
  return s.substr(std::min(i, s.size()), what.size()) == what;
}

// Index just past the first `end` at or after i; npos when there is none.
std::size_t past(std::string_view s, std::size_t i, std::string_view end) {
  const std::size_t found = s.find(end, i);
  return found == npos ? npos : found + end.size();
}

// Index past the '>' closing the markup declaration at i, quoted literals skipped.
std::size_t past_declaration(std::string_view s, std::size_t i) {
  char quote = 0;
  for (; i < s.size(); ++i) {
    if (quote != 0) {
      if (s[i] == quote) quote = 0;
    } else if (s[i] == '"' || s[i] == '\'') {
      quote = s[i];
    } else if (s[i] == '>') {
      return i + 1;
    }
  }
  return npos;
}

// `<!ENTITY name "value">` at i into `entities` (the first declaration of a name binds, as
// XML says); parameter entities (`<!ENTITY % name ...>`) are not used by SVG and skipped.
std::size_t read_entity(std::string_view s, std::size_t i, EntityMap& entities) {
  const std::size_t end = past_declaration(s, i);
  std::size_t j = skip_space(s, i + 8);
  const std::size_t n = name_length(s, j);
  if (end == npos || n == 0) return end;
  const std::string_view name = s.substr(j, n);
  j = skip_space(s, j + n);
  if (s[j] == '"' || s[j] == '\'') {
    const std::size_t close = s.find(s[j], j + 1);
    if (close < end) entities.emplace(name, Entity{name, s.substr(j + 1, close - j - 1), false});
  } else if (at(s, j, "SYSTEM") || at(s, j, "PUBLIC")) {
    entities.emplace(name, Entity{name, {}, true});
  }
  return end;
}

// The internal subset starting after '[' at i: its entities, and the index past the
// DOCTYPE's closing '>' (npos when the subset is malformed: pugixml then reports it).
std::size_t read_internal_subset(std::string_view s, std::size_t i, EntityMap& entities) {
  while (i != npos && i < s.size()) {
    i = skip_space(s, i);
    if (at(s, i, "]")) {
      i = skip_space(s, i + 1);
      return at(s, i, ">") ? i + 1 : npos;
    }
    if (at(s, i, "<!ENTITY")) {
      i = read_entity(s, i, entities);
    } else if (at(s, i, "<!--")) {
      i = past(s, i, "-->");
    } else if (at(s, i, "<?")) {
      i = past(s, i, "?>");
    } else if (at(s, i, "<!")) {
      i = past_declaration(s, i);
    } else if (at(s, i, "%")) {
      i = past(s, i, ";");
    } else {
      return npos;
    }
  }
  return npos;
}

// Where the body starts (past the DOCTYPE) with the subset's entities; npos when the
// document has no DOCTYPE with an internal subset before its root element.
std::size_t read_prolog(std::string_view s, EntityMap& entities) {
  std::size_t i = at(s, 0, "\xEF\xBB\xBF") ? 3 : 0;
  for (;;) {
    i = skip_space(s, i);
    if (at(s, i, "<?")) {
      i = past(s, i, "?>");
    } else if (at(s, i, "<!--")) {
      i = past(s, i, "-->");
    } else {
      break;
    }
    if (i == npos) return npos;
  }
  if (!at(s, i, "<!DOCTYPE")) return npos;
  char quote = 0;
  for (i += 9; i < s.size(); ++i) {  // the root name and external id, up to '[' or '>'
    if (quote != 0) {
      if (s[i] == quote) quote = 0;
    } else if (s[i] == '"' || s[i] == '\'') {
      quote = s[i];
    } else if (s[i] == '>') {
      return npos;
    } else if (s[i] == '[') {
      return read_internal_subset(s, i + 1, entities);
    }
  }
  return npos;
}

class Expander {
 public:
  Expander(const EntityMap& entities, const std::string& origin, std::size_t size)
      : entities_(entities), origin_(origin) {
    out_.text.reserve(size);
  }

  // Text with references expanded; in an attribute value (attr) the replacement text's
  // quotes and '<' are escaped so it stays one value.
  void expand(std::string_view t, bool attr, int depth) {
    std::size_t i = 0;
    while (i < t.size()) {
      const std::size_t amp = t.find('&', i);
      append(t.substr(i, amp == npos ? npos : amp - i), attr, depth);
      if (amp == npos) return;
      const std::size_t n = name_length(t, amp + 1);
      const std::string_view name = t.substr(amp + 1, n);
      const auto found = entities_.find(name);
      if (n == 0 || !at(t, amp + 1 + n, ";") || found == entities_.end()) {
        append("&", false, depth);  // a character reference, a predefined or unknown entity
        i = amp + 1;
        continue;
      }
      reference(found->first, found->second, attr, depth);
      i = amp + n + 2;
    }
  }

  // Copies the body from `from`: markup as it is, references in text and attribute values
  // expanded.
  ExpandedEntities run(std::string_view s, std::size_t from) {
    out_.text.append(s.substr(0, from));
    std::size_t i = from;
    while (i < s.size()) {
      const std::size_t lt = s.find('<', i);
      expand(s.substr(i, lt == npos ? npos : lt - i), false, 0);
      if (lt == npos) break;
      i = copy_markup(s, lt);
    }
    return std::move(out_);
  }

 private:
  void charge(std::size_t n) {
    used_ += n;
    if (used_ > kMaxEntityExpansion) {
      throw InputError(origin_ + ": DTD entities expand to more than " +
                       std::to_string(kMaxEntityExpansion >> 20) + " MiB (at &" +
                       std::string(stack_.empty() ? "" : stack_.front()) + ";)");
    }
  }

  void append(std::string_view t, bool attr, int depth) {
    if (depth > 0) charge(t.size());
    if (!attr || depth == 0) {
      sink_->append(t);
      return;
    }
    for (const char c : t) {
      if (c == '"' || c == '\'' || c == '<') {
        const std::string_view esc = c == '"' ? "&quot;" : c == '\'' ? "&apos;" : "&lt;";
        charge(esc.size());
        sink_->append(esc);
      } else {
        sink_->push_back(c);
      }
    }
  }

  void reference(std::string_view name, const Entity& e, bool attr, int depth) {
    const auto said = [&](const std::string& what) {
      return InputError(origin_ + ": DTD entity &" + std::string(name) + "; " + what);
    };
    const auto memo = memo_.find({name, attr});
    const int height = memo == memo_.end() ? 1 : memo->second.height;
    if (depth + height > kMaxEntityDepth) {
      throw said("nests references deeper than " + std::to_string(kMaxEntityDepth) + " levels");
    }
    for (const std::string_view open : stack_) {
      if (open == name) throw said("refers to itself");
    }
    charge(1);
    if (depth == 0) ++out_.references;
    deepest_ = std::max(deepest_, depth);
    if (e.external) {
      ++out_.external;
    } else if (memo != memo_.end()) {  // the same work again, charged as if redone
      charge(memo->second.cost);
      sink_->append(memo->second.text);
      out_.external += memo->second.external;
      deepest_ = std::max(deepest_, depth + height - 1);
    } else {
      memo_.emplace(std::pair{name, attr}, first_expansion(e, attr, depth));
    }
  }

  // Expands `e` into the output once, recording what a later reference repeats.
  Expansion first_expansion(const Entity& e, bool attr, int depth) {
    Expansion x;
    std::string* const outer = sink_;
    const std::size_t used = used_;
    const int external = out_.external, deepest = deepest_;
    sink_ = &x.text;
    deepest_ = depth;
    stack_.push_back(e.name);
    expand(e.value, attr, depth + 1);
    stack_.pop_back();
    sink_ = outer;
    x.cost = used_ - used;
    x.external = out_.external - external;
    x.height = deepest_ - depth + 1;
    deepest_ = std::max(deepest, deepest_);
    sink_->append(x.text);
    return x;
  }

  // The markup at s[i] == '<' copied (a tag's attribute values expanded); returns where
  // the text after it starts.
  std::size_t copy_markup(std::string_view s, std::size_t i) {
    std::size_t end = npos;
    if (at(s, i, "<!--")) {
      end = past(s, i, "-->");
    } else if (at(s, i, "<![CDATA[")) {
      end = past(s, i, "]]>");
    } else if (at(s, i, "<?")) {
      end = past(s, i, "?>");
    } else if (at(s, i, "<!")) {
      end = past_declaration(s, i);
    } else {
      return copy_tag(s, i);
    }
    end = std::min(end, s.size());
    out_.text.append(s.substr(i, end - i));
    return end;
  }

  std::size_t copy_tag(std::string_view s, std::size_t i) {
    while (i < s.size()) {
      const char c = s[i];
      if (c == '"' || c == '\'') {
        const std::size_t close = std::min(s.find(c, i + 1), s.size());
        out_.text.push_back(c);
        expand(s.substr(i + 1, close - i - 1), true, 0);
        if (close < s.size()) out_.text.push_back(c);
        i = close + 1;
        continue;
      }
      out_.text.push_back(c);
      ++i;
      if (c == '>') break;
    }
    return i;
  }

  const EntityMap& entities_;
  const std::string& origin_;
  ExpandedEntities out_;
  std::string* sink_ = &out_.text;  // where expanded text goes (an entity's memo at first)
  std::size_t used_ = 0;
  std::vector<std::string_view> stack_;  // entities being expanded, outermost first
  int deepest_ = 0;                      // deepest reference level reached so far
  // Each entity is expanded once per context (content, attribute value): billion laughs
  // then cost copies of what was built, not a walk per reference.
  std::map<std::pair<std::string_view, bool>, Expansion> memo_;
};

}  // namespace

std::optional<ExpandedEntities> expand_entities(std::string_view text, const std::string& origin) {
  EntityMap entities;
  const std::size_t body = read_prolog(text, entities);
  if (body == npos || entities.empty()) return std::nullopt;
  return Expander(entities, origin, text.size()).run(text, body);
}

}  // namespace strand::slicer
