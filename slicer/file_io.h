// Output files are written whole or not at all: write a sibling temp file, then rename.
#pragma once

#include <fstream>
#include <string>

namespace strand::slicer {

// Writes `content` to `path` atomically; throws InputError if the directory is not writable.
void write_file_atomic(const std::string& path, const std::string& content);
// Reads a whole file; throws InputError naming the path if it cannot be read.
std::string read_file(const std::string& path);

// A file written in pieces (large G-code streams as it is formatted) and put in place whole:
// text goes to the sibling temp file "<path>.strand-tmp"; commit() renames it over `path`.
// Destroyed without commit (an error midway), it removes the temp file, leaving no output.
class AtomicFile {
 public:
  explicit AtomicFile(const std::string& path);  // throws InputError if it cannot be created
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  std::ostream& out() { return out_; }
  // Flushes and renames into place; throws InputError (and removes the temp) on failure.
  void commit();

 private:
  std::string path_;
  std::string tmp_;
  std::ofstream out_;
  bool done_ = false;
};

}  // namespace strand::slicer
