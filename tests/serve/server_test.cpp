// `strand serve` over real HTTP on 127.0.0.1 (an ephemeral port, in-process server): the API,
// byte-identical G-code against `strand job`, the access rules (path traversal, oversized
// bodies, token, same-origin, Host) and the pages in headless Chromium.
#include "serve/server.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "serve/api.h"
#include "tests/support/chromium.h"
#include "tests/support/cli_runner.h"
#include "tests/support/http_client.h"

namespace strand::serve {
namespace {

using nlohmann::json;
using strand::testing::fresh_dir;
using strand::testing::run_strand;
using strand::testing::slurp;

using Reply = strand::testing::HttpReply;

// One request on a fresh connection, a JSON body (tests/support/http_client.h).
Reply http(int port, const std::string& method, const std::string& target, const std::string& body = "",
           const std::string& extra_headers = "") {
  return strand::testing::http_request(port, method, target, body, "application/json", extra_headers);
}

const std::string kJob =
    R"({"generator": "scaffold", "machine": "deltawasp-2040-clay", "params": {"nozzle": 0.84, "gap": 1.6, "size": "20x20", "layers": 2}})";

class ServerTest : public ::testing::Test {
 protected:
  void start(const std::string& token = "") {
    dir_ = fresh_dir("serve");
    ServeOptions o;
    o.port = 0;
    o.data_dir = dir_ + "/data";
    o.token = token;
    server_ = std::make_unique<Server>(o);
    port_ = server_->start();
    ASSERT_GT(port_, 0);
  }
  void TearDown() override {
    if (server_) server_->stop();
  }
  std::string dir_;
  std::unique_ptr<Server> server_;
  int port_ = 0;
};

TEST_F(ServerTest, HealthGeneratorsAndMachines) {
  start();
  const Reply h = http(port_, "GET", "/api/health");
  EXPECT_EQ(h.status, 200);
  EXPECT_EQ(h.j().value("ok", false), true);
  const json g = http(port_, "GET", "/api/generators").j();
  const json& scaffold = g.at("generators").at(0);
  EXPECT_EQ(scaffold.at("name"), "scaffold");
  bool nozzle = false;
  for (const auto& p : scaffold.at("params")) {
    if (p.at("key") == "nozzle") {
      nozzle = true;
      EXPECT_EQ(p.at("unit"), "mm");
      EXPECT_EQ(p.at("rule"), "must be in (0, 10]");
    }
  }
  EXPECT_TRUE(nozzle);
  bool clay = false;
  const json machines = http(port_, "GET", "/api/machines").j();
  for (const auto& m : machines.at("machines")) {
    if (m.at("name") == "deltawasp-2040-clay") clay = m.at("kind") == "printer";
  }
  EXPECT_TRUE(clay);
}

TEST_F(ServerTest, GeneratedGcodeIsByteIdenticalToStrandJob) {
  start();
  const Reply r = http(port_, "POST", "/api/generate", kJob);
  ASSERT_EQ(r.status, 200) << r.body;
  const json j = r.j();
  EXPECT_NE(j.at("summary").get<std::string>().find("porosity"), std::string::npos);
  EXPECT_EQ(j.at("check").at("ok"), true);
  ASSERT_TRUE(j.at("gcode").is_string());
  const Reply gcode = http(port_, "GET", j.at("gcode").get<std::string>());
  ASSERT_EQ(gcode.status, 200);
  const std::string cli = fresh_dir("serve-cli");
  {
    std::ofstream(cli + "/spec.json") << kJob;
  }
  ASSERT_EQ(run_strand("job spec.json", cli).exit_code, 0);
  EXPECT_TRUE(gcode.body == slurp(cli + "/spec.gcode")) << "the server's G-code differs from strand job's";
  EXPECT_EQ(http(port_, "GET", j.at("preview_png").get<std::string>()).status, 200);
  EXPECT_EQ(http(port_, "GET", j.at("preview_html").get<std::string>()).status, 200);
  // a job file's own output path is ignored: nothing is written outside the data directory
  json with_output = json::parse(kJob);
  with_output["output"] = cli + "/elsewhere.gcode";
  EXPECT_EQ(http(port_, "POST", "/api/generate", with_output.dump()).status, 200);
  EXPECT_FALSE(std::filesystem::exists(cli + "/elsewhere.gcode"));
}

TEST_F(ServerTest, SaveListGetDelete) {
  start();
  json body = json::parse(kJob);
  body["name"] = "first design";
  const Reply saved = http(port_, "POST", "/api/jobs", body.dump());
  ASSERT_EQ(saved.status, 201) << saved.body;
  const auto id = saved.j().at("id").get<long>();
  const json list = http(port_, "GET", "/api/jobs").j();
  ASSERT_EQ(list.at("jobs").size(), 1u);
  EXPECT_EQ(list.at("jobs").at(0).at("name"), "first design");
  http(port_, "POST", "/api/generate", kJob);  // unsaved: not in the gallery
  EXPECT_EQ(http(port_, "GET", "/api/jobs").j().at("jobs").size(), 1u);
  const std::string self = "/api/jobs/" + std::to_string(id);
  EXPECT_EQ(http(port_, "GET", self).j().at("job").at("generator"), "scaffold");
  EXPECT_EQ(http(port_, "GET", self + "/files/report.json").status, 200);
  EXPECT_EQ(http(port_, "GET", self + "/files/nothing.txt").status, 404);
  EXPECT_EQ(http(port_, "DELETE", self).status, 200);
  EXPECT_EQ(http(port_, "GET", self).status, 404);
  EXPECT_EQ(http(port_, "GET", "/api/jobs").j().at("jobs").size(), 0u);
  body.erase("name");
  EXPECT_EQ(http(port_, "POST", "/api/jobs", body.dump()).status, 400);  // a name is needed
}

TEST_F(ServerTest, BadRequestsGetOneLineJsonErrors) {
  start();
  for (const auto& [method, target, body, status] : std::vector<std::tuple<std::string, std::string, std::string, int>>{
           {"POST", "/api/generate", "not json", 400},
           {"POST", "/api/generate", "[1,2]", 400},
           {"POST", "/api/generate", R"({"generator":"scaffold","params":{"nozzle":-1}})", 400},
           {"POST", "/api/generate", R"({"generator":"nope"})", 400},
           {"POST", "/api/generate", R"({"generator":"scaffold","machine":"/etc/passwd","params":{"nozzle":1}})", 400},
           {"GET", "/api/generate", "", 405},
           {"GET", "/api/nothing", "", 404},
           {"GET", "/api/jobs/abc", "", 404},
           {"GET", "/api/jobs/99999999999999999999", "", 404},
           {"PUT", "/api/jobs", "", 405},
       }) {
    const Reply r = http(port_, method, target, body);
    EXPECT_EQ(r.status, status) << method << " " << target << " " << body;
    ASSERT_TRUE(r.j().is_object()) << r.body;
    EXPECT_TRUE(r.j().at("error").is_string());
    EXPECT_EQ(r.body.find('\n'), r.body.size() - 1) << "one line";
  }
  const Reply nozzle = http(port_, "POST", "/api/generate", R"({"generator":"scaffold","params":{"nozzle":-1}})");
  EXPECT_EQ(nozzle.j().at("error"), "scaffold.nozzle = -1: must be in (0, 10] (mm)");
}

TEST_F(ServerTest, PathTraversalFindsNothing) {
  start();
  const Reply r = http(port_, "POST", "/api/generate", kJob);
  ASSERT_EQ(r.status, 200);
  const std::string id = std::to_string(r.j().at("id").get<long>());
  for (const std::string& target :
       {"/api/jobs/" + id + "/files/..%2f..%2fetc%2fpasswd", "/api/jobs/" + id + "/files/..%2f..%2fstrand.sqlite",
        "/api/jobs/" + id + "/files/../../strand.sqlite", "/api/jobs/" + id + "/files/%2e%2e",
        "/api/jobs/.." + std::string("/files/report.json"), "/api/jobs/" + id + "/files/report.json%00.png"}) {
    const Reply t = http(port_, "GET", target);
    EXPECT_EQ(t.status, 404) << target;
    EXPECT_EQ(t.body.find("root:"), std::string::npos);
    EXPECT_EQ(t.body.find("SQLite"), std::string::npos);
  }
}

TEST_F(ServerTest, OversizedBodyIsRefused) {
  start();
  const Reply r = http(port_, "POST", "/api/generate", std::string(kMaxBodyBytes + 1, ' '));
  EXPECT_EQ(r.status, 413);
  EXPECT_TRUE(r.j().at("error").is_string()) << r.body;
}

TEST_F(ServerTest, CrossOriginAndForeignHostAreRefused) {
  start();
  EXPECT_EQ(http(port_, "POST", "/api/generate", kJob, "Origin: http://evil.example\r\n").status, 403);
  EXPECT_EQ(http(port_, "POST", "/api/generate", kJob, "Referer: http://evil.example/x\r\n").status, 403);
  EXPECT_EQ(http(port_, "POST", "/api/generate", kJob, "Sec-Fetch-Site: cross-site\r\n").status, 403);
  const std::string self = "http://127.0.0.1:" + std::to_string(port_);
  EXPECT_EQ(http(port_, "POST", "/api/generate", kJob, "Origin: " + self + "\r\nSec-Fetch-Site: same-origin\r\n").status, 200);
  // DNS rebinding: another name for this loopback server
  const Reply r = http(port_, "GET", "/api/jobs", "", "Host: evil.example\r\n");
  EXPECT_TRUE(r.status == 403 || r.status == 400) << r.status;
}

TEST_F(ServerTest, TokenIsRequiredWhenSet) {
  start("s3cret-token");
  EXPECT_EQ(http(port_, "GET", "/api/jobs").status, 401);
  EXPECT_EQ(http(port_, "GET", "/api/jobs", "", "X-Strand-Token: wrong\r\n").status, 401);
  EXPECT_EQ(http(port_, "POST", "/api/generate", kJob, "X-Strand-Token: wrong\r\n").status, 401);
  EXPECT_EQ(http(port_, "GET", "/api/jobs", "", "X-Strand-Token: s3cret-token\r\n").status, 200);
  EXPECT_EQ(http(port_, "GET", "/", "", "Cookie: strand_token=wrong\r\n").status, 401);
  const Reply in = http(port_, "GET", "/?token=s3cret-token");
  EXPECT_EQ(in.status, 303);
  EXPECT_NE(in.head.find("strand_token=s3cret-token"), std::string::npos);
  EXPECT_EQ(http(port_, "GET", "/?token=nope").status, 401);
  EXPECT_EQ(http(port_, "GET", "/", "", "Cookie: a=b; strand_token=s3cret-token\r\n").status, 200);
}

// The curl examples of docs/workbench.md (```sh lines starting with "curl "), in order, against
// this server, in a folder where samples/ is the source tree's: each must succeed (-sf fails on an
// error status).
TEST_F(ServerTest, WorkbenchDocsCurlExamplesRun) {
  start();
  if (strand::testing::run_in_shell("command -v curl", dir_).exit_code != 0) GTEST_SKIP() << "curl not installed";
  // the examples upload the sample meshes by their paths in the source tree
  std::filesystem::create_directory_symlink(std::string(STRAND_SOURCE_DIR) + "/samples", dir_ + "/samples");
  std::istringstream page(slurp(std::string(STRAND_SOURCE_DIR) + "/docs/workbench.md"));
  bool in_sh = false;
  int ran = 0;
  for (std::string line; std::getline(page, line);) {
    if (line.rfind("```", 0) == 0) {
      in_sh = !in_sh && line == "```sh";
      continue;
    }
    if (!in_sh || line.rfind("curl ", 0) != 0) continue;
    const std::string local = std::regex_replace(line, std::regex("127\\.0\\.0\\.1:8080"), "127.0.0.1:" + std::to_string(port_));
    const auto r = strand::testing::run_in_shell("timeout 60 " + local, dir_);
    EXPECT_EQ(r.exit_code, 0) << line << "\n" << r.out << r.err;
    ++ran;
  }
  EXPECT_GE(ran, 8);
  EXPECT_TRUE(std::filesystem::exists(dir_ + "/scaffold.gcode"));
  EXPECT_TRUE(std::filesystem::exists(dir_ + "/preview.png"));
}

TEST(ServeCli, NonLoopbackHostWithoutTokenExits2) {
  const auto r = run_strand("serve --host 0.0.0.0 --port 0 --data d");
  strand::testing::expect_input_error(r, "--token");
  const auto bad_port = run_strand("serve --port 70000 --data d");
  strand::testing::expect_input_error(bad_port, "--port");
}

TEST(ServeCli, PortZeroPrintsTheAddress) {
  const std::string dir = fresh_dir("serve-port");
  // serves until `timeout` stops it (exit 124) after printing where it listens
  const auto r = strand::testing::run_in_shell(std::string("timeout 3 '") + STRAND_CLI + "' serve --port 0 --data data", dir);
  EXPECT_TRUE(std::regex_search(r.out, std::regex(R"(^strand serve: http://127\.0\.0\.1:[0-9]+/ \(data in data\))"))) << r.out;
  EXPECT_TRUE(std::filesystem::exists(dir + "/data/strand.sqlite"));
}

// The design page in headless Chromium: its state is its URL; the summary follows a change.
TEST_F(ServerTest, DesignPageShowsTheSummaryOfItsUrl) {
  if (strand::testing::chromium_path().empty()) GTEST_SKIP() << "chromium not installed";
  start();
  const std::string base = "http://127.0.0.1:" + std::to_string(port_) +
                           "/?generator=scaffold&machine=deltawasp-2040-clay&nozzle=0.84&gap=1.6&size=20x20&layers=";
  const auto two = strand::testing::run_chromium(dir_, "--virtual-time-budget=15000 --dump-dom", base + "2");
  EXPECT_NE(two.out.find("data-state=\"done\""), std::string::npos) << two.out.substr(0, 2000);
  EXPECT_NE(two.out.find("layers         2,"), std::string::npos) << two.out;
  EXPECT_NE(two.out.find("check: ok"), std::string::npos);
  const auto three = strand::testing::run_chromium(dir_, "--virtual-time-budget=15000 --dump-dom", base + "3");
  EXPECT_NE(three.out.find("layers         3,"), std::string::npos) << three.out;
  EXPECT_FALSE(strand::testing::has_console_output(three.log)) << three.log;
  // an on/off parameter is a checkbox, set from the URL and sent as on: --stagger's layers
  const auto staggered = strand::testing::run_chromium(dir_, "--virtual-time-budget=15000 --dump-dom", base + "4&stagger=true");
  EXPECT_NE(staggered.out.find("id=\"p-stagger\" name=\"stagger\" type=\"checkbox\""), std::string::npos) << staggered.out;
  EXPECT_NE(staggered.out.find("filaments      [9,9,8,8] per layer"), std::string::npos) << staggered.out;
  // an invalid value: the CLI's message next to its field
  const std::string bad_url = "http://127.0.0.1:" + std::to_string(port_) +
                              "/?generator=scaffold&machine=deltawasp-2040-clay&nozzle=-1&gap=1.6&size=20x20&layers=2";
  const auto bad = strand::testing::run_chromium(dir_, "--virtual-time-budget=15000 --dump-dom", bad_url);
  EXPECT_NE(bad.out.find("id=\"e-nozzle\" class=\"err\">scaffold.nozzle = -1: must be in (0, 10] (mm)</span>"), std::string::npos)
      << bad.out;
  const auto shot = strand::testing::run_chromium(dir_, "--virtual-time-budget=15000 --window-size=1200,900 --screenshot='" + dir_ + "/design.png'", base + "2");
  EXPECT_TRUE(std::filesystem::exists(dir_ + "/design.png"));
}

TEST_F(ServerTest, GalleryPageListsSavedJobs) {
  if (strand::testing::chromium_path().empty()) GTEST_SKIP() << "chromium not installed";
  start();
  json body = json::parse(kJob);
  body["name"] = "gallery piece";
  ASSERT_EQ(http(port_, "POST", "/api/jobs", body.dump()).status, 201);
  const auto dom = strand::testing::run_chromium(
      dir_, "--virtual-time-budget=15000 --dump-dom", "http://127.0.0.1:" + std::to_string(port_) + "/gallery");
  EXPECT_NE(dom.out.find("data-count=\"1\""), std::string::npos) << dom.out.substr(0, 3000);
  EXPECT_NE(dom.out.find("gallery piece"), std::string::npos);
  EXPECT_NE(dom.out.find("/?generator=scaffold&amp;machine=deltawasp-2040-clay"), std::string::npos) << dom.out;
  EXPECT_NE(dom.out.find("scaffold.gcode"), std::string::npos);
  EXPECT_FALSE(strand::testing::has_console_output(dom.log)) << dom.log;
}

}  // namespace
}  // namespace strand::serve
