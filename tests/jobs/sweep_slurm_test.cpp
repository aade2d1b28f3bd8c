// `strand sweep --slurm` without a cluster: the scripts (run by sh against a stand-in strand),
// quoting of hostile names, the sbatch command lines (through a stand-in sbatch), --resume's
// choice of shards, --status, the shard lock, and bad input. The real Slurm is in
// slurm_cluster_test.cpp.
#include "jobs/sweep_slurm.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "jobs/sweep_journal.h"
#include "jobs/sweep_slurm_submit.h"
#include "slicer/input_error.h"
#include "tests/support/cli_runner.h"

namespace strand::testing {
namespace {

namespace fs = std::filesystem;
using jobs::SlurmRequest;

// 12 points of a small scaffold (3 gaps x 4 nozzles), under a second to run.
const char* const kSpec = R"({"job": {"generator": "scaffold", "params": {"size": "10x10", "height": 1}},
  "vary": {"gap": [1.2, 1.4, 1.6], "nozzle": [0.4, 0.5, 0.6, 0.7]}})";

void write(const std::string& path, const std::string& text, bool executable = false) {
  std::ofstream(path) << text;
  if (executable) fs::permissions(path, fs::perms::owner_all);
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::size_t start = 0;
  for (std::size_t end; (end = text.find('\n', start)) != std::string::npos; start = end + 1) {
    out.push_back(text.substr(start, end - start));
  }
  return out;
}

SlurmRequest request(const std::string& dir) {
  SlurmRequest r;
  r.strand = dir + "/bin/fake strand";
  r.spec = dir + "/my sweep's \"spec\" $(touch pwned) `touch pwned`; touch pwned.json";
  r.dir = dir + "/out dir";
  r.workdir = dir + "/work 'dir'";
  r.tasks = 4;
  return r;
}

TEST(SweepSlurmScript, RunsTheSameProgramWithEachWordIntactAndNoInjection) {
  const auto dir = fresh_dir("slurm-script");
  SlurmRequest r = request(dir);
  fs::create_directories(dir + "/bin");
  fs::create_directories(r.workdir);
  // The stand-in strand prints its working directory and each argument on its own line.
  write(r.strand, "#!/bin/sh\npwd\nfor a in \"$@\"; do printf '%s\\n' \"$a\"; done\n", true);
  write(dir + "/task.sbatch", jobs::array_script(r));
  const auto out = run_in_shell("SLURM_ARRAY_TASK_ID=3 sh task.sbatch", dir);
  ASSERT_EQ(out.exit_code, 0) << out.err;
  EXPECT_EQ(lines(out.out), (std::vector<std::string>{r.workdir, "sweep", r.spec, "-o", r.dir, "--shard", "3/4", "-j", "1"}));
  write(dir + "/merge.sbatch", jobs::merge_script(r));
  const auto merge = run_in_shell("SLURM_CPUS_PER_TASK=8 sh merge.sbatch", dir);
  EXPECT_EQ(lines(merge.out), (std::vector<std::string>{r.workdir, "sweep", "--merge", "-o", r.dir}));
  EXPECT_FALSE(exists(dir + "/pwned")) << "a file name ran as a command";
  EXPECT_FALSE(exists(r.workdir + "/pwned"));
}

TEST(SweepSlurmScript, TasksUseTheirAllocatedCoresAndTheLimitsGoInSbatchLines) {
  SlurmRequest r = request("/x");
  r.partition = "short";
  r.time = "01:30:00";
  r.mem = "4G";
  r.previews = false;
  const std::string s = jobs::array_script(r);
  EXPECT_EQ(s.rfind("#!/bin/sh\n", 0), 0u);
  for (const char* line : {"#SBATCH --partition=short\n", "#SBATCH --time=01:30:00\n", "#SBATCH --mem=4G\n"}) {
    EXPECT_NE(s.find(line), std::string::npos) << line << s;
  }
  EXPECT_NE(s.find("-j \"${SLURM_CPUS_PER_TASK:-1}\" --no-previews\n"), std::string::npos) << s;
  EXPECT_NE(jobs::merge_script(r).find("#SBATCH --partition=short\n"), std::string::npos);
}

TEST(SweepSlurmScript, ArrayRangesCollapseRuns) {
  EXPECT_EQ(jobs::array_ranges({1, 2, 3, 4}), "1-4");
  EXPECT_EQ(jobs::array_ranges({2, 4}), "2,4");
  EXPECT_EQ(jobs::array_ranges({1, 2, 4, 5, 6, 9}), "1-2,4-6,9");
}

TEST(SweepSlurmScript, SbatchArgumentsStayOnTheCommandLineOneWordEach) {
  SlurmRequest r = request("/x");
  r.sbatch_args = {"--comment=$(touch pwned)", "--account=lab"};
  const auto argv = jobs::array_sbatch_argv(r, {2, 4});
  EXPECT_EQ(argv, (std::vector<std::string>{"sbatch", "--parsable", "--array=2,4", "--output=/x/out dir/slurm/task-%a.log",
                                            "--open-mode=append", "--comment=$(touch pwned)", "--account=lab",
                                            "/x/out dir/slurm/sweep.sbatch"}));
  EXPECT_EQ(jobs::array_script(r).find("--comment"), std::string::npos);
  EXPECT_EQ(jobs::merge_sbatch_argv(r, "77")[2], "--dependency=afterany:77");
  // Printed for a user to paste: the shell gives back the same words.
  const auto echoed = run_in_shell("printf '%s\\n' " + jobs::command_line(argv), fresh_dir("slurm-words"));
  EXPECT_EQ(lines(echoed.out), argv);
}

TEST(SweepSlurmScript, BadOptionsAreRefusedBeforeAnythingIsWritten) {
  const struct {
    void (*edit)(SlurmRequest&);
    const char* mention;
  } cases[] = {
      {[](SlurmRequest& r) { r.tasks = 13; }, "--tasks = 13: must be in [1, 12]"},
      {[](SlurmRequest& r) { r.tasks = 0; }, "--tasks = 0: must be in [1, 12]"},
      {[](SlurmRequest& r) { r.partition = "debug\n#SBATCH --uid=0"; }, "--partition = "},
      {[](SlurmRequest& r) { r.time = "1 hour"; }, "--time = 1 hour: must be a Slurm time"},
      {[](SlurmRequest& r) { r.mem = "4 G"; }, "--mem = 4 G"},
      {[](SlurmRequest& r) { r.sbatch_args = {"--array=1-3"}; }, "strand sets --array itself"},
      {[](SlurmRequest& r) { r.sbatch_args = {"-oelsewhere.log"}; }, "strand sets -o itself"},
      {[](SlurmRequest& r) { r.sbatch_args = {"lab"}; }, "--sbatch-arg = lab: must be one sbatch option"},
      {[](SlurmRequest& r) { r.dir = "/x/100%"; }, "may not contain %"},
  };
  for (const auto& c : cases) {
    SlurmRequest r = request("/x");
    c.edit(r);
    try {
      jobs::check_slurm_request(r, 12);
      ADD_FAILURE() << "accepted: " << c.mention;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(c.mention), std::string::npos) << e.what();
    }
  }
  SlurmRequest ok = request("/x");
  ok.time = "2-00:00:00";
  ok.mem = "500M";
  ok.sbatch_args = {"--account=lab", "--qos=long"};
  EXPECT_NO_THROW(jobs::check_slurm_request(ok, 12));
}

TEST(SweepSlurmProcess, CapturesBothStreamsAndTheExitCode) {
  const auto r = jobs::run_process({"sh", "-c", "echo out; echo err >&2; exit 3"});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_EQ(r.out, "out\n");
  EXPECT_EQ(r.err, "err\n");
  EXPECT_EQ(jobs::run_process({"strand-no-such-program"}).exit_code, 127);
  EXPECT_EQ(jobs::find_on_path("sh").empty(), false);
  EXPECT_EQ(jobs::find_on_path("strand-no-such-program"), "");
}

// A directory with the sweep file and stand-in sbatch/scancel that log their arguments
// (one per line, then "--") and answer job ids from 101 up; `merge_refused`: the merge's
// sbatch fails.
std::string fake_cluster(const std::string& tag, bool merge_refused = false) {
  const auto dir = fresh_dir(tag);
  write(dir + "/s.json", kSpec);
  fs::create_directories(dir + "/bin");
  write(dir + "/bin/sbatch",
        "#!/bin/sh\nfor a in \"$@\"; do printf '%s\\n' \"$a\"; done >> " + dir + "/sbatch.log\necho -- >> " + dir +
            "/sbatch.log\nn=$(cat " + dir + "/next 2>/dev/null || echo 101)\necho $((n + 1)) > " + dir +
            "/next\n" + (merge_refused ? "case \"$*\" in *merge.sbatch) echo 'sbatch: error: Batch job submission failed' >&2; exit 1;; esac\n" : "") +
            "echo \"$n;cluster\"\n",
        true);
  write(dir + "/bin/scancel", "#!/bin/sh\necho \"$@\" >> " + dir + "/scancel.log\n", true);
  return dir;
}

std::string with_fake(const std::string& dir, const std::string& args) {
  return "PATH='" + dir + "/bin':/usr/bin:/bin '" + std::string(STRAND_CLI) + "' " + args;
}

TEST(SweepSlurmSubmit, SubmitsTheArrayThenTheMergeAfterItAndRecordsBoth) {
  const auto dir = fake_cluster("slurm-submit");
  const auto r = run_in_shell(with_fake(dir, "sweep s.json -o out --slurm --tasks 3 --sbatch-arg=--account=lab"), dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("array job 101 (tasks 1-3), merge job 102 after it"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("squeue -j 101,102"), std::string::npos) << r.out;
  const auto log = lines(slurp(dir + "/sbatch.log"));
  const std::vector<std::string> expected = {
      "--parsable", "--array=1-3", "--output=" + dir + "/out/slurm/task-%a.log", "--open-mode=append",
      "--account=lab", dir + "/out/slurm/sweep.sbatch", "--",
      "--parsable", "--dependency=afterany:101", "--output=" + dir + "/out/slurm/merge.log", "--open-mode=append",
      "--account=lab", dir + "/out/slurm/merge.sbatch", "--"};
  EXPECT_EQ(log, expected);
  const auto record = nlohmann::json::parse(slurp(dir + "/out/slurm/sweep.json"));
  EXPECT_EQ(record.at("tasks"), 3);
  EXPECT_EQ(record.at("spec"), dir + "/s.json");
  EXPECT_EQ(record.at("submissions"), (nlohmann::json::parse(R"([{"array": "101", "merge": "102", "shards": "1-3"}])")));
  EXPECT_NE(slurp(dir + "/out/slurm/sweep.sbatch").find("--shard \"$SLURM_ARRAY_TASK_ID/3\""), std::string::npos);
  EXPECT_FALSE(exists(dir + "/out/manifest.json")) << "nothing runs on the submitting machine";
}

TEST(SweepSlurmSubmit, AMergeSbatchRefusedCancelsTheArray) {
  const auto dir = fake_cluster("slurm-merge-refused", true);
  const auto r = run_in_shell(with_fake(dir, "sweep s.json -o out --slurm --tasks 2"), dir);
  expect_input_error(r, "sbatch refused the merge job: sbatch: error: Batch job submission failed");
  EXPECT_EQ(slurp(dir + "/scancel.log"), "101\n");
  EXPECT_FALSE(exists(dir + "/out/slurm/sweep.json"));
}

TEST(SweepSlurmSubmit, DryRunWritesTheScriptsAndSubmitsNothing) {
  const auto dir = fake_cluster("slurm-dry");
  const auto r = run_in_shell(with_fake(dir, "sweep s.json -o out --slurm --tasks 4 --dry-run"), dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(exists(dir + "/out/slurm/sweep.sbatch"));
  EXPECT_TRUE(exists(dir + "/out/slurm/merge.sbatch"));
  EXPECT_FALSE(exists(dir + "/sbatch.log"));
  EXPECT_FALSE(exists(dir + "/out/slurm/sweep.json"));
  EXPECT_NE(r.out.find("sbatch --parsable --array=1-4 "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("--dependency=afterany:ARRAY_JOB_ID"), std::string::npos) << r.out;
}

TEST(SweepSlurmSubmit, ResumeSubmitsOnlyTheShardsNotDone) {
  const auto dir = fake_cluster("slurm-resume");
  ASSERT_EQ(run_in_shell(with_fake(dir, "sweep s.json -o out --slurm --tasks 4"), dir).exit_code, 0);
  for (const char* shard : {"1/4", "3/4"}) {
    ASSERT_EQ(run_strand("sweep s.json -o out --no-previews --shard " + std::string(shard), dir).exit_code, 0);
  }
  const auto r = run_in_shell(with_fake(dir, "sweep s.json -o out --slurm --resume"), dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("(tasks 2,4)"), std::string::npos) << r.out;
  EXPECT_NE(slurp(dir + "/sbatch.log").find("--array=2,4\n"), std::string::npos);
  EXPECT_EQ(nlohmann::json::parse(slurp(dir + "/out/slurm/sweep.json")).at("submissions").size(), 2u);
  expect_input_error(run_in_shell(with_fake(dir, "sweep s.json -o out --slurm --resume --tasks 2"), dir),
                     "--tasks = 2: --resume keeps the 4 tasks");
}

TEST(SweepSlurmSubmit, BadInputExitsTwoAndLeavesNothing) {
  const auto dir = fake_cluster("slurm-bad");
  write(dir + "/bad.json", R"({"job": {"generator": "scaffold"}, "vary": {"nozle": [0.4]}})");
  const struct {
    std::string command, mention;
  } cases[] = {
      {"PATH=/nonexistent '" + std::string(STRAND_CLI) + "' sweep s.json -o out --slurm", "sbatch not found on PATH"},
      {with_fake(dir, "sweep bad.json -o out --slurm"), "sweep.vary.nozle: unknown parameter"},
      {with_fake(dir, "sweep s.json -o out --slurm --tasks 13"), "--tasks = 13: must be in [1, 12]"},
      {with_fake(dir, "sweep s.json -o out --slurm --time 'an hour'"), "--time = an hour"},
      {with_fake(dir, "sweep s.json -o out --slurm --resume"), "--resume: "},
      {with_fake(dir, "sweep s.json -o out --tasks 3"), "--tasks: only with --slurm"},
      {with_fake(dir, "sweep s.json -o out --slurm --shard 1/2"), "--shard = 1/2: --slurm gives"},
  };
  for (const auto& c : cases) {
    const auto r = run_in_shell(c.command, dir);
    SCOPED_TRACE(c.command);
    expect_input_error(r, c.mention);
    EXPECT_FALSE(exists(dir + "/out")) << c.command;
    EXPECT_FALSE(exists(dir + "/sbatch.log")) << c.command;
  }
}

TEST(SweepStatus, ReadsShardsFromManifestsAndJournals) {
  const auto dir = fresh_dir("sweep-status");
  write(dir + "/s.json", kSpec);
  ASSERT_EQ(run_strand("sweep s.json -o out --no-previews --shard 1/3", dir).exit_code, 0);
  {  // shard 2 stopped after one point: a journal with one row and no run holding it
    jobs::SweepJournal journal(dir + "/out/manifest-shard-2-of-3.journal.jsonl", jobs::Shard{2, 3}, 12);
    journal.append({{"index", 1}, {"name", "scaffold_gap-1.2_nozzle-0.5"}, {"status", "ok"}});
  }
  auto r = run_strand("sweep --status -o out", dir);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(lines(r.out), (std::vector<std::string>{
                              "sweep: out: 12 point(s) in 3 shard(s): 5 done, 0 running, 0 failed, 7 waiting",
                              "shard 1/3: 4 point(s), 4 done, 0 running, 0 failed (finished)",
                              "shard 2/3: 4 point(s), 1 done, 0 running, 0 failed (stopped)",
                              "shard 3/3: 4 point(s), 0 done, 0 running, 0 failed (not started)"}));
  // While a run holds shard 2, its points not done are running, and a second run is refused.
  jobs::SweepJournal held(dir + "/out/manifest-shard-2-of-3.journal.jsonl", jobs::Shard{2, 3}, 12);
  r = run_strand("sweep --status -o out", dir);
  EXPECT_NE(r.out.find("shard 2/3: 4 point(s), 1 done, 3 running, 0 failed (running)"), std::string::npos) << r.out;
  expect_input_error(run_strand("sweep s.json -o out --no-previews --shard 2/3", dir),
                     "--shard = 2/3: another strand sweep is running this shard");
  expect_input_error(run_strand("sweep --status -o nowhere", dir), "--status: -o = nowhere holds no sweep");
}

TEST(SweepStatus, MergeOfASubmittedSweepNamesTheMissingTaskAndItsLog) {
  const auto dir = fake_cluster("slurm-merge-missing");
  ASSERT_EQ(run_in_shell(with_fake(dir, "sweep s.json -o out --slurm --tasks 2"), dir).exit_code, 0);
  ASSERT_EQ(run_strand("sweep s.json -o out --no-previews --shard 1/2", dir).exit_code, 0);
  const auto r = run_strand("sweep --merge -o out", dir);
  expect_input_error(r, "--merge: 1 of 2 shards did not finish: shard 2/2 (array task 2, log out/slurm/task-2.log, "
                        "0 point(s) journalled); resume: strand sweep " + dir + "/s.json -o out --slurm --resume");
  EXPECT_FALSE(exists(dir + "/out/manifest.json"));
}

TEST(SweepStatus, MergeListsFailedPointsWithTheirTaskAndLog) {
  const auto dir = fake_cluster("slurm-merge-failed");
  write(dir + "/f.json", R"({"job": {"generator": "scaffold", "params": {"nozzle": 0.84, "gap": 1.6, "height": 1}},
                             "vary": {"size": ["10x10", "180x180", "12x12"]}})");
  ASSERT_EQ(run_in_shell(with_fake(dir, "sweep f.json -o out --slurm --tasks 2"), dir).exit_code, 0);
  EXPECT_EQ(run_strand("sweep f.json -o out --no-previews --shard 1/2", dir).exit_code, 0);
  EXPECT_EQ(run_strand("sweep f.json -o out --no-previews --shard 2/2", dir).exit_code, 1);
  const auto r = run_strand("sweep --merge -o out", dir);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  const auto out = lines(r.out);
  ASSERT_EQ(out.size(), 2u) << r.out;
  EXPECT_EQ(out[1].rfind("failed: point 1 scaffold_size-180x180: ", 0), 0u) << out[1];
  EXPECT_NE(out[1].find(" (array task 2, log out/slurm/task-2.log)"), std::string::npos) << out[1];
}

}  // namespace
}  // namespace strand::testing
