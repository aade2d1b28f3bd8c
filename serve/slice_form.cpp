// POST /api/slice's form: fields checked as `strand slice` checks its flags, on the HTTP
// thread (a bad one is a 400 naming it), and the upload told apart by its content. The
// client's file name names nothing: the mesh is kept as part.EXT in the job's directory,
// and a mesh that would make a reader open another file is refused before it is written.
#include <algorithm>
#include <cctype>
#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <string_view>

#include "patterns/registry.h"
#include "serve/api_state.h"
#include "serve/slice_api.h"
#include "slicer/input_error.h"
#include "slicer/params.h"
#include "slicer/unit_values.h"

namespace strand::serve {

using nlohmann::json;

namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

std::uint32_t le32(const std::string& b, std::size_t at) {
  std::uint32_t v = 0;
  for (int i = 3; i >= 0; --i) v = (v << 8) | static_cast<unsigned char>(b[at + static_cast<std::size_t>(i)]);
  return v;
}

// The first line that is not blank, trimmed.
std::string_view first_line(std::string_view text) {
  while (!text.empty()) {
    const std::size_t end = text.find('\n');
    const std::string_view line = trim(text.substr(0, end));
    if (!line.empty()) return line;
    if (end == std::string_view::npos) break;
    text.remove_prefix(end + 1);
  }
  return {};
}

bool has_line_starting(std::string_view text, std::string_view word) {
  for (std::size_t at = 0; at < text.size();) {
    const std::size_t end = std::min(text.find('\n', at), text.size());
    if (trim(text.substr(at, end - at)).starts_with(word)) return true;
    at = end + 1;
  }
  return false;
}

// glTF names buffers and images by URI; only data: URIs keep a reader inside the upload.
void check_gltf_uris(const json& g, const std::string& field) {
  for (const char* list : {"buffers", "images"}) {
    if (!g.contains(list) || !g.at(list).is_array()) continue;
    for (const json& item : g.at(list)) {
      if (!item.is_object() || !item.contains("uri") || !item.at("uri").is_string()) continue;
      const std::string uri = item.at("uri").get<std::string>();
      if (uri.rfind("data:", 0) == 0) continue;
      throw InputError(field + ": a glTF upload must hold its buffers and images (data: URIs, or a GLB); it names '" +
                       uri.substr(0, 80) + "'");
    }
  }
}

// An OBJ's material library is read from the OBJ's directory: a plain name stays in the
// job's own directory, a path could reach any file (or a device that never ends).
void check_obj_materials(std::string_view text, const std::string& field) {
  for (std::size_t at = 0; at < text.size();) {
    const std::size_t end = std::min(text.find('\n', at), text.size());
    const std::string_view line = trim(text.substr(at, end - at));
    at = end + 1;
    if (!line.starts_with("mtllib")) continue;
    const std::string_view lib = trim(line.substr(6));
    if (lib.find_first_of("/\\") != std::string_view::npos || lib.find("..") != std::string_view::npos) {
      throw InputError(field + ": an OBJ upload may name its material library by a plain file name only, not '" +
                       std::string(lib.substr(0, 80)) + "'");
    }
  }
}

}  // namespace

void check_mesh_references(const std::string& bytes, const std::string& ext, const std::string& field) {
  if (ext == ".gltf") {
    const json g = json::parse(bytes, nullptr, false);
    if (!g.is_object()) throw InputError(field + ": cannot read it as glTF (its JSON does not parse)");
    check_gltf_uris(g, field);
  } else if (ext == ".glb") {
    // header (magic, version, length), then the JSON chunk: length, type "JSON", data
    const bool json_chunk = bytes.size() >= 20 && bytes.compare(16, 4, "JSON") == 0 &&
                            le32(bytes, 12) <= bytes.size() - 20;
    const json g = json_chunk ? json::parse(bytes.substr(20, le32(bytes, 12)), nullptr, false) : json();
    if (!g.is_object()) throw InputError(field + ": cannot read it as GLB (no JSON chunk that parses)");
    check_gltf_uris(g, field);
  } else if (ext == ".obj") {
    check_obj_materials(bytes, field);
  }
}

namespace {

bool switch_value(const std::string& key, const std::string& v) {
  if (v == "1" || v == "true" || v == "on" || v == "yes") return true;
  if (v == "0" || v == "false" || v == "off" || v == "no" || v.empty()) return false;
  throw InputError("slice." + key + " = " + v.substr(0, 40) + ": must be true or false");
}

int whole_number(const std::string& key, const std::string& v) {
  std::size_t used = 0;
  int n = 0;
  try {
    n = std::stoi(v, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != v.size()) throw InputError("slice." + key + " = " + v.substr(0, 40) + ": must be a whole number");
  return n;
}

double number(const std::string& key, const std::string& v) {
  std::size_t used = 0;
  double x = 0.0;
  try {
    x = std::stod(v, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != v.size()) throw InputError("slice." + key + " = " + v.substr(0, 40) + ": must be a number");
  return x;
}

std::string choice(const std::string& text, const std::vector<std::string>& choices) {
  return slicer::match_choice(text, choices).value_or(text);
}

// The name shown in the gallery when the form gives none: the client's file name without
// its folders (it is never a path here), else "sliced part".
std::string shown_name(const std::string& filename) {
  const std::size_t slash = filename.find_last_of("/\\");
  std::string name = slash == std::string::npos ? filename : filename.substr(slash + 1);
  name.erase(std::remove_if(name.begin(), name.end(), [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; }),
             name.end());
  if (name.size() > kMaxNameBytes) name.resize(kMaxNameBytes);
  return name.empty() ? "sliced part" : name;
}

// The pattern flags given, checked against the chosen generator's table as the CLI checks them.
json pattern_values(const std::string& pattern, const std::map<std::string, std::string>& given) {
  const patterns::GeneratorSpec* g = patterns::find_generator(pattern);
  json values = json::object();
  if (!g) return values;  // produce_slice names the allowed patterns
  std::vector<std::string> problems;
  for (const auto& [key, text] : given) {
    const auto& defs = g->table().defs;
    const auto it = std::find_if(defs.begin(), defs.end(), [&key = key](const auto& d) { return d.key == key; });
    if (it == defs.end()) {
      problems.push_back("slice." + key + ": not a " + g->name + " flag (see strand " + g->name + " --help)");
      continue;
    }
    values[key] = slicer::parse_param_text(g->table(), *it, text);
  }
  if (!problems.empty()) throw InputError(problems);
  return values;
}

bool is_pattern_flag(const std::string& key) {
  for (const auto& g : patterns::generators()) {
    for (const auto& d : g.table().defs) {
      if (d.key == key) return true;
    }
  }
  return false;
}

}  // namespace

std::string mesh_extension(const std::string& bytes) {
  if (bytes.size() >= 84 && 84 + 50 * static_cast<std::uint64_t>(le32(bytes, 80)) == bytes.size()) return ".stl";
  if (bytes.rfind("glTF", 0) == 0) return ".glb";
  if (bytes.rfind("PK\x03\x04", 0) == 0) return ".3mf";
  const std::string_view head(bytes.data(), std::min<std::size_t>(bytes.size(), 1 << 16));
  if (head.starts_with("ply\n") || head.starts_with("ply\r\n")) return ".ply";  // ASCII or binary
  if (head.find('\0') != std::string_view::npos) return "";  // binary, none of the above
  const std::string_view first = first_line(head);
  if (first.starts_with("solid")) return ".stl";
  if (first == "ply") return ".ply";
  if (first.size() >= 3 && first.size() <= 9 && first.ends_with("OFF") &&
      first.substr(0, first.size() - 3).find_first_not_of("STCN4n") == std::string_view::npos) {
    return ".off";
  }
  if (!first.empty() && first.front() == '{') return ".gltf";
  if (first.starts_with("OFF")) return ".off";  // "OFF 8 6 0" on one line
  if (has_line_starting(head, "v ") || has_line_starting(head, "v\t")) return ".obj";
  return "";
}

SliceForm read_slice_form(const Request& r) {
  std::size_t bytes = 0;
  for (const Upload& u : r.files) bytes += u.content.size() + u.name.size();
  if (bytes > kMaxUploadBytes) {
    throw HttpError(413, "upload of " + std::to_string(bytes) + " bytes, more than the " +
                             std::to_string(kMaxUploadBytes) + " accepted");
  }
  if (r.files.empty()) throw InputError("slice: send multipart/form-data with a field file (the mesh) and the flags of strand slice");
  SliceForm f;
  jobs::SliceSettings& s = f.settings;
  std::map<std::string, std::string> pattern_text;
  std::map<std::string, bool> seen;
  bool have_file = false;
  for (const Upload& u : r.files) {
    const std::string& k = u.name;
    if (seen[k]) throw InputError("slice." + k.substr(0, 40) + ": given twice");
    seen[k] = true;
    if (k == "file") {
      have_file = true;
      f.mesh = u.content;
      const std::string ext = mesh_extension(u.content);
      if (ext.empty()) throw InputError("slice.file: not a mesh file (STL, OBJ, PLY, OFF, glTF/GLB or 3MF)");
      check_mesh_references(u.content, ext, "slice.file");
      f.input = "part" + ext;
      if (f.name.empty()) f.name = shown_name(u.filename);
      continue;
    }
    if (u.content.size() > 4096) throw InputError("slice." + k.substr(0, 40) + ": longer than 4096 bytes");
    const std::string v(trim(u.content));
    if (v.empty()) continue;  // an empty field takes the default
    if (k == "name") {
      if (std::any_of(v.begin(), v.end(), [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; }))
        throw InputError("slice.name: control characters are not allowed");
      if (v.size() > kMaxNameBytes) throw InputError("slice.name: longer than " + std::to_string(kMaxNameBytes) + " bytes");
      f.name = v;
      continue;
    }
    if (k == "machine") {
      s.machine = v;
    } else if (k == "pattern") {
      std::vector<std::string> names;
      for (const auto& g : patterns::generators()) names.push_back(g.name);
      s.pattern = choice(v, names);
    } else if (k == "perimeters") {
      s.perimeters = whole_number(k, v);
    } else if (k == "mesh-units") {
      s.mesh_units = choice(v, {"mm", "cm", "m", "in"});
    } else if (k == "place") {
      s.place = choice(v, {"center", "origin"});
    } else if (k == "up") {
      s.up = choice(v, {"z", "y"});
    } else if (k == "rotate") {
      s.rotate = v;
    } else if (k == "scale") {
      s.scale = number(k, v);
    } else if (k == "scale-to-fit") {
      s.scale_to_fit = v;
    } else if (k == "repair" || k == "strict") {
      (k == "repair" ? s.repair : s.strict) = switch_value(k, v);
    } else if (is_pattern_flag(k)) {
      pattern_text[k] = v;
    } else {
      throw InputError("slice." + k.substr(0, 40) +
                       ": unknown field (file, name, machine, and the flags of strand slice: pattern, perimeters, "
                       "mesh-units, place, rotate, scale, scale-to-fit, up, repair, strict, the pattern's own)");
    }
    if (k != "machine") f.fields[k] = v;
  }
  if (!have_file) throw InputError("slice.file: missing (the mesh: STL, OBJ, PLY, OFF, glTF/GLB or 3MF)");
  s.pattern_values = pattern_values(s.pattern, pattern_text);
  if (f.name.empty()) f.name = "sliced part";
  return f;
}

}  // namespace strand::serve
