// Sweeps kept in the gallery (serve/sweep_api.h) over real HTTP: one group per sweep with its
// contact sheet, the points' G-code as `strand sweep` writes it, files only by recorded names,
// bounds and refusals, and the group's card on /gallery in headless Chromium.
#include "serve/sweep_api.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "serve/server.h"
#include "tests/support/chromium.h"
#include "tests/support/cli_runner.h"
#include "tests/support/http_client.h"
#include "tests/support/serve_fixture.h"

namespace strand::serve {
namespace {

using nlohmann::json;
using strand::testing::fresh_dir;
using strand::testing::http_request;
using strand::testing::slurp;

// Two points (gap 1.2 and 1.6) of a two-layer scaffold; its output path must be ignored.
const std::string kSweep = R"({"job": {"generator": "scaffold", "machine": "deltawasp-2040-clay",
  "params": {"nozzle": 0.84, "size": "20x20", "layers": 2}, "output": "../../escaped.gcode"},
  "vary": {"gap": [1.2, 1.6]}})";

class SweepApiTest : public strand::testing::ServeFixture {
 protected:
  void SetUp() override { start_server("sweep-api"); }
  strand::testing::HttpReply post(const json& body) {
    return http_request(port_, "POST", "/api/sweeps", body.dump());
  }
};

TEST_F(SweepApiTest, SweepIsOneGalleryGroupWithItsContactSheet) {
  json body = json::parse(kSweep);
  body["name"] = "gap study";
  const auto r = post(body);
  ASSERT_EQ(r.status, 201) << r.body;
  const json j = r.j();
  EXPECT_NE(j.at("summary").get<std::string>().find("2 point(s): 2 ran, 0 failed"),
            std::string::npos)
      << j.at("summary");
  ASSERT_EQ(j.at("points").size(), 2u);
  const json list = http_request(port_, "GET", "/api/jobs").j().at("jobs");
  ASSERT_EQ(list.size(), 1u) << "one group, not one job per point";
  EXPECT_EQ(list.at(0).at("job").at("generator"), "sweep");
  const auto sheet = http_request(port_, "GET", j.at("contact_sheet").get<std::string>());
  ASSERT_EQ(sheet.status, 200);
  EXPECT_NE(sheet.body.find("previews/"), std::string::npos) << "the sheet links its previews";
  // a point's G-code is what `strand job` writes for that point
  const json& point = j.at("points").at(0);
  const auto gcode = http_request(port_, "GET", point.at("output").get<std::string>());
  ASSERT_EQ(gcode.status, 200);
  const std::string cli = fresh_dir("sweep-api-cli");
  std::ofstream(cli + "/spec.json")
      << R"({"generator": "scaffold", "machine": "deltawasp-2040-clay",
    "params": {"nozzle": 0.84, "size": "20x20", "layers": 2, "gap": )" +
             point.at("varied").at("gap").dump() + "}}";
  ASSERT_EQ(strand::testing::run_strand("job spec.json", cli).exit_code, 0);
  EXPECT_TRUE(gcode.body == slurp(cli + "/spec.gcode"))
      << "the sweep point's G-code differs from strand job's";
  const auto png = http_request(port_, "GET", point.at("preview").get<std::string>());
  EXPECT_EQ(png.body.rfind("\x89PNG", 0), 0u) << point.at("preview");
  EXPECT_FALSE(std::filesystem::exists(dir_ + "/escaped.gcode"));
  EXPECT_FALSE(
      std::filesystem::exists(std::filesystem::path(dir_).parent_path() / "escaped.gcode"));
  // files only by recorded names
  const std::string base = "/api/sweeps/" + std::to_string(j.at("id").get<long>()) + "/files/";
  for (const std::string& bad : {base + "../../strand.sqlite", base + "..%2f..%2fstrand.sqlite",
                                 base + "previews/../index.html", base + "nothing.gcode",
                                 std::string("/api/sweeps/99/files/index.html")}) {
    EXPECT_EQ(http_request(port_, "GET", bad).status, 404) << bad;
  }
  EXPECT_EQ(
      http_request(port_, "DELETE", "/api/jobs/" + std::to_string(j.at("id").get<long>())).status,
      200);
  EXPECT_EQ(http_request(port_, "GET", j.at("contact_sheet").get<std::string>()).status, 404);
}

TEST_F(SweepApiTest, RefusalsNameTheKey) {
  json body = json::parse(kSweep);
  EXPECT_NE(post(body).j().value("error", "").find("sweep.name"), std::string::npos)
      << "a name is needed";
  body["name"] = "too big";
  body["vary"] = {
      {"gap", {{"from", 1.0}, {"to", 1.0 + 0.01 * kMaxServedSweepPoints}, {"step", 0.01}}}};
  const auto big = post(body);
  EXPECT_EQ(big.status, 400);
  EXPECT_NE(big.j().value("error", "").find("at most " + std::to_string(kMaxServedSweepPoints)),
            std::string::npos)
      << big.body;
  body["vary"] = {{"gap", {1.2}}};
  body["job"]["machine"] = "/etc/passwd";
  EXPECT_NE(
      post(body).j().value("error", "").find("sweep.job.machine = /etc/passwd: not a machine"),
      std::string::npos);
  EXPECT_EQ(http_request(port_, "GET", "/api/sweeps").status, 405);
  EXPECT_EQ(http_request(port_, "GET", "/api/jobs").j().at("jobs").size(), 0u);
}

// The curl example of docs/workbench.md's "Sweeps in the gallery" (ServeDocs runs it too).
TEST_F(SweepApiTest, DocsCurlExampleRuns) {
  if (strand::testing::run_in_shell("command -v curl", dir_).exit_code != 0)
    GTEST_SKIP() << "curl not installed";
  const auto ran = strand::testing::run_doc_curl_lines("## Sweeps in the gallery", port_, dir_);
  ASSERT_EQ(ran.size(), 1u);
  EXPECT_EQ(ran[0].exit_code, 0) << ran[0].output;
  const json sweep = json::parse(slurp(dir_ + "/sweep.json"), nullptr, false);
  ASSERT_TRUE(sweep.is_object());
  EXPECT_EQ(sweep.value("name", ""), "gap study");
  EXPECT_EQ(sweep.value("points", json::array()).size(), 2u);
}

TEST_F(SweepApiTest, GalleryShowsTheGroupCard) {
  if (strand::testing::chromium_path().empty()) GTEST_SKIP() << "chromium not installed";
  json body = json::parse(kSweep);
  body["name"] = "gap study";
  ASSERT_EQ(post(body).status, 201);
  const auto dom =
      strand::testing::run_chromium(dir_, "--virtual-time-budget=15000 --dump-dom",
                                    "http://127.0.0.1:" + std::to_string(port_) + "/gallery");
  EXPECT_NE(dom.out.find("class=\"job group\""), std::string::npos) << dom.out.substr(0, 3000);
  EXPECT_NE(dom.out.find(">contact sheet</a>"), std::string::npos);
  EXPECT_NE(dom.out.find("sweep of scaffold on deltawasp-2040-clay"), std::string::npos);
  EXPECT_NE(dom.out.find("/previews/scaffold_gap-1.6.png"), std::string::npos) << dom.out;
  EXPECT_FALSE(strand::testing::has_console_output(dom.log)) << dom.log;
}

}  // namespace
}  // namespace strand::serve
