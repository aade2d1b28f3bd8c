// Whole-file reads and atomic writes.
#include "slicer/file_io.h"

#include <cstdio>
#include <filesystem>
#include <sstream>
#include <system_error>

#include "slicer/input_error.h"

namespace strand::slicer {

namespace fs = std::filesystem;

AtomicFile::AtomicFile(const std::string& path) : path_(path), tmp_(path + ".strand-tmp") {
  out_.open(tmp_, std::ios::binary | std::ios::trunc);
  if (!out_) throw InputError("output = " + path + ": cannot write here (check the directory)");
}

AtomicFile::~AtomicFile() {
  if (done_) return;
  out_.close();
  std::error_code ec;
  fs::remove(tmp_, ec);
}

void AtomicFile::commit() {
  out_.flush();
  const bool written = static_cast<bool>(out_);
  out_.close();
  done_ = true;
  std::error_code ec;
  if (!written) {
    fs::remove(tmp_, ec);
    throw InputError("output = " + path_ + ": write failed (disk full?)");
  }
  fs::rename(tmp_, path_, ec);
  if (ec) {
    fs::remove(tmp_, ec);
    throw InputError("output = " + path_ + ": cannot rename the finished file into place");
  }
}

void write_file_atomic(const std::string& path, const std::string& content) {
  AtomicFile file(path);
  file.out().write(content.data(), static_cast<std::streamsize>(content.size()));
  file.commit();
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("input = " + path + ": cannot read the file");
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace strand::slicer
