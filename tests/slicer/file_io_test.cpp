// Output transactions: all files or none, no temp left behind, inputs protected; bounded reads.
#include "slicer/file_io.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "slicer/input_error.h"
#include "tests/support/cli_runner.h"

namespace strand::slicer {
namespace {

namespace fs = std::filesystem;

std::size_t entries(const std::string& dir) {
  return static_cast<std::size_t>(std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
}

TEST(OutputFiles, NothingIsInPlaceUntilCommit) {
  const auto dir = testing::fresh_dir("io-commit");
  OutputFiles out;
  out.stage(dir + "/a.txt", "a");
  out.stage(dir + "/b.txt", "b");
  EXPECT_FALSE(fs::exists(dir + "/a.txt"));
  out.commit();
  EXPECT_EQ(testing::slurp(dir + "/a.txt"), "a");
  EXPECT_EQ(testing::slurp(dir + "/b.txt"), "b");
  EXPECT_EQ(entries(dir), 2u) << "no temp file left";
}

TEST(OutputFiles, AFailingStageRemovesTheOthersTemps) {
  const auto dir = testing::fresh_dir("io-fail");
  try {
    OutputFiles out;
    out.stage(dir + "/a.txt", "a");
    out.stage(dir + "/missing/b.txt", "b");
    FAIL() << "staged into a missing directory";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("output = " + dir + "/missing/b.txt"), std::string::npos);
  }
  EXPECT_EQ(entries(dir), 0u);
}

TEST(OutputFiles, AProtectedInputOrATwiceNamedOutputIsRefused) {
  const auto dir = testing::fresh_dir("io-protect");
  std::ofstream(dir + "/job.json") << "{}";
  OutputFiles out;
  out.protect_input(dir + "/job.json");
  EXPECT_THROW(out.stage(dir + "/./job.json", "x"), InputError);
  out.stage(dir + "/r.json", "1");
  EXPECT_THROW(out.stage(dir + "/r.json", "2"), InputError);
  EXPECT_EQ(testing::slurp(dir + "/job.json"), "{}");
}

TEST(ReadFile, DirectoriesAndMissingFilesAreNamed) {
  const auto dir = testing::fresh_dir("io-read");
  EXPECT_THROW(read_file(dir), InputError);
  EXPECT_THROW(read_file(dir + "/nothing"), InputError);
  std::ofstream(dir + "/x") << "abc";
  EXPECT_EQ(read_file(dir + "/x"), "abc");
}


TEST(OutputFiles, StreamedFileAppearsWholeAtCommit) {
  const auto dir = testing::fresh_dir("io-stream");
  OutputFiles out;
  std::ostream& s = out.stage_stream(dir + "/big.txt");
  for (int i = 0; i < 100000; ++i) s << "line " << i << "\n";
  out.stage(dir + "/small.txt", "s");
  EXPECT_FALSE(fs::exists(dir + "/big.txt")) << "nothing in place before commit";
  out.commit();
  const std::string text = testing::slurp(dir + "/big.txt");
  EXPECT_EQ(text.substr(0, 14), "line 0\nline 1\n");
  EXPECT_EQ(text.substr(text.size() - 11), "line 99999\n");
  EXPECT_EQ(entries(dir), 2u) << "no temp file left";
}

TEST(OutputFiles, UncommittedStreamLeavesNothing) {
  const auto dir = testing::fresh_dir("io-stream-abort");
  {
    OutputFiles out;
    out.stage_stream(dir + "/big.txt") << "partial";
  }
  EXPECT_EQ(entries(dir), 0u);
}

}  // namespace
}  // namespace strand::slicer
