#include "slicer/library_versions.h"

#include <CGAL/config.h>
#include <CGAL/version.h>
#include <OpenMesh/Core/System/config.h>
#include <potracelib.h>

#include "Model/COM/NMR_DLLInterfaces.h"

#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <polyclipping/clipper.hpp>
#include <pugixml.hpp>

namespace strand::slicer {

namespace {

std::string dotted(int major, int minor, int patch) {
  return std::to_string(major) + "." + std::to_string(minor) + "." + std::to_string(patch);
}

}  // namespace

std::vector<std::pair<std::string, std::string>> core_library_versions() {
  return {
      {"CGAL", CGAL_STRINGIZE(CGAL_VERSION)},
      {"OpenMesh", dotted(OM_GET_VER, OM_GET_MAJ, OM_GET_MIN)},
      {"Clipper", CLIPPER_VERSION},
      // "potracelib 1.16" -> "1.16"
      {"potrace",
       [] {
         const std::string v = potrace_version();
         const auto space = v.rfind(' ');
         return space == std::string::npos ? v : v.substr(space + 1);
       }()},
      {"lib3mf",
       [] {
         DWORD major = 0, minor = 0, micro = 0;
         NMR::lib3mf_getinterfaceversion(&major, &minor, &micro);
         return dotted(static_cast<int>(major), static_cast<int>(minor), static_cast<int>(micro));
       }()},
      {"pugixml",
       std::to_string(PUGIXML_VERSION / 1000) + "." + std::to_string(PUGIXML_VERSION % 1000 / 10)},
      {"Eigen", dotted(EIGEN_WORLD_VERSION, EIGEN_MAJOR_VERSION, EIGEN_MINOR_VERSION)},
      {"nlohmann_json", dotted(NLOHMANN_JSON_VERSION_MAJOR, NLOHMANN_JSON_VERSION_MINOR,
                               NLOHMANN_JSON_VERSION_PATCH)},
  };
}

}  // namespace strand::slicer
