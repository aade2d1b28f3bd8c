// `--substrate mesh --substrate-mesh FILE` for robot cells: the sample job's outputs, its check
// and preview through the record beside the CSV, a tampered CSV (exit 1 naming the row), and
// the bad-input rule (exit 2, one line naming the point, no file written).
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "postprocess/preview/preview_scene.h"
#include "tests/support/cli_runner.h"
#include "tests/support/mesh_shapes.h"
#include "tests/support/png_pixels.h"
#include "tests/support/sample_jobs.h"

namespace strand::testing {
namespace {

namespace fs = std::filesystem;

const std::string kSample = "/tetrachiral-sphere-cap-robot.json";

std::size_t files_in(const std::string& dir) {
  std::size_t n = 0;
  for (const auto& e : fs::directory_iterator(dir)) n += e.path().filename().string()[0] != '.';
  return n;
}

// Meshes written in their own folder, so the output folder stays empty when a job is refused.
std::string mesh_dir() {
  static const std::string dir = [] {
    const std::string d = fresh_dir("mesh-cli-meshes");
    using slicer::Vec3;
    write_binary_stl(saddle_mesh(Vec3(20.0, 0.0, 40.0), Vec3::UnitX(), 50.0, 60.0, 40),
                     d + "/saddle.stl");
    write_binary_stl(trough_mesh(Vec3(20.0, 0.0, 40.0), Vec3::UnitX(), 10.0, 60.0, 48, 30),
                     d + "/trough.stl");
    // The sample cap 2 m further out along the flange axis: beyond any pose of the arm.
    write_binary_stl(sphere_cap_mesh(Vec3(-20.0, 0.0, 2040.0), Vec3::UnitX(), 40.0, 50.0, 12, 48),
                     d + "/far-cap.stl");
    write_binary_stl(box_mesh(Vec3(20.0, 20.0, 20.0)), d + "/box.stl");
    return d;
  }();
  return dir;
}

const std::string kScaffold =
    "scaffold --nozzle 1.2 --gap 2 --size 24x24 --layers 2 --substrate mesh --substrate-mesh ";

void expect_rejected(const std::string& args, const std::string& must_mention) {
  const auto dir = fresh_dir("mesh-cli-bad");
  const auto r = run_strand(args, dir);
  expect_input_error(r, must_mention);
  EXPECT_EQ(files_in(dir), 0u) << "no output file after: " << args;
}

TEST(MeshSubstrateCli, TheSampleJobWritesChecksAndPreviewsOnItsMesh) {
  const auto dir = fresh_dir("mesh-cli-sample");
  const auto r =
      run_strand("job '" + samples_dir() + kSample + "' -o cap.csv --report cap.json", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* f : {"cap.csv", "Cap.java", "cap.src", "cap.dat", "cap.extruder.gcode",
                        "cap.substrate.json", "cap.json"})
    EXPECT_TRUE(exists(dir + "/" + f)) << f;
  EXPECT_NE(r.out.find("tetrachiral on a robot-held mesh -> cap.csv (kuka-iiwa14-wasp-cylinder)"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("least-squares conformal (CGAL), 3D/uv area ratio"), std::string::npos);
  EXPECT_NE(r.out.find("passes         3 in 3 layers"), std::string::npos) << r.out;
  const auto report = nlohmann::json::parse(slurp(dir + "/cap.json"));
  EXPECT_EQ(report["substrate"]["kind"], "mesh");
  EXPECT_EQ(report["outputs"]["substrate_record"], "cap.substrate.json");
  EXPECT_EQ(report["robot"]["joints"].size(), 7u);
  const auto record = nlohmann::json::parse(slurp(dir + "/cap.substrate.json"));
  // An absolute mesh path is kept; a relative one is named from the CSV's folder.
  EXPECT_EQ(record["mesh"], samples_dir() + "/meshes/sphere-cap.stl");
  EXPECT_EQ(record["layer_offsets_mm"].size(), 3u);

  // The check finds the mesh and the cell in the record.
  const auto check = run_strand("check cap.csv", dir);
  EXPECT_EQ(check.exit_code, 0) << check.out << check.err;
  EXPECT_NE(check.out.find("pose CSV on a mesh: 3 layers"), std::string::npos) << check.out;
  EXPECT_NE(check.out.find("check: OK"), std::string::npos);
  const auto json = run_strand("check cap.csv --machine kuka-iiwa14-wasp-cylinder --json", dir);
  EXPECT_EQ(json.exit_code, 0) << json.out;
  EXPECT_EQ(nlohmann::json::parse(json.out)["kind"], "pose CSV on a mesh");

  // Drawn over the mesh: the lattice's nodes and the translucent substrate.
  for (const char* f : {"p.png", "p.html", "p.glb"}) {
    const auto pr = run_strand(std::string("preview cap.csv -o ") + f, dir);
    ASSERT_EQ(pr.exit_code, 0) << pr.err;
    EXPECT_NE(pr.out.find("(3 layers"), std::string::npos) << pr.out;
  }
  const std::string png = slurp(dir + "/p.png");
  EXPECT_GT(png_stats(png).drawn_fraction, 0.1);
  const auto node = post::feature_colour(slicer::Feature::Node);
  EXPECT_GT(colour_spot(png, int(node.r * 255), int(node.g * 255), int(node.b * 255), 30).count,
            1000);
}

TEST(MeshSubstrateCli, ATamperedRowFailsTheCheckNamingIt) {
  const auto dir = fresh_dir("mesh-cli-tamper");
  ASSERT_EQ(run_strand(kScaffold + "'" + mesh_dir() + "/saddle.stl'" +
                           " --machine kuka-iiwa14-wasp-cylinder -o part.csv",
                       dir)
                .exit_code,
            0);
  ASSERT_EQ(run_strand("check part.csv", dir).exit_code, 0);
  // A deposit row's contact point 0.3 mm further out along x (px_mm): the saddle faces +x, so
  // the point leaves its layer's offset surface as well as the nozzle tip.
  std::vector<std::string> lines;
  {
    std::istringstream in(slurp(dir + "/part.csv"));
    for (std::string line; std::getline(in, line);) lines.push_back(line);
  }
  std::size_t row = 100;
  const auto cells_of = [](const std::string& line) {
    std::vector<std::string> cells;
    std::istringstream in(line);
    for (std::string c; std::getline(in, c, ',');) cells.push_back(c);
    return cells;
  };
  while (row + 1 < lines.size() && cells_of(lines[row + 1])[10] != "1") ++row;
  ASSERT_LT(row + 1, lines.size());
  auto cells = cells_of(lines[row + 1]);
  char text[32];
  std::snprintf(text, sizeof text, "%.4f", std::stod(cells[14]) + 0.3);
  cells[14] = text;
  std::string csv;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    std::string line = lines[i];
    if (i == row + 1) {
      line.clear();
      for (std::size_t c = 0; c < cells.size(); ++c) line += (c ? "," : "") + cells[c];
    }
    csv += line + "\n";
  }
  std::ofstream(dir + "/part.csv", std::ios::binary) << csv;
  const auto r = run_strand("check part.csv", dir);
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  const std::string named = "  row " + std::to_string(row) + ": ";
  EXPECT_NE(r.out.find(named + "contact 0.3000 mm from the nozzle tip"), std::string::npos)
      << r.out;
  const std::size_t off = r.out.find("deposits off their layer's offset surface");
  ASSERT_NE(off, std::string::npos) << r.out;
  EXPECT_NE(r.out.find(named + "contact 0.2", off), std::string::npos) << r.out;  // ~0.3 x cos
  EXPECT_NE(r.out.find("check: FAILED"), std::string::npos);
  // A mesh given on the command line is checked instead of the record's.
  const auto other =
      run_strand("check part.csv --substrate-mesh '" + mesh_dir() + "/far-cap.stl'", dir);
  EXPECT_EQ(other.exit_code, 1) << other.out;
}

TEST(MeshSubstrateCli, EveryRobotCellTakesAMesh) {
  for (const char* m : {"ur10e-wasp-cylinder", "abb-irb1200-wasp-cylinder"}) {
    const auto dir = fresh_dir("mesh-cli-cells");
    const auto r = run_strand(
        kScaffold + "'" + mesh_dir() + "/saddle.stl' --machine " + m + " -o part.csv", dir);
    ASSERT_EQ(r.exit_code, 0) << m << r.err;
    EXPECT_TRUE(exists(dir + "/part.substrate.json"));
    const auto check = run_strand(std::string("check part.csv --machine ") + m, dir);
    EXPECT_EQ(check.exit_code, 0) << m << check.out;
  }
}

TEST(MeshSubstrateCli, BadMeshJobsAreRefusedNamingThePoint) {
  const std::string kuka = " --machine kuka-iiwa14-wasp-cylinder -o p.csv";
  expect_rejected(kScaffold + "'" + mesh_dir() + "/far-cap.stl'" + kuka,
                  "the robot cannot present pattern point (u, v) = (");
  expect_rejected(
      "scaffold --nozzle 1.2 --gap 2 --size 26x30 --layers 1 --substrate mesh "
      "--substrate-mesh '" +
          mesh_dir() + "/trough.stl'" + kuka,
      "the nozzle would touch the mesh at (");
  expect_rejected(kScaffold + "'" + mesh_dir() + "/box.stl'" + kuka, "its outside faces every way");
  expect_rejected(
      "scaffold --nozzle 1.2 --gap 2 --size 80x80 --layers 1 --substrate mesh "
      "--substrate-mesh '" +
          mesh_dir() + "/saddle.stl'" + kuka,
      "the pattern leaves the mesh at pattern point (u, v) = (");
  expect_rejected(kScaffold + "missing.stl" + kuka, "substrate.mesh = missing.stl: no such file");
  expect_rejected("scaffold --nozzle 1.2 --gap 2 --size 24x24 --layers 1 --substrate mesh" + kuka,
                  "substrate.mesh: missing");
  expect_rejected(kScaffold + "'" + mesh_dir() + "/saddle.stl' --substrate-radius 20" + kuka,
                  "substrate.radius: only for a cylinder");
  expect_rejected(kScaffold + "'" + mesh_dir() + "/saddle.stl' -o p.gcode",
                  "substrate.type = mesh needs a robot-holds-substrate machine");
  expect_rejected(
      kScaffold + "'" + mesh_dir() + "/saddle.stl' --machine marlin-rotary-a -o p.gcode",
      "substrate.type = mesh needs a robot-holds-substrate machine");
}

}  // namespace
}  // namespace strand::testing
