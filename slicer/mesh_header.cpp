// PLY headers checked line by line before OpenMesh reads the file.
#include "slicer/mesh_header.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>
#include <string_view>
#include <vector>

#include "slicer/input_error.h"
#include "slicer/mesh_header_ply.h"
#include "slicer/mesh_io.h"

namespace strand::slicer {

namespace {

struct PlyHeaderReader {
  std::string path;
  std::uintmax_t size_bytes = 0;
  int line_no = 0;
  bool format = false;
  std::set<std::string> names;
  PlyLayout layout;  // a property belongs to the element line above it

  [[noreturn]] void fail(const std::string& why) const {
    throw InputError("mesh = " + path + ": PLY header line " + std::to_string(line_no) + ": " +
                     why);
  }

  // The next word as a PLY type: its bytes.
  int type(std::istringstream& w) const {
    std::string t;
    const int bytes = (w >> t) ? ply_type_bytes(t) : 0;
    if (bytes == 0) fail("a property type must be one of char .. float64");
    return bytes;
  }

  // A list's count type: an integer type (OpenMesh reads a float count as a size).
  void count_type(std::istringstream& w, PlyProperty& p) const {
    std::string t;
    w >> t;
    p.count_bytes = ply_type_bytes(t);
    if (p.count_bytes == 0 || t.find("float") != std::string::npos || t == "double")
      fail("a list count type must be an integer type (uchar, ushort, uint, ...)");
    p.count_signed = t[0] != 'u';
  }

  void line(const std::string& text) {
    ++line_no;
    if (std::any_of(text.begin(), text.end(), [](char c) {
          return c != '\t' && (static_cast<unsigned char>(c) < 0x20 || c == 0x7f);
        })) {
      fail("holds a byte that is not text");
    }
    std::istringstream w(text);
    std::string key;
    w >> key;
    if (line_no == 1) {
      if (key != "ply") fail("the file must start with 'ply'");
    } else if (key == "format") {
      std::string kind, version;
      w >> kind >> version;
      if (kind != "ascii" && kind != "binary_little_endian" && kind != "binary_big_endian")
        fail("format must be ascii, binary_little_endian or binary_big_endian");
      if (version != "1.0") fail("the format version must be 1.0");
      format = true;
      layout.format = kind == "ascii"                  ? PlyFormat::Ascii
                      : kind == "binary_little_endian" ? PlyFormat::BinaryLittleEndian
                                                       : PlyFormat::BinaryBigEndian;
    } else if (key == "element") {
      // The count as digits only: OpenMesh misreads ".4" or "1e9" and allocates gigabytes.
      std::string name, count_text;
      const bool read = static_cast<bool>(w >> name >> count_text);
      const bool digits = read && !count_text.empty() && count_text.size() <= 19 &&
                          count_text.find_first_not_of("0123456789") == std::string::npos;
      if (!digits || std::stod(count_text) > static_cast<double>(size_bytes))
        fail("an element count must be 0 .. " + std::to_string(size_bytes) + " (the file's bytes)");
      layout.elements.push_back({name, std::stoull(count_text), {}});
      names.insert(name);
    } else if (key == "property") {
      // OpenMesh adds it to the last element, and crashes when there is none (mesh_fuzz).
      if (layout.elements.empty()) fail("a property before any element line");
      std::string first;
      w >> first;
      PlyProperty p;
      if (first == "list") {
        p.list = true;
        count_type(w, p);
        p.bytes = type(w);
      } else {
        p.bytes = ply_type_bytes(first);
        if (p.bytes == 0) fail("a property type must be one of char .. float64");
      }
      std::string name;
      if (!(w >> name)) fail("a property needs a name");
      layout.elements.back().properties.push_back(p);
    } else if (!key.empty() && key != "comment" && key != "obj_info") {
      fail("'" + key.substr(0, 20) + "' is not a PLY header keyword");
    }
    std::string extra;  // OpenMesh looped without end on a format line with more words
    if (key != "comment" && key != "obj_info" && (w >> extra))
      fail("unexpected '" + extra.substr(0, 20) + "' at the end of the line");
  }
};

}  // namespace

void vet_ply_header(const std::string& path, std::uintmax_t size_bytes) {
  std::ifstream in(path, std::ios::binary);
  std::string head(
      static_cast<std::size_t>(std::min<std::uintmax_t>(size_bytes, kMaxPlyHeaderBytes)), '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(std::max<std::streamsize>(in.gcount(), 0)));
  PlyHeaderReader r{path, size_bytes};
  // The line must be exactly end_header: OpenMesh looped without end on "end_headernt v 0"
  // (mesh_fuzz).
  std::size_t end = head.find("\nend_header");
  while (end != std::string::npos && head.compare(end + 11, 1, "\n") != 0 &&
         head.compare(end + 11, 2, "\r\n") != 0) {
    end = head.find("\nend_header", end + 1);
  }
  if (end == std::string::npos) {
    r.line_no = 0;
    r.fail("no end_header line in the first " + std::to_string(kMaxPlyHeaderBytes / 1024) + " KiB");
  }
  std::istringstream lines(head.substr(0, end));
  std::string text;
  while (std::getline(lines, text)) {
    if (!text.empty() && text.back() == '\r') text.pop_back();
    r.line(text);
  }
  if (!r.format) r.fail("no format line before end_header");
  if (!r.names.count("vertex") || !r.names.count("face"))
    r.fail("a triangle mesh needs 'element vertex' and 'element face' lines");
  r.layout.body_offset = end + 12 + (head.compare(end + 11, 1, "\n") == 0 ? 0 : 1);
  vet_ply_body(path, size_bytes, r.layout);
}

// Words as `>>` splits them: at spaces, tabs, line ends, vertical tabs and form feeds
// (isspace in the C locale), without an istringstream per line, which cost more than
// OpenMesh's own reading of a file. Each word is followed in `line` by a space, a '#' or the
// end of the string, so strtod reads no further.
void split_words(std::string_view line, std::vector<std::string_view>& words) {
  words.clear();
  for (std::size_t i = 0; i < line.size();) {
    while (i < line.size() && is_word_space(line[i])) ++i;
    std::size_t j = i;
    while (j < line.size() && !is_word_space(line[j])) ++j;
    if (j > i) words.emplace_back(line.data() + i, j - i);
    i = j;
  }
}

namespace {

// Cuts `line` at its first '#', a comment's start.
void drop_comment(std::string& line) { line.resize(std::min(line.size(), line.find('#'))); }

// `t` is a word of split_words: strtod stops at its end.
bool non_finite_token(std::string_view t) {
  if (t.empty()) return false;
  char* end = nullptr;
  const double v = std::strtod(t.data(), &end);
  return end == t.data() + t.size() && !std::isfinite(v);
}

[[noreturn]] void non_finite(const std::string& path, const std::string& where,
                             std::string_view token) {
  throw InputError("mesh = " + path + ": " + where + " has a non-finite coordinate ('" +
                   std::string(token.substr(0, 20)) + "': NaN or infinity)");
}

}  // namespace

void vet_finite_vertices(const std::string& path, const std::string& ext,
                         std::uintmax_t size_bytes) {
  std::ifstream in(path, std::ios::binary);
  std::string head(80, '\0');
  in.read(head.data(), 80);
  head.resize(static_cast<std::size_t>(std::max<std::streamsize>(in.gcount(), 0)));
  if (ext == ".stl" && size_bytes >= 84) {
    std::uint32_t n = 0;
    in.read(reinterpret_cast<char*>(&n), 4);
    if (in && 84 + 50 * static_cast<std::uintmax_t>(n) == size_bytes) {  // binary STL
      for (std::uint32_t t = 0; t < n; ++t) {
        float f[12];
        std::uint16_t attr = 0;
        in.read(reinterpret_cast<char*>(f), sizeof f);
        in.read(reinterpret_cast<char*>(&attr), 2);
        if (!in) return;
        for (int k = 3; k < 12; ++k) {  // the normal (k < 3) is not used
          if (!std::isfinite(f[k])) {
            non_finite(path, "triangle " + std::to_string(t) + ", corner " + std::to_string(k / 3),
                       std::isnan(f[k]) ? "nan" : "inf");
          }
        }
      }
      return;
    }
  }
  in.clear();
  in.seekg(0);
  std::string line;
  std::vector<std::string_view> words;
  int line_no = 0;
  bool body = ext != ".ply";  // PLY: only the lines after end_header
  bool ply_ascii = false;
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    split_words(line, words);
    if (words.empty()) continue;
    const std::string_view first = words[0];
    if (!body) {
      if (first == "format") ply_ascii = words.size() > 1 && words[1] == "ascii";
      if (first == "end_header") {
        if (!ply_ascii) return;  // binary bodies are checked after reading
        body = true;
      }
      continue;
    }
    std::size_t from = 0;  // the first coordinate word
    if (ext == ".stl") {
      if (first != "vertex") continue;
      from = 1;
    } else if (ext == ".obj") {
      if (first != "v") continue;
      from = 1;
    } else if (first[0] == '#') {
      continue;
    }
    for (std::size_t k = from; k < words.size(); ++k) {
      const std::string_view t = words[k];
      if (non_finite_token(t)) non_finite(path, "line " + std::to_string(line_no), t);
      if (ext == ".ply") {  // OpenMesh spun for two minutes on a word in an ASCII PLY body
        char* end = nullptr;
        std::strtod(t.data(), &end);
        if (end != t.data() + t.size()) {
          throw InputError("mesh = " + path + ": PLY line " + std::to_string(line_no) + ": '" +
                           std::string(t.substr(0, 20)) + "' is not a number");
        }
      }
    }
  }
}

void vet_obj_faces(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  long long line_no = 0;
  std::uint64_t triangles = 0;
  std::vector<std::string_view> words;
  for (std::string line; std::getline(in, line);) {
    ++line_no;
    drop_comment(line);
    split_words(line, words);
    if (words.empty() || words[0] != "f") continue;
    int corners = 0;
    for (std::size_t k = 1; k < words.size(); ++k) {
      // "v", "v/vt", "v//vn" or "v/vt/vn": the vertex index is a non-zero integer.
      const std::string_view v = words[k].substr(0, words[k].find('/'));
      const std::size_t digits = v.find_first_not_of("-+");
      const bool index = digits != std::string_view::npos && digits <= 1 &&
                         v.find_first_not_of("0123456789", digits) == std::string_view::npos &&
                         v.find_first_not_of("0", digits) != std::string_view::npos;
      if (!index) {
        throw InputError("mesh = " + path + ": OBJ line " + std::to_string(line_no) +
                         ": a face corner must start with a vertex number");
      }
      ++corners;
    }
    if (corners < 3) {
      throw InputError("mesh = " + path + ": OBJ line " + std::to_string(line_no) +
                       ": a face needs at least 3 corners");
    }
    // OpenMesh makes n - 2 triangles of a face of n corners before any check of ours.
    triangles += static_cast<std::uint64_t>(corners) - 2;
    if (triangles > kMaxMeshTriangles) {
      throw InputError("mesh = " + path + ": OBJ line " + std::to_string(line_no) +
                       ": the faces make more than " + std::to_string(kMaxMeshTriangles) +
                       " triangles (n - 2 for a face of n corners); at most " +
                       std::to_string(kMaxMeshTriangles) + " are accepted");
    }
  }
}

}  // namespace strand::slicer
