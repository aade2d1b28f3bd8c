// The extension `strand._strand`: jobs, sweeps, plots and G-code files run through jobs/ as
// the CLI runs them, with the GIL released while they work. Values arrive as the text a user
// would give the CLI flag, so a value means what it means there and fails with its message.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <filesystem>
#include <map>
#include <string>

#include "jobs/curved_job.h"
#include "jobs/job_runner.h"
#include "jobs/plot_options.h"
#include "jobs/plot_pipeline.h"
#include "jobs/slice_job.h"
#include "jobs/sweep_manifest.h"
#include "jobs/sweep_runner.h"
#include "jobs/sweep_spec.h"
#include "jobs/ink_profile.h"
#include "machines/profile.h"
#include "patterns/registry.h"
#include "postprocess/inspect/gcode_parser.h"
#include "python/strand_result.h"
#include "slicer/file_io.h"
#include "slicer/input_error.h"
#include "slicer/json_input.h"
#include "slicer/params.h"
#include "slicer/substrate_params.h"
#include "slicer/svg_import.h"
#include "slicer/unit_values.h"

namespace strand::python {

namespace {

using Texts = std::map<std::string, std::string>;

const char* type_name(slicer::ParamType t) {
  switch (t) {
    case slicer::ParamType::Number: return "number";
    case slicer::ParamType::Integer: return "integer";
    case slicer::ParamType::Text: return "text";
    case slicer::ParamType::NumberList: return "number list";
    case slicer::ParamType::Size2: return "size";
    case slicer::ParamType::Switch: return "switch";  // on/off (--stagger): True or False
  }
  return "text";
}

nlohmann::json def_json(const slicer::ParamDef& d) {
  nlohmann::json j = {{"key", d.key},           {"type", type_name(d.type)},
                      {"unit", d.unit},         {"help", d.help},
                      {"default", d.default_value}, {"default_text", d.default_text},
                      {"choices", d.choices},   {"paper", d.paper},
                      {"rule", slicer::describe_rule(d)}};
  j["min"] = d.min ? nlohmann::json(*d.min) : nlohmann::json();
  j["max"] = d.max ? nlohmann::json(*d.max) : nlohmann::json();
  j["min_exclusive"] = d.min_exclusive;
  j["max_exclusive"] = d.max_exclusive;
  return j;
}

nlohmann::json table_json(const slicer::ParamTable& t) {
  nlohmann::json defs = nlohmann::json::array();
  for (const auto& d : t.defs) defs.push_back(def_json(d));
  return defs;
}

// The generators with the parameter tables their flags are built from; plot's and the
// substrate's tables.
std::string tables_json() {
  nlohmann::json gens = nlohmann::json::array();
  for (const auto& g : patterns::generators())
    gens.push_back({{"name", g.name}, {"summary", g.summary}, {"params", table_json(g.table())}});
  return slicer::dump_json({{"generators", gens},
                            {"plot", table_json(jobs::plot_table())},
                            {"substrate", table_json(slicer::substrate_table())}});
}

std::string machines_json() {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& p : machines::profile_catalog()) {
    nlohmann::json profile;
    try {
      profile = nlohmann::json::parse(p.json_text);
    } catch (const std::exception&) {  // an unreadable user file: its description says why
    }
    list.push_back({{"name", p.name}, {"description", p.description}, {"origin", p.origin},
                    {"shadows_shipped", p.shadows_shipped}, {"profile", profile}});
  }
  return slicer::dump_json(list);
}

// Flag texts to their JSON form, as the CLI's given_params reads them.
nlohmann::json given(const slicer::ParamTable& table, const Texts& texts) {
  nlohmann::json j = nlohmann::json::object();
  for (const auto& [key, text] : texts) {
    const slicer::ParamDef* def = nullptr;
    for (const auto& d : table.defs) def = d.key == key ? &d : def;
    if (!def) throw InputError(table.name + "." + key + ": unknown parameter");
    j[key] = slicer::parse_param_text(table, *def, text);
  }
  return j;
}

// --arc-tolerance's text ("0.02", "20um") in mm, with the flag's messages.
double arc_tolerance(const std::string& text) {
  const slicer::UnitValues v = slicer::parse_quantity(text, "mm");
  if (v.malformed) throw InputError("arc-tolerance = " + text + ": must be a number, " + slicer::expected_units("mm"));
  if (!v.unit_problem.empty()) throw InputError("arc-tolerance = " + text + ": " + v.unit_problem);
  return v.values.front();
}

// A flat job in memory with its program kept, or a curved job's files.
std::shared_ptr<RawResult> produce(const patterns::GeneratorSpec& g, const nlohmann::json& params,
                                   jobs::JobSettings s, py::object callback) {
  PyProgress progress(std::move(callback));
  s.progress = &progress;
  s.keep_program = true;
  auto r = std::make_shared<RawResult>();
  r->machine = s.machine;
  r->arc_tolerance_mm = s.arc_tolerance_mm;
  py::gil_scoped_release release;
  if (s.substrate.empty()) {
    post::Produced p = jobs::produce_job(g, params, s);
    r->name = jobs::job_output_path(g, s);
    r->gcode = std::move(p.gcode);
    r->files = {{r->name, r->gcode}};
    r->report = std::move(p.report);
    r->summary = std::move(p.summary);
    r->program = std::make_shared<const slicer::MotionProgram>(std::move(p.program));
  } else {
    post::CurvedProduced c = jobs::produce_curved_job(g, params, s);
    r->files = std::move(c.files);
    r->name = r->files.front().first;
    r->gcode = r->files.front().second;
    r->report = std::move(c.report);
    r->summary = std::move(c.summary);
  }
  return r;
}

// `strand GENERATOR --flags`: `material` an ink profile's name or path, `tools` the --tools
// text or its job-file JSON ({"by_feature": ...}); empty: none.
std::shared_ptr<RawResult> run_generator(const std::string& name, const Texts& texts,
                                         const Texts& substrate, const std::string& machine,
                                         const std::string& arc_text, const std::string& material,
                                         const std::string& tools, py::object callback) {
  const patterns::GeneratorSpec* g = patterns::find_generator(name);
  if (!g) throw InputError("generator = " + name + ": unknown");
  jobs::JobSettings s;
  if (!machine.empty()) s.machine = machine;
  if (!arc_text.empty()) s.arc_tolerance_mm = arc_tolerance(arc_text);
  s.substrate = given(slicer::substrate_table(), substrate);
  nlohmann::json params = given(g->table(), texts);
  if (!material.empty()) s.material = jobs::apply_ink_profile(jobs::load_ink_profile(material), material, g->table(), params);
  if (!tools.empty()) s.tools = tools.starts_with("{") ? slicer::parse_json(tools, "tools") : nlohmann::json(tools);
  return produce(*g, params, s, std::move(callback));
}

// `strand job FILE` (path set: read from it, a substrate mesh found beside it, the output
// named after it) or a job given as JSON text.
std::shared_ptr<RawResult> run_job(const std::string& text, const std::string& path, py::object callback) {
  const nlohmann::json j = path.empty() ? slicer::parse_json(text, "job")
                                        : slicer::parse_json(slicer::read_file(path), "job = " + path);
  if (!j.is_object()) throw InputError("job" + (path.empty() ? "" : " = " + path) + ": must be a JSON object");
  jobs::JobSpec job = jobs::job_spec_from_json(j, "job");
  auto& substrate = job.settings.substrate;
  if (!path.empty()) {
    if (substrate.is_object() && substrate.contains("mesh") && substrate.at("mesh").is_string()) {
      const std::filesystem::path mesh(substrate.at("mesh").get<std::string>());
      if (mesh.is_relative())
        substrate["mesh"] = (std::filesystem::path(path).parent_path() / mesh).lexically_normal().string();
    }
    job.settings.output_stem = std::filesystem::path(path).stem().string();
  }
  return produce(*job.generator, job.params, job.settings, std::move(callback));
}

// `strand sweep FILE -o DIR`: (manifest.json, manifest.csv) as written into DIR.
std::pair<std::string, std::string> run_sweep(const std::string& text, const std::string& dir, int jobs,
                                              bool previews, py::object callback) {
  const nlohmann::json source = slicer::parse_json(text, "sweep");
  const jobs::SweepSpec spec = jobs::sweep_spec_from_json(source);
  jobs::SweepOptions o;
  o.dir = dir;
  o.jobs = jobs;
  o.previews = previews;
  // Called under the runner's lock from any worker; Ctrl-C is seen when the main thread
  // (which works in the arena too) finishes a point.
  const jobs::ProgressFn progress = [&callback](const jobs::SweepProgress& p) {
    py::gil_scoped_acquire gil;
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    if (!callback.is_none()) callback("sweep", p.done, p.total);
  };
  jobs::SweepResult r;
  {
    py::gil_scoped_release release;
    r = jobs::run_sweep(spec, source, o, progress);
  }
  return {slicer::dump_json(r.manifest), jobs::manifest_csv(r.manifest)};
}

// `strand plot DRAWING.svg --machine M`, in memory.
std::shared_ptr<RawResult> run_plot(const std::string& svg, const Texts& texts, const std::string& machine,
                                    bool mirror, bool order, py::object callback) {
  PyProgress progress(std::move(callback));
  auto r = std::make_shared<RawResult>();
  r->machine = machine;
  r->name = std::filesystem::path(svg).filename().replace_extension(".gcode").string();
  jobs::PlotRequest request;
  request.parameters = slicer::resolve_params(jobs::plot_table(), given(jobs::plot_table(), texts));
  request.options = jobs::plot_options(request.parameters, mirror, order);
  request.input = svg;
  py::gil_scoped_release release;
  const machines::MachineProfile m = machines::load_profile(machine);
  request.drawing = slicer::import_svg(slicer::read_file(svg), svg);
  jobs::draw_text_into(request, jobs::text_options(request.parameters));
  jobs::PlotResult p = jobs::plot_drawing(std::move(request), m, &progress);
  p.report["gcode"] = r->name;
  r->gcode = std::move(p.gcode);
  r->files = {{r->name, r->gcode}};
  r->report = std::move(p.report);
  r->summary = std::move(p.summary);
  return r;
}

// `strand slice PART --pattern NAME [pattern flags]` (or --onto SUBSTRATE), in memory.
std::shared_ptr<RawResult> run_slice(const std::string& part, const std::string& onto,
                                     const std::string& pattern, const Texts& texts,
                                     const Texts& options, int perimeters, bool repair, bool strict,
                                     py::object callback) {
  PyProgress progress(std::move(callback));
  jobs::SliceSettings s;
  s.part = part;
  s.onto = onto;
  std::vector<std::string> names;
  for (const auto& g : patterns::generators()) names.push_back(g.name);
  s.pattern = slicer::match_choice(pattern, names).value_or(pattern);
  if (const auto* g = patterns::find_generator(s.pattern)) s.pattern_values = given(g->table(), texts);
  s.perimeters = perimeters;
  s.repair = repair;
  s.strict = strict;
  // The CLI's spellings: choices in any case, --scale a number, --arc-tolerance with a unit.
  const auto option = [&options](const char* key, const std::string& fallback) {
    const auto it = options.find(key);
    return it == options.end() ? fallback : it->second;
  };
  s.mesh_units = slicer::match_choice(option("mesh-units", "mm"), {"mm", "cm", "m", "in"}).value_or(option("mesh-units", "mm"));
  s.place = slicer::match_choice(option("place", "center"), {"center", "origin"}).value_or(option("place", "center"));
  s.up = slicer::match_choice(option("up", "z"), {"z", "y"}).value_or(option("up", "z"));
  s.rotate = option("rotate", s.rotate);
  s.scale_to_fit = option("scale-to-fit", "");
  s.machine = option("machine", s.machine);
  if (options.count("scale")) {
    const slicer::UnitValues v = slicer::parse_quantity(options.at("scale"), "");
    if (!v.ok()) throw InputError("slice.scale = " + options.at("scale") + ": must be a number");
    s.scale = v.values.front();
  }
  if (options.count("arc-tolerance")) s.arc_tolerance_mm = arc_tolerance(options.at("arc-tolerance"));
  if (options.count("threads")) s.threads = std::stoi(options.at("threads"));
  const std::string& input = part.empty() ? onto : part;
  s.output = input.empty() ? "slice.gcode" : std::filesystem::path(input).filename().stem().string() + ".gcode";
  s.progress = &progress;
  auto r = std::make_shared<RawResult>();
  r->machine = s.machine;
  r->arc_tolerance_mm = s.arc_tolerance_mm;
  r->name = s.output;
  py::gil_scoped_release release;
  jobs::SliceResult sliced = jobs::produce_slice(s);
  r->gcode = std::move(sliced.produced.gcode);
  r->files = {{r->name, r->gcode}};
  r->report = std::move(sliced.produced.report);
  r->summary = std::move(sliced.produced.summary);
  if (!sliced.produced.program.moves.empty())
    r->program = std::make_shared<const slicer::MotionProgram>(std::move(sliced.produced.program));
  return r;
}

// Any G-code file read back as `strand check` and `strand preview` read it.
std::shared_ptr<RawResult> read_gcode(const std::string& path, const std::string& machine) {
  auto r = std::make_shared<RawResult>();
  r->name = std::filesystem::path(path).filename().string();
  r->machine = machine;
  py::gil_scoped_release release;
  r->gcode = slicer::read_file(path);
  post::ParsedGcode parsed;
  try {
    parsed = post::parse_gcode(r->gcode);
  } catch (const InputError& e) {
    throw InputError("input = " + path + ": " + e.what());
  }
  if (parsed.program.moves.empty()) throw InputError("input = " + path + ": no moves (is it G-code?)");
  r->move_lines = std::move(parsed.move_lines);
  r->has_e = parsed.has_e;
  r->program = std::make_shared<const slicer::MotionProgram>(std::move(parsed.program));
  return r;
}

}  // namespace

}  // namespace strand::python

PYBIND11_MODULE(_strand, m) {
  namespace sp = strand::python;
  namespace py = pybind11;
  m.doc() = "Strand's C++ core; use the package `strand`, which wraps it.";
  // InputError is the user's to fix: ValueError with the CLI's one-line message.
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const strand::InputError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    }
  });
  sp::bind_result(m);
  m.def("tables_json", &sp::tables_json);
  m.def("machines_json", &sp::machines_json);
  m.def("run_generator", &sp::run_generator);
  m.def("run_job", &sp::run_job);
  m.def("run_sweep", &sp::run_sweep);
  m.def("run_plot", &sp::run_plot);
  m.def("run_slice", &sp::run_slice);
  m.def("read_gcode", &sp::read_gcode);
}
