// Whole-file reads and atomic writes.
#include "slicer/file_io.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

#include "slicer/input_error.h"

namespace strand::slicer {

namespace {

std::filesystem::path temp_path(const std::string& path) {
  std::filesystem::path tmp(path);
  tmp += ".strand-tmp";
  return tmp;
}

// Writes the temp file beside `path`; removes it and throws on failure.
void write_temp(const std::string& path, const std::string& content) {
  namespace fs = std::filesystem;
  const fs::path tmp = temp_path(path);
  std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
  if (!out) throw InputError("output = " + path + ": cannot write here (check the directory)");
  out.write(content.data(), static_cast<std::streamsize>(content.size()));
  out.flush();
  if (!out) {
    out.close();
    std::error_code ec;
    fs::remove(tmp, ec);
    throw InputError("output = " + path + ": write failed (disk full?)");
  }
}

void remove_temp(const std::string& path) {
  std::error_code ec;
  std::filesystem::remove(temp_path(path), ec);
}

}  // namespace

void write_file_atomic(const std::string& path, const std::string& content) {
  write_files_atomic({{path, content}});
}

void write_files_atomic(const std::vector<std::pair<std::string, std::string>>& files) {
  std::size_t written = 0;
  try {
    for (; written < files.size(); ++written)
      write_temp(files[written].first, files[written].second);
  } catch (const InputError&) {
    for (std::size_t i = 0; i < written; ++i) remove_temp(files[i].first);
    throw;
  }
  for (std::size_t i = 0; i < files.size(); ++i) {
    std::error_code ec;
    std::filesystem::rename(temp_path(files[i].first), files[i].first, ec);
    if (ec) {
      for (std::size_t j = i; j < files.size(); ++j) remove_temp(files[j].first);
      throw InputError("output = " + files[i].first +
                       ": cannot rename the finished file into place");
    }
  }
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("input = " + path + ": cannot read the file");
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace strand::slicer
