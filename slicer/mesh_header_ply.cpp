// The PLY body walked record by record, every count bounded before anything is allocated.
#include "slicer/mesh_header_ply.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <fstream>

#include "slicer/input_error.h"
#include "slicer/mesh_io.h"

namespace strand::slicer {

namespace {

// Words of an ASCII body, read through one buffer; `left()` is the bytes not yet read.
class PlyWords {
 public:
  PlyWords(const std::string& path, std::uint64_t offset, std::uint64_t size)
      : in_(path, std::ios::binary), left_(size > offset ? size - offset : 0) {
    in_.seekg(static_cast<std::streamoff>(offset));
  }

  // The next word into `word` (cut at 32 characters: only counts are read whole); false at
  // the end of the file.
  bool next(std::string& word) {
    word.clear();
    int c = 0;
    while ((c = get()) >= 0 && is_space(c)) {
    }
    for (; c >= 0 && !is_space(c); c = get()) {
      if (word.size() < 32) word.push_back(static_cast<char>(c));
    }
    return !word.empty();
  }

  std::uint64_t left() const { return left_ + (end_ - at_); }

 private:
  static bool is_space(int c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

  int get() {
    if (at_ == end_) {
      if (left_ == 0) return -1;
      in_.read(buffer_.data(),
               static_cast<std::streamsize>(std::min<std::uint64_t>(left_, buffer_.size())));
      const auto got = static_cast<std::size_t>(std::max<std::streamsize>(in_.gcount(), 0));
      if (got == 0) return -1;
      left_ -= got;
      at_ = 0;
      end_ = got;
    }
    return static_cast<unsigned char>(buffer_[at_++]);
  }

  std::ifstream in_;
  std::uint64_t left_;
  std::array<char, 1 << 16> buffer_{};
  std::size_t at_ = 0, end_ = 0;
};

struct BodyWalk {
  const std::string& path;
  const PlyLayout& layout;
  std::uint64_t triangles = 0;

  [[noreturn]] void fail(const std::string& why) const {
    throw InputError("mesh = " + path + ": PLY " + why);
  }

  // A face's list of `n` corners: n - 2 triangles, bounded as they are counted.
  void count_face(const PlyElement& e, std::size_t property, std::uint64_t n) {
    const auto first_list = std::find_if(e.properties.begin(), e.properties.end(),
                                         [](const PlyProperty& p) { return p.list; });
    if (e.name != "face" ||
        first_list - e.properties.begin() != static_cast<std::ptrdiff_t>(property))
      return;
    triangles += n >= 3 ? n - 2 : 0;
    if (triangles > kMaxMeshTriangles) {
      fail("faces: more than " + std::to_string(kMaxMeshTriangles) +
           " triangles (n - 2 for a face of n corners); at most " +
           std::to_string(kMaxMeshTriangles) + " are accepted");
    }
  }

  std::string record_name(const PlyElement& e, std::uint64_t r) const {
    return e.name.substr(0, 20) + " " + std::to_string(r);
  }

  // Every element's records, at their smallest, must fit in the bytes after the header.
  void check_counts(std::uint64_t body_bytes) const {
    std::uint64_t left = body_bytes;
    for (const PlyElement& e : layout.elements) {
      if (e.name == "vertex" && e.count > kMaxMeshVertices) {
        fail("element vertex " + std::to_string(e.count) + ": at most " +
             std::to_string(kMaxMeshVertices) + " vertices are accepted");
      }
      std::uint64_t smallest = 0;  // bytes of one record at the least
      for (const PlyProperty& p : e.properties) {
        if (layout.format == PlyFormat::Ascii)
          smallest += 2;  // a digit and a separator
        else
          smallest += static_cast<std::uint64_t>(p.list ? p.count_bytes : p.bytes);
      }
      if (smallest == 0) continue;
      const std::uint64_t room = (left + (layout.format == PlyFormat::Ascii ? 1 : 0)) / smallest;
      if (e.count > room) {
        fail("element " + e.name.substr(0, 20) + " " + std::to_string(e.count) +
             ": records of at least " + std::to_string(smallest) + " bytes each; the file has " +
             std::to_string(body_bytes) + " bytes after its header");
      }
      left -= std::min(left, e.count * smallest);
    }
  }

  void binary(std::uint64_t size_bytes) {
    std::ifstream in(path, std::ios::binary);
    in.seekg(static_cast<std::streamoff>(layout.body_offset));
    std::uint64_t left = size_bytes - layout.body_offset;
    const bool big = layout.format == PlyFormat::BinaryBigEndian;
    for (const PlyElement& e : layout.elements) {
      const bool lists = std::any_of(e.properties.begin(), e.properties.end(),
                                     [](const PlyProperty& p) { return p.list; });
      if (!lists) {  // fixed-size records: checked by check_counts, skipped in one step
        std::uint64_t bytes = 0;
        for (const PlyProperty& p : e.properties) bytes += static_cast<std::uint64_t>(p.bytes);
        left -= std::min(left, bytes * e.count);
        in.seekg(static_cast<std::streamoff>(size_bytes - left));
        continue;
      }
      for (std::uint64_t r = 0; r < e.count; ++r) {
        for (std::size_t k = 0; k < e.properties.size(); ++k) {
          const PlyProperty& p = e.properties[k];
          const auto head = static_cast<std::uint64_t>(p.list ? p.count_bytes : p.bytes);
          if (head > left) fail(record_name(e, r) + ": the file ends before this record does");
          unsigned char b[8] = {};
          in.read(reinterpret_cast<char*>(b), static_cast<std::streamsize>(head));
          if (!in) fail(record_name(e, r) + ": the file ends before this record does");
          left -= head;
          if (!p.list) continue;
          std::uint64_t n = 0;
          for (int i = 0; i < p.count_bytes; ++i) n = (n << 8) | b[big ? i : p.count_bytes - 1 - i];
          if (p.count_signed && (b[big ? 0 : p.count_bytes - 1] & 0x80) != 0)
            fail(record_name(e, r) + ": a negative list count");
          const std::uint64_t need = n * static_cast<std::uint64_t>(p.bytes);
          if (need > left) {
            fail(record_name(e, r) + ": a list of " + std::to_string(n) + " entries needs " +
                 std::to_string(need) + " bytes; " + std::to_string(left) +
                 " are left in the file");
          }
          count_face(e, k, n);
          in.ignore(static_cast<std::streamsize>(need));
          left -= need;
        }
      }
    }
  }

  void ascii(std::uint64_t size_bytes) {
    PlyWords words(path, layout.body_offset, size_bytes);
    std::string w;
    for (const PlyElement& e : layout.elements) {
      for (std::uint64_t r = 0; r < e.count; ++r) {
        for (std::size_t k = 0; k < e.properties.size(); ++k) {
          const PlyProperty& p = e.properties[k];
          if (!words.next(w)) fail(record_name(e, r) + ": the file ends before this record does");
          if (!p.list) continue;
          if (w.size() > 19 || w.find_first_not_of("0123456789") != std::string::npos)
            fail(record_name(e, r) + ": a list count must be a whole number, not '" + w + "'");
          const std::uint64_t n = std::stoull(w);
          // Each entry is a word and a separator: 2 bytes at least.
          if (n > (words.left() + 1) / 2) {
            fail(record_name(e, r) + ": a list of " + std::to_string(n) + " entries; only " +
                 std::to_string(words.left()) + " bytes are left in the file");
          }
          count_face(e, k, n);
          for (std::uint64_t i = 0; i < n; ++i) {
            if (!words.next(w)) fail(record_name(e, r) + ": the file ends before this record does");
          }
        }
      }
    }
  }
};

}  // namespace

int ply_type_bytes(const std::string& t) {
  if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
  if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
  if (t == "int" || t == "uint" || t == "int32" || t == "uint32" || t == "float" || t == "float32")
    return 4;
  if (t == "double" || t == "float64") return 8;
  return 0;
}

void vet_ply_body(const std::string& path, std::uintmax_t size_bytes, const PlyLayout& layout) {
  BodyWalk walk{path, layout};
  const std::uint64_t body = size_bytes > layout.body_offset ? size_bytes - layout.body_offset : 0;
  walk.check_counts(body);
  if (layout.format == PlyFormat::Ascii)
    walk.ascii(size_bytes);
  else
    walk.binary(size_bytes);
}

}  // namespace strand::slicer
