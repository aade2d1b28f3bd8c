// Internal-subset DTD entities of an SVG document (`<!ENTITY ns_svg "...">` as Illustrator
// writes, or whole drawings as `<!ENTITY Smile "<g>...</g>">`) expanded in the text before
// pugixml reads it, since pugixml knows only the five predefined entities.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace strand::slicer {

// Bytes the expansion may add to a document, each expanded reference counting one more
// (so entities that expand to nothing cannot make the work unbounded): "billion laughs"
// stop here with an InputError.
inline constexpr std::size_t kMaxEntityExpansion = std::size_t{16} << 20;
// Entity references inside entity values nest at most this deep.
inline constexpr int kMaxEntityDepth = 16;

struct ExpandedEntities {
  std::string text;    // the document with every declared internal entity expanded
  int references = 0;  // references expanded in the document (nested ones not counted)
  int external = 0;    // references to external entities (SYSTEM/PUBLIC), left out
};

// nullopt when the document declares no internal entities (the common case: no copy).
// Otherwise references in content and attribute values are replaced by their values (in
// attribute values with quotes and '<' escaped); comments, CDATA sections and processing
// instructions are left as they are, and so are references to undeclared entities,
// character references and the five predefined entities (pugixml reads those). Throws
// InputError naming `origin` for a reference cycle, nesting deeper than kMaxEntityDepth or
// an expansion beyond kMaxEntityExpansion.
std::optional<ExpandedEntities> expand_entities(std::string_view text, const std::string& origin);

}  // namespace strand::slicer
