// 3MF model parts rewritten in memory with libzip (see mesh_3mf_package.h).
#include "slicer/mesh_3mf_package.h"

#include <zip.h>

#include <algorithm>
#include <map>
#include <memory>

#include "slicer/input_error.h"
#include "slicer/mesh_3mf_zip.h"

namespace strand::slicer {

namespace {

[[noreturn]] void refuse(const std::string& path, const std::string& what) {
  throw InputError("mesh = " + path + ": " + what);
}


struct ZipSourceFree {
  void operator()(zip_source_t* s) const { zip_source_free(s); }
};

// Entry `index` inflated whole (its stated size was bounded with the archive's).
std::string inflate_entry(zip_t* zip, zip_uint64_t index, std::uint64_t size,
                          const std::string& path) {
  std::unique_ptr<zip_file_t, ZipFileClose> file(zip_fopen_index(zip, index, 0));
  std::string text(static_cast<std::size_t>(size), '\0');
  if (!file || zip_fread(file.get(), text.data(), size) != static_cast<zip_int64_t>(size))
    refuse(path, "cannot inflate a model part of the archive");
  return text;
}

// The archive `bytes` with entries replaced (index -> new content), written by libzip in
// memory (lib3mf then reads the new bytes).
std::string with_entries_replaced(const std::string& bytes,
                                  const std::map<zip_uint64_t, std::string>& entries,
                                  const std::string& path) {
  zip_error_t error;
  zip_error_init(&error);
  std::unique_ptr<zip_source_t, ZipSourceFree> source(
      zip_source_buffer_create(bytes.data(), bytes.size(), 0, &error));
  zip_error_fini(&error);
  if (!source) refuse(path, "cannot rewrite the archive");
  zip_source_keep(source.get());  // zip_close releases the archive, not the source
  zip_t* zip = zip_open_from_source(source.get(), 0, nullptr);
  if (!zip) refuse(path, "cannot rewrite the archive");
  for (const auto& [index, text] : entries) {
    zip_source_t* part = zip_source_buffer(zip, text.data(), text.size(), 0);
    if (!part || zip_file_replace(zip, index, part, 0) != 0) {
      if (part) zip_source_free(part);
      zip_discard(zip);
      refuse(path, "cannot rewrite the archive");
    }
  }
  if (zip_close(zip) != 0) {
    zip_discard(zip);
    refuse(path, "cannot rewrite the archive");
  }
  zip_stat_t st;
  zip_stat_init(&st);
  if (zip_source_stat(source.get(), &st) != 0 || zip_source_open(source.get()) != 0)
    refuse(path, "cannot rewrite the archive");
  std::string out(static_cast<std::size_t>(st.size), '\0');
  const zip_int64_t got = zip_source_read(source.get(), out.data(), st.size);
  zip_source_close(source.get());
  if (got != static_cast<zip_int64_t>(st.size)) refuse(path, "cannot rewrite the archive");
  return out;
}

// The 3MF Consortium's own Materials samples use `ms:` undeclared. Each such prefix gets a
// namespace of its own that no reader knows, so lib3mf skips those elements as an unknown
// extension's.
std::string declare_prefixes(std::string text, const std::set<std::string>& prefixes,
                             std::size_t at) {
  std::string declarations;
  for (const std::string& p : prefixes)
    declarations += " xmlns:" + p + "=\"urn:strand:undeclared-prefix:" + p + "\"";
  return text.insert(std::min(at, text.size()), declarations);
}

}  // namespace

std::string with_prefixes_declared(const std::string& bytes,
                                   const std::vector<PrefixDeclarations>& parts,
                                   const std::string& path) {
  std::map<zip_uint64_t, std::string> texts;
  {
    const auto zip = open_zip_in_memory(bytes, path, "cannot rewrite the archive");
    for (const PrefixDeclarations& p : parts) {
      const auto index = static_cast<zip_uint64_t>(p.index);
      texts[index] = declare_prefixes(inflate_entry(zip.get(), index, p.size, path), p.prefixes,
                                      p.root_name_end);
    }
  }
  return with_entries_replaced(bytes, texts, path);
}

std::unique_ptr<zip_t, ZipDiscard> open_zip_in_memory(const std::string& bytes,
                                                       const std::string& path,
                                                       const std::string& why) {
  zip_error_t error;
  zip_error_init(&error);
  zip_source_t* source = zip_source_buffer_create(bytes.data(), bytes.size(), 0, &error);
  std::unique_ptr<zip_t, ZipDiscard> zip(source ? zip_open_from_source(source, ZIP_RDONLY, &error)
                                                : nullptr);
  zip_error_fini(&error);
  if (!zip) {
    if (source) zip_source_free(source);
    refuse(path, why);
  }
  return zip;
}

}  // namespace strand::slicer
