// Sweeps kept in the gallery (serve/sweep_api.h) over real HTTP: one group per sweep with its
// contact sheet, the points' G-code as `strand sweep` writes it, files only by recorded names,
// bounds and refusals, and the group's card on /gallery in headless Chromium.
#include "serve/sweep_api.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <thread>

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

// The sweep's base job as a saved design: gap 1.6, named "two layers".
json two_layer_design() {
  json design = json::parse(kSweep).at("job");
  design["params"]["gap"] = 1.6;
  design["name"] = "two layers";
  return design;
}

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

// The curl example of docs/workbench.md's "Sweeps" (ServeDocs runs it too).
TEST_F(SweepApiTest, DocsCurlExampleRuns) {
  if (strand::testing::run_in_shell("command -v curl", dir_).exit_code != 0)
    GTEST_SKIP() << "curl not installed";
  const auto ran = strand::testing::run_doc_curl_lines("## Sweeps", port_, dir_);
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

// A saved design swept (from_job) without waiting: 202 at once with the progress address,
// which tells done of total while it runs and the points once it has finished; the points'
// G-code is the saved job's with only the varied parameter changed.
TEST_F(SweepApiTest, SweepFromASavedJobReportsProgress) {
  json design = two_layer_design();
  const auto saved = http_request(port_, "POST", "/api/jobs", design.dump());
  ASSERT_EQ(saved.status, 201) << saved.body;
  const std::int64_t job = saved.j().at("id");
  const json body = {{"name", "from the gallery"}, {"from_job", job}, {"vary", {{"gap", {1.2, 1.6}}}},
                     {"wait", false}};
  const auto r = post(body);
  ASSERT_EQ(r.status, 202) << r.body;
  EXPECT_EQ(r.j().at("total"), 2);
  const std::string url = r.j().at("progress_url");
  json state;
  std::set<int> done_seen;
  for (int i = 0; i < 600; ++i) {
    state = http_request(port_, "GET", url).j();
    done_seen.insert(state.value("done", -1));
    if (state.at("status") != "running") break;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  ASSERT_EQ(state.at("status"), "ok") << state.dump();
  EXPECT_EQ(state.at("done"), 2);
  EXPECT_EQ(state.at("failed"), 0);
  EXPECT_LE(*done_seen.rbegin(), 2);
  ASSERT_EQ(state.at("points").size(), 2u);
  EXPECT_EQ(state.at("job").at("sweep").at("job").at("params").at("size"), "20x20")
      << "the saved job's parameters are the base";
  // the point with the saved gap is byte for byte the saved design's G-code
  json same = body;
  same["vary"] = {{"gap", {1.6}}};
  same["wait"] = true;
  same["name"] = "one point";
  const json one = post(same).j();
  const auto point = http_request(port_, "GET", one.at("points").at(0).at("output").get<std::string>());
  design["params"]["gap"] = 1.6;
  design["name"] = "gap 1.6";
  const json direct = http_request(port_, "POST", "/api/jobs", design.dump()).j();
  EXPECT_EQ(point.body, http_request(port_, "GET", direct.at("gcode").get<std::string>()).body);
}

TEST_F(SweepApiTest, FromJobRefusalsNameTheKey) {
  const json vary = {{"gap", {1.2}}};
  const auto missing = post({{"name", "x"}, {"from_job", 99}, {"vary", vary}});
  EXPECT_EQ(missing.status, 400);
  EXPECT_NE(missing.body.find("sweep.from_job = 99: no saved job"), std::string::npos) << missing.body;
  const auto text = post({{"name", "x"}, {"from_job", "1; rm"}, {"vary", vary}});
  EXPECT_EQ(text.status, 400);
  EXPECT_NE(text.body.find("sweep.from_job: must be the id of a saved job"), std::string::npos) << text.body;
  json base = json::parse(kSweep);
  base["name"] = "s";
  ASSERT_EQ(post(base).status, 201);  // job 1 is a sweep: not a base
  const auto sweep = post({{"name", "x"}, {"from_job", 1}, {"vary", vary}});
  EXPECT_NE(sweep.body.find("is not a finished generator job"), std::string::npos) << sweep.body;
  base["from_job"] = 1;
  EXPECT_NE(post(base).body.find("either job or from_job"), std::string::npos);
  const auto wait = post({{"name", "x"}, {"wait", "no"}, {"job", base["job"]}, {"vary", vary}});
  EXPECT_NE(wait.body.find("sweep.wait: must be true or false"), std::string::npos) << wait.body;
  EXPECT_EQ(http_request(port_, "GET", "/api/sweeps/7").status, 404);
  EXPECT_EQ(http_request(port_, "POST", "/api/sweeps/1").status, 405);
  EXPECT_EQ(http_request(port_, "GET", "/api/jobs").j().at("jobs").size(), 1u) << "refusals keep nothing";
}

// The sweep page in Chromium (tests/serve/browser/sweep.py): a saved design chosen as the base,
// its gap varied, the run followed to 3 of 3, the contact sheet and the scatter shown.
TEST_F(SweepApiTest, BrowserSweepsASavedDesign) {
  json design = two_layer_design();
  const auto saved = http_request(port_, "POST", "/api/jobs", design.dump());
  ASSERT_EQ(saved.status, 201) << saved.body;
  const std::string page = url("/sweep?job=" + std::to_string(saved.j().at("id").get<int>()));
  const auto r = strand::testing::run_browser_script("tests/serve/browser/sweep.py", page, dir_);
  if (r.exit_code == 77) GTEST_SKIP() << "python3-selenium or chromium-driver not installed";
  ASSERT_EQ(r.exit_code, 0) << r.log << r.out;
  const json list = http_request(port_, "GET", "/api/jobs").j().at("jobs");
  ASSERT_EQ(list.size(), 2u);
  EXPECT_EQ(list.at(0).at("job").at("sweep").at("vary").at("gap"),
            json({{"from", 1.2}, {"to", 2}, {"step", 0.4}}));
}

}  // namespace
}  // namespace strand::serve
