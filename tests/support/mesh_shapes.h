// Closed triangle meshes with known geometry for tests, benchmarks and the sample files:
// boxes, tubes (cylinders with an optional bore), tori, a curved plate, and writers.
#pragma once

#include <string>

#include "slicer/mesh.h"

namespace strand::testing {

// Axis-aligned box from (0, 0, 0) to size, 12 triangles, outward.
slicer::Mesh box_mesh(const slicer::Vec3& size_mm);
// `b` moved by `offset` added to `a` as more triangles of one soup (no shared vertices): two
// shells that overlap without cutting each other, as in many real files.
slicer::Mesh with_shell(slicer::Mesh a, const slicer::Mesh& b, const slicer::Vec3& offset);
// Cylinder along z from z = 0 to height, radius r, `segments` around; with bore_mm > 0 a
// coaxial hole of that radius runs through it. Vertices lie on the true circles.
slicer::Mesh tube_mesh(double radius_mm, double bore_mm, double height_mm, int segments);
// Torus around the z axis resting on z = 0: ring radius R, tube radius r.
slicer::Mesh torus_mesh(double ring_mm, double tube_mm, int ring_segments, int tube_segments);
// Solids with holes, built as a box with inside-out shells inside it (the slicer's nonzero
// union makes a hole where a cavity's winding cancels the box's), each resting on z = 0:
// - a plate 30 x 20 x 3 with three through holes of radius 2.7 to 2.8 mm;
slicer::Mesh holed_plate_mesh();
// - a block 30 x 24 x 12 of genus 3: two holes through it upright and one along x;
slicer::Mesh genus3_block_mesh();
// - a Swiss-cheese block 30 x 24 x 14: three upright through holes and eight closed spherical
//   cavities of radius 1.5 to 3 mm.
slicer::Mesh swiss_cheese_block_mesh();
// Open height field z = f(x, y) over [-w/2, w/2] x [-d/2, d/2] with per-vertex UVs equal to
// (x, y): a gently curved plate substrate, z = sag * (1 - (x^2 + y^2) / (w^2 + d^2) * 2).
slicer::Mesh plate_mesh(double width_mm, double depth_mm, double sag_mm, int nx, int ny);

// Open patches for robot-held substrates (slicer/mesh_substrate.h), built in a frame with
// `facing` (unit) as its outward normal direction, the workpiece z axis made perpendicular to
// it as the second patch direction (y when facing is along z), outward triangles towards facing:
// - a sphere cap: sphere radius r, apex at centre + r * facing, half-angle deg;
slicer::Mesh sphere_cap_mesh(const slicer::Vec3& centre, const slicer::Vec3& facing, double radius_mm,
                             double half_angle_deg, int rings, int segments);
// - a saddle h = (a^2 - b^2) / (2 r) over the square [-w/2, w/2]^2 of the patch directions
//   (a across, b along the second direction), its centre at `centre`;
slicer::Mesh saddle_mesh(const slicer::Vec3& centre, const slicer::Vec3& facing, double width_mm,
                         double radius_mm, int n);
// - the inside of a half pipe (a trough) of radius r and length l along the second direction,
//   its bottom line through `centre`, open towards facing.
slicer::Mesh trough_mesh(const slicer::Vec3& centre, const slicer::Vec3& facing, double radius_mm,
                         double length_mm, int arcs, int lengths);

void write_binary_stl(const slicer::Mesh& m, const std::string& path);
void write_ascii_stl(const slicer::Mesh& m, const std::string& path);
// OBJ with vt lines when the mesh has UVs.
void write_obj(const slicer::Mesh& m, const std::string& path);
// `dir`/bowl.obj: a coarse concave bowl (6 x 6 quads, 5 mm apart, x = 20 + (y^2 + z^2) / 100
// about (20, 0, 40), normals along +x) for robot-held mesh tests; returns its path.
std::string write_concave_bowl_obj(const std::string& dir);
void write_off(const slicer::Mesh& m, const std::string& path);

}  // namespace strand::testing
