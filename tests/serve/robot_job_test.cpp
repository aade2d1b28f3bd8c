// Robot jobs in the workbench (serve/job_request.h, serve/job_archive.h) over real HTTP on
// 127.0.0.1: a job on a cylinder and on an uploaded mesh against `strand job` byte for byte,
// files.zip holding exactly the job's recorded files, bad substrate parameters and a nozzle
// check's refusal answered 400 with nothing kept, uploads bounded, paths never taken from the
// client, other sites refused; a flat job's files naming no server directory; the design page
// and the gallery's edit and duplicate driven in Chromium (robot_job.py).
#include <gtest/gtest.h>
#include <zip.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "serve/api.h"
#include "tests/support/chromium.h"
#include "tests/support/cli_runner.h"
#include "tests/support/http_client.h"
#include "tests/support/mesh_shapes.h"
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

// The thesis' curved specimen (samples/missing-rib-cylinder.json): its parameters, and the
// substrate as the CLI's flags name it.
const json kRibParams = {{"nozzle", 1.2}, {"rib", 6}, {"angle", 20}, {"rows", 4}, {"cols", 8}, {"layers", 3}};
const json kCapParams = {{"nozzle", 1.2}, {"cell", 10}, {"cols", 3}, {"rows", 3}, {"layers", 3}};
const char* const kKuka = "kuka-iiwa14-wasp-cylinder";

std::string source(const std::string& path) { return slurp(std::string(STRAND_SOURCE_DIR) + "/" + path); }

Reply get(int port, const std::string& target) { return strand::testing::http_request(port, "GET", target, "", "text/plain"); }
Reply post_json(int port, const std::string& target, const json& body, const std::string& headers = "") {
  return strand::testing::http_request(port, "POST", target, body.dump(), "application/json", headers);
}
Reply post_form(int port, const std::vector<Part>& parts, const std::string& headers = "") {
  const auto [body, type] = strand::testing::multipart_body(parts);
  return strand::testing::http_request(port, "POST", "/api/jobs", body, type, headers);
}

// A Transfer-Encoding: chunked body as its bytes.
std::string dechunk(const std::string& body) {
  std::string out;
  for (std::size_t at = 0; at < body.size();) {
    const std::size_t eol = body.find("\r\n", at);
    if (eol == std::string::npos) break;
    const std::size_t n = std::stoul(body.substr(at, eol - at), nullptr, 16);
    if (n == 0) break;
    out += body.substr(eol + 2, n);
    at = eol + 2 + n + 2;
  }
  return out;
}

struct Entry {
  std::string name, bytes;
  zip_uint32_t dos_date_time = 0;
};
// The archive's entries in its order, read back with libzip.
std::vector<Entry> unzip(const std::string& archive) {
  std::vector<Entry> out;
  zip_error_t error;
  zip_error_init(&error);
  zip_source_t* src = zip_source_buffer_create(archive.data(), archive.size(), 0, &error);
  zip_t* z = src ? zip_open_from_source(src, ZIP_RDONLY, &error) : nullptr;
  if (!z) {
    ADD_FAILURE() << "not a zip archive: " << zip_error_strerror(&error);
    if (src) zip_source_free(src);
    return out;
  }
  for (zip_int64_t i = 0; i < zip_get_num_entries(z, 0); ++i) {
    zip_stat_t st;
    zip_stat_index(z, static_cast<zip_uint64_t>(i), 0, &st);
    Entry e{st.name, std::string(st.size, '\0')};
    zip_file_t* f = zip_fopen_index(z, static_cast<zip_uint64_t>(i), 0);
    EXPECT_EQ(zip_fread(f, e.bytes.data(), st.size), static_cast<zip_int64_t>(st.size));
    zip_fclose(f);
    out.push_back(e);
  }
  zip_close(z);
  return out;
}

class RobotJobTest : public strand::testing::ServeFixture {
 protected:
  void SetUp() override { start_server("robot-job"); }
  void expect_nothing_saved() {
    EXPECT_EQ(get(port_, "/api/jobs").j().at("jobs").size(), 0u);
    const fs::path jobs = fs::path(dir_) / "data" / "jobs";
    EXPECT_TRUE(!fs::exists(jobs) || fs::is_empty(jobs)) << "a job directory was left";
  }
  // Every file `strand job job.json -o OUTPUT --report report.json` writes in `cli` is the
  // server's, byte for byte; the server adds only its previews. Returns the CLI's summary.
  std::string expect_files_as_cli(const json& answer, const std::string& cli, const std::string& output,
                                  const std::vector<std::string>& inputs) {
    const auto run = run_strand("job job.json -o " + output + " --report report.json --quiet", cli);
    EXPECT_EQ(run.exit_code, 0) << run.err;
    std::vector<std::string> cli_files = {"preview.html", "preview.png"};
    for (const auto& e : fs::directory_iterator(cli)) {
      const std::string name = e.path().filename().string();
      if (name != "job.json") cli_files.push_back(name);
    }
    std::sort(cli_files.begin(), cli_files.end());
    std::vector<std::string> served;
    for (const auto& f : answer.at("files")) served.push_back(f.at("name"));
    EXPECT_EQ(served, cli_files) << "the job's files are the CLI's set and the two previews";
    for (const auto& f : answer.at("files")) {
      const std::string name = f.at("name");
      if (name.rfind("preview.", 0) == 0) continue;
      const Reply r = get(port_, f.at("url"));
      EXPECT_EQ(r.status, 200) << name;
      EXPECT_TRUE(r.body == slurp(cli + "/" + name)) << name << " differs from strand job's";
    }
    for (const std::string& input : inputs) EXPECT_NE(std::find(served.begin(), served.end(), input), served.end());
    EXPECT_EQ(answer.at("summary").get<std::string>(), run.out) << "the summary is what strand job prints";
    EXPECT_EQ(answer.at("report"), json::parse(slurp(cli + "/report.json")));
    return run.out;
  }
};

TEST_F(RobotJobTest, CylinderJobIsByteIdenticalToStrandJob) {
  const Reply r = post_json(port_, "/api/jobs",
                            {{"name", "rib sleeve"}, {"generator", "missing-rib"}, {"machine", kKuka},
                             {"substrate", "cylinder"}, {"substrate-radius", 20}, {"substrate-length", 80},
                             {"params", kRibParams}});
  ASSERT_EQ(r.status, 201) << r.body;
  const json answer = r.j();
  EXPECT_EQ(answer.at("job").at("substrate"), json({{"type", "cylinder"}, {"radius", 20}, {"length", 80}}))
      << "kept as a job file keeps it";
  const std::string cli = fresh_dir("robot-cli");
  std::ofstream(cli + "/job.json") << json({{"generator", "missing-rib"}, {"machine", kKuka},
                                           {"substrate", {{"type", "cylinder"}, {"radius", 20}, {"length", 80}}},
                                           {"params", kRibParams}});
  const std::string summary = expect_files_as_cli(answer, cli, "missing-rib.csv", {"MissingRib.java", "missing_rib.src",
                                                                                  "missing_rib.dat", "missing-rib.extruder.gcode"});
  EXPECT_NE(summary.find("substrate      cylinder r 20.000 mm, length 80.000 mm"), std::string::npos) << summary;
  EXPECT_EQ(get(port_, answer.at("preview_png").get<std::string>()).body.rfind("\x89PNG", 0), 0u);
  EXPECT_EQ(answer.at("zip"), "/api/jobs/" + std::to_string(answer.at("id").get<int>()) + "/files.zip");
  // The other cells write their own controller's program from the same pose program.
  const Reply ur = post_json(port_, "/api/generate",
                             {{"generator", "missing-rib"}, {"machine", "ur10e-wasp-cylinder"},
                              {"substrate", {{"type", "cylinder"}, {"radius", 20}, {"length", 80}}}, {"params", kRibParams}});
  ASSERT_EQ(ur.status, 200) << ur.body;
  EXPECT_NE(ur.body.find("\"name\":\"missing-rib.script\""), std::string::npos) << "URScript listed";
}

TEST_F(RobotJobTest, ZipHoldsExactlyTheRecordedFilesTheSameBytesEveryTime) {
  const Reply r = post_json(port_, "/api/jobs",
                            {{"name", "rib"}, {"generator", "missing-rib"}, {"machine", kKuka}, {"substrate", "cylinder"},
                             {"substrate-radius", 20}, {"substrate-length", 80}, {"params", kRibParams}});
  ASSERT_EQ(r.status, 201) << r.body;
  const json answer = r.j();
  const fs::path folder = fs::path(dir_) / "data" / "jobs" / std::to_string(answer.at("id").get<int>());
  std::ofstream(folder / "stray.txt") << "not recorded";  // only recorded files go in
  const Reply zip = get(port_, answer.at("zip"));
  ASSERT_EQ(zip.status, 200) << zip.body;
  EXPECT_NE(zip.head.find("Content-Type: application/zip"), std::string::npos) << zip.head;
  EXPECT_NE(zip.head.find("attachment; filename=\"strand-job-"), std::string::npos) << zip.head;
  const std::string bytes = dechunk(zip.body);
  const std::vector<Entry> entries = unzip(bytes);
  ASSERT_EQ(entries.size(), answer.at("files").size());
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const json& f = answer.at("files").at(i);
    EXPECT_EQ(entries[i].name, f.at("name").get<std::string>()) << "sorted as the files list";
    EXPECT_TRUE(entries[i].bytes == get(port_, f.at("url")).body) << entries[i].name;
  }
  fs::last_write_time(folder / "missing-rib.csv", fs::file_time_type::clock::now() - std::chrono::hours(50));
  EXPECT_TRUE(dechunk(get(port_, answer.at("zip")).body) == bytes) << "the archive depends on the files alone";
  EXPECT_FALSE(fs::exists(fs::path(dir_) / "data" / "scratch") && !fs::is_empty(fs::path(dir_) / "data" / "scratch"))
      << "no scratch archive left";
  EXPECT_EQ(strand::testing::http_request(port_, "POST", answer.at("zip"), "{}").status, 405);
  EXPECT_EQ(get(port_, "/api/jobs/999/files.zip").status, 404);
}

TEST_F(RobotJobTest, UploadedMeshJobIsByteIdenticalToStrandJobOnThatMesh) {
  const std::string cap = source("samples/meshes/sphere-cap.stl");
  const json job = {{"name", "cap"}, {"generator", "tetrachiral"}, {"machine", kKuka}, {"params", kCapParams}};
  const Reply r = post_form(port_, {{"job", job.dump()}, {"substrate-mesh", cap, "../../my cap.stl"}});
  ASSERT_EQ(r.status, 201) << r.body;
  const json answer = r.j();
  EXPECT_EQ(answer.at("job").at("substrate"), json({{"type", "mesh"}, {"mesh", "substrate.stl"}}));
  const std::string cli = fresh_dir("robot-mesh-cli");
  std::ofstream(cli + "/substrate.stl", std::ios::binary) << cap;
  std::ofstream(cli + "/job.json") << json({{"generator", "tetrachiral"}, {"machine", kKuka},
                                           {"substrate", {{"type", "mesh"}, {"mesh", "substrate.stl"}}},
                                           {"params", kCapParams}});
  expect_files_as_cli(answer, cli, "tetrachiral.csv", {"substrate.stl", "tetrachiral.substrate.json"});
  const json record = json::parse(get(port_, "/api/jobs/" + std::to_string(answer.at("id").get<int>()) +
                                                 "/files/tetrachiral.substrate.json").body);
  EXPECT_EQ(record.at("mesh"), "substrate.stl") << "the record finds the mesh beside the CSV in the zip too";
  EXPECT_FALSE(fs::exists(fs::path(dir_) / "my cap.stl"));
}

TEST_F(RobotJobTest, BadSubstrateParametersGet400NamingThemAndNothingSaved) {
  const json base = {{"name", "x"}, {"generator", "missing-rib"}, {"machine", kKuka}, {"params", kRibParams}};
  const auto with = [&](const json& extra) { json j = base; j.update(extra); return j; };
  const std::vector<std::pair<json, std::string>> cases = {
      {with({{"substrate", "cylinder"}, {"substrate-radius", 0}, {"substrate-length", 80}}), "substrate.radius = 0: must be in (0, 10000] (mm)"},
      {with({{"substrate", "cylinder"}, {"substrate-radius", 20}}), "substrate.length: missing"},
      {with({{"substrate", "sphere"}, {"substrate-radius", 20}, {"substrate-length", 80}}), "substrate.type = sphere"},
      {with({{"substrate", {{"type", "cylinder"}, {"radius", 20}, {"length", 80}}}, {"substrate-radius", 30}}),
       "job.substrate-radius: given twice"},
      {with({{"substrate", {{"type", "mesh"}, {"mesh", "/etc/passwd"}}}}), "job.substrate-mesh: the server reads no path"},
      {with({{"substrate", "mesh"}, {"substrate-mesh", "../samples/meshes/sphere-cap.stl"}}), "job.substrate-mesh: the server reads no path"},
      {with({{"substrate", 7}}), "job.substrate: must be cylinder or mesh"},
  };
  for (const auto& [body, message] : cases) {
    const Reply r = post_json(port_, "/api/jobs", body);
    EXPECT_EQ(r.status, 400) << message << ": " << r.body;
    EXPECT_NE(r.j().value("error", "").find(message), std::string::npos) << r.body;
    EXPECT_EQ(r.body.find('\n'), r.body.size() - 1) << "one line";
  }
  const std::string cap = source("samples/meshes/sphere-cap.stl");
  const std::vector<std::pair<std::vector<Part>, std::string>> forms = {
      {{{"job", base.dump()}, {"substrate-mesh", "not a mesh\n", "a.stl"}}, "job.substrate-mesh: not a mesh file"},
      {{{"job", with({{"substrate", "cylinder"}}).dump()}, {"substrate-mesh", cap, "a.stl"}}, "job.substrate-mesh: only with substrate mesh"},
      {{{"substrate-mesh", cap, "a.stl"}}, "job: missing"},
      {{{"job", base.dump()}, {"colour", "red"}}, "job.colour: unknown field"},
      {{{"job", base.dump()}, {"substrate-mesh", "v 0 0 0\nv 1 0 0\nv 0 1 0\nmtllib ../../etc/x\nf 1 2 3\n", "a.obj"}},
       "job.substrate-mesh: an OBJ upload may name its material library by a plain file name only"},
  };
  for (const auto& [parts, message] : forms) {
    const Reply r = post_form(port_, parts);
    EXPECT_EQ(r.status, 400) << message << ": " << r.body;
    EXPECT_NE(r.j().value("error", "").find(message), std::string::npos) << r.body;
  }
  expect_nothing_saved();
}

// The planner's checks refuse, as `strand job` does: a pattern wider than the cylinder, and a
// mesh (a half pipe) whose far wall would enter the nozzle's cone. No file of the job is kept.
TEST_F(RobotJobTest, CheckRefusalGets400AndLeavesNoJobFiles) {
  const Reply wide = post_json(port_, "/api/jobs",
                               {{"name", "x"}, {"generator", "missing-rib"}, {"machine", kKuka}, {"substrate", "cylinder"},
                                {"substrate-radius", 15}, {"substrate-length", 80}, {"params", kRibParams}});
  EXPECT_EQ(wide.status, 400) << wide.body;
  EXPECT_NE(wide.j().value("error", "").find("substrate.wrap = patch: the pattern is 102.687 around"), std::string::npos)
      << wide.body;
  const std::string stl = fresh_dir("trough") + "/trough.stl";
  strand::testing::write_binary_stl(
      strand::testing::trough_mesh(slicer::Vec3(20.0, 0.0, 40.0), slicer::Vec3::UnitX(), 10.0, 60.0, 48, 30), stl);
  const json job = {{"name", "trough"}, {"generator", "scaffold"}, {"machine", kKuka},
                    {"params", {{"nozzle", 1.2}, {"gap", 2.0}, {"size", "26x30"}, {"layers", 1}}}};
  const Reply cone = post_form(port_, {{"job", job.dump()}, {"substrate-mesh", slurp(stl), "trough.stl"}});
  EXPECT_EQ(cone.status, 400) << cone.body;
  const std::string error = cone.j().value("error", "");
  EXPECT_EQ(error.rfind("substrate.mesh = substrate.stl: the nozzle would touch the mesh at (", 0), 0u) << error;
  EXPECT_EQ(error.find(dir_), std::string::npos) << "the data directory is not named";
  EXPECT_EQ(cone.body.find('\n'), cone.body.size() - 1) << "one line";
  expect_nothing_saved();
}

TEST_F(RobotJobTest, UploadsBoundedPathsRefusedOtherSitesRefused) {
  const json job = {{"name", "cap"}, {"generator", "tetrachiral"}, {"machine", kKuka}, {"params", kCapParams}};
  const Reply big = post_form(port_, {{"job", job.dump()}, {"substrate-mesh", std::string(kMaxUploadBytes + 1, 'x'), "a.stl"}});
  EXPECT_EQ(big.status, 413) << big.body;
  const std::vector<Part> parts = {{"job", job.dump()}, {"substrate-mesh", source("samples/meshes/sphere-cap.stl"), "a.stl"}};
  EXPECT_EQ(post_form(port_, parts, "Origin: http://evil.example\r\n").status, 403);
  EXPECT_EQ(post_form(port_, parts, "Sec-Fetch-Site: cross-site\r\n").status, 403);
  expect_nothing_saved();
  const Reply ok = post_form(port_, parts);
  ASSERT_EQ(ok.status, 201) << ok.body;
  const std::string id = std::to_string(ok.j().at("id").get<int>());
  for (const std::string& name : {std::string("..%2F..%2Fstrand.sqlite"), std::string("../substrate.stl"),
                                  std::string("%2Fetc%2Fpasswd")}) {
    EXPECT_EQ(get(port_, "/api/jobs/" + id + "/files/" + name).status, 404) << name;
  }
  EXPECT_EQ(get(port_, "/api/jobs/" + id + "/files.zip/x").status, 404);
}

// A flat job runs in its folder too: its files name their siblings as `strand job` run there
// does, never by the server's data directory (the report's output, the summary).
TEST_F(RobotJobTest, FlatJobFilesNameTheirSiblingsNotTheDataDirectory) {
  const json params = {{"nozzle", 0.84}, {"size", "10x10"}, {"gap", 1}, {"layers", 2}};
  const Reply r = post_json(port_, "/api/jobs", {{"name", "flat"}, {"generator", "scaffold"}, {"params", params}});
  ASSERT_EQ(r.status, 201) << r.body;
  const json answer = r.j();
  EXPECT_EQ(answer.at("report").at("output"), "scaffold.gcode");
  const std::string cli = fresh_dir("flat-cli");
  std::ofstream(cli + "/job.json") << json({{"generator", "scaffold"}, {"params", params}});
  expect_files_as_cli(answer, cli, "scaffold.gcode", {});
  const std::string data = dir_ + "/data";
  EXPECT_EQ(r.body.find(data), std::string::npos) << "the answer names the data directory";
  for (const auto& f : answer.at("files")) {
    EXPECT_EQ(get(port_, f.at("url")).body.find(data), std::string::npos) << f.at("name") << " names the data directory";
  }
}

TEST_F(RobotJobTest, RobotJobDocsCurlExamplesRun) {
  if (strand::testing::run_in_shell("command -v curl", dir_).exit_code != 0) GTEST_SKIP() << "curl not installed";
  const std::string root = dir_ + "/root";
  fs::create_directories(root + "/samples/meshes");
  std::ofstream(root + "/samples/meshes/sphere-cap.stl", std::ios::binary) << source("samples/meshes/sphere-cap.stl");
  const auto ran = strand::testing::run_doc_curl_lines("## Robot jobs", port_, root);
  ASSERT_EQ(ran.size(), 3u);
  for (const auto& c : ran) EXPECT_EQ(c.exit_code, 0) << c.line << "\n" << c.output;
  EXPECT_EQ(unzip(slurp(root + "/sleeve.zip")).size(), json::parse(slurp(root + "/sleeve.json")).at("files").size());
  EXPECT_EQ(json::parse(slurp(root + "/cap.json")).at("job").at("substrate").at("mesh"), "substrate.stl");
}

// The script also opens the gallery: a cylinder job's edit link carries its substrate, a mesh
// job's reopens on its recorded mesh, and its duplicate sends that mesh again.
TEST_F(RobotJobTest, BrowserRunsRobotJobsOnACylinderAndAnUploadedMesh) {
  const Reply sleeve = post_json(port_, "/api/jobs",
                                 {{"name", "sleeve r25"}, {"generator", "missing-rib"}, {"machine", kKuka}, {"substrate", "cylinder"},
                                  {"substrate-radius", 25}, {"substrate-length", 90}, {"params", kRibParams}});
  ASSERT_EQ(sleeve.status, 201) << sleeve.body;
  const auto r = strand::testing::run_browser_script("tests/serve/browser/robot_job.py", url("/"), dir_);
  if (r.exit_code == 77) GTEST_SKIP() << "python3-selenium or chromium-driver not installed";
  ASSERT_EQ(r.exit_code, 0) << r.log << r.out;
  const json list = get(port_, "/api/jobs").j().at("jobs");
  ASSERT_EQ(list.size(), 3u) << "the sleeve, the mesh job saved and its duplicate";
  std::vector<json> caps;
  for (const json& j : list) {
    if (j.at("name").get<std::string>().rfind("cap lattice", 0) == 0) caps.push_back(j);
  }
  ASSERT_EQ(caps.size(), 2u);
  for (const json& j : caps) EXPECT_EQ(j.at("job").at("substrate"), json({{"type", "mesh"}, {"mesh", "substrate.stl"}}));
  ASSERT_EQ(caps[0].at("files").size(), caps[1].at("files").size());
  for (std::size_t i = 0; i < caps[0].at("files").size(); ++i) {
    const json& a = caps[0].at("files").at(i);
    EXPECT_EQ(a.at("name"), caps[1].at("files").at(i).at("name"));
    EXPECT_TRUE(get(port_, a.at("url")).body == get(port_, caps[1].at("files").at(i).at("url")).body)
        << a.at("name") << ": the duplicate's differs";
  }
}

}  // namespace
}  // namespace strand::serve
