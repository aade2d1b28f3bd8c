// Sweeps in the gallery (Api::State::route_sweeps): POST /api/sweeps runs a sweep file (or a
// saved job's parameters varied: "from_job") as `strand sweep` does, on one worker, into the
// job's directory, and keeps it as one group with its contact sheet (index.html), waiting for
// it or ("wait": false) answering 202 at once; GET /api/sweeps/{id} tells its progress, then
// its points; GET /api/sweeps/{id}/files/{path} serves the group's files (the sheet links its
// previews as previews/NAME.png) by names the server recorded. GET /sweep is the sweep page.
#include "serve/sweep_api.h"

#include <algorithm>
#include <filesystem>

#include "jobs/sweep_runner.h"
#include "jobs/sweep_spec.h"
#include "machines/profile.h"
#include "serve/api_state.h"
#include "serve/job_wait.h"
#include "slicer/file_io.h"
#include "slicer/input_error.h"
#include "slicer/json_input.h"

namespace strand::serve {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// The sweep file without its name and output paths, checked; InputError names a bad key.
jobs::SweepSpec checked_sweep(json& j) {
  if (!j.is_object())
    throw InputError(
        "sweep: must be a JSON object (a sweep file: job, vary, mode, where, and name)");
  if (j.contains("job") && j["job"].is_object()) {  // paths are the server's to choose
    j["job"].erase("output");
    j["job"].erase("report");
  }
  jobs::SweepSpec spec = jobs::sweep_spec_from_json(j);
  const auto catalog = machines::profile_catalog();
  const std::string& machine = spec.job.settings.machine;
  if (std::none_of(catalog.begin(), catalog.end(),
                   [&](const auto& p) { return p.name == machine; })) {
    throw InputError("sweep.job.machine = " + machine.substr(0, 200) +
                     ": not a machine of this server (GET /api/machines lists them)");
  }
  std::size_t kept = 0;
  for (const jobs::SweepPoint& p : jobs::expand_points(spec)) {
    kept += p.dropped.empty();
    if (p.name.find_first_of("/\\") != std::string::npos || p.name.front() == '.') {
      throw InputError("sweep.vary: a value makes the point name " + p.name.substr(0, 100) +
                       ", not a file name");
    }
  }
  if (kept > kMaxServedSweepPoints) {
    throw InputError(
        "sweep.vary: " + std::to_string(kept) + " points; the workbench runs at most " +
        std::to_string(kMaxServedSweepPoints) + " (run larger sweeps with strand sweep)");
  }
  return spec;
}

// Runs on a worker: the sweep into `d`, then its files and points as the gallery shows them.
json sweep_into(const fs::path& d, std::int64_t id, const jobs::SweepSpec& spec,
                const json& source, const jobs::ProgressFn& progress) {
  jobs::SweepOptions o;
  o.dir = d.string();
  o.jobs = 1;  // one worker's share of the machine
  const jobs::SweepResult r = jobs::run_sweep(spec, source, o, progress);
  const std::string base = "/api/sweeps/" + std::to_string(id) + "/files/";
  json files = json::array();
  std::vector<fs::path> all;
  for (const auto& e : fs::recursive_directory_iterator(d)) {
    if (e.is_regular_file()) all.push_back(fs::relative(e.path(), d));
  }
  std::sort(all.begin(), all.end());
  for (const fs::path& rel : all) {
    files.push_back({{"name", rel.generic_string()},
                     {"url", base + rel.generic_string()},
                     {"bytes", fs::file_size(d / rel)}});
  }
  json points = json::array();
  json first_preview;
  for (const json& row : r.manifest.at("points")) {
    json p = {{"name", row.value("name", "")},
              {"status", row.value("status", "")},
              {"varied", row.value("parameters", json::object())}};
    for (const char* key : {"output", "preview", "preview_html"}) {
      if (row.contains(key) && row[key].is_string()) p[key] = base + row[key].get<std::string>();
    }
    if (first_preview.is_null() && p.contains("preview")) first_preview = p["preview"];
    points.push_back(p);
  }
  const std::string summary =
      "sweep: " + std::to_string(points.size()) + " point(s): " + std::to_string(r.ran) + " ran, " +
      std::to_string(r.failed) + " failed, " + std::to_string(r.dropped) + " dropped\n";
  return {{"summary", summary},
          {"files", files},
          {"points", points},
          {"contact_sheet", base + "index.html"},
          {"manifest_csv", base + "manifest.csv"},
          {"preview_png", first_preview},
          {"check", json()}};
}

// One file of a saved sweep, by a name in its recorded list ("previews/x.png"), never joined as
// given.
Response sweep_file(const fs::path& d, const JobRow& row, const std::string& name) {
  const json result = json::parse(row.result.empty() ? "{}" : row.result, nullptr, false);
  if (result.is_object()) {
    for (const auto& f : result.value("files", json::array())) {
      if (!f.is_object() || f.value("name", "") != name) continue;
      Response out;
      out.content_type = content_type_for(name);
      out.body = slicer::read_file((d / f.at("name").get<std::string>()).string());
      return out;
    }
  }
  throw HttpError(404, "sweep " + std::to_string(row.id) + " has no file " + name.substr(0, 200));
}

}  // namespace

Response Api::State::route_sweeps(const Request& r) {
  if (r.path == "/sweep") return page_response("sweep.html", r.method);
  const std::vector<std::string> p = split_path(r.path);  // api, sweeps[, id, files, ...]
  const bool get = r.method == "GET" || r.method == "HEAD";
  if (p.size() >= 3) {
    if (!get || (p.size() >= 4 && p[3] != "files") || p.size() == 4)
      throw HttpError(get ? 404 : 405, r.method.substr(0, 20) + " " + r.path.substr(0, 200) +
                                           (get ? ": no such endpoint" : ": use GET"));
    const std::int64_t id = parse_id(p[2]);
    const auto row = store.get(id);
    if (!row || json::parse(row->job, nullptr, false).value("generator", "") != "sweep")
      throw HttpError(404, "no sweep " + std::to_string(id));
    if (p.size() == 3) return json_response(200, sweep_state(*row));
    std::string name = p[4];
    for (std::size_t k = 5; k < p.size(); ++k) name += "/" + p[k];
    return sweep_file(job_dir(id), *row, name);
  }
  if (p.size() != 2)
    throw HttpError(404,
                    "no such endpoint: " + r.method.substr(0, 20) + " " + r.path.substr(0, 200));
  if (r.method != "POST") throw HttpError(405, r.method.substr(0, 20) + " /api/sweeps: use POST");
  json j = slicer::parse_json(r.body, "request");
  const std::string name = j.is_object() ? slicer::get_text(j, "name", "sweep", "") : "";
  if (name.empty())
    throw InputError("sweep.name: give the sweep a name to keep it in the gallery under");
  if (name.size() > kMaxNameBytes)
    throw InputError("sweep.name: longer than " + std::to_string(kMaxNameBytes) + " bytes");
  if (std::any_of(name.begin(), name.end(),
                  [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; })) {
    throw InputError("sweep.name: control characters are not allowed");
  }
  j.erase("name");
  bool wait = true;
  if (j.contains("wait")) {
    if (!j["wait"].is_boolean()) throw InputError("sweep.wait: must be true or false");
    wait = j["wait"].get<bool>();
    j.erase("wait");
  }
  if (j.contains("from_job")) j = with_saved_job(std::move(j));
  const jobs::SweepSpec spec = checked_sweep(j);
  if (!options.run_jobs) return json_response(200, {{"checked", true}});
  const json job = {{"generator", "sweep"}, {"machine", spec.job.settings.machine}, {"sweep", j}};
  const std::int64_t id = new_job(true, name, dump(job));
  const fs::path d = job_dir(id);
  const std::size_t total = jobs::expand_points(spec).size();
  {
    std::lock_guard<std::mutex> lock(sweep_mu);
    sweep_progress[id] = {{"done", 0}, {"total", total}, {"failed", 0}};
  }
  const auto forget = [this, id] {
    std::lock_guard<std::mutex> lock(sweep_mu);
    sweep_progress.erase(id);
  };
  const auto run = [this, d, id, spec, j, forget] {
    const jobs::ProgressFn progress = [this, id](const jobs::SweepProgress& at) {
      std::lock_guard<std::mutex> lock(sweep_mu);
      sweep_progress[id] = {{"done", at.done}, {"total", at.total}, {"failed", at.failed}};
    };
    json result = sweep_into(d, id, spec, j, progress);
    store.finish(id, "ok", dump(result));
    forget();
    return result;
  };
  if (wait) {
    run_and_wait(
        pool, id, [this, id, forget] { forget(); drop_job(id); }, run);
  } else {
    const bool queued = pool.submit([this, id, run, forget] {
      try {
        run();
      } catch (const std::exception& e) {  // the sweep's own error, kept for GET /api/sweeps/{id}
        std::error_code ec;
        fs::remove_all(job_dir(id), ec);  // no half sweep left behind
        store.finish(id, "failed", dump({{"error", std::string(e.what()).substr(0, 500)}}));
        forget();
      }
    });
    if (!queued) {
      forget();
      drop_job(id);
      throw HttpError(503, "the server is busy (" + std::to_string(kMaxWaitingJobs) +
                               " jobs waiting); try again");
    }
    return json_response(202, sweep_state(*store.get(id)));
  }
  const auto row = store.get(id);
  if (!row) throw HttpError(404, "sweep " + std::to_string(id) + " was deleted");
  return json_response(201, summary_of(*row, true));
}

// A sweep as GET /api/sweeps/{id} answers: while running its progress (done of total, failed),
// then what POST answered (points, files, contact sheet, manifest) or the error.
json Api::State::sweep_state(const JobRow& row) {
  json j = summary_of(row, false);
  std::lock_guard<std::mutex> lock(sweep_mu);
  const auto at = sweep_progress.find(row.id);
  if (at != sweep_progress.end()) {
    j.update(at->second);
  } else if (row.status == "ok" && j.contains("points")) {
    std::size_t failed = 0;
    for (const json& pt : j["points"]) failed += pt.value("status", "") == "failed";
    j["done"] = j["total"] = j["points"].size();
    j["failed"] = failed;
  }
  j["progress_url"] = "/api/sweeps/" + std::to_string(row.id);
  return j;
}

// The sweep's base job taken from saved job `from_job` (its generator, machine and
// parameters, as the gallery keeps them) in place of `job`.
json Api::State::with_saved_job(json j) {
  if (j.contains("job"))
    throw InputError("sweep: give either job or from_job, not both");
  const json& from = j["from_job"];
  if (!from.is_number_integer() || from.get<std::int64_t>() < 1)
    throw InputError("sweep.from_job: must be the id of a saved job (an integer >= 1)");
  const std::int64_t id = from.get<std::int64_t>();
  const auto row = store.get(id);
  if (!row || !row->saved)
    throw InputError("sweep.from_job = " + std::to_string(id) + ": no saved job with this id");
  json job = json::parse(row->job, nullptr, false);
  const std::string generator = job.is_object() ? job.value("generator", "") : "";
  if (generator.empty() || generator == "sweep" || generator == "slice" || generator == "plot" ||
      row->status != "ok") {
    throw InputError("sweep.from_job = " + std::to_string(id) +
                     ": job " + std::to_string(id) +
                     " is not a finished generator job (sweeps vary a designed job's parameters)");
  }
  j.erase("from_job");
  j["job"] = job;
  return j;
}

}  // namespace strand::serve
