// 3MF build items flattened into one triangle mesh through lib3mf's C interface.
#include "slicer/mesh_3mf.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <utility>
#include <vector>

#include "Model/COM/NMR_DLLInterfaces.h"
#include "slicer/file_io.h"
#include "slicer/input_error.h"
#include "slicer/mesh_3mf_screen.h"
#include "slicer/mesh_io.h"

namespace strand::slicer {

namespace {

using Affine = Eigen::Affine3d;

// Triangles [first, end) of `all` with the vertices they use (an item's vertices are
// contiguous in `all`, copied in order).
Mesh sub_mesh(const Mesh& all, std::size_t first, std::size_t end) {
  int lo = std::numeric_limits<int>::max(), hi = -1;
  for (std::size_t t = first; t < end; ++t) {
    for (int v : all.triangles[t]) lo = std::min(lo, v), hi = std::max(hi, v);
  }
  Mesh m;
  m.vertices_mm.assign(all.vertices_mm.begin() + lo, all.vertices_mm.begin() + hi + 1);
  for (std::size_t t = first; t < end; ++t) {
    const auto& f = all.triangles[t];
    m.triangles.push_back({f[0] - lo, f[1] - lo, f[2] - lo});
  }
  return m;
}

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

class Reader3mf {
 public:
  explicit Reader3mf(std::string path) : path_(std::move(path)) {}

  Mesh read() {
    // lib3mf reads the very bytes screened here (the file is read once).
    std::string bytes = read_file(path_);
    screen_3mf_package(bytes, path_);
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
    if (vertices > kMaxMeshVertices) {
      fail(std::to_string(vertices) + " vertices in its build items, more than the " +
           std::to_string(kMaxMeshVertices) + " limit");
    }
    for (const auto& [id, t] : placed) {
      item_starts_.push_back(mesh_.triangles.size());
      append(id, t, 0);
    }
    if (mesh_.triangles.empty()) fail("no triangles in its build items");
    return std::move(mesh_);
  }

  // read(), then the mesh cut where each build item's triangles begin (build order).
  std::vector<Mesh> read_items() {
    const Mesh all = read();
    std::vector<Mesh> out;
    for (std::size_t k = 0; k < item_starts_.size(); ++k) {
      const std::size_t end = k + 1 < item_starts_.size() ? item_starts_[k + 1] : all.triangles.size();
      if (end == item_starts_[k]) fail("build item " + std::to_string(k) + " has no triangles");
      out.push_back(sub_mesh(all, item_starts_[k], end));
    }
    return out;
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
    if (Handle mesh; mesh_object(id, mesh)) {
      DWORD count = 0;
      NMR::lib3mf_meshobject_gettrianglecount(mesh.p, &count);
      n = count;
      NMR::lib3mf_meshobject_getvertexcount(mesh.p, &count);
      v = count;
    } else if (Handle comps; components_object(id, comps)) {
      for_each_component(comps, [&](DWORD child, NMR::PLib3MFBase*) {
        n = saturating_add(n, triangles_of(child, depth + 1));
        v = saturating_add(v, vertices_[child]);
      });
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

  // Object `id` as a mesh object in `mesh`, or false.
  bool mesh_object(DWORD id, Handle& mesh) const {
    return is_mesh(id) && NMR::lib3mf_model_getmeshobjectbyid(model_.p, id, &mesh.p) == 0;
  }

  // Object `id` as a components object in `comps`, or false.
  bool components_object(DWORD id, Handle& comps) const {
    return NMR::lib3mf_model_getcomponentsobjectbyid(model_.p, id, &comps.p) == 0 && comps.p;
  }

  // The one walk over a components object's children: visit(child id, component handle), in
  // the file's order (the counting and the copying both step down the tree through it).
  template <class Visit>
  void for_each_component(const Handle& comps, Visit&& visit) const {
    DWORD count = 0;
    NMR::lib3mf_componentsobject_getcomponentcount(comps.p, &count);
    for (DWORD i = 0; i < count; ++i) {
      Handle c;
      if (NMR::lib3mf_componentsobject_getcomponent(comps.p, i, &c.p) != 0) fail("a component");
      DWORD child = 0;
      NMR::lib3mf_component_getobjectresourceid(c.p, &child);
      visit(child, c.p);
    }
  }

  void append(DWORD id, const Affine& t, int depth) {
    if (Handle mesh; mesh_object(id, mesh)) {
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
    if (depth > kMax3mfComponentDepth || !components_object(id, comps))
      fail("object " + std::to_string(id) + " cannot be placed");
    for_each_component(comps, [&](DWORD child, NMR::PLib3MFBase* c) {
      BOOL has_transform = false;
      NMR::lib3mf_component_hastransform(c, &has_transform);
      Affine local = Affine::Identity();
      if (has_transform) {
        NMR::MODELTRANSFORM m;
        NMR::lib3mf_component_gettransform(c, &m);
        local = affine_of(m, "component");
      }
      append(child, t * local, depth + 1);
    });
  }

  std::string path_;
  Handle model_;
  double mm_per_unit_ = 1.0;
  std::map<DWORD, std::uint64_t> counted_;
  std::map<DWORD, std::uint64_t> vertices_;  // the vertices an object's copy places
  Mesh mesh_;
  std::vector<std::size_t> item_starts_;  // each build item's first triangle in mesh_
};


}  // namespace

Mesh read_3mf(const std::string& path) { return Reader3mf(path).read(); }

std::vector<Mesh> read_3mf_objects(const std::string& path) { return Reader3mf(path).read_items(); }

}  // namespace strand::slicer