// 3MF build items flattened into one triangle mesh through lib3mf's C interface.
#include "slicer/mesh_3mf.h"

#include <zip.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <utility>
#include <vector>

#include "Model/COM/NMR_DLLInterfaces.h"
#include "slicer/file_io.h"
#include "slicer/input_error.h"
#include "slicer/mesh_io.h"

namespace strand::slicer {

namespace {

using Affine = Eigen::Affine3d;

// One lib3mf handle, released when it goes out of scope.
struct Handle {
  NMR::PLib3MFBase* p = nullptr;
  Handle() = default;
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle() {
    if (p) NMR::lib3mf_release(p);
  }
};

// ---- The package screened before lib3mf reads it ----
//
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

// Calls for the start and end tags of a document; attributes kept are those named in kKept.
struct XmlAttr {
  bool prefixed = false;
  std::string name;  // local name
  std::string value;
};

class XmlSink {
 public:
  virtual ~XmlSink() = default;
  virtual void start(const std::string& name, const std::vector<XmlAttr>& attrs,
                     bool self_closing) = 0;
  virtual void end() = 0;
};

// lib3mf's XML grammar, fed in pieces. Stops (broken()) where lib3mf's reader throws.
class XmlTokens {
 public:
  explicit XmlTokens(XmlSink& sink) : sink_(sink) {}

  void feed(const char* p, std::size_t n) {
    for (std::size_t i = 0; i < n && state_ != State::Broken; ++i) step(p[i]);
  }
  bool broken() const { return state_ == State::Broken; }

 private:
  enum class State {
    Text,
    Name,
    Comment,
    PiName,
    EndName,
    Attrs,
    AttrName,
    AttrNameSpaced,
    ValueStart,
    Value,
    CloseElement,
    ClosePi,
    Broken
  };
  static constexpr std::size_t kMaxName = 256;
  static constexpr std::size_t kMaxValue = 65536;
  static constexpr std::size_t kMaxKeptAttrs = 16;

  static bool space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }
  static bool kept(const std::string& local) {
    return local == "id" || local == "objectid" || local == "path" || local == "Type" ||
           local == "Target";
  }
  // "p:name" -> "name"; false for two colons (lib3mf refuses them).
  static bool local_name(const std::string& qualified, std::string& local, bool& prefixed) {
    const auto colon = qualified.find(':');
    if (colon != std::string::npos && qualified.find(':', colon + 1) != std::string::npos)
      return false;
    prefixed = colon != std::string::npos;
    local = prefixed ? qualified.substr(colon + 1) : qualified;
    return true;
  }
  void append(std::string& s, char c, std::size_t cap) {
    if (c == '\0') state_ = State::Broken;  // lib3mf: a name may not hold a zero byte
    if (s.size() < cap)
      s.push_back(c);
    else
      long_ = true;
  }
  void begin_element() {
    std::string local;
    bool prefixed = false;
    if (!local_name(name_, local, prefixed)) {
      state_ = State::Broken;
      return;
    }
    element_ = long_ ? std::string() : local;
    attrs_.clear();
  }
  void finish_attr() {
    std::string local;
    bool prefixed = false;
    if (!local_name(attr_name_, local, prefixed)) {
      state_ = State::Broken;
      return;
    }
    if (!in_pi_ && kept(local)) {
      if (attrs_.size() >= kMaxKeptAttrs) throw std::length_error("attributes");
      attrs_.push_back({prefixed, local, value_long_ ? std::string(1, '\x01') : value_});
    }
  }
  void finish_start(bool self_closing) {
    if (!in_pi_) sink_.start(element_, attrs_, self_closing);
    in_pi_ = false;
    state_ = State::Text;
  }

  void step(char c) {
    switch (state_) {
      case State::Text:
        if (c == '<') {
          name_.clear();
          long_ = false;
          state_ = State::Name;
        }
        return;
      case State::Name:
        if (space(c)) {
          if (name_.empty()) {
            state_ = State::Broken;
            return;
          }
          begin_element();
          if (state_ != State::Broken) state_ = State::Attrs;
        } else if (c == '?') {
          state_ = name_.empty() ? State::PiName : State::Broken;
        } else if (c == '>') {
          begin_element();
          if (state_ != State::Broken) finish_start(false);
        } else if (c == '/') {
          if (name_.empty()) {
            ends_ = 0;
            state_ = State::EndName;
          } else {
            begin_element();
            if (state_ != State::Broken) state_ = State::CloseElement;
          }
        } else {
          append(name_, c, kMaxName);
          if (name_ == "!--") {
            comment_ = 0;
            state_ = State::Comment;
          }
        }
        return;
      case State::Comment: {  // ends at the first "-->", as lib3mf's parseComment
        static constexpr char kEnd[3] = {'-', '-', '>'};
        if (c == kEnd[comment_]) {
          if (comment_ == 2)
            state_ = State::Text;
          else
            ++comment_;
        } else if (c != '-') {
          comment_ = 0;
        }
        return;
      }
      case State::PiName:
        if (space(c)) {
          if (name_.empty())
            state_ = State::Broken;
          else
            in_pi_ = true, attrs_.clear(), state_ = State::Attrs;
        } else if (c == '/') {
          state_ = State::Broken;
        } else if (c == '?') {
          state_ = name_.empty() ? State::Broken : State::ClosePi;
        } else {
          append(name_, c, kMaxName);
        }
        return;
      case State::EndName:
        if (c == '/' || c == '?' || (c == '>' && ends_ == 0)) {
          state_ = State::Broken;
        } else if (c == '>') {
          sink_.end();
          state_ = State::Text;
        } else {
          ++ends_;
        }
        return;
      case State::Attrs:
        if (space(c)) return;
        if (c == '>') {
          // A processing instruction closed by '>' or '/>' alone leaves lib3mf's reader in
          // a state this tokenizer does not model: refused.
          if (in_pi_)
            state_ = State::Broken;
          else
            finish_start(false);
        } else if (c == '/') {
          state_ = in_pi_ ? State::Broken : State::CloseElement;
        } else if (c == '?') {
          state_ = in_pi_ ? State::ClosePi : State::Broken;
        } else if (c == '"' || c == '\'') {
          state_ = State::Broken;
        } else {
          attr_name_.clear();
          long_ = false;
          if (c == '=') {
            value_spaced_ = false;
            state_ = State::ValueStart;
          } else {
            append(attr_name_, c, kMaxName);
            state_ = State::AttrName;
          }
        }
        return;
      case State::AttrName:
        if (space(c)) {
          state_ = State::AttrNameSpaced;
        } else if (c == '"' || c == '\'') {
          state_ = State::Broken;
        } else if (c == '=') {
          value_spaced_ = false;
          state_ = State::ValueStart;
        } else {
          append(attr_name_, c, kMaxName);
        }
        return;
      case State::AttrNameSpaced:
        if (space(c)) return;
        if (c == '=') {
          value_spaced_ = false;
          state_ = State::ValueStart;
        } else {
          state_ = State::Broken;
        }
        return;
      case State::ValueStart:
        if (space(c)) {
          value_spaced_ = true;
        } else if (c == '"' || c == '\'') {
          quote_ = c;
          value_.clear();
          value_long_ = false;
          state_ = State::Value;
        } else if (value_spaced_) {
          state_ = State::Broken;
        }
        return;
      case State::Value:
        if (c == quote_) {
          finish_attr();
          if (state_ != State::Broken) state_ = State::Attrs;
        } else if (value_.size() < kMaxValue) {
          value_.push_back(c);
        } else {
          value_long_ = true;
        }
        return;
      case State::CloseElement:
        if (c == '>')
          finish_start(true);
        else
          state_ = State::Broken;
        return;
      case State::ClosePi:
        if (c == '>')
          in_pi_ = false, state_ = State::Text;
        else
          state_ = State::Broken;
        return;
      case State::Broken:
        return;
    }
  }

  XmlSink& sink_;
  State state_ = State::Text;
  std::string name_, element_, attr_name_, value_;
  std::vector<XmlAttr> attrs_;
  bool long_ = false, value_long_ = false, value_spaced_ = false, in_pi_ = false;
  char quote_ = '"';
  int comment_ = 0;
  std::size_t ends_ = 0;
};

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
};

inline constexpr const char* kModelRelationship =
    "http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel";

// Reads one entry's tags into `counts`; `role` says which kind of part it is.
class PartSink : public XmlSink {
 public:
  enum class Role { Model, Relationships, Other };
  PartSink(PackageCounts& counts, std::string part, Role role, const std::string& path)
      : counts_(counts), part_(std::move(part)), role_(role), path_(path) {}

  void start(const std::string& name, const std::vector<XmlAttr>& attrs,
             bool self_closing) override {
    if (role_ == Role::Relationships && name == "Relationship") relationship(attrs);
    std::vector<long long> owners;
    if (role_ == Role::Model) model_element(name, attrs, owners);
    if (self_closing) return;
    if (stack_.size() >= static_cast<std::size_t>(kMax3mfXmlDepth)) {
      refuse(path_, "'" + part_ + "' nests its XML elements deeper than " +
                        std::to_string(kMax3mfXmlDepth) + " levels");
    }
    stack_.push_back(std::move(owners));
  }
  void end() override {
    if (!stack_.empty()) stack_.pop_back();
  }

 private:
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
  Role role_;
  const std::string& path_;
  std::vector<std::vector<long long>> stack_;  // per open element: the objects it opens
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

struct ZipDiscard {
  void operator()(zip_t* z) const { zip_discard(z); }
};
struct ZipFileClose {
  void operator()(zip_file_t* f) const { zip_fclose(f); }
};

// The archive as libzip (lib3mf's zip library) lists it: stated sizes summed and bounded,
// then the parts lib3mf reads as XML inflated (bounded by their stated sizes) and tokenized.
void screen_package(const std::string& bytes, const std::string& path) {
  zip_error_t error;
  zip_error_init(&error);
  zip_source_t* source = zip_source_buffer_create(bytes.data(), bytes.size(), 0, &error);
  std::unique_ptr<zip_t, ZipDiscard> zip(source ? zip_open_from_source(source, ZIP_RDONLY, &error)
                                                : nullptr);
  zip_error_fini(&error);
  if (!zip) {
    if (source) zip_source_free(source);
    refuse(path, "not a 3MF file (a 3MF is a zip archive)");
  }
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
    PartSink sink(counts, "/" + without_leading_slash(names[i]), role, path);
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
        refuse(path, "an element in '" + names[i] + "' repeats its attributes");
      }
      if (tokens.broken()) break;
    }
    if (tokens.broken())
      refuse(path, "'" + names[i] + "' is not well-formed XML as lib3mf reads it");
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
}

class Reader3mf {
 public:
  explicit Reader3mf(std::string path) : path_(std::move(path)) {}

  Mesh read() {
    // lib3mf reads the very bytes screened here (the file is read once).
    std::string bytes = read_file(path_);
    screen_package(bytes, path_);
    if (NMR::lib3mf_createmodel(&model_.p) != 0) fail("lib3mf could not start");
    Handle reader;
    if (NMR::lib3mf_model_queryreader(model_.p, "3mf", &reader.p) != 0)
      fail("lib3mf has no 3MF reader");
    if (NMR::lib3mf_reader_readfrombuffer(reader.p, reinterpret_cast<BYTE*>(bytes.data()),
                                          bytes.size()) != 0)
      fail("not a readable 3MF file (" + last_error(reader.p) + ")");
    DWORD unit = NMR::MODELUNIT_MILLIMETER;
    NMR::lib3mf_model_getunit(model_.p, &unit);
    mm_per_unit_ = mm_per_unit(unit);

    // The items to place, and the triangles they instantiate, counted before any copy.
    Handle items;
    if (NMR::lib3mf_model_getbuilditems(model_.p, &items.p) != 0) fail("no build items");
    std::vector<std::pair<DWORD, Affine>> placed;
    std::uint64_t triangles = 0, vertices = 0;
    for (BOOL has = false; NMR::lib3mf_builditemiterator_movenext(items.p, &has) == 0 && has;) {
      Handle item;
      if (NMR::lib3mf_builditemiterator_getcurrent(items.p, &item.p) != 0) fail("a build item");
      DWORD id = 0;
      if (NMR::lib3mf_builditem_getobjectresourceid(item.p, &id) != 0)
        fail("a build item without an object");
      BOOL has_transform = false;
      NMR::lib3mf_builditem_hasobjecttransform(item.p, &has_transform);
      Affine t = Affine::Identity();
      if (has_transform) {
        NMR::MODELTRANSFORM m;
        NMR::lib3mf_builditem_getobjecttransform(item.p, &m);
        t = affine_of(m, "build item");
      }
      triangles = saturating_add(triangles, triangles_of(id, 0));
      vertices = saturating_add(vertices, vertices_[id]);
      placed.emplace_back(id, t);
    }
    if (triangles > kMaxMeshTriangles) {
      fail(std::to_string(triangles) + " triangles in its build items, more than the " +
           std::to_string(kMaxMeshTriangles) + " limit");
    }
    // Every placed copy copies its object's vertices, used or not.
    if (vertices > 3 * kMaxMeshTriangles) {
      fail(std::to_string(vertices) + " vertices in its build items, more than the " +
           std::to_string(3 * kMaxMeshTriangles) + " limit");
    }
    for (const auto& [id, t] : placed) append(id, t, 0);
    if (mesh_.triangles.empty()) fail("no triangles in its build items");
    return std::move(mesh_);
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw InputError("mesh = " + path_ + ": " + what);
  }

  static std::string last_error(NMR::PLib3MFBase* p) {
    DWORD code = 0;
    LPCSTR message = nullptr;
    NMR::lib3mf_getlasterror(p, &code, &message);
    std::string s = message ? message : "error " + std::to_string(code);
    for (char& c : s) {
      if (static_cast<unsigned char>(c) < 0x20) c = ' ';
    }
    return s.substr(0, 200);
  }

  double mm_per_unit(DWORD unit) const {
    switch (unit) {
      case NMR::MODELUNIT_MICROMETER:
        return 1e-3;
      case NMR::MODELUNIT_MILLIMETER:
        return 1.0;
      case NMR::MODELUNIT_CENTIMETER:
        return 10.0;
      case NMR::MODELUNIT_INCH:
        return 25.4;
      case NMR::MODELUNIT_FOOT:
        return 304.8;
      case NMR::MODELUNIT_METER:
        return 1000.0;
      default:
        fail("unknown unit " + std::to_string(unit));
    }
  }

  static std::uint64_t saturating_add(std::uint64_t a, std::uint64_t b) {
    return a > UINT64_MAX - b ? UINT64_MAX : a + b;
  }

  Affine affine_of(const NMR::MODELTRANSFORM& m, const char* where) const {
    Affine t = Affine::Identity();
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 4; ++c) {
        const double v = m.m_fFields[r][c];
        if (!std::isfinite(v)) fail(std::string("a non-finite transform in a ") + where);
        t.matrix()(r, c) = v;
      }
    }
    return t;
  }

  // Triangles object `id` instantiates, components included (memoised, so a graph that fans
  // out 2^64 times is counted in one visit per object, saturating).
  std::uint64_t triangles_of(DWORD id, int depth) {
    if (depth > kMax3mfComponentDepth) {
      fail("components nested deeper than " + std::to_string(kMax3mfComponentDepth) +
           " levels (or a loop)");
    }
    if (const auto it = counted_.find(id); it != counted_.end()) return it->second;
    std::uint64_t n = 0, v = 0;
    if (Handle mesh;
        is_mesh(id) && NMR::lib3mf_model_getmeshobjectbyid(model_.p, id, &mesh.p) == 0) {
      DWORD count = 0;
      NMR::lib3mf_meshobject_gettrianglecount(mesh.p, &count);
      n = count;
      NMR::lib3mf_meshobject_getvertexcount(mesh.p, &count);
      v = count;
    } else if (Handle comps;
               NMR::lib3mf_model_getcomponentsobjectbyid(model_.p, id, &comps.p) == 0 && comps.p) {
      DWORD count = 0;
      NMR::lib3mf_componentsobject_getcomponentcount(comps.p, &count);
      for (DWORD i = 0; i < count; ++i) {
        Handle c;
        if (NMR::lib3mf_componentsobject_getcomponent(comps.p, i, &c.p) != 0) fail("a component");
        DWORD child = 0;
        NMR::lib3mf_component_getobjectresourceid(c.p, &child);
        n = saturating_add(n, triangles_of(child, depth + 1));
        v = saturating_add(v, vertices_[child]);
      }
    } else {
      fail("a build item or component names object " + std::to_string(id) +
           ", which is not a mesh or components object");
    }
    counted_[id] = n;
    vertices_[id] = v;
    return n;
  }

  bool is_mesh(DWORD id) const {
    Handle r;
    if (NMR::lib3mf_model_getresourcebyid(model_.p, id, &r.p) != 0) return false;
    BOOL mesh = false;
    if (NMR::lib3mf_object_ismeshobject(r.p, &mesh) != 0) return false;
    return mesh;
  }

  void append(DWORD id, const Affine& t, int depth) {
    if (Handle mesh;
        is_mesh(id) && NMR::lib3mf_model_getmeshobjectbyid(model_.p, id, &mesh.p) == 0) {
      DWORD nv = 0, nt = 0;
      NMR::lib3mf_meshobject_getvertexcount(mesh.p, &nv);
      NMR::lib3mf_meshobject_gettrianglecount(mesh.p, &nt);
      if (nt == 0) return;
      std::vector<NMR::MODELMESHVERTEX> v(nv);
      std::vector<NMR::MODELMESHTRIANGLE> tri(nt);
      DWORD got = 0;
      if (nv && NMR::lib3mf_meshobject_getvertices(mesh.p, v.data(), nv, &got) != 0)
        fail("vertices");
      if (NMR::lib3mf_meshobject_gettriangleindices(mesh.p, tri.data(), nt, &got) != 0)
        fail("triangles");
      const auto base = static_cast<long long>(mesh_.vertices_mm.size());
      for (const auto& p : v) {
        const Vec3 local(p.m_fPosition[0], p.m_fPosition[1], p.m_fPosition[2]);
        if (!local.allFinite()) fail("a vertex with a non-finite coordinate (NaN or inf)");
        const Vec3 world = (t * local) * mm_per_unit_;
        if (!world.allFinite()) fail("a vertex placed at a non-finite coordinate");
        mesh_.vertices_mm.push_back(world);
      }
      for (const auto& f : tri) {
        std::array<int, 3> out{};
        for (int k = 0; k < 3; ++k) {
          if (f.m_nIndices[k] >= nv) {
            fail("object " + std::to_string(id) + " has a triangle index " +
                 std::to_string(f.m_nIndices[k]) + " past its " + std::to_string(nv) + " vertices");
          }
          out[static_cast<std::size_t>(k)] = static_cast<int>(base + f.m_nIndices[k]);
        }
        // A transform that mirrors the object turns its triangles inside out; 3MF readers
        // restore the winding so the outside stays outside.
        if (t.linear().determinant() < 0) std::swap(out[1], out[2]);
        mesh_.triangles.push_back(out);
      }
      return;
    }
    Handle comps;
    if (depth > kMax3mfComponentDepth ||
        NMR::lib3mf_model_getcomponentsobjectbyid(model_.p, id, &comps.p) != 0 || !comps.p) {
      fail("object " + std::to_string(id) + " cannot be placed");
    }
    DWORD count = 0;
    NMR::lib3mf_componentsobject_getcomponentcount(comps.p, &count);
    for (DWORD i = 0; i < count; ++i) {
      Handle c;
      if (NMR::lib3mf_componentsobject_getcomponent(comps.p, i, &c.p) != 0) fail("a component");
      DWORD child = 0;
      NMR::lib3mf_component_getobjectresourceid(c.p, &child);
      BOOL has_transform = false;
      NMR::lib3mf_component_hastransform(c.p, &has_transform);
      Affine local = Affine::Identity();
      if (has_transform) {
        NMR::MODELTRANSFORM m;
        NMR::lib3mf_component_gettransform(c.p, &m);
        local = affine_of(m, "component");
      }
      append(child, t * local, depth + 1);
    }
  }

  std::string path_;
  Handle model_;
  double mm_per_unit_ = 1.0;
  std::map<DWORD, std::uint64_t> counted_;
  std::map<DWORD, std::uint64_t> vertices_;  // the vertices an object's copy places
  Mesh mesh_;
};

}  // namespace

Mesh read_3mf(const std::string& path) { return Reader3mf(path).read(); }

}  // namespace strand::slicer
