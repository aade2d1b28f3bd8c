// Reading SVG text: inherited font properties, white-space rules and the x/y/dx/dy lists
// that place each addressable character (SVG 1.1, 10.4-10.5 and 10.15).
#include "slicer/svg_text.h"

#include <fontconfig/fontconfig.h>

#include <algorithm>
#include <cctype>
#include <pugixml.hpp>

#include "slicer/input_error.h"
#include "slicer/svg_syntax.h"
#include "slicer/svg_text_reader.h"

namespace strand::slicer {

namespace {

// CSS absolute-size keywords in px (CSS 2.1 suggested table at medium = 16 px).
const std::map<std::string, double> kSizeKeywords = {
    {"xx-small", 9}, {"x-small", 10}, {"small", 13},   {"medium", 16},
    {"large", 18},   {"x-large", 24}, {"xx-large", 32}};

// A font-size value in px: keywords, relative keywords, % and em of the parent's size, ex of
// half of it, absolute lengths. Throws InputError for anything else.
double font_size_px(const std::string& text, double parent_px) {
  if (kSizeKeywords.count(text)) return kSizeKeywords.at(text);
  if (text == "smaller") return parent_px / 1.2;
  if (text == "larger") return parent_px * 1.2;
  LengthBasis basis;
  basis.font_size_px = parent_px;
  basis.viewport = Vec2(parent_px, parent_px);  // a percentage is of the parent's size
  return resolve_length_px(text, LengthAxis::X, basis, "font-size");
}

// "3q" cut short and with control characters replaced (notes reach G-code comments).
std::string quoted(const std::string& v) {
  std::string out = v.substr(0, 24);
  for (char& ch : out) {
    if (static_cast<unsigned char>(ch) < 0x20 || static_cast<unsigned char>(ch) > 0x7e) ch = '?';
  }
  return "\"" + out + (v.size() > 24 ? "...\"" : "\"");
}

// One raw character and the innermost element it came from.
struct RawChar {
  char32_t code;
  int owner;
};

struct Element {
  pugi::xml_node node;
  TextStyle style;
  std::size_t begin = 0, end = 0;  // range of its characters (raw indices, then kept ones)
  int path = -1;                   // the <textPath> it is or lies in (index in text_paths)
};

bool is_text_path(const pugi::xml_node& n) {
  const std::string_view name = n.name();
  const auto colon = name.find(':');
  return (colon == std::string_view::npos ? name : name.substr(colon + 1)) == "textPath";
}

struct Reader {
  const PropertyReader& properties;
  std::string origin;
  std::size_t max_chars = 0;
  Vec2 viewport = Vec2::Zero();
  std::vector<std::string>& notes;
  std::vector<pugi::xml_node>& text_paths;
  std::vector<RawChar> raw;
  std::vector<Element> elements;  // pre-order

  void walk(const pugi::xml_node& n, TextStyle style, int path) {
    const auto props = properties(n);
    if (props.count("display") && props.at("display") == "none") return;
    std::vector<std::string> root_notes;  // the <text> element's own were noted as it was entered
    inherit_text_style(props, style, viewport, elements.empty() ? root_notes : notes, true,
                       !elements.empty());
    const bool new_path = path < 0 && !elements.empty() && is_text_path(n);
    if (new_path) {
      path = static_cast<int>(text_paths.size());
      text_paths.push_back(n);
    }
    const int id = static_cast<int>(elements.size());
    elements.push_back({n, style, raw.size(), raw.size(), path});
    for (const auto& child : n.children()) {
      if (child.type() == pugi::node_pcdata || child.type() == pugi::node_cdata) {
        append(child.value(), id);
      } else if (child.type() == pugi::node_element) {
        walk(child, style, path);
      }
    }
    elements[id].end = raw.size();
  }

  // UTF-8 as utf8_to_u32 reads it, refused as soon as the text passes max_chars.
  void append(const char* text, int owner) {
    const std::string_view bytes(text);
    const auto* data = reinterpret_cast<const FcChar8*>(bytes.data());
    for (std::size_t i = 0; i < bytes.size();) {
      if (raw.size() >= max_chars) {
        throw InputError(origin + ": the drawing's text has more than " +
                         std::to_string(max_chars) + " characters");
      }
      FcChar32 c = 0;
      const int used =
          FcUtf8ToUcs4(data + i, &c, static_cast<int>(std::min<std::size_t>(bytes.size() - i, 8)));
      raw.push_back({used > 0 ? static_cast<char32_t>(c) : U'\uFFFD', owner});
      i += used > 0 ? static_cast<std::size_t>(used) : 1;
    }
  }
};

bool is_space(char32_t c) { return c == U' ' || c == U'\t' || c == U'\n' || c == U'\r'; }

// SVG 2 / CSS white-space: newlines and tabs are spaces; without xml:space="preserve"
// runs of spaces collapse to one and leading and trailing spaces go. Returns the raw index
// of each kept character.
std::vector<std::size_t> kept_characters(const std::vector<RawChar>& raw, bool preserve) {
  std::vector<std::size_t> kept;
  for (std::size_t i = 0; i < raw.size(); ++i) {
    if (!preserve && is_space(raw[i].code) && (kept.empty() || is_space(raw[kept.back()].code)))
      continue;
    kept.push_back(i);
  }
  if (!preserve) {
    while (!kept.empty() && is_space(raw[kept.back()].code)) kept.pop_back();
  }
  return kept;
}

// x, y, dx, dy: lengths with units, separated by commas or spaces; em of the element's own
// font-size, % of the viewport's width (x, dx) or height (y, dy).
std::vector<double> list_attribute(const pugi::xml_node& n, const char* name,
                                   const TextStyle& style, const Vec2& viewport,
                                   const std::string& origin) {
  std::vector<double> out;
  const auto a = n.attribute(name);
  if (!a) return out;
  const LengthAxis axis = name[0] == 'x' || name[1] == 'x' ? LengthAxis::X : LengthAxis::Y;
  const LengthBasis basis{style.font_size, viewport};
  std::string item;
  const std::string text = std::string(a.value()) + " ";
  for (char ch : text) {
    if (ch == ',' || std::isspace(static_cast<unsigned char>(ch))) {
      if (!item.empty())
        out.push_back(
            resolve_length_px(item, axis, basis, origin + ": <" + n.name() + "> " + name));
      item.clear();
    } else {
      item += ch;
    }
  }
  return out;
}

// A spacing value: normal (0) or a length (em of the element's font-size).
double spacing_px(const std::string& v, const TextStyle& style, const Vec2& viewport) {
  if (v == "normal") return 0.0;
  return resolve_length_px(v, LengthAxis::X, LengthBasis{style.font_size, viewport}, "spacing");
}

}  // namespace

void inherit_text_style(const std::map<std::string, std::string>& props, TextStyle& style,
                        const Vec2& viewport, std::vector<std::string>& notes, bool text_content,
                        bool tspan) {
  const auto get = [&](const char* key) -> const std::string* {
    const auto p = props.find(key);
    return p == props.end() || p->second == "inherit" ? nullptr : &p->second;
  };
  // a value in error is left out (CSS: an invalid declaration is ignored), with a note
  const auto apply = [&](const char* key, auto set) {
    const std::string* v = get(key);
    if (v == nullptr) return;
    try {
      set(*v);
    } catch (const InputError&) {
      notes.push_back(std::string(key) + " = " + quoted(*v));
    }
  };
  const TextStyle parent = style;
  apply("font-size",
        [&](const std::string& v) { style.font_size = font_size_px(v, parent.font_size); });
  if (const auto* v = get("font-family")) style.font_family = *v;
  if (const auto* v = get("font-weight")) style.font_weight = *v;
  if (const auto* v = get("font-style")) style.font_style = *v;
  if (const auto* a = get("text-anchor")) {
    style.anchor = *a == "middle" ? TextAnchor::Middle
                   : *a == "end"  ? TextAnchor::End
                                  : TextAnchor::Start;
  }
  if (const auto* v = get("xml:space")) style.preserve_space = *v == "preserve";
  apply("letter-spacing",
        [&](const std::string& v) { style.letter_spacing = spacing_px(v, style, viewport); });
  apply("word-spacing",
        [&](const std::string& v) { style.word_spacing = spacing_px(v, style, viewport); });
  if (!text_content) return;
  apply("text-decoration", [&](const std::string& v) {
    unsigned flags = 0;  // decorations add to the ancestors' (a child cannot remove them)
    std::size_t b = 0;
    while (b < v.size()) {
      const std::size_t e = std::min(v.find(' ', b), v.size());
      const std::string word = v.substr(b, e - b);
      if (word == "underline")
        flags |= kUnderline;
      else if (word == "overline")
        flags |= kOverline;
      else if (word == "line-through")
        flags |= kLineThrough;
      else if (word != "none" && word != "blink" && !word.empty())
        throw InputError("text-decoration");
      b = e + 1;
    }
    style.decoration |= flags;
  });
  if (!tspan) return;
  apply("baseline-shift", [&](const std::string& v) {
    // sub and super as browsers place them for a font without metrics; % of the line height
    // (the font-size here), lengths in em of the element's own font-size
    double shift = 0.0;
    if (v == "sub")
      shift = -0.2 * style.font_size;
    else if (v == "super")
      shift = 0.4 * style.font_size;
    else if (v != "baseline")
      shift = resolve_length_px(v, LengthAxis::X,
                                LengthBasis{style.font_size, Vec2(style.font_size, 0.0)},
                                "baseline-shift");
    style.baseline_shift = parent.baseline_shift + shift;
  });
}

std::vector<TextChar> read_text_chars(const pugi::xml_node& text, const TextStyle& inherited,
                                      const PropertyReader& properties, const Vec2& viewport,
                                      std::vector<std::string>& notes, const std::string& origin,
                                      std::size_t max_chars,
                                      std::vector<pugi::xml_node>& text_paths) {
  std::vector<pugi::xml_node> paths;  // every textPath read, those without characters too
  Reader r{properties, origin, max_chars, viewport, notes, paths, {}, {}};
  r.walk(text, inherited, -1);
  if (r.elements.empty()) return {};
  const std::vector<std::size_t> kept = kept_characters(r.raw, r.elements[0].style.preserve_space);
  std::vector<TextChar> out;
  std::vector<int> renumbered(paths.size(), -1);  // textPaths that keep a character, in order
  for (std::size_t k : kept) {
    TextChar c;
    c.code = is_space(r.raw[k].code) ? U' ' : r.raw[k].code;
    const Element& owner = r.elements[r.raw[k].owner];
    c.style = owner.style;
    if (owner.path >= 0) {
      if (renumbered[owner.path] < 0) {
        renumbered[owner.path] = static_cast<int>(text_paths.size());
        text_paths.push_back(paths[owner.path]);
      }
      c.path = renumbered[owner.path];
    }
    out.push_back(c);
  }
  // Lists of outer elements first; inner elements override them for their own characters.
  // Absolute positions from outside a textPath do not reach the characters on it.
  for (const auto& e : r.elements) {
    const auto first = std::lower_bound(kept.begin(), kept.end(), e.begin) - kept.begin();
    const auto last = std::lower_bound(kept.begin(), kept.end(), e.end) - kept.begin();
    const auto apply = [&](const char* name, auto set) {
      const auto values = list_attribute(e.node, name, e.style, viewport, origin);
      for (std::size_t i = 0; i < values.size() && first + static_cast<long>(i) < last; ++i)
        set(out[first + i], values[i]);
    };
    const bool outside = e.path < 0;
    apply("x", [outside](TextChar& c, double v) {
      if (!outside || c.path < 0) c.x = v;
    });
    apply("y", [outside](TextChar& c, double v) {
      if (!outside || c.path < 0) c.y = v;
    });
    apply("dx", [](TextChar& c, double v) { c.dx = v; });
    apply("dy", [](TextChar& c, double v) { c.dy = v; });
  }
  return out;
}

std::u32string utf8_to_u32(const std::string& text) {
  std::u32string out;
  const auto* bytes = reinterpret_cast<const FcChar8*>(text.data());
  for (std::size_t i = 0; i < text.size();) {
    FcChar32 c = 0;
    const int used = FcUtf8ToUcs4(bytes + i, &c, static_cast<int>(text.size() - i));
    out.push_back(used > 0 ? static_cast<char32_t>(c) : U'\uFFFD');
    i += used > 0 ? static_cast<std::size_t>(used) : 1;
  }
  return out;
}

std::string u32_to_utf8(const std::u32string& text) {
  std::string out;
  for (char32_t c : text) {
    FcChar8 buf[FC_UTF8_MAX_LEN];
    const int n = FcUcs4ToUtf8(static_cast<FcChar32>(c), buf);
    out.append(reinterpret_cast<const char*>(buf), static_cast<std::size_t>(n));
  }
  return out;
}

}  // namespace strand::slicer
