// Default output names: each command that writes one file names it after its input (in the
// current directory) when -o is not given, and never writes over its own input.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "cli/output_path.h"
#include "tests/support/cli_runner.h"

namespace strand::testing {
namespace {

namespace fs = std::filesystem;

const std::string kSource = STRAND_SOURCE_DIR;

void copy(const std::string& from, const std::string& to) {
  fs::copy_file(from, to, fs::copy_options::overwrite_existing);
}

TEST(OutputFromInput, StemWithoutDirectoryPlusSuffix) {
  EXPECT_EQ(cli::output_from_input("drawing.svg", ".gcode"), "drawing.gcode");
  EXPECT_EQ(cli::output_from_input("art/drawings/cat.v2.svg", ".gcode"), "cat.v2.gcode");
  EXPECT_EQ(cli::output_from_input("part.gcode", "-preview.png"), "part-preview.png");
  EXPECT_EQ(cli::output_from_input("scan", ".svg"), "scan.svg");
  EXPECT_EQ(cli::output_from_input("dir/", ".svg"), "strand.svg");
}

TEST(OutputsCli, PlotWritesTheDrawingsNameWithGcode) {
  const auto dir = fresh_dir("out-plot");
  fs::create_directories(dir + "/art");
  copy(kSource + "/samples/plot/lines.svg", dir + "/art/drawing.svg");
  const auto r = run_strand("plot art/drawing.svg --fit 100x100", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(exists(dir + "/drawing.gcode"));
  EXPECT_NE(r.out.find("plot art/drawing.svg -> drawing.gcode"), std::string::npos) << r.out;
}

TEST(OutputsCli, PreviewWritesThePartsNameWithPreviewPng) {
  const auto dir = fresh_dir("out-preview");
  ASSERT_EQ(run_strand("scaffold --nozzle 0.84 --gap 1.6 --size 20x20 --layers 2 -o part.gcode", dir)
                .exit_code,
            0);
  const auto r = run_strand("preview part.gcode", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(exists(dir + "/part-preview.png"));
  EXPECT_EQ(slurp(dir + "/part-preview.png").substr(1, 3), "PNG");
  EXPECT_NE(r.out.find("-> part-preview.png"), std::string::npos) << r.out;
}

TEST(OutputsCli, TraceWritesTheImagesNameWithSvg) {
  const auto dir = fresh_dir("out-trace");
  copy(kSource + "/samples/plot/photo.png", dir + "/img.png");
  const auto r = run_strand("trace img.png", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(exists(dir + "/img.svg"));
  EXPECT_NE(r.out.find("trace img.png -> img.svg"), std::string::npos) << r.out;
}

TEST(OutputsCli, SliceWritesThePartsNameWithGcode) {
  const auto dir = fresh_dir("out-slice");
  copy(kSource + "/tests/data/box-20x20x3.stl", dir + "/box.stl");
  const auto r = run_strand("slice box.stl --nozzle 0.6 --gap 1 --machine marlin-xyz-200", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(exists(dir + "/box.gcode"));
  EXPECT_FALSE(exists(dir + "/slice.gcode"));
  EXPECT_NE(r.out.find("-> box.gcode"), std::string::npos) << r.out;
}

TEST(OutputsCli, AJobWithoutOutputWritesTheJobFilesName) {
  const auto dir = fresh_dir("out-job");
  std::ofstream(dir + "/spec.json")
      << R"({"generator": "scaffold", "params": {"nozzle": 0.84, "gap": 1.6, "size": "20x20", "layers": 2}})";
  const auto r = run_strand("job spec.json", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(exists(dir + "/spec.gcode"));
  EXPECT_FALSE(exists(dir + "/scaffold.gcode"));
}

TEST(OutputsCli, TextWithoutOutputWritesTextSvg) {
  const auto dir = fresh_dir("out-text");
  const auto r = run_strand("text Hi", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(exists(dir + "/text.svg"));
}

// An image named like the output it would get: the default would be the input itself.
TEST(OutputsCli, TheDefaultNeverOverwritesTheInput) {
  const auto dir = fresh_dir("out-self");
  copy(kSource + "/samples/plot/photo.png", dir + "/photo.gcode");
  const std::string before = slurp(dir + "/photo.gcode");
  expect_input_error(run_strand("plot photo.gcode --trace --fit 100x100", dir),
                     "output = photo.gcode: would overwrite the input photo.gcode");
  EXPECT_EQ(slurp(dir + "/photo.gcode"), before);
  copy(kSource + "/samples/plot/photo.png", dir + "/scan.svg");
  expect_input_error(run_strand("trace scan.svg", dir),
                     "output = scan.svg: would overwrite the input scan.svg");
  EXPECT_EQ(slurp(dir + "/scan.svg"), before);
  // and an explicit -o naming the input
  copy(kSource + "/samples/plot/lines.svg", dir + "/lines.svg");
  expect_input_error(run_strand("plot lines.svg -o lines.svg", dir),
                     "output = lines.svg: would overwrite the input lines.svg");
  ASSERT_EQ(run_strand("scaffold --nozzle 0.84 --gap 1.6 --size 20x20 --layers 2 -o p.png", dir)
                .exit_code,
            0);
  const std::string gcode = slurp(dir + "/p.png");
  expect_input_error(run_strand("preview p.png -o p.png", dir),
                     "output = p.png: would overwrite the input p.png");
  EXPECT_EQ(slurp(dir + "/p.png"), gcode);
}

}  // namespace
}  // namespace strand::testing

namespace strand::testing {
namespace {

// Jobs are written layer by layer into a temp file: a part that leaves the build volume at
// layer 546 fails after hundreds of layers were formatted, and still leaves no output, no
// temp file, and an earlier file of that name as it was.
TEST(OutputsCli, APartFailingHalfWayLeavesNoFileAndTheOldOneUntouched) {
  const auto dir = fresh_dir("out-fails-late");
  {
    std::ofstream old(dir + "/s.gcode");
    old << "old file\n";
  }
  const auto r = run_strand("scaffold --nozzle 0.84 --gap 1.6 --size 20x20 --layers 600 --machine "
                            "marlin-xyz-200 -o s.gcode --report s.json --viewer-e",
                            dir);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("part does not fit machine marlin-xyz-200: z 200.323 mm > 200 mm"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  std::vector<std::string> files;
  for (const auto& e : fs::directory_iterator(dir)) files.push_back(e.path().filename().string());
  EXPECT_EQ(files, std::vector<std::string>{"s.gcode"}) << "no report, viewer copy or temp file";
  EXPECT_EQ(slurp(dir + "/s.gcode"), "old file\n");
}

}  // namespace
}  // namespace strand::testing
