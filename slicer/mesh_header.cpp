// PLY headers checked line by line before OpenMesh reads the file.
#include "slicer/mesh_header.h"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <set>
#include <cmath>
#include <sstream>
#include <vector>

#include "slicer/input_error.h"

namespace strand::slicer {

namespace {

const std::set<std::string> kPlyTypes = {"char",   "uchar",  "short",  "ushort",  "int",
                                         "uint",   "float",  "double", "int8",    "uint8",
                                         "int16",  "uint16", "int32",  "uint32",  "float32",
                                         "float64"};

struct PlyHeaderReader {
  std::string path;
  std::uintmax_t size_bytes = 0;
  int line_no = 0;
  bool format = false;
  int elements = 0;  // a property belongs to the element line above it
  std::set<std::string> names;

  [[noreturn]] void fail(const std::string& why) const {
    throw InputError("mesh = " + path + ": PLY header line " + std::to_string(line_no) + ": " + why);
  }

  void type(std::istringstream& w) const {
    std::string t;
    if (!(w >> t) || !kPlyTypes.count(t)) fail("a property type must be one of char .. float64");
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
    } else if (key == "element") {
      std::string name;
      double count = -1.0;
      if (!(w >> name >> count) || count < 0 || count > static_cast<double>(size_bytes))
        fail("an element count must be 0 .. " + std::to_string(size_bytes) + " (the file's bytes)");
      ++elements;
      names.insert(name);
    } else if (key == "property") {
      // OpenMesh adds it to the last element, and crashes when there is none (mesh_fuzz).
      if (elements == 0) fail("a property before any element line");
      std::string first;
      w >> first;
      if (first == "list") {
        type(w);
        type(w);
      } else if (!kPlyTypes.count(first)) {
        fail("a property type must be one of char .. float64");
      }
      std::string name;
      if (!(w >> name)) fail("a property needs a name");
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
  std::string head(static_cast<std::size_t>(std::min<std::uintmax_t>(size_bytes, kMaxPlyHeaderBytes)), '\0');
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
}

void vet_off_file(const std::string& path, std::uintmax_t size_bytes) {
  std::ifstream in(path, std::ios::binary);
  const auto fail = [&](const std::string& why) {
    throw InputError("mesh = " + path + ": OFF " + why);
  };
  std::string token;
  std::vector<double> counts;
  bool keyword = false;
  long long index = 0;
  for (std::string line; std::getline(in, line);) {
    std::istringstream words(line.substr(0, line.find('#')));
    while (words >> token) {
      ++index;
      if (!keyword) {  // OFF with its optional prefixes (C, N, ST, 4, n)
        const auto at = token.find("OFF");
        if (at == std::string::npos || token.size() != at + 3) fail("files start with OFF");
        keyword = true;
        continue;
      }
      if (token == "BINARY") fail("binary files are not read (save as ASCII OFF)");
      char* end = nullptr;
      const double v = std::strtod(token.c_str(), &end);
      if (end != token.c_str() + token.size() || !std::isfinite(v)) {
        fail("token " + std::to_string(index) + " is not a number");
      }
      if (counts.size() < 3) counts.push_back(v);
    }
  }
  if (counts.size() < 3) fail("files give vertex, face and edge counts after OFF");
  for (int k = 0; k < 2; ++k) {
    if (counts[k] < 0 || counts[k] != std::floor(counts[k]) ||
        counts[k] > static_cast<double>(size_bytes)) {
      fail(std::string(k == 0 ? "vertex" : "face") + " count must be a whole number 0 .. " +
           std::to_string(size_bytes) + " (the file's bytes)");
    }
  }
}

}  // namespace strand::slicer
