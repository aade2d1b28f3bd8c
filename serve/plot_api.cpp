// POST /api/plot: form fields checked against the tables of `strand plot` and `strand trace`
// on the HTTP thread (a bad one is a 400 naming it), the plot itself on a worker. The client's
// file name is never used: the server names the input drawing.svg (or drawing.png, .jpg,
// .img) and writes it, the G-code, report and previews into the job's directory.
#include "serve/plot_api.h"

#include <algorithm>
#include <filesystem>

#include "jobs/plot_options.h"
#include "jobs/plot_pipeline.h"
#include "jobs/sweep_check.h"
#include "jobs/sweep_runner.h"
#include "jobs/trace_input.h"
#include "machines/profile.h"
#include "postprocess/inspect/gcode_parser.h"
#include "postprocess/preview/preview_html.h"
#include "postprocess/preview/preview_scene.h"
#include "serve/api_state.h"
#include "serve/job_wait.h"
#include "slicer/file_io.h"
#include "slicer/input_error.h"
#include "slicer/json_input.h"
#include "slicer/params.h"
#include "slicer/svg_import.h"
#include "slicer/tolerances.h"

namespace strand::serve {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// The input's kind by its first bytes: the name of the file the server keeps, or "".
std::string input_name(const std::string& bytes) {
  if (bytes.rfind("\x89PNG\r\n\x1a\n", 0) == 0) return "drawing.png";
  if (bytes.rfind("\xff\xd8\xff", 0) == 0) return "drawing.jpg";
  if (bytes.rfind("GIF8", 0) == 0 || bytes.rfind("BM", 0) == 0 ||
      (bytes.size() > 2 && bytes[0] == 'P' && bytes[1] >= '1' && bytes[1] <= '6')) {
    return "drawing.img";
  }
  if (bytes.substr(0, 1 << 16).find("<svg") != std::string::npos) return "drawing.svg";
  return "";
}

bool flag_value(const std::string& key, const std::string& v) {
  if (v == "1" || v == "true" || v == "on" || v == "yes") return true;
  if (v == "0" || v == "false" || v == "off" || v == "no" || v.empty()) return false;
  throw InputError("plot." + key + " = " + v.substr(0, 40) + ": must be true or false");
}

const slicer::ParamDef* find_def(const slicer::ParamTable& t, const std::string& key) {
  const auto it =
      std::find_if(t.defs.begin(), t.defs.end(), [&](const auto& d) { return d.key == key; });
  return it == t.defs.end() ? nullptr : &*it;
}

void check_name(const std::string& name) {
  if (name.size() > kMaxNameBytes)
    throw InputError("plot.name: longer than " + std::to_string(kMaxNameBytes) + " bytes");
  if (std::any_of(name.begin(), name.end(),
                  [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; })) {
    throw InputError("plot.name: control characters are not allowed");
  }
}

}  // namespace

PlotForm read_plot_form(const Request& r) {
  std::size_t bytes = 0;
  for (const Upload& u : r.files) bytes += u.content.size() + u.name.size();
  if (bytes > kMaxUploadBytes) {
    throw HttpError(413, "upload of " + std::to_string(bytes) + " bytes, more than the " +
                             std::to_string(kMaxUploadBytes) + " accepted");
  }
  if (r.files.empty())
    throw InputError(
        "plot: send multipart/form-data with a field file (SVG or image) or svg (SVG text)");
  PlotForm f;
  json seen = json::object();
  bool have_drawing = false;
  for (const Upload& u : r.files) {
    const std::string& k = u.name;
    if (seen.contains(k)) throw InputError("plot." + k.substr(0, 40) + ": given twice");
    seen[k] = true;
    if (k == "file" || k == "svg") {
      if (have_drawing) throw InputError("plot." + k + ": give one of file and svg");
      have_drawing = true;
      f.drawing = u.content;
      f.input = k == "svg" ? "drawing.svg" : input_name(u.content);
      if (f.input.empty())
        throw InputError(
            "plot.file: neither an SVG drawing nor an image (PNG, JPEG, GIF, BMP, PBM/PGM/PPM)");
      f.image = f.input != "drawing.svg";
      continue;
    }
    if (u.content.size() > 4096)
      throw InputError("plot." + k.substr(0, 40) + ": longer than 4096 bytes");
    if (k == "machine") {
      f.machine = u.content;
    } else if (k == "name") {
      f.name = u.content;
      check_name(f.name);
    } else if (k == "mirror" || k == "order") {
      (k == "mirror" ? f.mirror : f.order) = flag_value(k, u.content);
    } else if (const auto* d = find_def(jobs::plot_table(), k)) {
      if (!u.content.empty())
        f.plot_given[k] = slicer::parse_param_text(jobs::plot_table(), *d, u.content);
    } else if (const auto* t = find_def(jobs::trace_table(), k)) {
      if (!u.content.empty())
        f.trace_given[k] = slicer::parse_param_text(jobs::trace_table(), *t, u.content);
    } else {
      throw InputError("plot." + k.substr(0, 40) +
                       ": unknown field (file or svg, machine, name, mirror, order, "
                       "and the options of strand plot and strand trace)");
    }
    if (k != "name" && k != "machine" && !u.content.empty()) f.fields[k] = u.content;
  }
  if (!have_drawing) throw InputError("plot.file: missing (an SVG or an image; or svg: SVG text)");
  if (!f.image && !f.trace_given.empty())
    throw InputError("trace." + f.trace_given.begin().key() + ": applies to images, not to an SVG");
  return f;
}

namespace {

void check_plotter(const std::string& name) {
  const auto catalog = machines::profile_catalog();
  const bool known =
      std::any_of(catalog.begin(), catalog.end(), [&](const auto& p) { return p.name == name; });
  if (!known || !machines::load_profile(name).plotter.enabled) {
    throw InputError("plot.machine = " + name.substr(0, 200) +
                     ": not a plotter of this server (GET /api/machines, kind plotter)");
  }
}

// Runs on a worker: what `strand plot drawing.svg --machine M [options]` does, the files
// written into `d`, and the check and previews of the G-code.
json plot_into(const fs::path& d, std::int64_t id, const PlotForm& f, const json& plot_values,
               const json& trace_values) {
  jobs::PlotRequest r;
  r.parameters = plot_values;
  r.options = jobs::plot_options(plot_values, f.mirror, f.order);
  r.input = f.input;
  const machines::MachineProfile m = machines::load_profile(f.machine);
  if (f.image) {
    const jobs::TracedImage t =
        jobs::trace_bytes(f.drawing, f.input, jobs::trace_options(trace_values));
    jobs::use_traced(r, t, trace_values, f.plot_given.contains("hatch-angle"), f.input);
  } else {
    r.drawing = slicer::import_svg(f.drawing, f.input);
    jobs::draw_text_into(r, jobs::text_options(plot_values));
  }
  jobs::PlotResult p = jobs::plot_drawing(std::move(r), m);
  p.report["gcode"] = "drawing.gcode";
  slicer::write_file_atomic((d / f.input).string(), f.drawing);
  slicer::write_file_atomic((d / "drawing.gcode").string(), p.gcode);
  slicer::write_file_atomic((d / "report.json").string(), slicer::dump_json(p.report) + "\n");
  json result = {{"summary", p.summary},
                 {"report", p.report},
                 {"check", jobs::sweep_check_summary(p.gcode, f.machine)}};
  result["figures"] = {{"time_s", p.report["estimate"]["time_s"]},
                       {"strokes", p.report["strokes"]["after_merge"]}};
  const post::ParsedGcode parsed = post::parse_gcode(p.gcode);
  const post::PreviewScene scene =
      post::preview_scene(parsed.program, slicer::kDefaultArcToleranceMm, parsed.pen_colours);
  slicer::write_file_atomic((d / "preview.png").string(), jobs::thumbnail_png(scene));
  slicer::write_file_atomic((d / "preview.html").string(),
                            post::render_html(scene, "drawing.gcode"));
  const std::string base = "/api/jobs/" + std::to_string(id) + "/files/";
  json files = json::array();
  for (const std::string& name : {f.input, std::string("drawing.gcode"), std::string("preview.html"),
                                 std::string("preview.png"), std::string("report.json")}) {
    files.push_back({{"name", name}, {"url", base + name}, {"bytes", fs::file_size(d / name)}});
  }
  result["files"] = files;
  result["gcode"] = base + "drawing.gcode";
  result["input"] = base + f.input;
  result["preview_png"] = base + "preview.png";
  result["preview_html"] = base + "preview.html";
  return result;
}

}  // namespace

Response Api::State::route_plot(const Request& r) {
  if (r.path == "/draw") return page_response("draw.html", r.method);
  if (r.method != "POST")
    throw HttpError(405, r.method.substr(0, 20) + " /api/plot: use POST (multipart/form-data)");
  const PlotForm f = read_plot_form(r);
  check_plotter(f.machine);
  // Checked here, before a job exists: a bad option is a 400 with the CLI's line.
  const json plot_values = slicer::resolve_params(jobs::plot_table(), f.plot_given);
  jobs::plot_options(plot_values, f.mirror, f.order);
  if (!f.image) jobs::text_options(plot_values);
  const json trace_values =
      f.image ? slicer::resolve_params(jobs::trace_table(), f.trace_given) : json();
  if (f.image) jobs::trace_options(trace_values);
  if (!options.run_jobs) return json_response(200, {{"checked", true}});

  const json job = {
      {"generator", "plot"}, {"machine", f.machine}, {"params", f.fields}, {"input", f.input}};
  const bool save = !f.name.empty();
  const std::int64_t id = new_job(save, f.name, dump(job));
  const fs::path d = job_dir(id);
  // The worker records the result itself, so a plot that outlasts the wait still finishes.
  run_and_wait(
      pool, id, [this, id] { drop_job(id); },
      [this, d, id, f, plot_values, trace_values] {
        json result = plot_into(d, id, f, plot_values, trace_values);
        store.finish(id, "ok", dump(result));
        return result;
      });
  for (const std::int64_t old : store.stale_unsaved(kKeepUnsavedJobs)) drop_job(old);
  const auto row = store.get(id);
  if (!row) throw HttpError(404, "job " + std::to_string(id) + " was deleted");
  return json_response(save ? 201 : 200, summary_of(*row, true));
}

}  // namespace strand::serve
