// The 3MF package screen: libzip's directory, then the model parts tokenized and counted, and
// the component graph measured without expanding it (see mesh_3mf_screen.h).
#include "slicer/mesh_3mf_screen.h"

#include <zip.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdlib>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

#include "slicer/input_error.h"
#include "slicer/mesh_3mf.h"
#include "slicer/mesh_3mf_package.h"
#include "slicer/mesh_3mf_xml.h"
#include "slicer/mesh_3mf_zip.h"
#include "slicer/mesh_io.h"

namespace strand::slicer {

namespace {

// lib3mf 1.8.1 does unbounded work while it reads, before any caller sees the model: every
// build item walks its whole component tree (isValidForSlices: a 1 KB file of 40 levels of
// two components each is 2^40 visits, hours), a chain of nested components recurses once per
// level (stack), and resources, components and build items are found by linear searches
// (20,000 of them take seconds, 100,000 minutes). So the model parts are read here first by
// a tokenizer that follows lib3mf's own XML grammar (CXmlReader_Native), and the counts, the
// nesting and the component graph are bounded before lib3mf gets the bytes. Wherever this
// reading could differ from lib3mf's it errs on the side of more: elements in any namespace
// count, a reference that cannot be resolved here stands for every object with its id.

[[noreturn]] void refuse(const std::string& path, const std::string& what) {
  throw InputError("mesh = " + path + ": " + what);
}

// lib3mf's reading of an id (fnStringToUint32: strtoul, then a space or the end; its
// ULONG_MAX test never fires on a 64-bit long, so "-1" is 4294967295): the low 32 bits.
// nullopt where lib3mf throws.
std::optional<std::uint32_t> lib3mf_id(const std::string& value) {
  if (value.find('\x01') != std::string::npos) return std::nullopt;  // cut: too long
  char* end = nullptr;
  const unsigned long v = std::strtoul(value.c_str(), &end, 10);
  if (end == value.c_str() || (*end != '\0' && *end != ' ')) return std::nullopt;
  return static_cast<std::uint32_t>(v);
}

std::string without_leading_slash(const std::string& s) {
  return !s.empty() && (s[0] == '/' || s[0] == '\\') ? s.substr(1) : s;
}

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

// What the model parts hold, as far as the bounds need it.
struct PackageCounts {
  struct Object {
    std::string part;
    std::uint32_t id = 0;
  };
  struct Reference {  // a component (owner >= 0) or a build item (owner < 0)
    long long owner = -1;
    std::string part;  // the part it names (its p:path) or its own part
    std::uint32_t id = 0;
  };
  std::vector<Object> objects;
  std::vector<Reference> components, items;
  std::uint64_t elements = 0;         // start tags in model parts
  std::uint64_t lib3mf_elements = 0;  // resources (elements with an id), components, items
  std::uint64_t triangles = 0;
  std::vector<std::string> model_targets;  // 3D model relationship targets (.rels parts)
  // Per model part (archive index): prefixes used where no xmlns declares them, and where the
  // root element's name ends (declarations for them go there).
  std::map<std::size_t, std::set<std::string>> undeclared;
  std::map<std::size_t, std::size_t> root_name_end;
};

// Namespaces Strand reads, or may ignore without losing geometry (colours, textures, the
// production extension's UUIDs and part paths, which lib3mf resolves). A file that requires
// any other extension is refused: its geometry may be in it (slices, beams) or depend on it.
bool supported_namespace(const std::string& ns) {
  return ns == "http://schemas.microsoft.com/3dmanufacturing/core/2015/02" ||
         ns == "http://schemas.microsoft.com/3dmanufacturing/material/2015/02" ||
         ns == "http://schemas.microsoft.com/3dmanufacturing/production/2015/06";
}

inline constexpr const char* kModelRelationship =
    "http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel";

// Reads one entry's tags into `counts`; `role` says which kind of part it is.
class PartSink : public XmlSink {
 public:
  enum class Role { Model, Relationships, Other };
  PartSink(PackageCounts& counts, std::string part, std::size_t index, Role role,
           const std::string& path)
      : counts_(counts), part_(std::move(part)), index_(index), role_(role), path_(path) {}

  void start(const std::string& name, const std::string& prefix,
             const std::vector<XmlAttr>& attrs, bool self_closing) override {
    if (role_ == Role::Relationships && name == "Relationship") relationship(attrs);
    std::vector<long long> owners;
    if (role_ == Role::Model) {
      namespaces(name, prefix, attrs);
      model_element(name, attrs, owners);
    }
    if (self_closing) {
      if (role_ == Role::Model) scopes_.pop_back();
      return;
    }
    if (stack_.size() >= static_cast<std::size_t>(kMax3mfXmlDepth)) {
      refuse(path_, "'" + part_ + "' nests its XML elements deeper than " +
                        std::to_string(kMax3mfXmlDepth) + " levels");
    }
    stack_.push_back(std::move(owners));
  }
  void end() override {
    if (!stack_.empty()) stack_.pop_back();
    if (!scopes_.empty()) scopes_.pop_back();
  }

 private:
  using Scope = std::vector<std::pair<std::string, std::string>>;  // prefix, namespace

  const std::string* resolve(const std::string& prefix) const {
    for (auto s = scopes_.rbegin(); s != scopes_.rend(); ++s) {
      for (const auto& [p, ns] : *s) {
        if (p == prefix) return &ns;
      }
    }
    return nullptr;
  }

  // The element's namespace declarations opened, its prefixes and its attributes' looked
  // up (one lib3mf cannot resolve stops its reading: "Could not get XML Namespace"), and on
  // the root the required extensions checked.
  void namespaces(const std::string& name, const std::string& prefix,
                  const std::vector<XmlAttr>& attrs) {
    Scope scope;
    for (const auto& a : attrs) {
      if (a.prefix == "xmlns") scope.emplace_back(a.name, a.value);
    }
    const bool root = scopes_.empty();
    scopes_.push_back(std::move(scope));
    auto& undeclared = counts_.undeclared[index_];
    const auto use = [&](const std::string& p) {
      if (!p.empty() && p != "xml" && p != "xmlns" && !resolve(p) && undeclared.size() < 64)
        undeclared.insert(p);
    };
    use(prefix);
    for (const auto& a : attrs) use(a.prefix);
    if (!root || name != "model" || !prefix.empty()) return;
    for (const auto& a : attrs) {
      if (a.prefixed || a.name != "requiredextensions") continue;
      std::istringstream words(a.value);
      for (std::string p; words >> p;) {
        const std::string* ns = resolve(p);
        if (!ns) {
          refuse(path_, "'" + part_ + "' requires the extension of prefix '" + p.substr(0, 40) +
                            "', which no xmlns:" + p.substr(0, 40) + " declares");
        }
        if (!supported_namespace(*ns)) {
          refuse(path_, "the file requires the 3MF extension " + ns->substr(0, 200) +
                            " (requiredextensions '" + p.substr(0, 40) +
                            "'), which Strand does not read");
        }
      }
    }
  }

  void relationship(const std::vector<XmlAttr>& attrs) {
    bool model = false;
    for (const auto& a : attrs)
      model = model || (!a.prefixed && a.name == "Type" && a.value == kModelRelationship);
    if (!model) return;
    for (const auto& a : attrs) {
      if (!a.prefixed && a.name == "Target") counts_.model_targets.push_back(a.value);
    }
  }

  void model_element(const std::string& name, const std::vector<XmlAttr>& attrs,
                     std::vector<long long>& owners) {
    if (++counts_.elements > kMax3mfXmlElements) {
      refuse(path_, "the model has more than " + std::to_string(kMax3mfXmlElements) +
                        " XML elements (vertices, triangles and the rest)");
    }
    std::vector<std::uint32_t> ids, object_ids;
    std::vector<std::string> paths;
    for (const auto& a : attrs) {
      if (!a.prefixed && a.name == "id") {
        if (const auto id = lib3mf_id(a.value)) ids.push_back(*id);
      }
      if (!a.prefixed && a.name == "objectid") {
        if (const auto id = lib3mf_id(a.value)) object_ids.push_back(*id);
      }
      if (a.name == "path")
        paths.push_back("/" + without_leading_slash(a.value));  // as part_ is named
    }
    const bool resource = std::any_of(
        attrs.begin(), attrs.end(), [](const XmlAttr& a) { return !a.prefixed && a.name == "id"; });
    const bool reference = name == "component" || name == "item";
    if (resource || reference) {
      if (++counts_.lib3mf_elements > kMax3mfResources) {
        refuse(path_,
               "the model has more than " + std::to_string(kMax3mfResources) +
                   " resources, components and build items (lib3mf's reading grows with their "
                   "square)");
      }
    }
    if (name == "object") {
      for (const std::uint32_t id : ids) {
        owners.push_back(static_cast<long long>(counts_.objects.size()));
        counts_.objects.push_back({part_, id});
      }
    } else if (name == "triangle") {
      ++counts_.triangles;
    } else if (reference) {
      if (paths.empty()) paths.push_back(part_);
      std::vector<long long> owner_objects{-1};
      if (name == "component") {
        owner_objects.clear();
        for (auto level = stack_.rbegin(); level != stack_.rend(); ++level) {
          if (!level->empty()) {
            owner_objects = *level;
            break;
          }
        }
      }
      auto& list = name == "component" ? counts_.components : counts_.items;
      for (const long long owner : owner_objects) {
        for (const auto& part : paths) {
          for (const std::uint32_t id : object_ids) list.push_back({owner, part, id});
        }
      }
    }
  }

  PackageCounts& counts_;
  std::string part_;
  std::size_t index_;  // in the archive
  Role role_;
  const std::string& path_;
  std::vector<std::vector<long long>> stack_;  // per open element: the objects it opens
  std::vector<Scope> scopes_;                  // per open element of a model part
};

// Component nesting and the objects every build item places (each nested copy counted), from
// the counts: refuses a loop, nesting past kMax3mfComponentDepth and more than
// kMax3mfPlacements placed objects, without expanding anything (each object visited once).
void check_component_graph(const PackageCounts& c, const std::string& path) {
  // A reference names a group: the objects with its part and id, or, when none has that part
  // (a p:path lib3mf may resolve otherwise), every object with its id.
  std::map<std::pair<std::string, std::uint32_t>, std::size_t> by_key;
  std::map<std::uint32_t, std::size_t> by_id;
  std::vector<std::vector<std::size_t>> groups;
  for (std::size_t i = 0; i < c.objects.size(); ++i) {
    const auto [key, new_key] =
        by_key.try_emplace({c.objects[i].part, c.objects[i].id}, groups.size());
    if (new_key) groups.emplace_back();
    groups[key->second].push_back(i);
    const auto [id, new_id] = by_id.try_emplace(c.objects[i].id, groups.size());
    if (new_id) groups.emplace_back();
    groups[id->second].push_back(i);
  }
  const auto resolve = [&](const PackageCounts::Reference& r) -> std::optional<std::size_t> {
    if (const auto it = by_key.find({r.part, r.id}); it != by_key.end()) return it->second;
    if (const auto it = by_id.find(r.id); it != by_id.end()) return it->second;
    return std::nullopt;  // lib3mf refuses the file: nothing to expand
  };
  std::vector<std::vector<std::size_t>> children(c.objects.size());  // groups
  for (const auto& r : c.components) {
    if (r.owner < 0) continue;
    if (const auto g = resolve(r)) children[static_cast<std::size_t>(r.owner)].push_back(*g);
  }
  struct Measure {
    char state = 0;            // 0 new, 1 on the current path, 2 done
    int height = 0;            // component levels below
    std::uint64_t placed = 0;  // objects placed by placing it, itself included
  };
  std::vector<Measure> object(c.objects.size()), group(groups.size());
  constexpr std::uint64_t kSaturated = std::numeric_limits<std::uint64_t>::max();
  const auto add = [&](std::uint64_t a, std::uint64_t b) {
    return a > kSaturated - b ? kSaturated : a + b;
  };
  const std::string nesting =
      "components nest deeper than " + std::to_string(kMax3mfComponentDepth) + " levels";
  const std::string loop = "components refer to each other in a loop";
  std::function<void(std::size_t, int)> visit_group;
  const std::function<void(std::size_t, int)> visit_object = [&](std::size_t n, int depth) {
    if (object[n].state == 2) return;
    if (object[n].state == 1) refuse(path, loop);
    if (depth > kMax3mfComponentDepth) refuse(path, nesting);  // also bounds this recursion
    object[n].state = 1;
    Measure m{2, 0, 1};
    for (const std::size_t g : children[n]) {
      visit_group(g, depth + 1);
      m.height = std::max(m.height, group[g].height + 1);
      m.placed = add(m.placed, group[g].placed);
    }
    object[n] = m;
  };
  visit_group = [&](std::size_t g, int depth) {
    if (group[g].state == 2) return;
    if (group[g].state == 1) refuse(path, loop);
    group[g].state = 1;
    Measure m{2, 0, 0};
    for (const std::size_t n : groups[g]) {
      visit_object(n, depth);
      m.height = std::max(m.height, object[n].height);
      m.placed = add(m.placed, object[n].placed);
    }
    group[g] = m;
  };
  std::uint64_t total = 0;
  for (const auto& r : c.items) {
    const auto g = resolve(r);
    if (!g) continue;
    visit_group(*g, 0);
    if (group[*g].height > kMax3mfComponentDepth) refuse(path, nesting);
    total = add(total, group[*g].placed);
  }
  if (total > kMax3mfPlacements) {
    refuse(path, "its build items place " +
                     (total == kSaturated ? std::string("more than 2^64") : std::to_string(total)) +
                     " objects, each nested component copy counted; at most " +
                     std::to_string(kMax3mfPlacements) + " are accepted");
  }
}

}  // namespace

// The archive as libzip (lib3mf's zip library) lists it: stated sizes summed and bounded,
// then the parts lib3mf reads as XML inflated (bounded by their stated sizes) and tokenized.
void screen_3mf_package(std::string& bytes, const std::string& path) {
  auto zip = open_zip_in_memory(bytes, path, "not a 3MF file (a 3MF is a zip archive)");
  const zip_int64_t count = zip_get_num_entries(zip.get(), 0);
  std::vector<std::string> names;
  std::vector<std::uint64_t> sizes;
  std::uint64_t total = 0;
  for (zip_int64_t i = 0; i < count; ++i) {
    const auto index = static_cast<zip_uint64_t>(i);
    const char* name = zip_get_name(zip.get(), index, ZIP_FL_ENC_GUESS);
    zip_stat_t st;
    zip_stat_init(&st);
    std::uint64_t size = 0;
    if (zip_stat_index(zip.get(), index, 0, &st) == 0 && (st.valid & ZIP_STAT_SIZE)) size = st.size;
    names.emplace_back(name ? name : "");
    sizes.push_back(size);
    total = total > std::numeric_limits<std::uint64_t>::max() - size
                ? std::numeric_limits<std::uint64_t>::max()
                : total + size;
  }
  if (total > kMax3mfUncompressedBytes) {
    refuse(path, "the archive inflates to " + std::to_string(total >> 20) + " MiB, more than the " +
                     std::to_string(kMax3mfUncompressedBytes >> 20) + " MiB limit");
  }
  PackageCounts counts;
  const auto scan = [&](std::size_t i, PartSink::Role role) {
    PartSink sink(counts, "/" + without_leading_slash(names[i]), i, role, path);
    XmlTokens tokens(sink);
    std::unique_ptr<zip_file_t, ZipFileClose> file(
        zip_fopen_index(zip.get(), static_cast<zip_uint64_t>(i), 0));
    if (!file) refuse(path, "cannot inflate '" + names[i] + "' in the archive");
    std::vector<char> buffer(1 << 16);
    std::uint64_t read = 0;
    for (;;) {
      const zip_int64_t n = zip_fread(file.get(), buffer.data(), buffer.size());
      if (n < 0) refuse(path, "'" + names[i] + "' in the archive is damaged (it does not inflate)");
      if (n == 0) break;
      read += static_cast<std::uint64_t>(n);
      if (read > sizes[i])
        refuse(path, "'" + names[i] + "' inflates past the size the archive states");
      try {
        tokens.feed(buffer.data(), static_cast<std::size_t>(n));
      } catch (const std::length_error&) {
        refuse(path, "an element in '" + names[i] +
                         "' repeats its attributes (or has more than 64 ids, namespace "
                         "declarations and prefixed attributes)");
      }
      if (tokens.broken()) break;
    }
    if (tokens.broken())
      refuse(path, "'" + names[i] + "' is not well-formed XML as lib3mf reads it");
    counts.root_name_end[i] = tokens.root_name_end();
  };
  std::vector<char> model(names.size(), 0);
  for (std::size_t i = 0; i < names.size(); ++i) {
    std::string lower = names[i];
    std::transform(lower.begin(), lower.end(), lower.begin(),
                   [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
    if (ends_with(lower, ".rels")) scan(i, PartSink::Role::Relationships);
    if (names[i] == "[Content_Types].xml") scan(i, PartSink::Role::Other);
    if (ends_with(lower, ".model")) model[i] = 1;
  }
  // Every part a 3D model relationship could name, however its target is resolved.
  for (const std::string& target : counts.model_targets) {
    const std::string bare = without_leading_slash(target);
    for (std::size_t i = 0; i < names.size(); ++i) {
      if (!bare.empty() && (names[i] == bare || ends_with(names[i], "/" + bare))) model[i] = 1;
    }
  }
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (model[i]) scan(i, PartSink::Role::Model);
  }
  if (counts.triangles > kMaxMeshTriangles) {
    refuse(path, std::to_string(counts.triangles) + " triangles in the file; at most " +
                     std::to_string(kMaxMeshTriangles) + " are accepted");
  }
  check_component_graph(counts, path);
  std::vector<PrefixDeclarations> declare;
  for (const auto& [i, prefixes] : counts.undeclared) {
    if (!prefixes.empty()) declare.push_back({i, sizes[i], prefixes, counts.root_name_end[i]});
  }
  if (declare.empty()) return;
  zip.reset();
  bytes = with_prefixes_declared(bytes, declare, path);
}

}  // namespace strand::slicer
