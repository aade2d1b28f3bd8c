// A job's files zipped with libzip into a scratch file, then streamed from it.
#include "serve/job_archive.h"

#include <unistd.h>
#include <zip.h>

#include <algorithm>
#include <ctime>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <system_error>

#include "serve/api_state.h"

namespace strand::serve {

namespace fs = std::filesystem;

namespace {

// Piece of the archive sent at a time.
constexpr std::size_t kArchivePieceBytes = 64 << 10;

// libzip 1.7 turns a time_t into the entry's DOS date through localtime: the local
// 1980-01-01 00:00 (the DOS epoch) reads back as that date in every time zone.
std::time_t dos_epoch() {
  std::tm t{};
  t.tm_year = 80;
  t.tm_mday = 1;
  t.tm_isdst = -1;
  return std::mktime(&t);
}

[[noreturn]] void fail(zip_t* z, const std::string& what) {
  const std::string why = z ? zip_strerror(z) : "cannot open";
  if (z) zip_discard(z);
  throw std::runtime_error("files.zip: " + what + " (" + why + ")");
}

}  // namespace

void write_job_archive(const fs::path& zip_path, const fs::path& dir, std::vector<std::string> names) {
  std::sort(names.begin(), names.end());
  int error = 0;
  zip_t* z = zip_open(zip_path.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &error);
  if (!z) fail(nullptr, "cannot create the archive");
  const std::time_t epoch = dos_epoch();
  for (const std::string& name : names) {
    zip_source_t* src = zip_source_file(z, (dir / name).c_str(), 0, -1);
    if (!src) fail(z, "cannot read " + name);
    const zip_int64_t at = zip_file_add(z, name.c_str(), src, ZIP_FL_ENC_UTF_8);
    if (at < 0) {
      zip_source_free(src);
      fail(z, "cannot add " + name);
    }
    const auto i = static_cast<zip_uint64_t>(at);
    if (zip_file_set_mtime(z, i, epoch, 0) != 0 ||
        zip_file_set_external_attributes(z, i, 0, ZIP_OPSYS_UNIX, 0100644u << 16) != 0 ||
        zip_set_file_compression(z, i, ZIP_CM_DEFLATE, 6) != 0) {
      fail(z, "cannot set the entry of " + name);
    }
  }
  if (zip_close(z) != 0) fail(z, "cannot write the archive");
}

Response archive_response(const fs::path& scratch, const fs::path& dir, const std::vector<std::string>& names,
                          const std::string& download_name) {
  std::uintmax_t total = 0;
  for (const std::string& name : names) total += fs::file_size(dir / name);
  if (total > kMaxArchiveInputBytes) {
    throw HttpError(413, "the job's files are " + std::to_string(total) + " bytes, more than the " +
                             std::to_string(kMaxArchiveInputBytes) + " one archive holds; download them one by one");
  }
  fs::create_directories(scratch);
  std::string path = (scratch / "files-XXXXXX").string();
  const int fd = ::mkstemp(path.data());
  if (fd < 0) throw std::system_error(errno, std::generic_category(), "files.zip: cannot make a scratch file");
  ::close(fd);
  auto in = std::make_shared<std::ifstream>();
  try {
    write_job_archive(path, dir, names);
    in->open(path, std::ios::binary);
  } catch (...) {
    fs::remove(path);
    throw;
  }
  fs::remove(path);  // the open stream keeps the bytes until it is closed
  if (!*in) throw std::runtime_error("files.zip: cannot read the archive back");
  Response out;
  out.content_type = "application/zip";
  out.headers.emplace_back("Content-Disposition", "attachment; filename=\"" + download_name + "\"");
  out.stream = [in](std::string& piece) {
    piece.resize(kArchivePieceBytes);
    in->read(piece.data(), static_cast<std::streamsize>(piece.size()));
    piece.resize(static_cast<std::size_t>(in->gcount()));
    return !piece.empty();
  };
  return out;
}

}  // namespace strand::serve
