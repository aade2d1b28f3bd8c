// Routes, access rules (loopback Host, token, same-origin) and the job handlers of the
// workbench. Client input never names a path: jobs are numbered by SQLite, their files are
// named by the server and looked up by exact name in the job's recorded list.
#include <sys/stat.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <future>
#include <new>
#include <nlohmann/json.hpp>
#include <thread>

#include "jobs/curved_preview.h"
#include "jobs/job_runner.h"
#include "jobs/sweep_check.h"
#include "jobs/sweep_runner.h"
#include "machines/profile.h"
#include "patterns/registry.h"
#include "postprocess/inspect/gcode_parser.h"
#include "postprocess/preview/preview_html.h"
#include "postprocess/preview/preview_scene.h"
#include "serve/api.h"
#include "serve/api_state.h"
#include "serve/job_archive.h"
#include "serve/job_request.h"
#include "serve/queue_api.h"
#include "serve/store.h"
#include "serve/view_api.h"
#include "serve/worker_pool.h"
#include "slicer/file_io.h"
#include "slicer/input_error.h"
#include "slicer/json_input.h"
#include "slicer/params.h"
#include "slicer/tolerances.h"

namespace strand::serve {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

const char* type_name(slicer::ParamType t) {
  switch (t) {
    case slicer::ParamType::Number: return "number";
    case slicer::ParamType::Integer: return "integer";
    case slicer::ParamType::Text: return "text";
    case slicer::ParamType::NumberList: return "number-list";
    case slicer::ParamType::Size2: return "size";
    case slicer::ParamType::Switch: return "switch";
  }
  return "text";
}

json param_json(const slicer::ParamDef& d) {
  json j = {{"key", d.key},         {"type", type_name(d.type)}, {"unit", d.unit},
            {"help", d.help},       {"default", d.default_value}, {"default_text", d.default_text},
            {"rule", slicer::describe_rule(d)}};
  j["min"] = d.min ? json(*d.min) : json();
  j["min_exclusive"] = d.min_exclusive;
  j["max"] = d.max ? json(*d.max) : json();
  j["max_exclusive"] = d.max_exclusive;
  j["choices"] = d.choices;
  if (d.paper) j["paper"] = true;
  return j;
}

json generators_json() {
  json list = json::array();
  for (const auto& g : patterns::generators()) {
    json params = json::array();
    for (const auto& d : g.table().defs) params.push_back(param_json(d));
    list.push_back({{"name", g.name}, {"summary", g.summary}, {"params", params}});
  }
  return {{"generators", list}};
}

std::string machine_kind(const machines::MachineProfile& m) {
  if (m.plotter.enabled) return "plotter";
  if (m.robot.enabled) return "robot";
  if (m.rotary.enabled) return "rotary";
  return "printer";
}

json machines_json() {
  json list = json::array();
  for (const auto& p : machines::profile_catalog()) {
    json m = {{"name", p.name}, {"description", p.description}, {"origin", p.origin == "shipped" ? "shipped" : "user"}};
    try {
      const auto profile = machines::load_profile(p.name);
      m["kind"] = machine_kind(profile);
      m["firmware"] = machines::to_string(profile.firmware);
    } catch (const std::exception& e) {
      m["kind"] = "invalid";
      m["error"] = e.what();
    }
    list.push_back(m);
  }
  return {{"machines", list}};
}

}  // namespace

namespace {

fs::path prepare_dir(const std::string& dir) {
  std::error_code ec;
  fs::create_directories(fs::path(dir) / "jobs", ec);
  if (ec) throw InputError("--data = " + dir + ": cannot create the directory (" + ec.message() + ")");
  ::chmod(dir.c_str(), 0700);  // designs are the user's own
  return fs::path(dir);
}

}  // namespace

Api::Api(const ApiOptions& options) : s_(std::make_unique<State>(options, prepare_dir(options.data_dir))) {}
Api::~Api() = default;

std::string default_data_dir() {
  const char* xdg = std::getenv("XDG_DATA_HOME");
  if (xdg && *xdg) return (fs::path(xdg) / "strand").string();
  const char* home = std::getenv("HOME");
  if (home && *home) return (fs::path(home) / ".local" / "share" / "strand").string();
  return "strand-data";
}

bool is_loopback_host(const std::string& host) {
  if (host == "localhost" || host == "::1" || host == "[::1]") return true;
  if (host.rfind("127.", 0) != 0) return false;
  int dots = 0;
  for (const char c : host) {
    if (c == '.') ++dots;
    else if (c < '0' || c > '9') return false;
  }
  return dots == 3;
}

json Api::State::summary_of(const JobRow& row, bool with_report) {
  json j = row.result.empty() ? json::object() : json::parse(row.result, nullptr, false);
  if (j.is_discarded() || !j.is_object()) j = json::object();
  if (!with_report) j.erase("report");
  j["id"] = row.id;
  j["name"] = row.name;
  j["saved"] = row.saved;
  j["created"] = row.created;
  j["status"] = row.status;
  const json job = json::parse(row.job, nullptr, false);
  j["job"] = job.is_discarded() ? json::object() : job;
  return j;
}

// Runs on a worker: the job written by jobs/ exactly as `strand job` writes it, then the
// check and the previews of its G-code.
json Api::State::produce(std::int64_t id, const jobs::JobSpec& spec, const std::string& ext) {
  const fs::path d = job_dir(id);
  jobs::JobSettings st = spec.settings;
  st.inputs.clear();
  // In its folder: the files name each other as `strand job` run there does, never by the
  // data directory's path.
  st.folder = d.string();
  st.output = spec.generator->name + ext;
  st.report = "report.json";
  const post::Produced produced = jobs::run_job(*spec.generator, spec.params, st);
  // The summary names the files as the gallery does: without the data directory.
  std::string summary = produced.summary;
  const std::string prefix = d.string() + "/";
  for (auto at = summary.find(prefix); at != std::string::npos; at = summary.find(prefix, at)) summary.erase(at, prefix.size());
  json result = {{"summary", summary}, {"report", produced.report}, {"figures", figures_of(produced.report)}};
  result["check"] = json();
  const std::string base = "/api/jobs/" + std::to_string(id) + "/files/";
  if (!st.substrate.empty()) {  // poses or rotary G-code drawn on the substrate, as strand preview draws them
    const std::string file = (d / st.output).string();
    try {
      const post::PreviewScene scene = jobs::curved_file_scene(file, slicer::read_file(file), slicer::kDefaultArcToleranceMm);
      slicer::write_file_atomic((d / "preview.png").string(), jobs::thumbnail_png(scene));
      slicer::write_file_atomic((d / "preview.html").string(), post::render_html(scene, st.output));
    } catch (const std::exception&) {
    }
  } else if (ext == ".gcode") {
    const std::string gcode = slicer::read_file((d / st.output).string());
    result["check"] = jobs::sweep_check_summary(gcode, st.machine);
    try {
      const post::PreviewScene scene =
          post::preview_scene(post::parse_gcode(gcode).program, slicer::kDefaultArcToleranceMm);
      slicer::write_file_atomic((d / "preview.png").string(), jobs::thumbnail_png(scene));
      slicer::write_file_atomic((d / "preview.html").string(),
                                post::render_html(scene, spec.generator->name + ".gcode"));
    } catch (const std::exception&) {  // no preview for a file the viewer cannot draw
    }
  }
  json files = json::array();
  std::vector<fs::directory_entry> entries(fs::directory_iterator(d), fs::directory_iterator{});
  std::sort(entries.begin(), entries.end());
  for (const auto& e : entries) {
    if (!e.is_regular_file()) continue;
    const std::string name = e.path().filename().string();
    files.push_back({{"name", name}, {"url", base + name}, {"bytes", e.file_size()}});
  }
  result["files"] = files;
  const auto url_if = [&](const std::string& name) {
    return fs::is_regular_file(d / name) ? json(base + name) : json();
  };
  result["gcode"] = url_if(spec.generator->name + ".gcode");
  result["preview_png"] = url_if("preview.png");
  result["preview_html"] = url_if("preview.html");
  result["zip"] = "/api/jobs/" + std::to_string(id) + "/files.zip";
  return result;
}

Response Api::State::run(const Request& r, bool save) {
  JobRequest request = read_job_request(r);  // a curved substrate's keys gathered and checked
  json& j = request.job;
  std::string name;
  if (save) {
    name = slicer::get_text(j, "name", "job", "");
    if (name.empty()) throw InputError("job.name: give the design a name to save it under");
    if (name.size() > kMaxNameBytes) throw InputError("job.name: longer than " + std::to_string(kMaxNameBytes) + " bytes");
    if (std::any_of(name.begin(), name.end(), [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; })) {
      throw InputError("job.name: control characters are not allowed");
    }
    j.erase("name");
  }
  // Paths are the server's to choose: a job file's own output and report are ignored.
  j.erase("output");
  j.erase("report");
  // So are the files read: an ink profile by name (its materials/NAME.json), never by path.
  if (j.contains("material") && j.at("material").is_string() && j.at("material").get<std::string>().ends_with(".json")) {
    throw InputError("job.material: give the ink profile's name (materials/NAME.json on the server), not a path");
  }
  const jobs::JobSpec spec = jobs::job_spec_from_json(j, "job");
  const auto catalog = machines::profile_catalog();
  if (std::none_of(catalog.begin(), catalog.end(), [&](const auto& p) { return p.name == spec.settings.machine; })) {
    throw InputError("job.machine = " + spec.settings.machine.substr(0, 200) +
                     ": not a machine of this server (GET /api/machines lists them)");
  }
  const machines::MachineProfile machine = machines::load_profile(spec.settings.machine);
  slicer::resolve_params(spec.generator->table(), spec.params);  // the one-line message, early
  const std::string ext = machine.robot.enabled ? ".csv" : ".gcode";
  if (!options.run_jobs) return json_response(200, {{"checked", true}});

  const std::int64_t id = new_job(save, name, dump(j));
  if (!request.mesh.empty()) {  // the uploaded substrate (job.substrate.mesh), read from the job's folder
    try {
      slicer::write_file_atomic((job_dir(id) / request.mesh_name).string(), request.mesh);
    } catch (...) {
      drop_job(id);
      throw;
    }
  }
  auto promise = std::make_shared<std::promise<json>>();
  std::future<json> done = promise->get_future();
  const bool queued = pool.submit([this, id, spec, ext, promise] {
    try {
      promise->set_value(produce(id, spec, ext));
    } catch (...) {
      promise->set_exception(std::current_exception());
    }
  });
  if (!queued) {
    drop_job(id);
    throw HttpError(503, "the server is busy (" + std::to_string(kMaxWaitingJobs) + " jobs waiting); try again");
  }
  if (done.wait_for(std::chrono::seconds(kMaxJobWaitSeconds)) != std::future_status::ready) {
    throw HttpError(503, "job " + std::to_string(id) + " takes longer than " + std::to_string(kMaxJobWaitSeconds) +
                             " s; see GET /api/jobs/" + std::to_string(id));
  }
  json result;
  try {
    result = done.get();
  } catch (const InputError&) {
    drop_job(id);
    throw;
  } catch (const std::exception& e) {
    drop_job(id);
    throw HttpError(500, std::string("internal error: ") + e.what());
  }
  store.finish(id, "ok", dump(result));
  for (const std::int64_t old : store.stale_unsaved(kKeepUnsavedJobs)) drop_job(old);
  const auto row = store.get(id);
  if (!row) throw HttpError(404, "job " + std::to_string(id) + " was deleted");
  return json_response(save ? 201 : 200, summary_of(*row, true));
}

Response Api::State::route(const Request& r) {
  const std::vector<std::string> p = split_path(r.path);
  const bool get = r.method == "GET" || r.method == "HEAD";
  if (r.path == "/") return page_response("design.html", r.method);
  if (r.path == "/gallery") return page_response("gallery.html", r.method);
  if (r.path == "/draw" || r.path == "/api/plot") return route_plot(r);
  if (r.path == "/slice" || r.path == "/api/slice") return route_slice(r);
  if (is_queue_path(r.path)) return route_queue(r);
  if (is_view_path(r.path)) return route_view(r);
  if (r.path == "/sweep" || r.path == "/api/sweeps" || r.path.rfind("/api/sweeps/", 0) == 0)
    return route_sweeps(r);
  if (p.size() < 2 || p[0] != "api") throw HttpError(404, "no such page: " + r.path.substr(0, 200));
  const auto method_not_allowed = [&](const std::string& allowed) {
    return HttpError(405, r.method.substr(0, 20) + " " + r.path.substr(0, 200) + ": use " + allowed);
  };
  if (p.size() == 2 && p[1] == "health") {
    if (!get) throw method_not_allowed("GET");
    return json_response(200, {{"ok", true}, {"version", STRAND_VERSION}});
  }
  if (p.size() == 2 && p[1] == "generators") {
    if (!get) throw method_not_allowed("GET");
    return json_response(200, generators_json());
  }
  if (p.size() == 2 && p[1] == "machines") {
    if (!get) throw method_not_allowed("GET");
    return json_response(200, machines_json());
  }
  if (p.size() == 2 && p[1] == "generate") {
    if (r.method != "POST") throw method_not_allowed("POST");
    return run(r, false);
  }
  if (p.size() >= 2 && p[1] == "jobs") {
    if (p.size() == 2) {
      if (r.method == "POST") return run(r, true);
      if (!get) throw method_not_allowed("GET or POST");
      json list = json::array();
      for (const JobRow& row : store.saved_jobs()) list.push_back(summary_of(row, false));
      return json_response(200, {{"jobs", list}});
    }
    const std::int64_t id = parse_id(p[2]);
    const auto row = store.get(id);
    if (!row) throw HttpError(404, "no job " + std::to_string(id));
    if (p.size() == 3) {
      if (r.method == "DELETE") {
        if (row->status == "running") throw HttpError(409, "job " + std::to_string(id) + " is still running");
        drop_job(id);
        return json_response(200, {{"deleted", id}});
      }
      if (!get) throw method_not_allowed("GET or DELETE");
      return json_response(200, summary_of(*row, true));
    }
    if (p.size() == 4 && p[3] == "files.zip") {
      if (!get) throw method_not_allowed("GET");
      std::vector<std::string> names;  // the recorded names only, never the folder's listing
      for (const auto& f : summary_of(*row, false).value("files", json::array()))
        if (f.is_object() && f.contains("name") && f.at("name").is_string()) names.push_back(f.at("name").get<std::string>());
      if (names.empty()) throw HttpError(404, "job " + std::to_string(id) + " has no files");
      return archive_response(dir / "scratch", job_dir(id), names, "strand-job-" + std::to_string(id) + ".zip");
    }
    if (p.size() == 5 && p[3] == "files") {
      if (!get) throw method_not_allowed("GET");
      const json result = summary_of(*row, false);
      // The name must be one the server recorded for this job: never joined as given.
      for (const auto& f : result.value("files", json::array())) {
        if (f.is_object() && f.value("name", "") == p[4]) {
          const std::string name = f.at("name").get<std::string>();
          Response out;
          out.content_type = content_type_for(name);
          out.body = slicer::read_file((job_dir(id) / name).string());
          if (out.content_type.rfind("text/html", 0) != 0 && out.content_type != "image/png") {
            out.headers.emplace_back("Content-Disposition", "inline; filename=\"" + name + "\"");
          }
          return out;
        }
      }
      throw HttpError(404, "job " + std::to_string(id) + " has no file " + p[4].substr(0, 200) +
                               " (GET /api/jobs/" + std::to_string(id) + " lists them)");
    }
  }
  throw HttpError(404, "no such endpoint: " + r.method.substr(0, 20) + " " + r.path.substr(0, 200));
}

Response Api::handle(const Request& r) {
  Response out;
  try {
    if (r.body.size() > kMaxBodyBytes) {
      throw HttpError(413, "request body of " + std::to_string(r.body.size()) + " bytes, more than the " +
                               std::to_string(kMaxBodyBytes) + " accepted");
    }
    const std::string host = header(r, "host");
    if (s_->options.token.empty() && !host.empty() && !is_loopback_host(host_name(host))) {
      // DNS rebinding: a page of another site reaching this loopback server under its own name.
      throw HttpError(403, "Host " + host.substr(0, 100) + ": this server answers to localhost only (start it with --host and --token for others)");
    }
    const std::string& token = s_->options.token;
    if (!token.empty() && !(r.method == "GET" && r.path == "/api/health")) {
      const auto q = r.query.find("token");
      if (r.method == "GET" && r.path == "/" && q != r.query.end()) {
        if (!equal_constant_time(q->second, token)) throw HttpError(401, "wrong token");
        Response redirect;
        redirect.status = 303;
        redirect.content_type = "text/plain";
        redirect.body = "signed in\n";
        redirect.headers.emplace_back("Location", "/");
        redirect.headers.emplace_back("Set-Cookie", "strand_token=" + token + "; Path=/; HttpOnly; SameSite=Strict");
        out = redirect;
      } else {
        const std::string given = !header(r, "x-strand-token").empty() ? header(r, "x-strand-token") : cookie(r, "strand_token");
        if (given.empty()) throw HttpError(401, "this server needs its token: header X-Strand-Token, or open /?token=...");
        if (!equal_constant_time(given, token)) throw HttpError(401, "wrong token");
      }
    }
    if (out.status != 303) {
      const bool changes = r.method != "GET" && r.method != "HEAD" && r.method != "OPTIONS";
      if (changes && !same_origin(r)) throw HttpError(403, "cross-origin request refused (Origin, Referer or Sec-Fetch-Site names another site)");
      out = s_->route(r);
    }
  } catch (const HttpError& e) {
    out = error(e.status, e.what());
  } catch (const InputError& e) {
    out = error(400, e.what());
  } catch (const json::exception& e) {
    out = error(400, std::string("unexpected value in the request (") + e.what() + ")");
  } catch (const std::bad_alloc&) {
    out = error(503, "out of memory");
  } catch (const std::exception& e) {
    out = error(500, std::string("internal error: ") + e.what());
  }
  out.headers.emplace_back("X-Content-Type-Options", "nosniff");
  out.headers.emplace_back("X-Frame-Options", "SAMEORIGIN");
  out.headers.emplace_back("Cache-Control", "no-store");
  return out;
}

}  // namespace strand::serve
