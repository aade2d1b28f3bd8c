// `strand --version`: the program's version and the libraries it was built with.
#pragma once

#include <string>

namespace strand::cli {

// "0.1.0"
std::string version_number();

// "strand 0.1.0\n" then one line "built with CGAL 5.5.1, OpenMesh 9.0.0, ..." (ends with \n).
std::string version_text();

}  // namespace strand::cli
