// The streaming screen of a 3MF package before lib3mf reads it: the archive's stated sizes,
// then the XML depth, element counts and component graph of the parts lib3mf would read.
#pragma once

#include <string>

namespace strand::slicer {

// Throws InputError ("mesh = <path>: ...") for a package past any bound in mesh_3mf.h:
// inflated size, XML nesting or elements, resources, triangles, component nesting, a
// component loop, or placed objects; for a package lib3mf would not read as XML; and for a
// model whose `requiredextensions` names an extension Strand does not read (anything but
// core, materials and production) or a prefix no xmlns declares. Extensions not required
// are ignored, as PrusaSlicer does: where a model part uses a prefix no xmlns declares
// (which stops lib3mf), `bytes` is rewritten with that prefix declared on the part's root.
void screen_3mf_package(std::string& bytes, const std::string& path);

}  // namespace strand::slicer
