// Output files are written whole or not at all: write a sibling temp file, then rename.
#pragma once

#include <string>

namespace strand::slicer {

// Writes `content` to `path` atomically; throws InputError if the directory is not writable.
void write_file_atomic(const std::string& path, const std::string& content);
// Reads a whole file; throws InputError naming the path if it cannot be read.
std::string read_file(const std::string& path);

}  // namespace strand::slicer
