// A 3MF's zip archive read in memory with libzip (lib3mf's own zip library): owners of its
// handles and the archive opened read-only, for the screen and the prefix rewrite.
#pragma once

#include <zip.h>

#include <memory>
#include <string>

namespace strand::slicer {

struct ZipDiscard {
  void operator()(zip_t* z) const { zip_discard(z); }
};
struct ZipFileClose {
  void operator()(zip_file_t* f) const { zip_fclose(f); }
};

// `bytes` (which must outlive the archive) opened read-only; InputError "mesh = PATH: WHY"
// when libzip cannot read them as a zip archive.
std::unique_ptr<zip_t, ZipDiscard> open_zip_in_memory(const std::string& bytes,
                                                      const std::string& path,
                                                      const std::string& why);

}  // namespace strand::slicer
