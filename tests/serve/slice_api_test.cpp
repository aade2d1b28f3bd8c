// The workbench's slicing (serve/slice_api.h) over real HTTP on 127.0.0.1: POST /api/slice
// against `strand slice` byte for byte (an STL and a 3MF with defects), its refusals (400
// with the CLI's line, 413 past the upload bound, 403 from another site) leaving nothing
// saved, client file names that never become paths, the navigation bar of every page, the
// slice page driven in Chromium (selenium) and every page's first look at two window sizes.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "serve/slice_api.h"
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

Reply post_slice(int port, const std::vector<Part>& parts, const std::string& headers = "") {
  const auto [body, type] = strand::testing::multipart_body(parts);
  return strand::testing::http_request(port, "POST", "/api/slice", body, type, headers);
}

Reply get(int port, const std::string& target) {
  return strand::testing::http_request(port, "GET", target, "", "text/plain");
}

std::string source(const std::string& path) { return slurp(std::string(STRAND_SOURCE_DIR) + "/" + path); }

class SliceApiTest : public strand::testing::ServeFixture {
 protected:
  void SetUp() override { start_server("slice"); }
  // No job in the gallery and no job directory: a refused request left nothing behind.
  void expect_nothing_saved() {
    EXPECT_EQ(get(port_, "/api/jobs").j().at("jobs").size(), 0u);
    const fs::path jobs = fs::path(dir_) / "data" / "jobs";
    EXPECT_TRUE(!fs::exists(jobs) || fs::is_empty(jobs)) << "a job directory was left";
  }
  // The server's slice of `mesh` (kept as `input`) against `strand slice input FLAGS` run in
  // a fresh directory: G-code bytes, report and printed summary.
  json expect_same_as_cli(const std::string& mesh, const std::string& input, const std::vector<Part>& flags,
                          const std::string& cli_flags) {
    std::vector<Part> parts = {{"file", mesh, "my mesh" + fs::path(input).extension().string()}};
    parts.insert(parts.end(), flags.begin(), flags.end());
    const Reply r = post_slice(port_, parts);
    EXPECT_EQ(r.status, 201) << r.body;
    const json j = r.j();
    if (r.status != 201) return j;
    EXPECT_EQ(j.at("job").at("generator"), "slice");
    EXPECT_EQ(j.at("job").at("input"), input);
    const std::string cli = fresh_dir("slice-cli");
    std::ofstream(cli + "/" + input, std::ios::binary) << mesh;
    const auto run = run_strand("slice " + input + " " + cli_flags + " --report part.json --quiet", cli);
    EXPECT_EQ(run.exit_code, 0) << run.err;
    const std::string stem = fs::path(input).stem().string();
    const Reply gcode = get(port_, j.at("gcode").get<std::string>());
    EXPECT_EQ(gcode.status, 200);
    EXPECT_TRUE(gcode.body == slurp(cli + "/" + stem + ".gcode")) << "the server's G-code differs from strand slice's";
    EXPECT_EQ(j.at("summary").get<std::string>(), run.out) << "the summary is what strand slice prints";
    EXPECT_EQ(j.at("report"), json::parse(slurp(cli + "/part.json"))) << "the report is strand slice's";
    EXPECT_EQ(get(port_, j.at("input").get<std::string>()).body, mesh) << "the mesh is kept as sent";
    return j;
  }
};

TEST_F(SliceApiTest, SlicedStlIsByteIdenticalToStrandSliceAndSaved) {
  const json j = expect_same_as_cli(source("samples/meshes/bone-plug.stl"), "part.stl",
                                    {{"pattern", "scaffold"},
                                     {"nozzle", "0.6"},
                                     {"gap", "1"},
                                     {"perimeters", "1"},
                                     {"scale-to-fit", "30x30x30"},
                                     {"machine", "deltawasp-2040-clay"},
                                     {"name", "bone plug"}},
                                    "--pattern scaffold --nozzle 0.6 --gap 1 --perimeters 1 --scale-to-fit 30x30x30 "
                                    "--machine deltawasp-2040-clay");
  if (HasFailure()) return;
  EXPECT_EQ(j.at("part").at("size_mm"), json::array({30.0, 30.0, 18.0}));
  EXPECT_EQ(j.at("part").at("scale"), 1.5);
  EXPECT_EQ(j.at("check").at("ok"), true);
  EXPECT_EQ(j.at("check").at("crossings"), 0);
  EXPECT_EQ(j.at("figures").at("layers"), 34);
  EXPECT_EQ(get(port_, j.at("preview_png").get<std::string>()).body.rfind("\x89PNG", 0), 0u);
  EXPECT_EQ(get(port_, j.at("preview_html").get<std::string>()).status, 200);
  const json list = get(port_, "/api/jobs").j().at("jobs");
  ASSERT_EQ(list.size(), 1u) << "kept in the gallery";
  EXPECT_EQ(list.at(0).at("name"), "bone plug");
  EXPECT_EQ(list.at(0).at("job").at("params").at("scale-to-fit"), "30x30x30");
  EXPECT_EQ(get(port_, "/api/jobs/" + std::to_string(j.at("id").get<int>())).j().at("summary"), j.at("summary"));
}

// A 3MF of meshing gears (self-intersecting) with the tetrachiral lattice and a rotation:
// the defects found are in the answer's part, the bytes are still the CLI's.
TEST_F(SliceApiTest, Sliced3mfWithDefectsIsByteIdenticalAndSaysWhatWasFound) {
  const json j = expect_same_as_cli(source("tests/data/meshes-public/cube_gears.3mf"), "part.3mf",
                                    {{"pattern", "Tetrachiral"}, {"nozzle", "0.6"}, {"cell", "5"},
                                     {"node-core", "1.2"}, {"scale-to-fit", "30x30x30"}, {"rotate", "0,0,30"}},
                                    "--pattern Tetrachiral --nozzle 0.6 --cell 5 --node-core 1.2 "
                                    "--scale-to-fit 30x30x30 --rotate 0,0,30");
  if (HasFailure()) return;
  const std::string notes = j.at("part").at("notes").dump();
  EXPECT_NE(notes.find("self-intersecting"), std::string::npos) << notes;
  EXPECT_NE(j.at("summary").get<std::string>().find("note           mesh:"), std::string::npos);
  EXPECT_EQ(j.at("name"), "my mesh.3mf") << "no name given: the client's file name, shown only";
}

TEST_F(SliceApiTest, BadUploadsGet400WithTheCliLineAndNothingSaved) {
  const std::string plug = source("samples/meshes/bone-plug.stl");
  const std::vector<std::pair<std::vector<Part>, std::string>> cases = {
      {{{"file", "hello, not a mesh\n", "a.stl"}}, "slice.file: not a mesh file"},
      {{{"file", std::string(200, '\0'), "a.stl"}}, "slice.file: not a mesh file"},
      {{{"file", "solid x\nendsolid x\n", "a.stl"}}, "mesh = part.stl: no triangles in the file"},
      {{{"file", source("tests/data/ply-list-count-2e31.ply"), "a.ply"}},
       "mesh = part.ply: PLY face 0: a list of 2147483647 entries needs"},
      {{{"file", plug, "a.stl"}, {"nozzle", "-1"}}, "scaffold.nozzle = -1: must be in (0, 10] (mm)"},
      {{{"file", plug, "a.stl"}, {"pattern", "tetrachiral"}, {"nozzle", "0.4"}, {"cell", "5"}, {"rows", "4"}},
       "tetrachiral.rows = 4: makes no sense for a sliced part"},
      {{{"file", plug, "a.stl"}, {"cell", "5"}}, "slice.cell: not a scaffold flag"},
      {{{"file", plug, "a.stl"}, {"rotate", "1,2"}}, "slice.rotate = 1,2"},
      {{{"file", plug, "a.stl"}, {"perimeters", "one"}}, "slice.perimeters = one: must be a whole number"},
      {{{"file", plug, "a.stl"}, {"mesh-units", "furlong"}}, "slice.mesh-units = furlong"},
      {{{"file", plug, "a.stl"}, {"machine", "../../etc/passwd"}}, "slice.machine = ../../etc/passwd: not a machine"},
      {{{"file", plug, "a.stl"}, {"colour", "red"}}, "slice.colour: unknown field"},
      {{{"nozzle", "0.6"}}, "slice.file: missing"},
      {{{"file", "v 0 0 0\nv 1 0 0\nv 0 1 0\nmtllib ../../../../dev/zero\nf 1 2 3\n", "a.obj"}},
       "slice.file: an OBJ upload may name its material library by a plain file name only"},
      {{{"file", R"({"asset":{"version":"2.0"},"buffers":[{"uri":"/etc/passwd","byteLength":8}]})", "a.gltf"}},
       "slice.file: a glTF upload must hold its buffers and images"},
  };
  for (const auto& [parts, message] : cases) {
    const Reply r = post_slice(port_, parts);
    EXPECT_EQ(r.status, 400) << message << ": " << r.body;
    EXPECT_NE(r.j().value("error", "").find(message), std::string::npos) << r.body;
    EXPECT_EQ(r.body.find('\n'), r.body.size() - 1) << "one line";
  }
  EXPECT_EQ(strand::testing::http_request(port_, "POST", "/api/slice", "{}").status, 400) << "not multipart";
  EXPECT_EQ(get(port_, "/api/slice").status, 405);
  expect_nothing_saved();
}

TEST_F(SliceApiTest, OversizeUploadGets413BeforeItIsReadAndNothingSaved) {
  const Reply r = post_slice(port_, {{"file", std::string(kMaxUploadBytes + 1, 'x'), "big.stl"}});
  EXPECT_EQ(r.status, 413);
  EXPECT_NE(r.j().value("error", "").find(std::to_string(kMaxUploadBytes)), std::string::npos) << r.body;
  expect_nothing_saved();
  // the handler's own bound, for requests that do not come through cpp-httplib (the fuzz target)
  Api api(ApiOptions{dir_ + "/direct", ""});
  Request big;
  big.method = "POST";
  big.path = "/api/slice";
  big.files.push_back({"file", "big.stl", "model/stl", std::string(kMaxUploadBytes + 1, 'x')});
  EXPECT_EQ(api.handle(big).status, 413);
}

TEST_F(SliceApiTest, ForeignOriginIsRefusedAsTheOtherPostsAre) {
  const std::vector<Part> parts = {
      {"file", source("samples/meshes/bone-plug.stl"), "a.stl"}, {"nozzle", "0.6"}, {"gap", "1"}};
  EXPECT_EQ(post_slice(port_, parts, "Origin: http://evil.example\r\n").status, 403);
  EXPECT_EQ(post_slice(port_, parts, "Referer: http://evil.example/x\r\n").status, 403);
  EXPECT_EQ(post_slice(port_, parts, "Sec-Fetch-Site: cross-site\r\n").status, 403);
  expect_nothing_saved();
  const std::string self = "http://127.0.0.1:" + std::to_string(port_);
  EXPECT_EQ(post_slice(port_, parts, "Origin: " + self + "\r\nSec-Fetch-Site: same-origin\r\n").status, 201);
}

TEST_F(SliceApiTest, ClientFileNamesNeverBecomePaths) {
  const std::string plug = source("samples/meshes/bone-plug.stl");
  const std::string absolute = (fs::temp_directory_path() / "strand-slice-outside.stl").string();
  for (const std::string& name : {std::string("../../../outside.stl"), absolute, std::string("..\\..\\x.stl"),
                                  std::string("a/../../b.obj")}) {
    const Reply r = post_slice(port_, {{"file", plug, name}, {"nozzle", "0.6"}, {"gap", "1"}});
    ASSERT_EQ(r.status, 201) << name << ": " << r.body;
    const json answer = r.j();
    EXPECT_EQ(answer.at("job").at("input"), "part.stl") << "told by its content, not its name";
    for (const auto& f : answer.at("files")) {
      const std::string n = f.at("name");
      EXPECT_EQ(n.find_first_of("/\\"), std::string::npos) << n;
    }
  }
  EXPECT_FALSE(fs::exists(fs::path(dir_) / "outside.stl"));
  EXPECT_FALSE(fs::exists(absolute));
  for (const auto& e : fs::recursive_directory_iterator(dir_)) {
    if (!e.is_regular_file()) continue;
    const std::string name = e.path().filename().string();
    EXPECT_TRUE(name.rfind("strand.sqlite", 0) == 0 || name.rfind("part.", 0) == 0 || name.rfind("preview.", 0) == 0 ||
                name == "report.json")
        << e.path();
  }
}

TEST(SliceMeshExtension, ToldApartByContent) {
  EXPECT_EQ(mesh_extension(std::string(80, 's') + std::string("\1\0\0\0", 4) + std::string(50, '\0')), ".stl");
  EXPECT_EQ(mesh_extension("solid cube\nfacet normal 0 0 1\n"), ".stl");
  EXPECT_EQ(mesh_extension("# exported\nv 0 0 0\nf 1 2 3\n"), ".obj");
  EXPECT_EQ(mesh_extension("ply\nformat ascii 1.0\n"), ".ply");
  EXPECT_EQ(mesh_extension(std::string("ply\nformat binary_little_endian 1.0\nend_header\n\0\0", 49)), ".ply");
  EXPECT_EQ(mesh_extension("OFF\n8 6 0\n"), ".off");
  EXPECT_EQ(mesh_extension("COFF\n8 6 0\n"), ".off");
  EXPECT_EQ(mesh_extension(" {\"asset\": {}}"), ".gltf");
  EXPECT_EQ(mesh_extension(std::string("glTF\2\0\0\0", 8)), ".glb");
  EXPECT_EQ(mesh_extension(std::string("PK\3\4", 4)), ".3mf");
  EXPECT_EQ(mesh_extension("<svg/>"), "");
  EXPECT_EQ(mesh_extension(""), "");
}

// The ```sh slice example of docs/workbench.md, run as from the repository's root (the bone
// plug copied to samples/meshes/ of a fresh directory): it succeeds and keeps the part.
TEST_F(SliceApiTest, SliceDocsCurlExampleRuns) {
  if (strand::testing::run_in_shell("command -v curl", dir_).exit_code != 0) GTEST_SKIP() << "curl not installed";
  const std::string root = dir_ + "/root";
  fs::create_directories(root + "/samples/meshes");
  std::ofstream(root + "/samples/meshes/bone-plug.stl", std::ios::binary) << source("samples/meshes/bone-plug.stl");
  std::istringstream page(source("docs/workbench.md"));
  bool in_block = false;
  int ran = 0;
  for (std::string line; std::getline(page, line);) {
    if (line.rfind("```", 0) == 0) {
      in_block = !in_block && line == "```sh slice";
      continue;
    }
    if (!in_block || line.rfind("curl ", 0) != 0) continue;
    const std::string local =
        std::regex_replace(line, std::regex("127\\.0\\.0\\.1:8080"), "127.0.0.1:" + std::to_string(port_));
    const auto r = strand::testing::run_in_shell("timeout 60 " + local, root);
    EXPECT_EQ(r.exit_code, 0) << line << "\n" << r.out << r.err;
    ++ran;
  }
  EXPECT_GE(ran, 1);
  const json sliced = json::parse(slurp(root + "/sliced.json"), nullptr, false);
  ASSERT_TRUE(sliced.is_object());
  EXPECT_EQ(sliced.value("name", ""), "bone plug");
  EXPECT_EQ(sliced.value("part", json::object()).value("size_mm", json()), json::array({30.0, 30.0, 18.0}));
}

// Every page's navigation bar reaches the slice page and the queue.
TEST_F(SliceApiTest, EveryPageLinksSliceAndQueue) {
  for (const char* page : {"/", "/slice", "/draw", "/gallery", "/queue"}) {
    const Reply r = get(port_, page);
    ASSERT_EQ(r.status, 200) << page;
    EXPECT_NE(r.body.find("href=\"/slice\""), std::string::npos) << page;
    EXPECT_TRUE(r.body.find("href=\"/queue\"") != std::string::npos || std::string(page) == "/queue") << page;
  }
}

// First impressions (tests/serve/browser/first_look.py): every page opened fresh at 1366x768
// and on a 390 px phone shows its example (the design page the thesis scaffold, generated and
// checked ok) without an error, no wider than the window, its bar, form and result apart, and
// a bar that links every page.
TEST_F(SliceApiTest, BrowserFirstLookAtEveryPage) {
  const auto r = strand::testing::run_browser_script("tests/serve/browser/first_look.py", url("/"), dir_);
  if (r.exit_code == 77) GTEST_SKIP() << "python3-selenium or chromium-driver not installed";
  ASSERT_EQ(r.exit_code, 0) << r.log << r.out;
  for (const char* page : {"design", "slice", "draw", "gallery", "sweep", "queue"})
    for (const char* size : {"wide", "phone"})
      EXPECT_TRUE(fs::exists(dir_ + "/workbench-" + page + "-" + size + ".png")) << page << " " << size;
}

// The slice page in Chromium: the bone plug chosen in the file input and sliced with the
// page's defaults (the thesis' values); the part's size, the summary and the saved job show.
TEST_F(SliceApiTest, BrowserSlicesAnUploadedMesh) {
  const auto r = strand::testing::run_browser_script("tests/serve/browser/slice.py", url("/slice"), dir_);
  if (r.exit_code == 77) GTEST_SKIP() << "python3-selenium or chromium-driver not installed";
  ASSERT_EQ(r.exit_code, 0) << r.log << r.out;
  const json list = get(port_, "/api/jobs").j().at("jobs");
  ASSERT_EQ(list.size(), 1u);
  EXPECT_EQ(list.at(0).at("name"), "bone-plug.stl");
  EXPECT_EQ(list.at(0).at("job").at("params").at("scale-to-fit"), "30x30x30");
  EXPECT_EQ(list.at(0).at("job").at("params").at("nozzle"), "0.6");
}

}  // namespace
}  // namespace strand::serve
