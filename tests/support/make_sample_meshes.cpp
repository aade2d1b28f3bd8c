// Writes the sample meshes in samples/meshes/ (run once by hand; the files are committed):
//   strand_make_sample_meshes path/to/samples/meshes
// or the benchmark's 100k-triangle torus (tests/bench/slice_vs_prusaslicer.sh):
//   strand_make_sample_meshes --torus-100k FILE.stl
#include <iostream>
#include <string>

#include "tests/support/mesh_shapes.h"

int main(int argc, char** argv) {
  using namespace strand::testing;
  if (argc == 3 && std::string(argv[1]) == "--torus-100k") {
    write_binary_stl(torus_mesh(45.0, 30.0, 500, 100), argv[2]);  // as mesh_slice_bench.cpp
    return 0;
  }
  if (argc != 2) {
    std::cerr << "usage: strand_make_sample_meshes DIR | --torus-100k FILE\n";
    return 2;
  }
  const std::string dir = argv[1];
  // A bone plug: a 20 mm cylinder, 12 mm tall, with a 6 mm bore for a fixation pin.
  write_binary_stl(tube_mesh(10.0, 3.0, 12.0, 128), dir + "/bone-plug.stl");
  // A torus resting on the bed: ring radius 15 mm, tube radius 5 mm.
  write_binary_stl(torus_mesh(15.0, 5.0, 64, 32), dir + "/torus.stl");
  // A gently curved plate substrate, 60 x 40 mm, 3 mm sag, UVs = (x, y) in mm.
  write_obj(plate_mesh(60.0, 40.0, 3.0, 30, 20), dir + "/curved-plate.obj");
  // A sphere cap for a robot to hold (--substrate mesh): sphere radius 40 mm, 50 deg half-angle,
  // facing the workpiece frame's +x with its apex at (20, 0, 40), as a 40 x 80 mm cylinder's
  // u = 0 line at mid-length (the mesh's coordinates are the workpiece frame on the flange).
  write_binary_stl(sphere_cap_mesh({-20.0, 0.0, 40.0}, {1.0, 0.0, 0.0}, 40.0, 50.0, 20, 72),
                   dir + "/sphere-cap.stl");
  return 0;
}
