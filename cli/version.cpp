#include "cli/version.h"

#include <cairo.h>
#include <oneapi/tbb/version.h>

#include <CLI/Version.hpp>

#include "slicer/library_versions.h"

namespace strand::cli {

std::string version_number() { return STRAND_VERSION; }

std::string version_text() {
  auto libraries = slicer::core_library_versions();
  libraries.emplace_back("cairo", cairo_version_string());
  libraries.emplace_back("oneTBB", TBB_VERSION_STRING);
  libraries.emplace_back("CLI11", CLI11_VERSION);
  std::string built_with;
  for (const auto& [name, version] : libraries) {
    built_with += (built_with.empty() ? "" : ", ") + name + " " + version;
  }
  return "strand " STRAND_VERSION "\nbuilt with " + built_with + "\n";
}

}  // namespace strand::cli
