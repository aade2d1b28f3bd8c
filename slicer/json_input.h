// JSON from users (jobs, sweeps, profiles): parsed with bounded nesting, every library
// exception turned into one InputError line, and typed reads that name the key path.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace strand::slicer {

// Deepest nesting of arrays/objects accepted; real files use fewer than ten levels.
inline constexpr int kMaxJsonDepth = 64;

// Parses `text`; `what` names the input in messages ("job = spec.json"). Throws InputError
// for malformed JSON (with the byte offset), numbers out of range, or nesting deeper than
// kMaxJsonDepth.
nlohmann::json parse_json(const std::string& text, const std::string& what);

// Typed reads of an optional key of object `j`; `where` is the key path prefix ("job").
// A present key of the wrong type, or a number that is not finite, throws InputError
// "where.key = value: must be ...".
std::string get_text(const nlohmann::json& j, const std::string& key, const std::string& where,
                     const std::string& fallback);
double get_number(const nlohmann::json& j, const std::string& key, const std::string& where,
                  double fallback);
bool get_bool(const nlohmann::json& j, const std::string& key, const std::string& where,
              bool fallback);

// JSON text for files and stdout; bytes that are not UTF-8 (copied from a G-code comment or a
// command-line argument) are replaced instead of failing the dump.
std::string dump_json(const nlohmann::json& j, int indent = 2);

}  // namespace strand::slicer
