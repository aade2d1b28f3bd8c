// A G-code file read line by line through a fixed buffer, as often as a reading needs, so a
// file of millions of moves is never held whole (`strand check`).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>

#include "postprocess/inspect/gcode_parser.h"

namespace strand::post {

class GcodeFile {
 public:
  // Throws InputError as slicer::read_file does: missing, a directory, a device or FIFO, or
  // larger than slicer::kMaxInputBytes.
  explicit GcodeFile(std::string path);
  const std::string& path() const { return path_; }
  std::uintmax_t size_bytes() const { return size_; }

  // Every line in order, without its '\n' (the text after the last '\n' too, as the text
  // readers split it); `read_bytes`, when set, is told the bytes read so far after each
  // buffer. Throws InputError when the file cannot be read.
  void each_line(const std::function<void(std::string_view)>& each,
                 const std::function<void(std::uintmax_t)>& read_bytes = {}) const;
  // What parse_gcode_layers needs to know first (one pass).
  GcodeScan scan() const;
  // The whole text, for readers that need it (O-word programs, curved files).
  std::string text() const;

 private:
  std::string path_;
  std::uintmax_t size_ = 0;
};

}  // namespace strand::post
