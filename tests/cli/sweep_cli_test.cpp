// `strand sweep` from the outside: manifest vs files, -j independence, shards and merge,
// re-runs, failed points, bad input.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>

#include "jobs/content_hash.h"
#include "tests/support/chromium.h"
#include "tests/support/cli_runner.h"

namespace strand::testing {
namespace {

namespace fs = std::filesystem;

const std::string kSample = std::string(STRAND_SOURCE_DIR) + "/samples/sweeps/scaffold-nozzle-gap.json";

// Every regular file under `dir` by relative path, with its bytes.
std::map<std::string, std::string> tree(const std::string& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    if (e.is_regular_file() && e.path().filename().string()[0] != '.') {
      files[fs::relative(e.path(), dir).string()] = slurp(e.path().string());
    }
  }
  return files;
}

void write(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

TEST(SweepCli, ManifestRowsMatchTheFilesWritten) {
  const auto dir = fresh_dir("sweep-rows");
  const auto r = run_strand("sweep " + kSample + " -o out -j 2", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto m = nlohmann::json::parse(slurp(dir + "/out/manifest.json"));
  ASSERT_EQ(m.at("points").size(), 6u);
  std::size_t gcodes = 0;
  for (const auto& row : m.at("points")) {
    if (row.at("status") == "dropped") {
      EXPECT_FALSE(exists(dir + "/out/" + row.at("name").get<std::string>() + ".gcode"));
      continue;
    }
    ASSERT_EQ(row.at("status"), "ok") << row.dump();
    const std::string gcode = slurp(dir + "/out/" + row.at("output").get<std::string>());
    EXPECT_EQ(jobs::fnv1a_hex(gcode), row.at("content_hash"));
    EXPECT_NE(gcode.find("param nozzle = " + row.at("parameters").at("nozzle").dump()), std::string::npos);
    EXPECT_TRUE(row.at("check").at("ok").get<bool>()) << row.dump();
    EXPECT_GT(row.at("ink_volume_ml").get<double>(), 0.0);
    EXPECT_TRUE(exists(dir + "/out/" + row.at("preview").get<std::string>()));
    EXPECT_TRUE(exists(dir + "/out/" + row.at("preview_html").get<std::string>()));
    ++gcodes;
  }
  EXPECT_EQ(gcodes, 5u);
  std::size_t gcode_files = 0;
  for (const auto& e : fs::directory_iterator(dir + "/out")) gcode_files += e.path().extension() == ".gcode";
  EXPECT_EQ(gcode_files, gcodes);
  const std::string csv = slurp(dir + "/out/manifest.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 7);
  const std::string index = slurp(dir + "/out/index.html");
  EXPECT_EQ(std::count(index.begin(), index.end(), '<') > 0, true);
  for (const auto& row : m.at("points")) EXPECT_NE(index.find(row.at("name").get<std::string>()), std::string::npos);
}

TEST(SweepCli, HundredPointsEachRowMatchesItsFile) {
  const auto dir = fresh_dir("sweep-100");
  write(dir + "/s.json", R"({"job": {"generator": "scaffold", "params": {"size": "12x12", "height": 2}},
    "vary": {"nozzle": {"from": 0.4, "to": 0.85, "step": 0.05}, "gap": {"from": 0.9, "to": 1.8, "step": 0.1}}})");
  const auto r = run_strand("sweep s.json -o out --no-previews", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto m = nlohmann::json::parse(slurp(dir + "/out/manifest.json"));
  ASSERT_EQ(m.at("points").size(), 100u);
  std::set<std::string> listed;
  for (const auto& row : m.at("points")) {
    ASSERT_EQ(row.at("status"), "ok") << row.dump();
    listed.insert(row.at("output").get<std::string>());
    EXPECT_EQ(jobs::fnv1a_hex(slurp(dir + "/out/" + row.at("output").get<std::string>())), row.at("content_hash"));
  }
  std::set<std::string> on_disk;
  for (const auto& e : fs::directory_iterator(dir + "/out")) {
    if (e.path().extension() == ".gcode") on_disk.insert(e.path().filename().string());
  }
  EXPECT_EQ(listed, on_disk);
}

TEST(SweepCli, ChromiumShowsEverySpecimenOnTheContactSheet) {
  if (chromium_path().empty()) GTEST_SKIP() << "chromium is not installed (apt-get install chromium)";
  const auto dir = fresh_dir("sweep-index");
  ASSERT_EQ(run_strand("sweep " + kSample + " -o out", dir).exit_code, 0);
  const auto r = run_chromium(dir, "--dump-dom", dir + "/out/index.html");
  EXPECT_NE(r.out.find("cards: 6, thumbnails shown: 5"), std::string::npos) << r.out.substr(0, 600);
  EXPECT_FALSE(has_console_output(r.log)) << r.log;
}

TEST(SweepCli, OneAndTwoWorkersGiveIdenticalFiles) {
  const auto dir = fresh_dir("sweep-j");
  ASSERT_EQ(run_strand("sweep " + kSample + " -o a -j 1", dir).exit_code, 0);
  ASSERT_EQ(run_strand("sweep " + kSample + " -o b -j 2", dir).exit_code, 0);
  const auto a = tree(dir + "/a"), b = tree(dir + "/b");
  EXPECT_EQ(a.size(), b.size());
  EXPECT_TRUE(a == b);
}

TEST(SweepCli, ShardsMergedEqualTheUnshardedRun) {
  const auto dir = fresh_dir("sweep-shard");
  ASSERT_EQ(run_strand("sweep " + kSample + " -o whole", dir).exit_code, 0);
  for (const char* s : {"1/3", "2/3", "3/3"}) {
    const auto r = run_strand("sweep " + kSample + " -o parts --shard " + s, dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  EXPECT_FALSE(exists(dir + "/parts/manifest.json"));
  const auto r = run_strand("sweep --merge -o parts", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto whole = tree(dir + "/whole"), parts = tree(dir + "/parts");
  for (const char* s : {"1-of-3", "2-of-3", "3-of-3"}) EXPECT_EQ(parts.erase(std::string("manifest-shard-") + s + ".json"), 1u);
  EXPECT_EQ(whole.size(), parts.size());
  EXPECT_TRUE(whole == parts);
}

TEST(SweepCli, MergeTakesShardFilesAsArguments) {
  const auto dir = fresh_dir("sweep-merge-args");
  ASSERT_EQ(run_strand("sweep " + kSample + " -o whole", dir).exit_code, 0);
  for (const char* s : {"1/2", "2/2"}) ASSERT_EQ(run_strand("sweep " + kSample + " -o parts --shard " + s, dir).exit_code, 0);
  const auto r = run_strand("sweep --merge parts/manifest-shard-2-of-2.json parts/manifest-shard-1-of-2.json -o parts", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(slurp(dir + "/parts/manifest.json"), slurp(dir + "/whole/manifest.json"));
  EXPECT_EQ(slurp(dir + "/parts/manifest.csv"), slurp(dir + "/whole/manifest.csv"));
}

TEST(SweepCli, MergeRejectsAMissingShard) {
  const auto dir = fresh_dir("sweep-merge-missing");
  ASSERT_EQ(run_strand("sweep " + kSample + " -o parts --shard 1/2", dir).exit_code, 0);
  const auto r = run_strand("sweep --merge -o parts", dir);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("1 of 2 shards"), std::string::npos) << r.err;
}

TEST(SweepCli, RerunSkipsUpToDatePointsAndRedoesChangedFiles) {
  const auto dir = fresh_dir("sweep-rerun");
  ASSERT_EQ(run_strand("sweep " + kSample + " -o out", dir).exit_code, 0);
  const auto before = tree(dir + "/out");
  const auto again = run_strand("sweep " + kSample + " -o out", dir);
  EXPECT_NE(again.out.find("0 ran, 5 up to date"), std::string::npos) << again.out;
  write(dir + "/out/scaffold_gap-1.2_nozzle-0.6.gcode", "truncated");
  const auto third = run_strand("sweep " + kSample + " -o out", dir);
  EXPECT_NE(third.out.find("1 ran, 4 up to date"), std::string::npos) << third.out;
  EXPECT_TRUE(before == tree(dir + "/out"));
}

TEST(SweepCli, EditingAMachineProfileFileRerunsThePoints) {
  const auto dir = fresh_dir("sweep-machine");
  std::string profile = slurp(std::string(STRAND_SOURCE_DIR) + "/machines/profiles/marlin-xyz-200.json");
  write(dir + "/m.json", profile);
  write(dir + "/s.json", R"({"job": {"generator": "scaffold", "machine": "m.json",
    "params": {"nozzle": 0.84, "size": "12x12", "height": 2}}, "vary": {"gap": [1.0, 1.6]}})");
  ASSERT_EQ(run_strand("sweep s.json -o out --no-previews", dir).exit_code, 0);
  EXPECT_NE(run_strand("sweep s.json -o out --no-previews", dir).out.find("0 ran, 2 up to date"), std::string::npos);
  profile.replace(profile.find("Generic Cartesian"), 7, "Edited ");
  write(dir + "/m.json", profile);
  const auto r = run_strand("sweep s.json -o out --no-previews", dir);
  EXPECT_NE(r.out.find("2 ran, 0 up to date"), std::string::npos) << r.out << r.err;
}

TEST(SweepCli, AnInterruptedSweepResumesFromItsJournal) {
  const auto dir = fresh_dir("sweep-journal");
  ASSERT_EQ(run_strand("sweep " + kSample + " -o out", dir).exit_code, 0);
  EXPECT_FALSE(exists(dir + "/out/manifest.journal.jsonl"));
  const auto before = tree(dir + "/out");
  // As if killed before the manifest: finished points only in the journal, last line torn.
  std::string journal;
  const auto manifest = nlohmann::json::parse(slurp(dir + "/out/manifest.json"));
  for (const auto& row : manifest.at("points")) {
    if (row.at("status") == "ok") journal += row.dump() + "\n";
  }
  fs::remove(dir + "/out/manifest.json");
  write(dir + "/out/manifest.journal.jsonl", journal + "{\"name\": \"scaff");
  const auto r = run_strand("sweep " + kSample + " -o out", dir);
  EXPECT_NE(r.out.find("0 ran, 5 up to date"), std::string::npos) << r.out << r.err;
  EXPECT_FALSE(exists(dir + "/out/manifest.journal.jsonl"));
  EXPECT_TRUE(before == tree(dir + "/out"));
}

TEST(SweepCli, AFailedPointIsListedAndTheOthersStillRun) {
  const auto dir = fresh_dir("sweep-fail");
  write(dir + "/s.json", R"({"job": {"generator": "scaffold", "params": {"nozzle": 0.84, "gap": 1.6, "height": 3}, "report": "r.json"},
                             "vary": {"size": ["20x20", "180x180", "30x30"]}})");
  const auto r = run_strand("sweep s.json -o out", dir);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  const auto m = nlohmann::json::parse(slurp(dir + "/out/manifest.json"));
  ASSERT_EQ(m.at("points").size(), 3u);
  EXPECT_EQ(m["points"][0]["status"], "ok");
  EXPECT_EQ(m["points"][1]["status"], "failed");
  EXPECT_FALSE(m["points"][1].value("error", "").empty());
  EXPECT_EQ(m["points"][2]["status"], "ok");
  const auto report = nlohmann::json::parse(slurp(dir + "/out/" + m["points"][2]["report"].get<std::string>()));
  EXPECT_EQ(report.at("parameters").at("size"), (nlohmann::json{30, 30}));
  EXPECT_NE(slurp(dir + "/out/manifest.csv").find("failed"), std::string::npos);
}

TEST(SweepCli, PlainProgressLinesWhenNotATerminal) {
  const auto dir = fresh_dir("sweep-progress");
  const auto r = run_strand("sweep " + kSample + " -o out -j 1", dir);
  EXPECT_NE(r.err.find("sweep: 6/6 "), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find('\r'), std::string::npos);
}

struct BadCase {
  const char* name;
  const char* sweep;
  const char* args;
  const char* must_mention;
};

class SweepBadInput : public ::testing::TestWithParam<BadCase> {};

TEST_P(SweepBadInput, ExitTwoOneLineNoOutput) {
  const auto dir = fresh_dir("sweep-bad");
  write(dir + "/s.json", GetParam().sweep);
  const auto r = run_strand(std::string("sweep s.json -o out ") + GetParam().args, dir);
  expect_input_error(r, GetParam().must_mention);
  EXPECT_FALSE(exists(dir + "/out/manifest.json"));
}

#define JOB R"("job": {"generator": "scaffold", "params": {"nozzle": 0.84, "gap": 1.6, "size": "20x20", "height": 3}})"
INSTANTIATE_TEST_SUITE_P(
    Cases, SweepBadInput,
    ::testing::Values(
        BadCase{"unknown_parameter", "{" JOB R"(, "vary": {"nozle": [0.4]}})", "", "sweep.vary.nozle: unknown parameter"},
        BadCase{"empty_product", "{" JOB R"(, "vary": {"nozzle": []}})", "", "sweep.vary.nozzle: empty list"},
        BadCase{"step_zero", "{" JOB R"(, "vary": {"gap": {"from": 1, "to": 2, "step": 0}}})", "", "sweep.vary.gap.step = 0"},
        BadCase{"wrong_sign", "{" JOB R"(, "vary": {"gap": {"from": 2, "to": 1, "step": 0.5}}})", "", "sweep.vary.gap.step"},
        BadCase{"shard_too_big", "{" JOB R"(, "vary": {"gap": [1, 2]}})", "--shard 4/3", "--shard = 4/3"},
        BadCase{"shard_zero", "{" JOB R"(, "vary": {"gap": [1, 2]}})", "--shard 0/3", "--shard = 0/3"},
        BadCase{"malformed", "{", "", "sweep = s.json: malformed JSON"}),
    [](const auto& info) { return std::string(info.param.name); });
#undef JOB

}  // namespace
}  // namespace strand::testing
