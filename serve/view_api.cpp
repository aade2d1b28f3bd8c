// The viewer's data for a saved job: its pose program (CSV) or G-code read once into
// DIR/jobs/{id}/view/ (index.json, blocks.bin: server-named files), then served in layer ranges.
#include "serve/view_api.h"

#include <filesystem>
#include <fstream>
#include <mutex>
#include <nlohmann/json.hpp>

#include "jobs/curved_preview.h"
#include "jobs/slice_placement.h"
#include "machines/profile.h"
#include "postprocess/inspect/curved_files.h"
#include "postprocess/preview/viewer_data.h"
#include "postprocess/preview/viewer_html.h"
#include "serve/api_state.h"
#include "slicer/file_io.h"
#include "slicer/input_error.h"
#include "slicer/tolerances.h"

namespace strand::serve {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// One build at a time: a million-move file takes a second or two and its blocks tens of MiB.
std::mutex build_mu;

// The file the viewer shows: the job's pose program when it has one, else its first G-code,
// by a name from the job's recorded list.
std::string viewed_file(const json& result) {
  std::string gcode;
  for (const auto& f : result.value("files", json::array())) {
    const std::string name = f.is_object() ? f.value("name", "") : "";
    if (name.ends_with(".csv")) return name;
    if (gcode.empty() && name.ends_with(".gcode")) gcode = name;
  }
  return gcode;
}

post::ViewerData build(const fs::path& dir, const std::string& name, const std::string& machine) {
  const std::string path = (dir / name).string();
  const std::string text = slicer::read_file(path);
  const double tol = slicer::kDefaultArcToleranceMm;
  if (name.ends_with(".csv") || post::is_rotary_gcode(text))
    return post::viewer_data_from_scene(jobs::curved_file_scene(path, text, tol), name);
  std::unique_ptr<machines::MachineProfile> m;
  try {  // the job's machine gives the trapezoidal time, as its report has it
    if (!machine.empty()) m = std::make_unique<machines::MachineProfile>(machines::load_profile(machine));
  } catch (const std::exception&) {
  }
  return post::viewer_data_from_gcode(text, m.get(), tol, name);
}

// A slice's part (or --onto substrate) read from the job's kept input file and placed as its
// report's "mesh_placement" records (jobs/slice_placement.h); other jobs have none.
void add_slice_mesh(post::ViewerData& data, const fs::path& dir) {
  const fs::path report = dir / "report.json";
  if (!fs::is_regular_file(report)) return;
  const json r = json::parse(slicer::read_file(report.string()), nullptr, false);
  if (!r.is_object() || !r.contains("mesh_placement")) return;
  const json& placement = r["mesh_placement"];
  try {
    jobs::PlacedMesh m = jobs::placed_mesh_from(placement, dir.string());
    (placement.value("role", "") == "substrate" ? data.substrate : data.part) = std::move(m.mesh);
    data.part_note = m.note;
  } catch (const InputError& e) {  // named without the data directory
    std::string what = e.what();
    for (auto at = what.find(dir.string() + "/"); at != std::string::npos; at = what.find(dir.string() + "/"))
      what.erase(at, dir.string().size() + 1);
    data.part_note = "the mesh is not drawn: " + what;
  }
}

std::size_t layer_param(const Request& r, const std::string& key, std::size_t layers) {
  const auto q = r.query.find(key);
  const std::string text = q == r.query.end() ? "" : q->second;
  const std::string rule = ": must be a layer in [0, " + std::to_string(layers - 1) + "]";
  if (text.empty() || text.size() > 9 || text.find_first_not_of("0123456789") != std::string::npos)
    throw InputError("view." + key + " = " + text.substr(0, 40) + rule);
  const std::size_t v = std::stoul(text);
  if (v >= layers) throw InputError("view." + key + " = " + text + rule);
  return v;
}

}  // namespace

bool is_view_path(const std::string& path) {
  if (path.rfind("/view/", 0) == 0 || path == "/assets/viewer.js") return true;
  const std::vector<std::string> p = split_path(path);
  return p.size() >= 4 && p[0] == "api" && p[1] == "jobs" && p[3] == "view";
}

Response Api::State::route_view(const Request& r) {
  if (r.method != "GET" && r.method != "HEAD") throw HttpError(405, r.method.substr(0, 20) + " " + r.path.substr(0, 200) + ": use GET");
  if (r.path == "/assets/viewer.js") {
    Response out;
    out.content_type = "text/javascript; charset=utf-8";
    out.body = post::viewer_script();
    return out;
  }
  const std::vector<std::string> p = split_path(r.path);
  if (p.size() == 2 && p[0] == "view") {
    parse_id(p[1]);  // digits only; the page reads the rest from the API
    return page_response("view.html", r.method);
  }
  if (p.size() > 5 || (p.size() == 5 && p[4] != "layers")) throw HttpError(404, "no such endpoint: " + r.path.substr(0, 200));
  const std::int64_t id = parse_id(p[2]);
  const auto row = store.get(id);
  if (!row) throw HttpError(404, "no job " + std::to_string(id));
  const json result = summary_of(*row, false);
  const std::string name = viewed_file(result);
  if (name.empty()) throw HttpError(404, "job " + std::to_string(id) + " has no G-code or pose program to view");
  const fs::path cache = job_dir(id) / "view";
  json index;
  {
    std::lock_guard<std::mutex> lock(build_mu);
    if (!fs::is_regular_file(cache / "index.json")) {
      post::ViewerData data = build(job_dir(id), name, result.value("job", json::object()).value("machine", ""));
      add_slice_mesh(data, job_dir(id));
      fs::create_directories(cache);
      slicer::write_file_atomic((cache / "blocks.bin").string(), data.blocks);
      index = post::viewer_index(data);
      index["name"] = row->name;
      slicer::write_file_atomic((cache / "index.json").string(), index.dump());
    } else {
      index = json::parse(slicer::read_file((cache / "index.json").string()));
    }
  }
  if (p.size() == 4) return json_response(200, index);
  const json& layers = index.at("layers");
  const std::size_t from = layer_param(r, "from", layers.size()), to = layer_param(r, "to", layers.size());
  if (from > to) throw InputError("view.from = " + std::to_string(from) + ": must be at most view.to = " + std::to_string(to));
  const std::size_t begin = layers[from].at("offset"), end = layers[to].at("offset").get<std::size_t>() + layers[to].at("bytes").get<std::size_t>();
  Response out;
  out.content_type = "application/octet-stream";
  out.body.resize(end - begin);
  std::ifstream in(cache / "blocks.bin", std::ios::binary);
  in.seekg(static_cast<std::streamoff>(begin));
  if (!in.read(out.body.data(), static_cast<std::streamsize>(out.body.size())))
    throw HttpError(500, "job " + std::to_string(id) + ": the viewer's blocks are shorter than their index");
  return out;
}

}  // namespace strand::serve
