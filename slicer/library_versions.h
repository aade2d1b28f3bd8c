// The versions of the libraries the core was built with (`strand --version`).
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace strand::slicer {

// (library, version) pairs, in a fixed order: CGAL, OpenMesh, Clipper, potrace, pugixml,
// Eigen, nlohmann_json. Versions come from the headers compiled in, potrace's from the library
// loaded at run time.
std::vector<std::pair<std::string, std::string>> core_library_versions();

}  // namespace strand::slicer
