// Rewriting model parts of a 3MF package in memory (libzip) before lib3mf reads it: the
// prefixes a part uses without declaring them, declared on its root element.
#pragma once

#include <cstddef>
#include <cstdint>
#include <set>
#include <string>
#include <vector>

namespace strand::slicer {

// One model part to rewrite: its archive index and stated (bounded) inflated size, the
// prefixes to declare and the byte offset just past its root element's name.
struct PrefixDeclarations {
  std::size_t index = 0;
  std::uint64_t size = 0;
  std::set<std::string> prefixes;
  std::size_t root_name_end = 0;
};

// The package `bytes` with each part given ` xmlns:p="urn:strand:undeclared-prefix:p"` for
// its prefixes: lib3mf stops on a prefix no xmlns declares ("Could not get XML Namespace")
// where PrusaSlicer reads on, and skips elements of a namespace it does not know. Throws
// InputError ("mesh = <path>: ...") when the archive cannot be inflated or written.
std::string with_prefixes_declared(const std::string& bytes,
                                   const std::vector<PrefixDeclarations>& parts,
                                   const std::string& path);

}  // namespace strand::slicer
