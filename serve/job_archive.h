// GET /api/jobs/{id}/files.zip: a job's recorded files (a robot cell's whole program set:
// pose CSV, Sunrise, KRL, URScript or RAPID, the extruder's G-code, report, previews) as one
// zip archive, the same bytes for the same files: names sorted, fixed times and modes.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "serve/api.h"

namespace strand::serve {

// Largest sum of a job's file sizes put into one archive (a 1M-move G-code file and its
// viewer copy are about 80 MB); a larger job is downloaded file by file.
inline constexpr std::uintmax_t kMaxArchiveInputBytes = std::uintmax_t{1} << 30;

// Writes the files `names` of `dir` to `zip_path`: sorted by name, deflated, every entry dated
// 1980-01-01 00:00 with Unix mode 0644, so the archive's bytes depend on the files alone.
// Throws std::runtime_error when libzip cannot write it.
void write_job_archive(const std::filesystem::path& zip_path, const std::filesystem::path& dir,
                       std::vector<std::string> names);

// The archive streamed as `download_name` (attachment): built in a file under `scratch`, which
// is unlinked once opened, and sent in pieces, so memory does not grow with the job. HttpError
// 413 past kMaxArchiveInputBytes.
Response archive_response(const std::filesystem::path& scratch, const std::filesystem::path& dir,
                          const std::vector<std::string>& names, const std::string& download_name);

}  // namespace strand::serve
