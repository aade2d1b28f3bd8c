// 3MF (3D Manufacturing Format) to Mesh with lib3mf: every build item of the file, its
// components and their transforms applied, the model's unit converted to mm, all objects in
// one mesh placed as the file places them. 3MF is +Z up like Strand.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "slicer/mesh.h"

namespace strand::slicer {

// Bounds checked before lib3mf or the copy do the work (docs/limits.md): the archive's
// uncompressed size (a 3MF is a zip: a small file may inflate to gigabytes), the nesting of
// components and the triangles all build items instantiate.
inline constexpr std::uint64_t kMax3mfUncompressedBytes = std::uint64_t{512} << 20;
inline constexpr int kMax3mfComponentDepth = 64;
// Checked on the model parts before lib3mf reads them: lib3mf 1.8.1 walks every build item's
// whole component tree while reading (a fan-out of 2^40 copies in a 1 KB file would take
// hours) and finds resources, components and build items by linear search (10,000 of them
// take about 4 s, 100,000 minutes).
inline constexpr std::uint64_t kMax3mfPlacements = 1'000'000;    // each nested copy counted
inline constexpr std::uint64_t kMax3mfResources = 10'000;        // resources, components, items
inline constexpr std::uint64_t kMax3mfXmlElements = 16'000'000;  // in the model parts
inline constexpr int kMax3mfXmlDepth = 64;  // XML element nesting of any part lib3mf reads

// Throws InputError (one line naming the file) for an archive that is not a 3MF, a model
// lib3mf refuses, a component loop or nesting past the bound, too many triangles, vertices,
// placed objects, resources or XML elements, an index out of range, a non-finite coordinate
// or transform, or a file with no triangles.
Mesh read_3mf(const std::string& path);
// The same checks, each build item kept apart in build order (its components and transforms
// applied): a multi-object print's objects (issue 33). Throws also for an item with no
// triangles.
std::vector<Mesh> read_3mf_objects(const std::string& path);

}  // namespace strand::slicer
