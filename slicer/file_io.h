// Output files are written whole or not at all: write a sibling temp file, then rename.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace strand::slicer {

// Writes `content` to `path` atomically; throws InputError if the directory is not writable.
void write_file_atomic(const std::string& path, const std::string& content);
// Writes several files as one transaction: every temp file first, then the renames, so an
// error while writing leaves none of them (earlier files of the set are never replaced
// unless every temp was written). Throws InputError like write_file_atomic.
void write_files_atomic(const std::vector<std::pair<std::string, std::string>>& files);
// Reads a whole file; throws InputError naming the path if it cannot be read.
std::string read_file(const std::string& path);

}  // namespace strand::slicer
