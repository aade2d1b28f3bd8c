// Queue handlers: requests checked at the edge (a saved job's file by exact name, a serial
// device that exists, a baud rate and firmware from the lists `strand send` takes), then
// handed to serve::Queue. Nothing here touches a serial port.
#include "serve/queue_api.h"

#include "serve/api_state.h"

#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "jobs/job_runner.h"
#include "machines/send/serial_port.h"
#include "serve/queue.h"
#include "slicer/input_error.h"
#include "slicer/json_input.h"

namespace strand::serve {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// Entries of GET /api/ports at most.
constexpr std::size_t kMaxListedPorts = 64;

const char* const kFirmwares[] = {"marlin", "reprap", "klipper", "grbl"};

std::string shown(const std::string& s) { return s.substr(0, 200); }

// A path under /dev without "." or ".." parts that names a character device (stat follows
// links such as /dev/serial/by-id/...). The device is not opened: opening resets many boards.
void check_port(const std::string& port) {
  const fs::path p(port);
  const bool plain = port.rfind("/dev/", 0) == 0 && port.size() <= 200 &&
                     std::none_of(p.begin(), p.end(), [](const fs::path& part) { return part == "." || part == ".."; });
  struct stat st {};
  if (!plain || ::stat(port.c_str(), &st) != 0 || !S_ISCHR(st.st_mode)) {
    throw InputError("queue.port = " + shown(port) + ": must be a serial device under /dev that exists (GET /api/ports lists them)");
  }
}

json ports_json(Queue& queue) {
  std::set<std::string> paths;
  const auto add_matching = [&](const fs::path& dir, const std::vector<std::string>& prefixes) {
    std::error_code ec;
    for (fs::directory_iterator it(dir, ec), end; !ec && it != end && paths.size() < kMaxListedPorts; it.increment(ec)) {
      const std::string name = it->path().filename().string();
      if (std::any_of(prefixes.begin(), prefixes.end(), [&](const std::string& p) { return name.rfind(p, 0) == 0; })) {
        paths.insert(it->path().string());
      }
    }
  };
  add_matching("/dev/serial/by-id", {""});
  add_matching("/dev", {"ttyUSB", "ttyACM", "ttyAMA", "rfcomm"});
  const json listed = queue.list();  // kept: the loop reads into it
  for (const json& m : listed.at("machines")) paths.insert(m.at("port").get<std::string>());
  json list = json::array();
  for (const std::string& p : paths) {
    struct stat st {};
    if (::stat(p.c_str(), &st) != 0 || !S_ISCHR(st.st_mode)) continue;
    std::error_code ec;
    const fs::path device = fs::canonical(p, ec);
    list.push_back({{"path", p}, {"device", ec ? p : device.string()}});
  }
  return {{"ports", list}};
}

std::string firmware_of(const json& body, const std::optional<MachinePort>& saved, const std::string& machine) {
  std::string fw = saved ? saved->firmware : "";
  if (fw.empty()) {
    try {
      fw = machines::to_string(machines::load_profile(machine).firmware);
    } catch (const std::exception&) {
      fw = "marlin";
    }
  }
  fw = slicer::get_text(body, "firmware", "queue", fw);
  std::transform(fw.begin(), fw.end(), fw.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (std::find(std::begin(kFirmwares), std::end(kFirmwares), fw) == std::end(kFirmwares)) {
    throw InputError("queue.firmware = " + shown(fw) + ": must be one of marlin, reprap, klipper, grbl");
  }
  return fw;
}

Response add_entry(Store& store, Queue& queue, const Request& r) {
  const json body = slicer::parse_json(r.body, "request");
  if (!body.is_object()) throw InputError("request: must be a JSON object (job, file, port, baud, firmware)");
  for (const auto& [key, value] : body.items()) {
    if (key != "job" && key != "file" && key != "port" && key != "baud" && key != "firmware") {
      throw InputError("queue." + shown(key) + ": unknown key (job, file, port, baud, firmware)");
    }
  }
  const json& job_field = body.contains("job") ? body.at("job") : json();
  std::int64_t job_id = 0;
  if (job_field.is_number_integer()) {
    job_id = job_field.get<std::int64_t>();
  } else if (job_field.is_string()) {
    job_id = parse_id(job_field.get<std::string>());
  } else {
    throw InputError("queue.job: required, the id of a saved job (GET /api/jobs lists them)");
  }
  const auto row = store.get(job_id);
  if (!row || !row->saved || row->status != "ok") {
    throw HttpError(404, "queue.job = " + std::to_string(job_id) + ": no saved job with that id (GET /api/jobs lists them)");
  }
  json job = json::parse(row->result, nullptr, false);
  if (!job.is_object()) job = json::object();
  const std::string file = slicer::get_text(body, "file", "queue", "");
  // Looked up by exact name in the job's recorded list: never joined as given.
  const json files = job.value("files", json::array());
  const bool listed = std::any_of(files.begin(), files.end(), [&](const json& f) {
    return f.is_object() && f.value("name", "") == file;
  });
  if (file.empty() || !listed || !file.ends_with(".gcode")) {
    throw InputError("queue.file = " + shown(file) + ": must be the name of a .gcode file of job " +
                     std::to_string(job_id) + " (GET /api/jobs/" + std::to_string(job_id) + " lists them)");
  }
  const json spec = json::parse(row->job, nullptr, false);
  const std::string machine = spec.is_object() && spec.contains("machine") && spec.at("machine").is_string()
                                  ? spec.at("machine").get<std::string>()
                                  : jobs::JobSettings{}.machine;
  const std::optional<MachinePort> saved = queue.saved_machine(machine);
  QueueRow q;
  q.job = job_id;
  q.job_name = row->name;
  q.file = file;
  q.machine = machine;
  q.port = slicer::get_text(body, "port", "queue", saved ? saved->port : "");
  if (q.port.empty()) throw InputError("queue.port: required (a serial device such as /dev/ttyUSB0; GET /api/ports lists them)");
  check_port(q.port);
  const double baud = slicer::get_number(body, "baud", "queue", saved ? saved->baud : 115200);
  if (baud != static_cast<int>(baud) || !machines::supported_baud(static_cast<int>(baud))) {
    throw InputError("queue.baud = " + (baud == std::floor(baud) && std::abs(baud) < 1e15 ? std::to_string(static_cast<long long>(baud)) : json(baud).dump()) +
                     ": must be one of 9600, 19200, 38400, 57600, 115200, 230400, 460800, 500000, 921600, 1000000");
  }
  q.baud = static_cast<int>(baud);
  q.firmware = firmware_of(body, saved, machine);
  return json_response(201, queue.add(q));
}

}  // namespace

bool is_queue_path(const std::string& path) {
  return path == "/queue" || path == "/api/ports" || path == "/api/events" || path == "/api/queue" ||
         path.rfind("/api/queue/", 0) == 0;
}

Response Api::State::route_queue(const Request& r) {
  const std::vector<std::string> p = split_path(r.path);
  const bool get = r.method == "GET" || r.method == "HEAD";
  const auto only = [&](bool ok, const std::string& allowed) {
    if (!ok) throw HttpError(405, r.method.substr(0, 20) + " " + r.path.substr(0, 200) + ": use " + allowed);
  };
  if (r.path == "/queue") return page_response("queue.html", r.method);
  if (r.path == "/api/ports") {
    only(get, "GET");
    return json_response(200, ports_json(*queue));
  }
  if (r.path == "/api/events") {
    only(r.method == "GET", "GET");
    Response out;
    out.stream = queue->events().subscribe();
    if (!out.stream) {
      throw HttpError(503, "GET /api/events: " + std::to_string(kMaxEventClients) + " listeners already, the most served");
    }
    out.content_type = "text/event-stream";
    out.headers.emplace_back("X-Accel-Buffering", "no");
    return out;
  }
  if (p.size() == 2) {  // /api/queue
    if (r.method == "POST") return add_entry(store, *queue, r);
    only(get, "GET or POST");
    return json_response(200, queue->list());
  }
  if (p.size() == 4) {
    only(r.method == "POST", "POST");
    std::int64_t id = 0;
    try {
      id = parse_id(p[2]);
    } catch (const HttpError&) {
      throw HttpError(404, "no queue entry " + shown(p[2]) + " (ids are numbers, see GET /api/queue)");
    }
    return json_response(200, queue->act(id, p[3]));
  }
  throw HttpError(404, "no such endpoint: " + r.method.substr(0, 20) + " " + r.path.substr(0, 200));
}

}  // namespace strand::serve
