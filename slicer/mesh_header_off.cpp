// OFF files walked word by word in the order OpenMesh's ASCII reader takes them, before it does.
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <string>
#include <string_view>
#include <vector>

#include "slicer/input_error.h"
#include "slicer/mesh_header.h"
#include "slicer/mesh_io.h"

namespace strand::slicer {

namespace {

// Bytes OpenMesh may copy trimming the rest of vertex and face lines (about 0.1 s): 12 million
// vertices with a colour and a line end each copy well under it.
constexpr std::uint64_t kMaxTrimCopies = std::uint64_t{1} << 30;

// OpenMesh's read_ascii takes the first line as the header, then with `>>` (which skips
// spaces and line ends alike) the vertex, face and edge counts; per vertex its three
// coordinates (six with NOFF's normals) and then the rest of that line with std::getline
// (colours and texture coordinates, parsed apart); per face a corner count and that many
// vertex numbers (and with COFF the rest of the line). The walk keeps the same place.
class OffWalk {
 public:
  explicit OffWalk(const std::string& path) : path_(path), in_(path, std::ios::binary) {}

  [[noreturn]] void fail(const std::string& why) const {
    throw InputError("mesh = " + path_ + ": OFF " + why);
  }
  [[noreturn]] void fail_here(const std::string& why) const {
    fail("line " + std::to_string(line_no_) + ": " + why);
  }

  // The first line's keyword, [ST][C][N]OFF, alone on it (a comment aside).
  std::string header() {
    if (!next_line()) fail("files start with OFF");
    if (words_.empty()) fail("files start with OFF on line 1");
    const std::string keyword(words_[0]);
    const auto at = keyword.find("OFF");
    if (at == std::string::npos || at + 3 != keyword.size()) fail("files start with OFF");
    const std::string prefix = keyword.substr(0, at);
    if (prefix != "" && prefix != "ST" && prefix != "C" && prefix != "N" && prefix != "STC" &&
        prefix != "STN" && prefix != "CN" && prefix != "STCN") {
      fail("header '" + shown(keyword) + "': OpenMesh reads OFF, COFF, NOFF, STOFF and their " +
           "combinations (3 coordinates a vertex)");
    }
    if (words_.size() > 1 && words_[1] == "BINARY") {
      fail("binary files are not read (save as ASCII OFF)");
    }
    // OpenMesh skips the rest of this line: counts there were never read (a 2 GB reservation
    // for "OFF 3 0 1").
    if (words_.size() > 1) {
      fail("line 1 holds only OFF: the vertex, face and edge counts go on the next line");
    }
    at_ = words_.size();
    comment_ = false;
    return prefix;
  }

  // The next word `>>` takes, across line ends; `what` names it for the messages.
  std::string_view word(const std::string& what) {
    while (at_ == words_.size()) {
      if (comment_) {
        fail_here("a '#' comment where OpenMesh reads " + what +
                  " (its OFF reader has no comments: remove it)");
      }
      if (!next_line()) fail("the file ends before " + what);
    }
    return words_[at_++];
  }

  // What std::getline takes after a `>>`: the rest of the current line. OpenMesh then counts
  // its items (getColorType): it trims the spaces round them one character at a time, each a
  // copy of the rest (a line padded with spaces is quadratic), and with colours (COFF) prints
  // to std::cerr for more than 6 (a vertex's colour is 1 to 4 numbers, after any 2 texture
  // coordinates).
  void drop_rest_of_line(bool colours, bool texcoords) {
    const std::size_t from = at_ == 0
                                 ? 0
                                 : static_cast<std::size_t>(words_[at_ - 1].data() +
                                                            words_[at_ - 1].size() - line_.data());
    const std::string_view rest = std::string_view(line_).substr(from);
    std::size_t lead = 0, trail = 0;
    while (lead < rest.size() && is_word_space(rest[lead])) ++lead;
    while (trail < rest.size() - lead && is_word_space(rest[rest.size() - 1 - trail])) ++trail;
    trim_copies_ += static_cast<std::uint64_t>(lead + trail) * rest.size();
    if (trim_copies_ > kMaxTrimCopies) {
      fail_here(
          "too many spaces round the words after vertices and faces: OpenMesh trims "
          "them one character at a time, each a copy of the line (over " +
          std::to_string(kMaxTrimCopies) + " bytes copied); remove them");
    }
    const std::string_view items = rest.substr(lead, rest.size() - lead - trail);
    long long count = items.empty() ? 0 : 1;
    for (const char c : items) count += c == ' ' ? 1 : 0;
    if (texcoords) count -= 2;
    if (colours && (count < 0 || count > 6)) {
      fail_here("a colour of " + std::to_string(count) +
                " items after the numbers (OpenMesh reads 0 to 4 and prints an error otherwise)");
    }
    at_ = words_.size();
    comment_ = false;
  }
  std::size_t words_left_on_line() const { return words_.size() - at_; }

  // A whole number as `>>` into an unsigned int reads it, at most `max`.
  std::uint64_t whole(const std::string& what, std::uint64_t max) {
    const std::string_view w = word(what);
    const bool digits =
        !w.empty() && w.size() <= 19 && w.find_first_not_of("0123456789") == std::string_view::npos;
    const std::uint64_t v = digits ? std::strtoull(std::string(w).c_str(), nullptr, 10) : 0;
    if (!digits || v > max) {
      fail_here(what + " must be a whole number 0 .. " + std::to_string(max) + " (it is '" +
                shown(w) + "')");
    }
    return v;
  }

  // A coordinate as `>>` into a float reads it whole: a sign, decimal digits with at most one
  // point, an optional exponent; within a float's range (a larger one stops the stream).
  void coordinate(const std::string& what) {
    const std::string_view w = word(what);
    std::size_t i = w.size() > 0 && (w[0] == '+' || w[0] == '-') ? 1 : 0;
    const auto run = [&] {
      const std::size_t from = i;
      while (i < w.size() && w[i] >= '0' && w[i] <= '9') ++i;
      return i - from;
    };
    std::size_t mantissa = run();
    if (i < w.size() && w[i] == '.') {
      ++i;
      mantissa += run();
    }
    bool ok = mantissa > 0;
    if (ok && i < w.size() && (w[i] == 'e' || w[i] == 'E')) {
      ++i;
      if (i < w.size() && (w[i] == '+' || w[i] == '-')) ++i;
      ok = run() > 0;
    }
    errno = 0;  // ERANGE: past a float, or below its smallest normal (so as not to rely on >>)
    const float v = ok && i == w.size() ? std::strtof(std::string(w).c_str(), nullptr) : 0.0f;
    if (!ok || i != w.size() || errno == ERANGE || !std::isfinite(v)) {
      fail_here(what + " '" + shown(w) + "' is not a decimal number within a float's range");
    }
  }

 private:
  static std::string shown(std::string_view w) { return std::string(w.substr(0, 20)); }

  bool next_line() {
    if (!std::getline(in_, line_)) return false;
    ++line_no_;
    const std::size_t cut = line_.find('#');
    comment_ = cut != std::string::npos;
    split_words(std::string_view(line_).substr(0, cut), words_);
    at_ = 0;
    return true;
  }

  std::string path_;
  std::ifstream in_;
  std::string line_;
  std::vector<std::string_view> words_;
  std::size_t at_ = 0;
  bool comment_ = false;           // the current line ends in a comment
  std::uint64_t trim_copies_ = 0;  // bytes OpenMesh's trimming copies, so far
  long long line_no_ = 0;
};

}  // namespace

void vet_off_file(const std::string& path) {
  OffWalk walk(path);
  const std::string prefix = walk.header();
  const bool normals = prefix.find('N') != std::string::npos;
  const bool colours = prefix.find('C') != std::string::npos;
  const bool texcoords = prefix.find("ST") != std::string::npos;
  const std::uint64_t vertices = walk.whole("the vertex count", kMaxMeshVertices);
  const std::uint64_t faces = walk.whole("the face count", kMaxMeshTriangles);
  walk.whole("the edge count", 0xFFFFFFFFu);
  for (std::uint64_t v = 0; v < vertices; ++v) {
    const std::string name = "a coordinate of vertex " + std::to_string(v);
    for (int k = 0; k < (normals ? 6 : 3); ++k) walk.coordinate(name);
    walk.drop_rest_of_line(colours, texcoords);
  }
  std::uint64_t triangles = 0;
  for (std::uint64_t f = 0; f < faces; ++f) {
    const std::string face = "face " + std::to_string(f);
    const std::uint64_t corners = walk.whole(face + "'s corner count", kMaxMeshTriangles + 2);
    triangles += corners >= 3 ? corners - 2 : 0;
    if (triangles > kMaxMeshTriangles) {
      walk.fail_here("the faces make more than " + std::to_string(kMaxMeshTriangles) +
                     " triangles (n - 2 for a face of n corners); at most " +
                     std::to_string(kMaxMeshTriangles) + " are accepted");
    }
    for (std::uint64_t k = 0; k < corners; ++k) {
      if (vertices == 0) walk.fail_here(face + " names a vertex; the file has none");
      walk.whole(face + "'s vertex number", vertices - 1);
    }
    if (colours) {
      walk.drop_rest_of_line(true, false);
    } else if (walk.words_left_on_line() > 0 && f + 1 < faces) {
      walk.fail_here(face + " has " + std::to_string(walk.words_left_on_line()) +
                     " words after its " + std::to_string(corners) +
                     " vertex numbers (a colour?): OpenMesh would read them as the next " +
                     "face (face colours need a COFF header)");
    }
  }
}

}  // namespace strand::slicer
