// Output transactions: all files or none, no temp left behind, inputs protected; bounded reads.
#include "slicer/file_io.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <functional>

#include "slicer/input_error.h"
#include "tests/support/cli_runner.h"

namespace strand::slicer {
namespace {

namespace fs = std::filesystem;

std::size_t entries(const std::string& dir) {
  return static_cast<std::size_t>(
      std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
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

// A body streamed first and its head given last (G-code whose header holds the totals) is
// put together at commit: the head, then every byte of the body, and no temp left.
TEST(OutputFiles, APrependedHeadGoesBeforeTheStreamedBody) {
  const auto dir = testing::fresh_dir("io-prepend");
  std::string expected_body;
  {
    OutputFiles out;
    std::ostream& s = out.stage_stream(dir + "/job.gcode");
    for (int i = 0; i < 300000; ++i) {  // 4 MB: more than one copy call's worth is fine too
      const std::string line = "G1 X" + std::to_string(i) + "\n";
      s << line;
      expected_body += line;
    }
    out.stage(dir + "/report.json", "{}");
    out.prepend(dir + "/job.gcode", "; head line 1\n; head line 2\n");
    EXPECT_THROW(out.prepend(dir + "/report.json", "x"), std::logic_error) << "only a streamed file has a body to go after";
    EXPECT_FALSE(fs::exists(dir + "/job.gcode"));
    out.commit();
  }
  EXPECT_EQ(testing::slurp(dir + "/job.gcode"), "; head line 1\n; head line 2\n" + expected_body);
  EXPECT_EQ(entries(dir), 2u) << "no temp file left";

  const auto abandoned = testing::fresh_dir("io-prepend-abort");
  {
    OutputFiles out;
    out.stage_stream(abandoned + "/job.gcode") << "body";
    out.prepend(abandoned + "/job.gcode", "head\n");
  }
  EXPECT_EQ(entries(abandoned), 0u) << "an uncommitted set leaves nothing";
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

namespace strand::slicer {
namespace {

// The set of five files a robot job writes, with contents tagged by run.
const std::vector<std::string> kSet = {"p.csv", "P.java", "p.src", "p.dat", "p.extruder.gcode"};

// The last file is streamed with its head given last, as G-code is.
void write_set(const std::string& dir, const std::string& tag,
               std::function<void(std::size_t)> hook = nullptr) {
  OutputFiles out;
  for (std::size_t i = 0; i + 1 < kSet.size(); ++i) out.stage(dir + "/" + kSet[i], tag + " " + kSet[i]);
  out.stage_stream(dir + "/" + kSet.back()) << kSet.back();
  out.prepend(dir + "/" + kSet.back(), tag + " ");
  if (hook) out.on_rename(std::move(hook));
  out.commit();
}

// "old", "new" or "mixed" for the set in `dir`.
std::string set_state(const std::string& dir) {
  std::size_t old_files = 0, new_files = 0;
  for (const auto& name : kSet) {
    const std::string text = testing::slurp(dir + "/" + name);
    old_files += text == "old " + name;
    new_files += text == "new " + name;
  }
  if (old_files == kSet.size()) return "old";
  if (new_files == kSet.size()) return "new";
  return "mixed";
}

TEST(OutputSet, AKillBetweenAnyTwoRenamesIsCompletedByTheNextRun) {
  for (std::size_t kill_after = 0; kill_after < kSet.size(); ++kill_after) {
    const auto dir = testing::fresh_dir("io-kill");
    write_set(dir, "old");
    // A child process commits the new set and is killed (SIGKILL: no handler runs) after
    // `kill_after` renames.
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      write_set(dir, "new", [&](std::size_t done) {
        if (done == kill_after) raise(SIGKILL);
      });
      _exit(0);
    }
    int status = 0;
    waitpid(child, &status, 0);
    ASSERT_TRUE(WIFSIGNALED(status));
    EXPECT_EQ(set_state(dir), kill_after == 0 ? "old" : "mixed") << "before recovery";
    EXPECT_TRUE(fs::exists(dir + "/p.csv.strand-commit")) << "the journal says what is left";
    // What any later run does first when it stages the set's first file.
    EXPECT_TRUE(recover_output_set(dir + "/p.csv"));
    EXPECT_EQ(set_state(dir), "new") << "killed after " << kill_after << " renames";
    EXPECT_FALSE(fs::exists(dir + "/p.csv.strand-commit"));
    for (const auto& name : kSet)
      EXPECT_FALSE(fs::exists(dir + "/" + name + ".strand-tmp")) << name;
  }
}

TEST(OutputSet, TheNextRunStagingTheSetCompletesItBeforeWritingItsOwn) {
  const auto dir = testing::fresh_dir("io-next");
  write_set(dir, "old");
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    write_set(dir, "new", [](std::size_t done) {
      if (done == 2) raise(SIGKILL);
    });
    _exit(0);
  }
  int status = 0;
  waitpid(child, &status, 0);
  ASSERT_EQ(set_state(dir), "mixed");
  // A third run that is itself interrupted before committing: the set it finds is completed,
  // and its own unfinished temps are removed.
  {
    OutputFiles out;
    out.stage(dir + "/p.csv", "third p.csv");
    EXPECT_EQ(set_state(dir), "new");
  }
  EXPECT_EQ(set_state(dir), "new");
  EXPECT_EQ(entries(dir), kSet.size()) << "no journal or temp left";
}

TEST(OutputSet, AJournalOfAnotherLiveCommitIsLeftAlone) {
  const auto dir = testing::fresh_dir("io-live");
  write_set(dir, "old");
  // Another process is committing (it holds the journal's lock): recovery must not touch it.
  std::ofstream(dir + "/p.csv.strand-tmp") << "new p.csv";
  std::ofstream(dir + "/p.csv.strand-commit")
      << "strand output set v1\n"
      << fs::absolute(dir + "/p.csv.strand-tmp").string() << "\t"
      << fs::absolute(dir + "/p.csv").string() << "\n";
  const int fd = ::open((dir + "/p.csv.strand-commit").c_str(), O_RDONLY);
  ASSERT_EQ(::flock(fd, LOCK_EX), 0);
  const pid_t child = fork();
  if (child == 0) _exit(recover_output_set(dir + "/p.csv") ? 1 : 0);
  int status = 0;
  waitpid(child, &status, 0);
  EXPECT_EQ(WEXITSTATUS(status), 0);
  EXPECT_EQ(testing::slurp(dir + "/p.csv"), "old p.csv");
  ::close(fd);
  EXPECT_TRUE(recover_output_set(dir + "/p.csv")) << "once the lock is gone it is completed";
  EXPECT_EQ(testing::slurp(dir + "/p.csv"), "new p.csv");
}

TEST(OutputSet, AJournalCannotMoveFilesThatAreNotItsOwnTemps) {
  const auto dir = testing::fresh_dir("io-evil");
  std::ofstream(dir + "/secret") << "s";
  std::ofstream(dir + "/p.csv.strand-commit") << "strand output set v1\n"
                                              << fs::absolute(dir + "/secret").string() << "\t"
                                              << fs::absolute(dir + "/p.csv").string() << "\n";
  EXPECT_FALSE(recover_output_set(dir + "/p.csv"));
  EXPECT_EQ(testing::slurp(dir + "/secret"), "s");
  EXPECT_FALSE(fs::exists(dir + "/p.csv"));
  EXPECT_FALSE(fs::exists(dir + "/p.csv.strand-commit"));
}

TEST(ReadFile, FifosAndDevicesAreRefusedWithoutBlocking) {
  const auto dir = testing::fresh_dir("io-fifo");
  ASSERT_EQ(mkfifo((dir + "/pipe").c_str(), 0600), 0);
  for (const std::string& path :
       {dir + "/pipe", std::string("/dev/zero"), std::string("/dev/null")}) {
    try {
      read_file(path);
      ADD_FAILURE() << path << " was read";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("not a regular file"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace strand::slicer
