// The workbench's drawings (serve/plot_api.h) over real HTTP on 127.0.0.1: POST /api/plot
// against `strand plot` byte for byte (SVG and traced image), its bounds and refusals, the
// Draw section's curl examples, and the draw and design pages driven in Chromium (selenium).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "serve/plot_api.h"
#include "serve/server.h"
#include "tests/support/chromium.h"
#include "tests/support/cli_runner.h"
#include "tests/support/http_client.h"
#include "tests/support/serve_fixture.h"

namespace strand::serve {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using strand::testing::fresh_dir;
using strand::testing::run_strand;
using strand::testing::slurp;

using Reply = strand::testing::HttpReply;
using Part = strand::testing::FormPart;

Reply http(int port, const std::string& method, const std::string& target, const std::string& body,
           const std::string& content_type) {
  return strand::testing::http_request(port, method, target, body, content_type);
}

Reply post_plot(int port, const std::vector<Part>& parts) {
  const auto [body, type] = strand::testing::multipart_body(parts);
  return http(port, "POST", "/api/plot", body, type);
}

Reply get(int port, const std::string& target) {
  return http(port, "GET", target, "", "text/plain");
}

// Lines, a circle, a filled rectangle (hatched) and a word lettered in Hershey.
const std::string kSvg =
    R"(<svg xmlns="http://www.w3.org/2000/svg" width="120mm" height="80mm" viewBox="0 0 120 80">
<line x1="10" y1="10" x2="110" y2="70" stroke="#000"/>
<circle cx="60" cy="40" r="25" fill="none" stroke="#000"/>
<rect x="20" y="50" width="20" height="15" fill="#000"/>
<text x="70" y="20" font-size="8">Strand</text>
</svg>
)";

// A 64 x 48 grey image (PGM): a dark disc on a mid-grey band on white, two levels when traced.
std::string grey_image() {
  std::string pixels;
  for (int y = 0; y < 48; ++y) {
    for (int x = 0; x < 64; ++x) {
      const bool disc = (x - 20) * (x - 20) + (y - 24) * (y - 24) < 144;
      pixels += static_cast<char>(disc ? 20 : (x > 36 && x < 58 && y > 8 && y < 40) ? 120 : 250);
    }
  }
  return "P5\n64 48\n255\n" + pixels;
}

class DrawTest : public strand::testing::ServeFixture {
 protected:
  void SetUp() override { start_server("draw"); }
  std::string url(const std::string& path = "/") const {
    return "http://127.0.0.1:" + std::to_string(port_) + path;
  }
};

TEST_F(DrawTest, PlottedSvgIsByteIdenticalToStrandPlot) {
  const Reply r = post_plot(port_, {{"file", kSvg, "mine.svg"},
                                    {"machine", "xy-plotter-servo"},
                                    {"fit", "A6 landscape"},
                                    {"hatch-angle", "30"},
                                    {"font", "hershey:rowmans"}});
  ASSERT_EQ(r.status, 200) << r.body;
  const json j = r.j();
  EXPECT_NE(j.at("summary").get<std::string>().find("strokes"), std::string::npos);
  EXPECT_NE(j.at("summary").get<std::string>().find("text"), std::string::npos) << "lettered";
  EXPECT_EQ(j.at("check").at("outside_volume"), 0);
  EXPECT_EQ(j.at("job").at("generator"), "plot");
  const Reply gcode = get(port_, j.at("gcode").get<std::string>());
  ASSERT_EQ(gcode.status, 200);
  const std::string cli = fresh_dir("draw-cli");
  std::ofstream(cli + "/drawing.svg") << kSvg;
  const auto run = run_strand(
      "plot drawing.svg --machine xy-plotter-servo --fit 'A6 landscape' --hatch-angle 30 "
      "--font hershey:rowmans -o drawing.gcode",
      cli);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_TRUE(gcode.body == slurp(cli + "/drawing.gcode"))
      << "the server's G-code differs from strand plot's";
  EXPECT_NE(gcode.body.find("M280 P0 S30"), std::string::npos) << "the pen goes down";
  const Reply png = get(port_, j.at("preview_png").get<std::string>());
  EXPECT_EQ(png.body.rfind("\x89PNG", 0), 0u);
  EXPECT_EQ(get(port_, j.at("preview_html").get<std::string>()).status, 200);
  EXPECT_EQ(get(port_, j.at("input").get<std::string>()).body, kSvg)
      << "the drawing is kept as sent";
  EXPECT_EQ(get(port_, "/api/jobs").j().at("jobs").size(), 0u) << "not saved without a name";
}

TEST_F(DrawTest, ImageIsTracedAsStrandPlotTraces) {
  const std::string image = grey_image();
  const Reply r =
      post_plot(port_, {{"file", image, "photo.pgm"}, {"levels", "2"}, {"fit", "60x45"}});
  ASSERT_EQ(r.status, 200) << r.body;
  EXPECT_NE(r.j().at("summary").get<std::string>().find("2 level(s)"), std::string::npos) << r.body;
  const Reply gcode = get(port_, r.j().at("gcode").get<std::string>());
  const std::string cli = fresh_dir("draw-trace-cli");
  std::ofstream(cli + "/drawing.img", std::ios::binary) << image;
  const auto run =
      run_strand("plot drawing.img --trace --levels 2 --fit 60x45 -o drawing.gcode", cli);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_TRUE(gcode.body == slurp(cli + "/drawing.gcode"))
      << "the server's traced G-code differs from strand plot --trace";
  // the PNG preview of that plot, uploaded in turn, is traced as a PNG
  const Reply png = get(port_, r.j().at("preview_png").get<std::string>());
  const Reply again = post_plot(port_, {{"file", png.body, "preview.png"}, {"threshold", "0.6"}});
  ASSERT_EQ(again.status, 200) << again.body;
  EXPECT_NE(again.j().at("summary").get<std::string>().find("traced"), std::string::npos);
  EXPECT_EQ(again.j().at("job").at("input"), "drawing.png");
}

TEST_F(DrawTest, SavedPlotIsInTheGallery) {
  const Reply r = post_plot(port_, {{"svg", kSvg}, {"name", "my drawing"}, {"pens", "#000=2"}});
  ASSERT_EQ(r.status, 201) << r.body;
  const json list = get(port_, "/api/jobs").j().at("jobs");
  ASSERT_EQ(list.size(), 1u);
  EXPECT_EQ(list.at(0).at("name"), "my drawing");
  EXPECT_EQ(list.at(0).at("job").at("generator"), "plot");
  EXPECT_EQ(list.at(0).at("job").at("params").at("pens"), "#000=2");
  EXPECT_TRUE(list.at(0).at("preview_png").is_string());
}

TEST_F(DrawTest, OversizedUploadGets413Json) {
  const Reply r = post_plot(port_, {{"file", std::string(kMaxUploadBytes + 1, 'x'), "big.svg"}});
  EXPECT_EQ(r.status, 413);
  EXPECT_NE(r.j().value("error", "").find(std::to_string(kMaxUploadBytes)), std::string::npos)
      << r.body;
  // the handler's own bound, for requests that do not come through cpp-httplib (the fuzz target)
  Api api(ApiOptions{dir_ + "/direct", ""});
  Request big;
  big.method = "POST";
  big.path = "/api/plot";
  big.files.push_back({"file", "big.svg", "image/svg+xml", std::string(kMaxUploadBytes + 1, 'x')});
  const Response d = api.handle(big);
  EXPECT_EQ(d.status, 413);
  EXPECT_NE(d.body.find("\"error\""), std::string::npos);
}

TEST_F(DrawTest, BadOptionsGet400NamingThem) {
  const std::vector<std::pair<std::vector<Part>, std::string>> cases = {
      {{{"svg", kSvg}, {"tolerance", "99"}}, "plot.tolerance = 99: must be in [0.001, 5] (mm)"},
      {{{"svg", kSvg}, {"fill", "zigzag"}}, "plot.fill = zigzag"},
      {{{"svg", kSvg}, {"colour", "red"}}, "plot.colour: unknown field"},
      {{{"svg", kSvg}, {"machine", "deltawasp-2040-clay"}},
       "plot.machine = deltawasp-2040-clay: not a plotter"},
      {{{"svg", kSvg}, {"machine", "../../etc/passwd"}},
       "plot.machine = ../../etc/passwd: not a plotter"},
      {{{"svg", kSvg}, {"levels", "2"}}, "trace.levels: applies to images"},
      {{{"file", grey_image(), "a.pgm"}, {"levels", "12"}}, "trace.levels = 12: must be in [1, 8]"},
      {{{"file", "hello", "a.txt"}}, "plot.file: neither an SVG drawing nor an image"},
      {{{"machine", "xy-plotter-servo"}}, "plot.file: missing"},
      {{{"svg", kSvg}, {"mirror", "maybe"}}, "plot.mirror = maybe: must be true or false"},
      {{{"svg", "<svg xmlns=\"http://www.w3.org/2000/svg\"><line x1=\"0\"/></svg>"}},
       "drawing.svg"},
  };
  for (const auto& [parts, message] : cases) {
    const Reply r = post_plot(port_, parts);
    EXPECT_EQ(r.status, 400) << message << ": " << r.body;
    EXPECT_NE(r.j().value("error", "").find(message), std::string::npos) << r.body;
    EXPECT_EQ(r.body.find('\n'), r.body.size() - 1) << "one line";
  }
  EXPECT_EQ(http(port_, "POST", "/api/plot", "{}", "application/json").status, 400)
      << "not multipart";
  EXPECT_EQ(get(port_, "/api/plot").status, 405);
  EXPECT_EQ(get(port_, "/api/jobs").j().at("jobs").size(), 0u);
}

TEST_F(DrawTest, ClientFileNamesNeverBecomePaths) {
  const std::string absolute = (fs::temp_directory_path() / "strand-draw-outside.svg").string();
  for (const std::string& name : {std::string("../../../outside.svg"), absolute,
                                  std::string("..\\..\\x.svg"), std::string("a/../../b.svg")}) {
    const Reply r = post_plot(port_, {{"file", kSvg, name}, {"name", "t"}});
    ASSERT_EQ(r.status, 201) << name << ": " << r.body;
    const json answer = r.j();  // kept: the loop reads into it
    for (const auto& f : answer.at("files")) {
      const std::string n = f.at("name");
      EXPECT_EQ(n.find('/'), std::string::npos) << n;
      EXPECT_EQ(n.find(".."), std::string::npos) << n;
    }
    EXPECT_EQ(r.j().at("job").at("input"), "drawing.svg");
  }
  EXPECT_FALSE(fs::exists(dir_ + "/outside.svg"));
  EXPECT_FALSE(fs::exists(fs::path(dir_).parent_path() / "outside.svg"));
  EXPECT_FALSE(fs::exists(absolute));
  // every file the server wrote is inside its data directory, under a name it chose
  for (const auto& e : fs::recursive_directory_iterator(dir_)) {
    if (!e.is_regular_file()) continue;
    const std::string name = e.path().filename().string();
    EXPECT_TRUE(name == "strand.sqlite" || name.rfind("strand.sqlite-", 0) == 0 ||
                name.rfind("drawing.", 0) == 0 || name.rfind("preview.", 0) == 0 ||
                name == "report.json")
        << e.path();
  }
}

// The Draw section's curl examples of docs/workbench.md, in order (ServeDocs runs them after
// the other sections' examples; here they run alone, after the download they trace).
TEST_F(DrawTest, DrawDocsCurlExamplesRun) {
  if (strand::testing::run_in_shell("command -v curl", dir_).exit_code != 0)
    GTEST_SKIP() << "curl not installed";
  const Reply plotted = post_plot(port_, {{"svg", kSvg}, {"name", "for the preview"}});
  ASSERT_EQ(plotted.status, 201);
  std::ofstream(dir_ + "/preview.png", std::ios::binary)
      << get(port_, plotted.j().at("preview_png").get<std::string>()).body;
  const auto ran = strand::testing::run_doc_curl_lines("## Draw", port_, dir_);
  for (const auto& c : ran) EXPECT_EQ(c.exit_code, 0) << c.line << "\n" << c.output;
  EXPECT_GE(ran.size(), 3u);
  const json drawn = json::parse(slurp(dir_ + "/plotted.json"), nullptr, false);
  ASSERT_TRUE(drawn.is_object());
  EXPECT_EQ(drawn.value("check", json::object()).value("ok", false), true) << drawn.dump();
  const json traced = json::parse(slurp(dir_ + "/traced.json"), nullptr, false);
  ASSERT_TRUE(traced.is_object());
  EXPECT_EQ(traced.value("name", ""), "traced preview");
  EXPECT_NE(get(port_, drawn.value("gcode", "/none")).body.find("M280 P0 S30"), std::string::npos);
}

// Runs tests/serve/browser/<script>.py against this server; skipped without selenium.
void browse(const std::string& script, const std::string& url, const std::string& dir) {
  const auto r = strand::testing::run_browser_script("tests/serve/browser/" + script, url, dir);
  if (r.exit_code == 77) GTEST_SKIP() << "python3-selenium or chromium-driver not installed";
  EXPECT_EQ(r.exit_code, 0) << r.log << r.out;
}

// A line drawn with the mouse on the draw page's canvas, plotted: the G-code puts the pen
// down and draws, the preview appears.
TEST_F(DrawTest, BrowserDrawsALineAndPlotsIt) {
  browse("draw.py", url("/draw"), dir_);
  if (HasFatalFailure() || IsSkipped()) return;
  EXPECT_NE(slurp(dir_ + "/drawn.gcode").find("M280 P0 S30"), std::string::npos);
}

// The design page: a changed parameter changes the summary and the preview's canvas; Save
// puts the design in the gallery.
TEST_F(DrawTest, BrowserDesignChangeAndSaveShowsInGallery) {
  browse("design_save.py",
         url("/?generator=scaffold&machine=deltawasp-2040-clay&nozzle=0.84&gap=1.6&size=20x20&"
             "layers=2"),
         dir_);
  if (HasFatalFailure() || IsSkipped()) return;
  const json list = get(port_, "/api/jobs").j().at("jobs");
  ASSERT_EQ(list.size(), 1u);
  EXPECT_EQ(list.at(0).at("name"), "browser save");
  EXPECT_EQ(list.at(0).at("job").at("params").at("layers"), "3");
}

}  // namespace
}  // namespace strand::serve
