// Bounded JSON parsing and typed reads for user files.
#include "slicer/json_input.h"

#include <cmath>

#include "slicer/input_error.h"

namespace strand::slicer {

namespace {

// Depth of the deepest array/object, strings skipped; stops counting past the limit so a
// hostile file costs one linear scan and no recursion.
int nesting_depth(const std::string& text, std::size_t* at) {
  int depth = 0, deepest = 0;
  bool in_string = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\') {
        ++i;
      } else if (c == '"') {
        in_string = false;
      }
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > deepest) deepest = depth, *at = i;
      if (deepest > kMaxJsonDepth) return deepest;
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return deepest;
}

std::string shown(const nlohmann::json& v) {
  const std::string text = v.dump(-1, ' ', true, nlohmann::json::error_handler_t::replace);
  return text.size() > 60 ? text.substr(0, 57) + "..." : text;
}

}  // namespace

nlohmann::json parse_json(const std::string& text, const std::string& what) {
  std::size_t at = 0;
  if (nesting_depth(text, &at) > kMaxJsonDepth) {
    throw InputError(what + ": nested deeper than " + std::to_string(kMaxJsonDepth) +
                     " levels at byte " + std::to_string(at));
  }
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw InputError(what + ": malformed JSON at byte " + std::to_string(e.byte));
  } catch (const nlohmann::json::exception& e) {
    // Numbers beyond double range ("1e999") and the like.
    throw InputError(what + ": unreadable JSON value (" + std::string(e.what()).substr(0, 80) +
                     ")");
  }
}

std::string get_text(const nlohmann::json& j, const std::string& key, const std::string& where,
                     const std::string& fallback) {
  if (!j.contains(key)) return fallback;
  const auto& v = j.at(key);
  if (!v.is_string()) throw InputError(where + "." + key + " = " + shown(v) + ": must be text");
  return v.get<std::string>();
}

double get_number(const nlohmann::json& j, const std::string& key, const std::string& where,
                  double fallback) {
  if (!j.contains(key)) return fallback;
  const auto& v = j.at(key);
  if (!v.is_number() || !std::isfinite(v.get<double>())) {
    throw InputError(where + "." + key + " = " + shown(v) + ": must be a finite number");
  }
  return v.get<double>();
}

bool get_bool(const nlohmann::json& j, const std::string& key, const std::string& where,
              bool fallback) {
  if (!j.contains(key)) return fallback;
  const auto& v = j.at(key);
  if (!v.is_boolean()) throw InputError(where + "." + key + " = " + shown(v) + ": must be true or false");
  return v.get<bool>();
}

std::string dump_json(const nlohmann::json& j, int indent) {
  return j.dump(indent, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace strand::slicer
