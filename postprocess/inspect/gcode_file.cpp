// Line by line through one 1 MiB buffer; a line longer than the buffer is gathered apart.
#include "postprocess/inspect/gcode_file.h"

#include <cstdio>
#include <filesystem>
#include <memory>

#include "slicer/file_io.h"
#include "slicer/input_error.h"

namespace strand::post {

namespace fs = std::filesystem;

namespace {

constexpr std::size_t kBufferBytes = std::size_t{1} << 20;

}  // namespace

GcodeFile::GcodeFile(std::string path) : path_(std::move(path)) {
  // The same refusals, in the same words, as slicer::read_file.
  std::error_code ec;
  const auto status = fs::status(path_, ec);
  const std::string at = "input = " + path_ + ": ";
  if (ec || !fs::exists(status)) throw InputError(at + "no such file");
  if (fs::is_directory(status)) throw InputError(at + "is a directory, not a file");
  if (fs::is_fifo(status)) throw InputError(at + "is a FIFO (named pipe), not a regular file");
  if (fs::is_character_file(status) || fs::is_block_file(status))
    throw InputError(at + "is a device, not a regular file");
  if (fs::is_socket(status)) throw InputError(at + "is a socket, not a regular file");
  if (!fs::is_regular_file(status)) throw InputError(at + "cannot read the file");
  size_ = fs::file_size(path_, ec);
  if (ec) throw InputError(at + "cannot read the file");
  if (size_ > slicer::kMaxInputBytes) {
    throw InputError(at + std::to_string(size_ >> 20) + " MiB, larger than the " +
                     std::to_string(slicer::kMaxInputBytes >> 20) + " MiB limit");
  }
}

void GcodeFile::each_line(const std::function<void(std::string_view)>& each,
                          const std::function<void(std::uintmax_t)>& read_bytes) const {
  const std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path_.c_str(), "rb"),
                                                           &std::fclose);
  if (!f) throw InputError("input = " + path_ + ": cannot read the file");
  std::string buffer(kBufferBytes, '\0');
  std::string carried;  // the start of a line the last buffer ended in
  std::uintmax_t total = 0;
  for (;;) {
    const std::size_t n = std::fread(buffer.data(), 1, buffer.size(), f.get());
    if (n == 0) break;
    total += n;
    if (total > slicer::kMaxInputBytes) {  // the file grew since it was opened
      throw InputError("input = " + path_ + ": larger than the " +
                       std::to_string(slicer::kMaxInputBytes >> 20) + " MiB limit");
    }
    const std::string_view chunk(buffer.data(), n);
    std::size_t pos = 0;
    for (std::size_t nl = chunk.find('\n'); nl != std::string_view::npos;
         nl = chunk.find('\n', pos)) {
      if (carried.empty()) {
        each(chunk.substr(pos, nl - pos));
      } else {
        carried.append(chunk.substr(pos, nl - pos));
        each(carried);
        carried.clear();
      }
      pos = nl + 1;
    }
    carried.append(chunk.substr(pos));
    if (read_bytes) read_bytes(total);
  }
  if (std::ferror(f.get())) throw InputError("input = " + path_ + ": cannot read the file");
  each(carried);
}

GcodeScan GcodeFile::scan() const {
  GcodeScan scan;
  each_line([&scan](std::string_view l) { scan.add_line(l); });
  return scan;
}

std::string GcodeFile::text() const { return slicer::read_file(path_); }

}  // namespace strand::post
