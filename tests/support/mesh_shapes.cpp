// Test meshes built from their parametric surfaces; writers in the formats the reader takes.
#include "tests/support/mesh_shapes.h"

#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>

#include "slicer/file_io.h"
#include "slicer/units.h"

namespace strand::testing {

using slicer::Mesh;
using slicer::Vec3;

namespace {

void quad(Mesh& m, int a, int b, int c, int d) {  // a-b-c-d counter-clockwise from outside
  m.triangles.push_back({a, b, c});
  m.triangles.push_back({a, c, d});
}

int add(Mesh& m, const Vec3& v) {
  m.vertices_mm.push_back(v);
  return static_cast<int>(m.vertices_mm.size()) - 1;
}

Vec3 normal_of(const Mesh& m, const std::array<int, 3>& t) {
  const Vec3 n =
      (m.vertices_mm[t[1]] - m.vertices_mm[t[0]]).cross(m.vertices_mm[t[2]] - m.vertices_mm[t[0]]);
  return n.norm() > 0 ? Vec3(n.normalized()) : Vec3::UnitZ();
}

}  // namespace

Mesh box_mesh(const Vec3& s) {
  Mesh m;
  for (int i = 0; i < 8; ++i)
    add(m, Vec3((i & 1) ? s.x() : 0, (i & 2) ? s.y() : 0, (i & 4) ? s.z() : 0));
  quad(m, 0, 2, 3, 1);  // bottom (z = 0), seen from below
  quad(m, 4, 5, 7, 6);  // top
  quad(m, 0, 1, 5, 4);  // y = 0
  quad(m, 2, 6, 7, 3);  // y = max
  quad(m, 0, 4, 6, 2);  // x = 0
  quad(m, 1, 3, 7, 5);  // x = max
  return m;
}

Mesh tube_mesh(double r, double bore, double h, int n) {
  Mesh m;
  auto ring = [&](double radius, double z) {
    const int first = static_cast<int>(m.vertices_mm.size());
    for (int i = 0; i < n; ++i) {
      const double a = slicer::kTwoPi * i / n;
      add(m, Vec3(radius * std::cos(a), radius * std::sin(a), z));
    }
    return first;
  };
  const int ob = ring(r, 0.0), ot = ring(r, h);
  for (int i = 0; i < n; ++i) quad(m, ob + i, ob + (i + 1) % n, ot + (i + 1) % n, ot + i);
  if (bore > 0) {
    const int ib = ring(bore, 0.0), it = ring(bore, h);
    for (int i = 0; i < n; ++i) {
      const int j = (i + 1) % n;
      quad(m, ib + j, ib + i, it + i, it + j);  // inner wall faces the axis
      quad(m, ot + i, ot + j, it + j, it + i);  // top annulus
      quad(m, ob + j, ob + i, ib + i, ib + j);  // bottom annulus
    }
    return m;
  }
  const int cb = add(m, Vec3(0, 0, 0)), ct = add(m, Vec3(0, 0, h));
  for (int i = 0; i < n; ++i) {
    m.triangles.push_back({cb, ob + (i + 1) % n, ob + i});
    m.triangles.push_back({ct, ot + i, ot + (i + 1) % n});
  }
  return m;
}

Mesh torus_mesh(double R, double r, int nu, int nv) {
  Mesh m;
  for (int i = 0; i < nu; ++i) {
    const double u = slicer::kTwoPi * i / nu;
    for (int j = 0; j < nv; ++j) {
      const double v = slicer::kTwoPi * j / nv;
      const double w = R + r * std::cos(v);
      add(m, Vec3(w * std::cos(u), w * std::sin(u), r + r * std::sin(v)));
    }
  }
  auto id = [&](int i, int j) { return (i % nu) * nv + (j % nv); };
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) quad(m, id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
  }
  return m;
}

namespace {

// `part` moved by `at` (after turning its z axis to `axis`), inside out when `cavity`, added.
void append(Mesh& m, const Mesh& part, const Vec3& at, bool cavity, const Eigen::Matrix3d& turn) {
  const int base = static_cast<int>(m.vertices_mm.size());
  for (const Vec3& v : part.vertices_mm) m.vertices_mm.push_back(turn * v + at);
  for (auto t : part.triangles) {
    if (cavity) std::swap(t[1], t[2]);
    m.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  }
}

const Eigen::Matrix3d kUpright = Eigen::Matrix3d::Identity();

Mesh sphere_mesh(double r, int rings, int segments) {
  Mesh m;
  const int south = add(m, Vec3(0, 0, -r));
  for (int i = 1; i < rings; ++i) {
    const double lat = -slicer::kPi / 2 + slicer::kPi * i / rings;
    for (int j = 0; j < segments; ++j) {
      const double lon = slicer::kTwoPi * j / segments;
      add(m, r * Vec3(std::cos(lat) * std::cos(lon), std::cos(lat) * std::sin(lon), std::sin(lat)));
    }
  }
  const int north = add(m, Vec3(0, 0, r));
  auto id = [&](int i, int j) { return 1 + (i - 1) * segments + (j % segments); };
  for (int j = 0; j < segments; ++j) {
    m.triangles.push_back({south, id(1, j + 1), id(1, j)});
    m.triangles.push_back({north, id(rings - 1, j), id(rings - 1, j + 1)});
    for (int i = 1; i + 1 < rings; ++i) quad(m, id(i, j), id(i, j + 1), id(i + 1, j + 1), id(i + 1, j));
  }
  return m;
}

}  // namespace

Mesh holed_plate_mesh() {
  Mesh m = box_mesh(Vec3(30, 20, 3));
  append(m, tube_mesh(2.8, 0, 3, 48), Vec3(13.6, 9.9, 0), true, kUpright);
  append(m, tube_mesh(2.7, 0, 3, 48), Vec3(26.0, 14.4, 0), true, kUpright);
  append(m, tube_mesh(2.8, 0, 3, 48), Vec3(21.5, 9.0, 0), true, kUpright);
  return m;
}

Mesh genus3_block_mesh() {
  Mesh m = box_mesh(Vec3(30, 24, 12));
  append(m, tube_mesh(2.6, 0, 12, 48), Vec3(16.0, 7.5, 0), true, kUpright);
  append(m, tube_mesh(2.0, 0, 12, 48), Vec3(22.9, 6.1, 0), true, kUpright);
  Eigen::Matrix3d along_x;  // the tube's axis turned to x (x, y, z -> z, x, y)
  along_x << 0, 0, 1, 1, 0, 0, 0, 1, 0;
  append(m, tube_mesh(2.0, 0, 30, 48), Vec3(0, 19.7, 8.0), true, along_x);
  return m;
}

Mesh swiss_cheese_block_mesh() {
  Mesh m = box_mesh(Vec3(30, 24, 14));
  append(m, tube_mesh(2, 0, 14, 40), Vec3(6, 6, 0), true, kUpright);
  append(m, tube_mesh(3, 0, 14, 40), Vec3(15, 17, 0), true, kUpright);
  append(m, tube_mesh(1.5, 0, 14, 40), Vec3(25, 7, 0), true, kUpright);
  const double cavities[8][4] = {{11, 7, 4, 2.5}, {21, 12, 5, 3},   {6, 16, 9, 2},
                                 {25, 19, 9, 2},  {14, 9, 10, 1.5}, {20, 4, 11, 2},
                                 {9, 20, 4, 1.8}, {19, 6, 3, 1.5}};
  for (const auto& c : cavities)
    append(m, sphere_mesh(c[3], 12, 24), Vec3(c[0], c[1], c[2]), true, kUpright);
  return m;
}

Mesh plate_mesh(double w, double d, double sag, int nx, int ny) {
  Mesh m;
  for (int j = 0; j <= ny; ++j) {
    for (int i = 0; i <= nx; ++i) {
      const double x = -w / 2 + w * i / nx, y = -d / 2 + d * j / ny;
      add(m, Vec3(x, y, sag * (1.0 - 2.0 * (x * x + y * y) / (w * w + d * d))));
      m.uv.emplace_back(x, y);
    }
  }
  auto id = [&](int i, int j) { return j * (nx + 1) + i; };
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) quad(m, id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
  }
  return m;
}

namespace {

// The patch frame: columns across, along (the workpiece z made perpendicular to facing), facing.
Eigen::Matrix3d patch_frame(const Vec3& facing) {
  const Vec3 f = facing.normalized();
  Vec3 along = Vec3::UnitZ() - Vec3::UnitZ().dot(f) * f;
  if (along.norm() < 1e-6) along = Vec3::UnitY() - Vec3::UnitY().dot(f) * f;
  along.normalize();
  Eigen::Matrix3d m;
  m.col(0) = along.cross(f);
  m.col(1) = along;
  m.col(2) = f;
  return m;
}

// A grid of (rows + 1) x (cols + 1) points p(i, j), triangulated with each triangle turned
// so its normal agrees with `outward` at its first corner.
template <class P, class N>
Mesh grid_mesh(int rows, int cols, P p, N outward) {
  Mesh m;
  for (int i = 0; i <= rows; ++i)
    for (int j = 0; j <= cols; ++j) add(m, p(i, j));
  auto id = [&](int i, int j) { return i * (cols + 1) + j; };
  auto tri = [&](int a, int b, int c) {
    const std::array<int, 3> t{a, b, c};
    if (normal_of(m, t).dot(outward(m.vertices_mm[a])) < 0) m.triangles.push_back({a, c, b});
    else m.triangles.push_back(t);
  };
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < cols; ++j) {
      tri(id(i, j), id(i + 1, j), id(i + 1, j + 1));
      tri(id(i, j), id(i + 1, j + 1), id(i, j + 1));
    }
  }
  return m;
}

}  // namespace

Mesh sphere_cap_mesh(const Vec3& centre, const Vec3& facing, double r, double half_angle_deg,
                     int rings, int segments) {
  const Eigen::Matrix3d f = patch_frame(facing);
  Mesh m;
  const int apex = add(m, centre + r * f.col(2));
  const double cap = slicer::deg_to_rad(half_angle_deg);
  for (int i = 1; i <= rings; ++i) {
    const double phi = cap * i / rings;
    for (int j = 0; j < segments; ++j) {
      const double lam = slicer::kTwoPi * j / segments;
      add(m, centre + r * (std::cos(phi) * f.col(2) +
                           std::sin(phi) * (std::cos(lam) * f.col(0) + std::sin(lam) * f.col(1))));
    }
  }
  auto id = [&](int i, int j) { return 1 + (i - 1) * segments + (j % segments); };
  for (int j = 0; j < segments; ++j) m.triangles.push_back({apex, id(1, j), id(1, j + 1)});
  for (int i = 1; i < rings; ++i)
    for (int j = 0; j < segments; ++j) quad(m, id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
  return m;
}

Mesh saddle_mesh(const Vec3& centre, const Vec3& facing, double w, double r, int n) {
  const Eigen::Matrix3d f = patch_frame(facing);
  const auto at = [&](int i, int j) {
    const double a = -w / 2 + w * j / n, b = -w / 2 + w * i / n;
    return Vec3(centre + a * f.col(0) + b * f.col(1) + (a * a - b * b) / (2 * r) * f.col(2));
  };
  return grid_mesh(n, n, at, [&](const Vec3&) { return Vec3(f.col(2)); });
}

Mesh trough_mesh(const Vec3& centre, const Vec3& facing, double r, double l, int arcs,
                 int lengths) {
  const Eigen::Matrix3d f = patch_frame(facing);
  const Vec3 axis_point = centre + r * f.col(2);  // the pipe's axis through its centre line
  const auto at = [&](int i, int j) {
    const double phi = -slicer::kPi / 2 + slicer::kPi * j / arcs, s = -l / 2 + l * i / lengths;
    return Vec3(axis_point + r * (std::sin(phi) * f.col(0) - std::cos(phi) * f.col(2)) +
                s * f.col(1));
  };
  // The inside faces the pipe's axis.
  const auto inward = [&](const Vec3& p) {
    const Vec3 d = axis_point - p;
    return Vec3(d - d.dot(f.col(1)) * f.col(1));
  };
  return grid_mesh(lengths, arcs, at, inward);
}

void write_binary_stl(const Mesh& m, const std::string& path) {
  const std::string title = "strand test mesh (mm)";
  std::string out = title + std::string(80 - title.size(), ' ');  // the 80-byte header
  auto put = [&](const void* p, std::size_t n) { out.append(static_cast<const char*>(p), n); };
  const std::uint32_t count = static_cast<std::uint32_t>(m.triangles.size());
  put(&count, 4);
  for (const auto& t : m.triangles) {
    const Vec3 n = normal_of(m, t);
    for (int k = 0; k < 3; ++k) {
      const float f = static_cast<float>(n[k]);
      put(&f, 4);
    }
    for (int c = 0; c < 3; ++c) {
      for (int k = 0; k < 3; ++k) {
        const float f = static_cast<float>(m.vertices_mm[t[c]][k]);
        put(&f, 4);
      }
    }
    const std::uint16_t attr = 0;
    put(&attr, 2);
  }
  slicer::write_file_atomic(path, out);
}

void write_ascii_stl(const Mesh& m, const std::string& path) {
  std::ostringstream o;
  o.precision(9);
  o << "solid strand\n";
  for (const auto& t : m.triangles) {
    const Vec3 n = normal_of(m, t);
    o << "facet normal " << n.x() << " " << n.y() << " " << n.z() << "\n outer loop\n";
    for (int c = 0; c < 3; ++c) {
      const Vec3& v = m.vertices_mm[t[c]];
      o << "  vertex " << v.x() << " " << v.y() << " " << v.z() << "\n";
    }
    o << " endloop\nendfacet\n";
  }
  o << "endsolid strand\n";
  slicer::write_file_atomic(path, o.str());
}

void write_obj(const Mesh& m, const std::string& path) {
  std::ostringstream o;
  o.precision(9);
  for (const Vec3& v : m.vertices_mm) o << "v " << v.x() << " " << v.y() << " " << v.z() << "\n";
  for (const auto& t : m.uv) o << "vt " << t.x() << " " << t.y() << "\n";
  for (const auto& t : m.triangles) {
    o << "f";
    for (int c = 0; c < 3; ++c) {
      o << " " << t[c] + 1;
      if (!m.uv.empty()) o << "/" << t[c] + 1;
    }
    o << "\n";
  }
  slicer::write_file_atomic(path, o.str());
}

void write_off(const Mesh& m, const std::string& path) {
  std::ostringstream o;
  o.precision(9);
  o << "OFF\n" << m.vertices_mm.size() << " " << m.triangles.size() << " 0\n";
  for (const Vec3& v : m.vertices_mm) o << v.x() << " " << v.y() << " " << v.z() << "\n";
  for (const auto& t : m.triangles) o << "3 " << t[0] << " " << t[1] << " " << t[2] << "\n";
  slicer::write_file_atomic(path, o.str());
}

std::string write_concave_bowl_obj(const std::string& dir) {
  const std::string path = dir + "/bowl.obj";
  std::ofstream o(path);
  constexpr int kN = 7;
  for (int i = 0; i < kN; ++i) {
    for (int j = 0; j < kN; ++j) {
      const double y = -15.0 + 5.0 * i, z = -15.0 + 5.0 * j;
      o << "v " << 20.0 + (y * y + z * z) / 100.0 << " " << y << " " << 40.0 + z << "\n";
    }
  }
  const auto id = [](int i, int j) { return i * kN + j + 1; };
  for (int i = 0; i + 1 < kN; ++i) {
    for (int j = 0; j + 1 < kN; ++j) {  // counter-clockwise in (y, z): normals along +x
      o << "f " << id(i, j) << " " << id(i + 1, j) << " " << id(i + 1, j + 1) << "\n";
      o << "f " << id(i, j) << " " << id(i + 1, j + 1) << " " << id(i, j + 1) << "\n";
    }
  }
  return path;
}

slicer::Mesh with_shell(slicer::Mesh a, const slicer::Mesh& b, const slicer::Vec3& offset) {
  const int base = static_cast<int>(a.vertices_mm.size());
  for (const auto& v : b.vertices_mm) a.vertices_mm.push_back(v + offset);
  for (const auto& t : b.triangles) a.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  return a;
}

}  // namespace strand::testing
