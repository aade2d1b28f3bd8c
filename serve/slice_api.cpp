// GET /slice and POST /api/slice: the form read on the HTTP thread (slice_form.cpp), the
// slice itself on a worker through jobs::produce_slice, as `strand slice part.EXT [flags]`
// runs it in the job's directory; the job kept in the gallery.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "jobs/slice_job.h"
#include "jobs/sweep_check.h"
#include "jobs/sweep_runner.h"
#include "machines/profile.h"
#include "postprocess/inspect/gcode_parser.h"
#include "postprocess/preview/preview_html.h"
#include "postprocess/preview/preview_scene.h"
#include "serve/api_state.h"
#include "serve/job_wait.h"
#include "serve/slice_api.h"
#include "slicer/file_io.h"
#include "slicer/input_error.h"
#include "slicer/json_input.h"
#include "slicer/mesh.h"

namespace strand::serve {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

std::string without(std::string text, const std::string& prefix) {
  for (auto at = text.find(prefix); at != std::string::npos; at = text.find(prefix, at)) text.erase(at, prefix.size());
  return text;
}

std::string fixed3(const char* format, double a, double b, double c) {
  char line[160];
  std::snprintf(line, sizeof line, format, a, b, c);
  return line;
}

// Runs on a worker: the upload written as part.EXT, sliced, and the G-code, report and
// previews (the mesh drawn under the paths in the HTML one, as `--preview` draws it) beside it.
json slice_into(const fs::path& d, std::int64_t id, const SliceForm& f) {
  jobs::SliceSettings s = f.settings;
  s.part = (d / f.input).string();
  s.part_name = f.input;
  s.output = "part.gcode";
  slicer::write_file_atomic(s.part, f.mesh);
  std::string part_line;
  s.on_part_size = [&part_line](const slicer::Vec3& size) {
    part_line = fixed3("part %.3f x %.3f x %.3f mm\n", size.x(), size.y(), size.z());
  };
  jobs::SliceResult r;
  try {
    r = jobs::produce_slice(s);
  } catch (const InputError& e) {  // named as the CLI names the file: without the data directory
    throw InputError(without(e.what(), d.string() + "/"));
  }
  slicer::write_file_atomic((d / s.output).string(), r.produced.gcode);
  slicer::write_file_atomic((d / "report.json").string(), slicer::dump_json(r.produced.report) + "\n");
  json result = {{"summary", without(part_line + jobs::slice_summary_text(r, s), d.string() + "/")},
                 {"report", r.produced.report},
                 {"figures", figures_of(r.produced.report)},
                 {"check", jobs::sweep_check_summary(r.produced.gcode, s.machine)}};
  const slicer::Vec3 size = slicer::bounds(r.part.mesh).size_mm();
  result["part"] = {{"size_mm", {size.x(), size.y(), size.z()}},
                    {"scale", r.scale},
                    {"triangles", r.part.mesh.triangles.size()},
                    {"defects", r.part.defects},
                    {"repairs", r.part.changes},
                    {"notes", r.notes}};
  post::PreviewScene scene = post::preview_scene(post::parse_gcode(r.produced.gcode).program, s.arc_tolerance_mm);
  slicer::write_file_atomic((d / "preview.png").string(), jobs::thumbnail_png(scene));
  scene.substrate = slicer::to_triangle_mesh(r.part.mesh);
  scene.substrate_hides_paths = false;  // a filled part is drawn under its fill
  const slicer::Vec2 centre = machines::load_profile(s.machine).volume.part_center_mm;
  for (auto& v : scene.substrate.vertices_mm) v += slicer::Vec3(centre.x(), centre.y(), 0.0);
  slicer::write_file_atomic((d / "preview.html").string(), post::render_html(scene, s.output));
  const std::string base = "/api/jobs/" + std::to_string(id) + "/files/";
  json files = json::array();
  for (const std::string& name : {f.input, s.output, std::string("preview.html"), std::string("preview.png"),
                                  std::string("report.json")}) {
    files.push_back({{"name", name}, {"url", base + name}, {"bytes", fs::file_size(d / name)}});
  }
  result["files"] = files;
  result["gcode"] = base + s.output;
  result["input"] = base + f.input;
  result["preview_png"] = base + "preview.png";
  result["preview_html"] = base + "preview.html";
  return result;
}

// A machine of this server by name, never a path: as POST /api/jobs checks it.
void check_machine(const std::string& name) {
  const auto catalog = machines::profile_catalog();
  if (std::none_of(catalog.begin(), catalog.end(), [&](const auto& p) { return p.name == name; })) {
    throw InputError("slice.machine = " + name.substr(0, 200) + ": not a machine of this server (GET /api/machines lists them)");
  }
}

}  // namespace

Response Api::State::route_slice(const Request& r) {
  if (r.path == "/slice") return page_response("slice.html", r.method);
  if (r.method != "POST") throw HttpError(405, r.method.substr(0, 20) + " /api/slice: use POST (multipart/form-data)");
  const SliceForm f = read_slice_form(r);
  check_machine(f.settings.machine);
  if (!options.run_jobs) return json_response(200, {{"checked", true}});

  json job = {{"generator", "slice"}, {"machine", f.settings.machine}, {"params", f.fields}, {"input", f.input}};
  const std::int64_t id = new_job(true, f.name, dump(job));
  const fs::path d = job_dir(id);
  // The worker records the result itself, so a slice that outlasts the wait still finishes.
  run_and_wait(
      pool, id, [this, id] { drop_job(id); },
      [this, d, id, f] {
        json result = slice_into(d, id, f);
        store.finish(id, "ok", dump(result));
        return result;
      });
  const auto row = store.get(id);
  if (!row) throw HttpError(404, "job " + std::to_string(id) + " was deleted");
  return json_response(201, summary_of(*row, true));
}

}  // namespace strand::serve
