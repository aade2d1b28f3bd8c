// The 3D viewer (serve/view_api.h) over real HTTP: the index's layer stats are the job's
// report, layer ranges come as binary blocks, bad ranges get one line, and the page in headless
// Chromium (tests/serve/browser/view.py), with the standalone `strand preview -o x.html`.
#include "serve/view_api.h"

#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "postprocess/preview/viewer_data.h"
#include "tests/support/chromium.h"
#include "tests/support/cli_runner.h"
#include "tests/support/http_client.h"
#include "tests/support/serve_fixture.h"

namespace strand::serve {
namespace {

using nlohmann::json;
using strand::testing::http_request;

const std::string kJob = R"({"name": "scaffold", "generator": "scaffold", "machine": "deltawasp-2040-clay",
  "params": {"nozzle": 0.84, "gap": 1.6, "size": "20x20", "layers": 4}})";

class ViewApiTest : public strand::testing::ServeFixture {
 protected:
  void SetUp() override {
    start_server("view");
    const auto r = http_request(port_, "POST", "/api/jobs", kJob, "application/json");
    ASSERT_EQ(r.status, 201) << r.body;
    job_ = r.j();
  }
  strand::testing::HttpReply get(const std::string& target) { return http_request(port_, "GET", target, "", "text/plain"); }
  json job_;
};

TEST_F(ViewApiTest, IndexHasTheReportsLayersAndRangesAreBlocks) {
  const auto r = get("/api/jobs/1/view");
  ASSERT_EQ(r.status, 200) << r.body;
  const json index = r.j();
  const json& report = job_.at("report").at("layers");
  ASSERT_EQ(index.at("layers").size(), report.size());
  std::size_t bytes = 0;
  for (std::size_t i = 0; i < report.size(); ++i) {
    const json& l = index.at("layers").at(i);
    EXPECT_EQ(l.at("strands"), report.at(i).at("strands")) << i;
    EXPECT_NEAR(l.at("deposit_length_mm").get<double>(), report.at(i).at("deposit_length_mm").get<double>(), 1e-3) << i;
    EXPECT_NEAR(l.at("z").get<double>(), report.at(i).at("z_mm").get<double>(), 1e-3) << i;
    bytes += l.at("bytes").get<std::size_t>();
  }
  EXPECT_EQ(index.at("time"), "trapezoid");
  const auto all = get("/api/jobs/1/view/layers?from=0&to=3");
  ASSERT_EQ(all.status, 200);
  EXPECT_EQ(all.body.size(), bytes);
  const auto one = get("/api/jobs/1/view/layers?from=2&to=2");
  ASSERT_EQ(one.status, 200);
  const json& l2 = index.at("layers").at(2);
  EXPECT_EQ(one.body, all.body.substr(l2.at("offset").get<std::size_t>(), l2.at("bytes").get<std::size_t>()));
  const auto segs = post::decode_viewer_block(one.body, l2.at("segments"));
  ASSERT_FALSE(segs.empty());
  EXPECT_NEAR(segs.back().to_mm.z(), l2.at("z").get<double>(), 1e-4);
}

TEST_F(ViewApiTest, BadRangesAndMethodsAreRefused) {
  EXPECT_EQ(get("/api/jobs/1/view/layers?from=0&to=4").body, R"({"error":"view.to = 4: must be a layer in [0, 3]"})" "\n");
  EXPECT_EQ(get("/api/jobs/1/view/layers?from=-1&to=2").status, 400);
  EXPECT_EQ(get("/api/jobs/1/view/layers?from=3&to=2").status, 400);
  EXPECT_EQ(get("/api/jobs/1/view/layers?to=2").status, 400);
  EXPECT_EQ(get("/api/jobs/9/view").status, 404);
  EXPECT_EQ(get("/api/jobs/1/view/blocks.bin").status, 404);
  EXPECT_EQ(get("/view/x").status, 404);
  EXPECT_EQ(http_request(port_, "POST", "/api/jobs/1/view", "{}", "application/json").status, 405);
  const auto script = get("/assets/viewer.js");
  EXPECT_EQ(script.status, 200);
  EXPECT_NE(script.body.find("Three.js Authors"), std::string::npos) << "three.js is bundled, with its licence";
}

// A sliced part (turned, stood up, scaled to fit) is drawn from its kept upload as the report's
// placement puts it: the part's size, on the bed; a generator job has no part.
TEST_F(ViewApiTest, ASliceShowsItsPartOnTheBedAndAGeneratorJobNone) {
  const auto [body, type] = strand::testing::multipart_body(
      {{"file", strand::testing::slurp(std::string(STRAND_SOURCE_DIR) + "/samples/meshes/bone-plug.stl"), "plug.stl"},
       {"nozzle", "0.84"}, {"gap", "1.6"}, {"rotate", "0,0,30"}, {"up", "y"}, {"scale-to-fit", "16x16x16"}});
  const auto slice = http_request(port_, "POST", "/api/slice", body, type);
  ASSERT_EQ(slice.status, 201) << slice.body;
  const std::string id = std::to_string(slice.j().at("id").get<int>());
  const json report = json::parse(get("/api/jobs/" + id + "/files/report.json").body);
  EXPECT_EQ(report.at("mesh_placement").at("files"), json::array({slice.j().at("job").at("input")}));
  const auto r = get("/api/jobs/" + id + "/view");
  ASSERT_EQ(r.status, 200) << r.body;
  const json index = r.j();
  ASSERT_TRUE(index.contains("part")) << r.body.substr(0, 400);
  EXPECT_FALSE(index.contains("part_note"));
  const json& v = index.at("part").at("v");
  ASSERT_GT(v.size(), 9u);
  EXPECT_EQ(index.at("part").at("t").size() % 3, 0u);
  double lo[3] = {1e9, 1e9, 1e9}, hi[3] = {-1e9, -1e9, -1e9};
  for (std::size_t i = 0; i < v.size(); ++i) {
    lo[i % 3] = std::min(lo[i % 3], v[i].get<double>());
    hi[i % 3] = std::max(hi[i % 3], v[i].get<double>());
  }
  const json& size = report.at("derived").at("size_mm");
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(hi[k] - lo[k], size.at(k).get<double>(), 0.01) << "axis " << k;
  EXPECT_NEAR(lo[2], 0.0, 0.01) << "the part sits on the bed";
  EXPECT_NEAR((lo[0] + hi[0]) / 2, 0.0, 0.01) << "centred as sliced (the delta's centre)";
  const json generator = get("/api/jobs/1/view").j();
  EXPECT_FALSE(generator.contains("part"));
  EXPECT_FALSE(generator.contains("part_note"));
}

TEST_F(ViewApiTest, BrowserMovesTheSliderAndReadsTheLayerStats) {
  // The standalone page of the same G-code, opened by the script from disk.
  const std::string gcode = get("/api/jobs/1/files/scaffold.gcode").body;
  std::ofstream(dir_ + "/scaffold.gcode") << gcode;
  ASSERT_EQ(strand::testing::run_strand("preview scaffold.gcode -o standalone.html", dir_).exit_code, 0);
  const std::string url = "http://127.0.0.1:" + std::to_string(port_) + "/view/1";
  const auto r = strand::testing::run_browser_script("tests/serve/browser/view.py", url, dir_);
  if (r.exit_code == 77) GTEST_SKIP() << "python3-selenium or chromium-driver not installed";
  ASSERT_EQ(r.exit_code, 0) << r.log << r.out;
}

}  // namespace
}  // namespace strand::serve
