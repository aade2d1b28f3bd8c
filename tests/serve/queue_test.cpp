// The workbench's machine queue over real HTTP against the simulated firmware on a
// pseudo-terminal: a queued job streamed to the end (exactly the file's commands, progress
// over Server-Sent Events), pause/resume, cancel, a firmware error and resume from its line,
// a server destroyed mid-job and resumed by the next one, refused requests, the page in a
// browser and the curl examples of docs/workbench.md's Queue section.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <chrono>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "machines/profile.h"
#include "machines/send/protocol.h"
#include "machines/send/resume.h"
#include "serve/queue_store.h"
#include "serve/server.h"
#include "tests/support/chromium.h"
#include "tests/support/cli_runner.h"
#include "tests/support/http_client.h"
#include "tests/support/firmware_sim.h"

namespace strand::serve {
namespace {

using nlohmann::json;
using strand::testing::fresh_dir;
using strand::testing::slurp;

using strand::testing::connect_to;

void send_request(int fd, int port, const std::string& method, const std::string& target, const std::string& body,
                  const std::string& extra) {
  const std::string req = method + " " + target + " HTTP/1.1\r\nHost: 127.0.0.1:" + std::to_string(port) +
                          "\r\nConnection: close\r\nContent-Type: application/json\r\nContent-Length: " +
                          std::to_string(body.size()) + "\r\n" + extra + "\r\n" + body;
  ::send(fd, req.data(), req.size(), MSG_NOSIGNAL);
}

struct Reply {
  int status = 0;
  std::string body;
  json j() const { return json::parse(body, nullptr, false); }
};

Reply http(int port, const std::string& method, const std::string& target, const std::string& body = "",
           const std::string& extra = "") {
  Reply r;
  const int fd = connect_to(port, 30);
  if (fd < 0) return r;
  send_request(fd, port, method, target, body, extra);
  std::string all;
  char buf[65536];
  for (ssize_t n; (n = ::recv(fd, buf, sizeof buf, 0)) > 0;) all.append(buf, static_cast<std::size_t>(n));
  ::close(fd);
  const auto end = all.find("\r\n\r\n");
  if (end == std::string::npos || all.size() < 12) return r;
  r.status = std::stoi(all.substr(9, 3));
  r.body = all.substr(end + 4);
  return r;
}

// An open GET /api/events: what has arrived so far, read without blocking for long.
struct EventStream {
  int fd = -1;
  std::string seen;
  EventStream(int port) : fd(connect_to(port, 1)) {
    if (fd >= 0) send_request(fd, port, "GET", "/api/events", "", "");
  }
  ~EventStream() {
    if (fd >= 0) ::close(fd);
  }
  // Reads until `part` arrives (true) or `timeout_s` passes.
  bool wait_for(const std::string& part, double timeout_s) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
    char buf[4096];
    while (seen.find(part) == std::string::npos && std::chrono::steady_clock::now() < end) {
      const ssize_t n = ::recv(fd, buf, sizeof buf, 0);
      if (n == 0) break;
      if (n > 0) seen.append(buf, static_cast<std::size_t>(n));
    }
    return seen.find(part) != std::string::npos;
  }
};

const std::string kJob =
    R"({"name": "queue test", "generator": "scaffold", "machine": "deltawasp-2040-clay", "params": {"nozzle": 0.84, "gap": 1.6, "size": "20x20", "layers": 2}})";

std::string trimmed(std::string s) {
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

class QueueTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fresh_dir("queue");
    start_server();
    const Reply saved = http(port_, "POST", "/api/jobs", kJob);
    ASSERT_EQ(saved.status, 201) << saved.body;
    job_ = saved.j().at("id").get<int>();
    all_ = machines::commands_of(slurp(data() + "/jobs/" + std::to_string(job_) + "/scaffold.gcode"), "scaffold.gcode");
    std::erase_if(all_, [](const machines::Command& c) { return machines::sets_line_number(c.text); });
    ASSERT_GT(all_.size(), 40u);
  }
  void TearDown() override { server_.reset(); }
  std::string data() const { return dir_ + "/data"; }
  void start_server() {
    ServeOptions o;
    o.port = 0;
    o.data_dir = data();
    server_ = std::make_unique<Server>(o);
    port_ = server_->start();
    ASSERT_GT(port_, 0);
  }
  json queue(const std::string& port) {
    const Reply r = http(port_, "POST", "/api/queue",
                         json{{"job", job_}, {"file", "scaffold.gcode"}, {"port", port}, {"baud", 115200}, {"firmware", "marlin"}}.dump());
    EXPECT_EQ(r.status, 201) << r.body;
    return r.j();
  }
  Reply act(const json& entry, const std::string& action) {
    return http(port_, "POST", "/api/queue/" + std::to_string(entry.value("id", 0)) + "/" + action);
  }
  json entry(int id) {
    for (const json& e : http(port_, "GET", "/api/queue").j().value("entries", json::array())) {
      if (e.at("id") == id) return e;
    }
    return json::object();
  }
  // Polls GET /api/queue (20 ms apart) until `done` holds for the entry; 30 s at most.
  json wait(int id, const std::function<bool(const json&)>& done, const std::string& what) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    json e;
    while (std::chrono::steady_clock::now() < end) {
      e = entry(id);
      if (done(e)) return e;
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    ADD_FAILURE() << "timed out waiting for " << what << ": " << e.dump();
    return e;
  }
  json wait_state(int id, const std::string& state) {
    return wait(id, [&](const json& e) { return e.value("state", "") == state; }, state);
  }
  std::vector<std::string> texts_before(int line) const {
    std::vector<std::string> out;
    for (const auto& c : all_) {
      if (c.file_line < line) out.push_back(c.text);
    }
    return out;
  }
  // What the firmware must have run for a stop before `line` and a resume there: the file's
  // commands before it, the resume preamble of `strand send --resume-from`, the rest.
  std::vector<std::string> expected_with_resume(int line) const {
    std::vector<std::string> out = texts_before(line);
    machines::MachineProfile m = machines::load_profile("deltawasp-2040-clay");
    m.firmware = machines::Firmware::Marlin;
    for (const auto& p : machines::resume_preamble(m, machines::modal_state_before(all_, line, m)))
      out.push_back(trimmed(p.substr(0, p.find(';'))));
    for (const auto& c : all_) {
      if (c.file_line >= line) out.push_back(c.text);
    }
    return out;
  }
  static std::vector<std::string> trimmed_all(std::vector<std::string> v) {
    for (auto& s : v) s = trimmed(s);
    return v;
  }

  std::string dir_;
  std::unique_ptr<Server> server_;
  int port_ = 0;
  int job_ = 0;
  std::vector<machines::Command> all_;
};

TEST_F(QueueTest, StreamsAQueuedJobToTheEndWithProgressEvents) {
  testing::FirmwareSim sim(false, {});
  EventStream events(port_);
  ASSERT_TRUE(events.wait_for(": queue events", 5)) << events.seen;
  const json e = queue(sim.port());
  EXPECT_EQ(e.at("state"), "queued");
  EXPECT_EQ(act(e, "start").status, 200);
  const json done = wait_state(e.at("id"), "done");
  EXPECT_EQ(done.at("percent"), 100.0);
  EXPECT_EQ(done.at("acked"), static_cast<int>(all_.size()));
  EXPECT_EQ(done.at("line"), all_.back().file_line);
  EXPECT_EQ(done.at("time_left_s"), 0.0);
  EXPECT_EQ(trimmed_all(sim.executed()), texts_before(all_.back().file_line + 1));  // exactly the file
  EXPECT_EQ(sim.unrequested_duplicates(), 0);
  EXPECT_TRUE(events.wait_for("\"percent\":100.0", 5)) << events.seen.substr(0, 2000);
  EXPECT_NE(events.seen.find("\"state\":\"running\""), std::string::npos);
  // the machine's connection is saved for the next entry
  const json machines = http(port_, "GET", "/api/queue").j().at("machines");
  ASSERT_EQ(machines.size(), 1u);
  EXPECT_EQ(machines[0].at("port"), sim.port());
  EXPECT_EQ(machines[0].at("name"), "deltawasp-2040-clay");
}

TEST_F(QueueTest, PauseStopsBetweenLinesAndResumeSendsTheRestOnce) {
  testing::FirmwareSim sim(false, {.busy_at = 30});  // command 30 takes 600 ms
  const json e = queue(sim.port());
  const int id = e.at("id");
  ASSERT_EQ(act(e, "start").status, 200);
  wait(id, [](const json& x) { return x.value("acked", 0) >= 29; }, "29 commands acknowledged");
  const Reply paused_reply = act(e, "pause");
  EXPECT_EQ(paused_reply.status, 200) << paused_reply.body;
  const json paused = wait_state(id, "paused");
  const int line = paused.at("resume_line");
  EXPECT_GT(line, all_.front().file_line);
  EXPECT_LT(paused.at("percent").get<double>(), 100.0);
  EXPECT_EQ(trimmed_all(sim.executed()), texts_before(line));  // nothing sent after the pause
  EXPECT_EQ(act(e, "start").status, 409);                        // start is for queued entries
  ASSERT_EQ(act(e, "resume").status, 200);
  wait_state(id, "done");
  EXPECT_EQ(trimmed_all(sim.executed()), expected_with_resume(line));
}

TEST_F(QueueTest, CancelStopsARunningJobAndDropsAQueuedOne) {
  testing::FirmwareSim sim(false, {.busy_at = 30});
  const json running = queue(sim.port());
  const json waiting = queue(sim.port());
  ASSERT_EQ(act(running, "start").status, 200);
  EXPECT_EQ(act(waiting, "start").status, 409);  // one job per port
  wait(running.at("id"), [](const json& x) { return x.value("acked", 0) >= 29; }, "29 commands acknowledged");
  ASSERT_EQ(act(running, "cancel").status, 200);
  const json cancelled = wait_state(running.at("id"), "cancelled");
  EXPECT_LT(sim.executed().size(), all_.size());
  EXPECT_EQ(act(running, "resume").status, 409);
  EXPECT_EQ(act(waiting, "cancel").status, 200);
  EXPECT_EQ(entry(waiting.at("id")).at("state"), "cancelled");
  // the port is free again: "return home" runs on it
  const std::size_t before = sim.executed().size();
  ASSERT_EQ(act(running, "home").status, 200);
  wait(running.at("id"), [](const json& x) { return !x.value("homing", true); }, "the return home");
  const auto after = sim.executed();
  ASSERT_EQ(after.size(), before + 1);
  EXPECT_EQ(after.back(), "G28");
}

TEST_F(QueueTest, FirmwareErrorStopsWithItsLineAndResumesFromThere) {
  testing::FirmwareSim sim(false, {.klipper_error_at = 20});  // "!! Move out of range", not run
  const json e = queue(sim.port());
  ASSERT_EQ(act(e, "start").status, 200);
  const json failed = wait_state(e.at("id"), "failed");
  const int line = all_[19].file_line;
  EXPECT_EQ(failed.at("resume_line"), line);
  EXPECT_EQ(failed.at("line"), all_[18].file_line);
  EXPECT_NE(failed.at("message").get<std::string>().find("line " + std::to_string(line) + ": !! Move out of range"),
            std::string::npos)
      << failed.dump();
  EXPECT_NE(failed.at("messages").dump().find("Move out of range"), std::string::npos);
  EXPECT_EQ(trimmed_all(sim.executed()), texts_before(line));
  ASSERT_EQ(act(e, "resume").status, 200);
  wait_state(e.at("id"), "done");
  EXPECT_EQ(trimmed_all(sim.executed()), expected_with_resume(line));
}

TEST_F(QueueTest, AJobCutOffByTheServerStoppingResumesOnTheNextFromItsLastAcknowledgedLine) {
  testing::FirmwareSim sim(false, {.busy_at = 30});
  const json e = queue(sim.port());
  const int id = e.at("id");
  ASSERT_EQ(act(e, "start").status, 200);
  wait(id, [](const json& x) { return x.value("acked", 0) >= 29; }, "29 commands acknowledged");
  server_.reset();  // mid-job
  start_server();
  const json cut = entry(id);
  ASSERT_EQ(cut.value("state", ""), "interrupted") << cut.dump();
  const int line = cut.at("resume_line");
  const auto ran = trimmed_all(sim.executed());
  ASSERT_GE(ran.size(), 29u);
  EXPECT_EQ(cut.at("line"), all_[ran.size() - 1].file_line);  // the last acknowledged line
  EXPECT_EQ(line, all_[ran.size()].file_line);
  EXPECT_EQ(ran, texts_before(line));
  ASSERT_EQ(act(e, "resume").status, 200);
  wait_state(id, "done");
  EXPECT_EQ(trimmed_all(sim.executed()), expected_with_resume(line));  // the rest, and only the rest
}

// A server killed outright leaves its row "running": the next one reads it as interrupted
// at the last line written.
TEST(QueueStore, ARowLeftRunningOpensInterruptedAtItsLastAcknowledgedLine) {
  const std::string path = fresh_dir("queue-store") + "/strand.sqlite";
  std::int64_t id = 0;
  {
    QueueStore store(path);
    QueueRow r;
    r.job = 1;
    r.job_name = "j";
    r.file = "scaffold.gcode";
    r.machine = "deltawasp-2040-clay";
    r.port = "/dev/ttyUSB0";
    r.firmware = "marlin";
    r.state = "running";
    id = store.insert(r);
    store.progress(id, 41, 42, 30);
  }
  QueueStore again(path);
  const auto rows = again.rows();
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].id, id);
  EXPECT_EQ(rows[0].state, "interrupted");
  EXPECT_EQ(rows[0].line, 41);
  EXPECT_EQ(rows[0].resume_line, 42);
  EXPECT_NE(rows[0].message.find("last acknowledged line 41"), std::string::npos);
}

TEST_F(QueueTest, BadRequestsGetOneLineJsonErrors) {
  testing::FirmwareSim sim(false, {});
  const auto post = [&](json body) {
    json b = {{"job", job_}, {"file", "scaffold.gcode"}, {"port", sim.port()}};
    b.update(body);
    return http(port_, "POST", "/api/queue", b.dump());
  };
  const auto expect_error = [](const Reply& r, int status, const std::string& part) {
    EXPECT_EQ(r.status, status) << r.body;
    const std::string error = r.j().value("error", "");
    EXPECT_NE(error.find(part), std::string::npos) << r.body;
    EXPECT_EQ(error.find('\n'), std::string::npos);
  };
  expect_error(post({{"port", "/dev/strand-no-such-tty"}}), 400, "queue.port = /dev/strand-no-such-tty: must be a serial device");
  expect_error(post({{"port", "/dev/../etc/passwd"}}), 400, "queue.port");
  expect_error(post({{"port", "/etc/passwd"}}), 400, "queue.port");
  expect_error(post({{"port", sim.port() + "/.."}}), 400, "queue.port");
  expect_error(post({{"file", "../../strand.sqlite"}}), 400, "queue.file = ../../strand.sqlite: must be the name of a .gcode file");
  expect_error(post({{"file", "report.json"}}), 400, "queue.file");
  expect_error(post({{"job", 999}}), 404, "queue.job = 999");
  expect_error(post({{"baud", 12345}}), 400, "queue.baud = 12345: must be one of");
  expect_error(post({{"firmware", "smoothie"}}), 400, "queue.firmware = smoothie: must be one of marlin");
  expect_error(post({{"speed", 2}}), 400, "queue.speed: unknown key");
  expect_error(http(port_, "POST", "/api/queue", "{not json"), 400, "request");
  expect_error(http(port_, "DELETE", "/api/queue"), 405, "use GET or POST");
  expect_error(http(port_, "GET", "/api/queue/1/pause"), 405, "use POST");
  expect_error(http(port_, "POST", "/api/ports"), 405, "use GET");
  expect_error(http(port_, "POST", "/api/queue/abc/pause"), 404, "no queue entry abc");
  expect_error(http(port_, "POST", "/api/queue/77/pause"), 404, "no queue entry 77");
  const json e = post(json::object()).j();
  expect_error(http(port_, "POST", "/api/queue/" + std::to_string(e.value("id", 0)) + "/explode"), 404, "no queue action explode");
  expect_error(http(port_, "POST", "/api/queue/" + std::to_string(e.value("id", 0)) + "/pause"), 409, "is queued: pause needs a running entry");
  expect_error(http(port_, "POST", "/api/queue", json{{"job", job_}, {"file", "scaffold.gcode"}, {"port", sim.port()}}.dump(),
                    "Origin: http://evil.example\r\n"),
               403, "cross-origin");
  // listeners are bounded: the fifth GET /api/events is refused while four are open
  std::vector<std::unique_ptr<EventStream>> open;
  for (std::size_t i = 0; i < 4; ++i) {
    open.push_back(std::make_unique<EventStream>(port_));
    ASSERT_TRUE(open.back()->wait_for(": queue events", 5));
  }
  expect_error(http(port_, "GET", "/api/events"), 503, "4 listeners already");
}

// The page in Chromium (selenium): start the queued job on the simulated port and watch its
// progress reach 100 %; then a screenshot of the page.
TEST_F(QueueTest, BrowserStartsAQueuedJobAndSeesItDone) {
  testing::FirmwareSim sim(false, {});
  const json e = queue(sim.port());
  const std::string url = "http://127.0.0.1:" + std::to_string(port_) + "/queue";
  const auto r = strand::testing::run_browser_script("tests/serve/browser/queue_page.py", url, dir_);
  if (r.exit_code == 77) GTEST_SKIP() << "python3-selenium or chromium-driver not installed";
  EXPECT_EQ(r.exit_code, 0) << r.log << r.out;
  EXPECT_EQ(entry(e.at("id")).at("state"), "done");
  EXPECT_EQ(trimmed_all(sim.executed()), texts_before(all_.back().file_line + 1));
}

// The ```sh queue examples of docs/workbench.md, in order, against this server with the
// simulated firmware's port for /dev/ttyUSB0; after a pause the test waits for the entry to
// stop (as one watching the page would) before the next line.
TEST_F(QueueTest, WorkbenchDocsQueueExamplesRun) {
  if (strand::testing::run_in_shell("command -v curl", dir_).exit_code != 0) GTEST_SKIP() << "curl not installed";
  server_.reset();
  std::filesystem::remove_all(data());  // the examples start from an empty data directory
  start_server();
  testing::FirmwareSim sim(false, {.busy_at = 30});
  std::istringstream page(slurp(std::string(STRAND_SOURCE_DIR) + "/docs/workbench.md"));
  bool in_block = false;
  int ran = 0;
  for (std::string line; std::getline(page, line);) {
    if (line.rfind("```", 0) == 0) {
      in_block = !in_block && line == "```sh queue";
      continue;
    }
    if (!in_block || line.rfind("curl ", 0) != 0) continue;
    std::string local = std::regex_replace(line, std::regex("127\\.0\\.0\\.1:8080"), "127.0.0.1:" + std::to_string(port_));
    local = std::regex_replace(local, std::regex("/dev/ttyUSB0"), sim.port());
    const auto r = strand::testing::run_in_shell("timeout 60 " + local, dir_);
    EXPECT_EQ(r.exit_code, 0) << line << "\n" << r.out << r.err;
    ++ran;
    std::smatch m;
    if (std::regex_search(line, m, std::regex("/api/queue/([0-9]+)/(pause|resume|home)"))) {
      const int id = std::stoi(m[1]);
      const std::string action = m[2];
      wait(id, [&](const json& x) {
        return action == "pause" ? x.value("state", "") == "paused"
               : action == "resume" ? x.value("state", "") == "done"
                                    : !x.value("homing", true);
      }, action + " of entry " + m[1].str());
    }
  }
  EXPECT_GE(ran, 8);
  EXPECT_EQ(entry(1).value("state", ""), "done");
  EXPECT_EQ(entry(2).value("state", ""), "cancelled");
}

}  // namespace
}  // namespace strand::serve
