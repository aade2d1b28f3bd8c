// The result object's views: moves as a NumPy structured array over the program itself (no
// copy), the check and the previews as the CLI computes them, and atomic writes.
#include "python/strand_result.h"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cctype>
#include <cmath>
#include <cstddef>
#include <cstdlib>

#include "machines/profile.h"
#include "postprocess/inspect/check.h"
#include "postprocess/inspect/gcode_parser.h"
#include "postprocess/preview/preview_html.h"
#include "postprocess/preview/preview_image.h"
#include "postprocess/preview/viewer_data.h"
#include "postprocess/preview/viewer_html.h"
#include "slicer/file_io.h"
#include "slicer/input_error.h"
#include "slicer/json_input.h"
#include "slicer/tolerances.h"

namespace strand::python {

void PyProgress::phase(const std::string& name, std::size_t steps) {
  phase_ = name;
  steps_ = steps;
  notify(0);
}

void PyProgress::step(std::size_t done) { notify(done); }

void PyProgress::notify(std::size_t done) {
  py::gil_scoped_acquire gil;
  if (PyErr_CheckSignals() != 0) throw py::error_already_set();
  if (!callback_.is_none()) callback_(phase_, done, steps_);
}

namespace {

std::ptrdiff_t offset(const slicer::Move& m, const void* field) {
  return static_cast<const char*>(field) - reinterpret_cast<const char*>(&m);
}

// The fields of slicer::Move where they lie in memory (the dtype has Move's size, so a row
// is a Move and the array is the program's own storage).
py::dtype move_dtype() {
  const slicer::Move m;
  py::list names, formats, offsets;
  const auto add = [&](const char* name, const char* format, const void* field) {
    names.append(name);
    formats.append(format);
    offsets.append(offset(m, field));
  };
  add("x", "<f8", &m.end_mm.x());
  add("y", "<f8", &m.end_mm.y());
  add("z", "<f8", &m.end_mm.z());
  add("feed", "<f8", &m.feed_mm_per_min);
  add("volume", "<f8", &m.volume_mm3);
  add("width", "<f8", &m.width_mm);
  add("cx", "<f8", &m.center_mm.x());
  add("cy", "<f8", &m.center_mm.y());
  add("layer", "<i4", &m.layer);
  add("tool", "<i2", &m.tool);
  add("kind", "u1", &m.kind);
  add("feature", "u1", &m.feature);
  add("arc", "?", &m.is_arc);
  add("ccw", "?", &m.ccw);
  add("coast", "?", &m.coast);
  py::dict d;
  d["names"] = names;
  d["formats"] = formats;
  d["offsets"] = offsets;
  d["itemsize"] = sizeof(slicer::Move);
  return py::dtype::from_args(d);
}

// The program, read back from the file text the first time when the job did not keep it.
std::shared_ptr<const slicer::MotionProgram> program_of(RawResult& r) {
  if (!r.program) {
    post::ParsedGcode parsed = post::parse_gcode(r.gcode);
    r.move_lines = std::move(parsed.move_lines);
    r.has_e = parsed.has_e;
    r.program = std::make_shared<const slicer::MotionProgram>(std::move(parsed.program));
  }
  return r.program;
}

// A read-only view whose base keeps the program alive.
template <typename T>
py::array view(const std::shared_ptr<const slicer::MotionProgram>& p, const py::dtype& dt,
               const T* data, std::size_t count, std::size_t stride) {
  auto* keep = new std::shared_ptr<const slicer::MotionProgram>(p);
  py::capsule base(keep, [](void* k) { delete static_cast<std::shared_ptr<const slicer::MotionProgram>*>(k); });
  py::array a(dt, {count}, {stride}, data, base);
  py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}

py::array moves(RawResult& r) {
  const auto p = program_of(r);
  return view(p, move_dtype(), p->moves.data(), p->moves.size(), sizeof(slicer::Move));
}

// The E step of every line of a file (relative, whatever the file's E mode): M82/M83 switch
// the mode, G92 E sets the position, E on G0-G3 moves it. The parser keeps no E per move.
std::vector<double> e_steps_by_line(const std::string& text) {
  std::vector<double> steps(1, 0.0);  // [line], 1-based
  bool relative = false;
  double e = 0.0;
  std::size_t start = 0;
  while (start <= text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(start, end - start);
    line = line.substr(0, line.find(';'));
    for (auto& c : line) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    double step = 0.0;
    const auto word = [&line](char letter, double& value) {
      const std::size_t at = line.find(letter);
      if (at == std::string::npos) return false;
      value = std::strtod(line.c_str() + at + 1, nullptr);
      return std::isfinite(value);
    };
    double code = -1.0, v = 0.0;
    const bool g = word('G', code), m = !g && word('M', v);
    if (m && v == 82.0) relative = false;
    if (m && v == 83.0) relative = true;
    if (g && code == 92.0 && word('E', v)) e = v;
    if (g && code >= 0.0 && code <= 3.0 && word('E', v)) {
      step = relative ? v : v - e;
      e = relative ? e + v : v;
    }
    steps.push_back(step);
    start = end + 1;
  }
  return steps;
}

// Ink per move as the file's E words count it: a job for an E-volumetric machine writes
// volume / mm3_per_e, other deposition (valves, pens) none; a file read back has its E words.
py::array_t<double> e_values(RawResult& r) {
  const auto p = program_of(r);
  py::array_t<double> e(static_cast<py::ssize_t>(p->moves.size()));
  auto out = e.mutable_unchecked<1>();
  if (!r.move_lines.empty()) {
    const std::vector<double> steps = r.has_e ? e_steps_by_line(r.gcode) : std::vector<double>{};
    for (std::size_t i = 0; i < p->moves.size(); ++i) {
      const auto line = static_cast<std::size_t>(r.move_lines.at(i));
      out(i) = line < steps.size() ? steps[line] : 0.0;
    }
    return e;
  }
  double per_e = 0.0;
  if (!r.machine.empty()) {
    const machines::MachineProfile m = machines::load_profile(r.machine);
    if (m.deposition.model == machines::DepositionModel::EVolumetric) per_e = m.deposition.mm3_per_e;
  }
  for (std::size_t i = 0; i < p->moves.size(); ++i) {
    const slicer::Move& mv = p->moves[i];
    out(i) = per_e > 0.0 && mv.kind == slicer::MoveKind::Deposit ? mv.volume_mm3 / per_e : 0.0;
  }
  return e;
}

py::array_t<double> layer_z(RawResult& r) {
  const auto p = program_of(r);
  py::array_t<double> z(static_cast<py::ssize_t>(p->layers.size()));
  auto out = z.mutable_unchecked<1>();
  for (std::size_t i = 0; i < p->layers.size(); ++i) out(i) = p->layers[i].z_mm;
  return z;
}

// `strand check FILE --machine M --json`, on the text in memory.
std::string check_json(const RawResult& r) {
  std::unique_ptr<machines::MachineProfile> machine;
  if (!r.machine.empty()) machine = std::make_unique<machines::MachineProfile>(machines::load_profile(r.machine));
  post::CheckInput in = post::read_for_check(r.gcode, machine.get(), std::nullopt);
  post::CheckOptions options;
  options.rules = in.rules;
  options.touch_mm = slicer::kGcodeResolutionMm;
  options.machine = machine.get();
  return slicer::dump_json(post::to_json(post::check_parsed(in.parsed, options)));
}

// The scene `strand preview FILE` draws: the file parsed as that command parses it.
post::PreviewScene scene_of(const RawResult& r) {
  const post::ParsedGcode parsed = post::parse_gcode(r.gcode);
  post::PreviewScene scene = post::preview_scene(parsed.program, r.arc_tolerance_mm, parsed.pen_colours);
  if (scene.paths.empty()) throw InputError("preview: no moves to draw");
  return scene;
}

py::bytes preview_png(const RawResult& r, int width_px, int height_px, const std::string& view,
                      int layer, bool travel, bool by_layer) {
  post::ImageOptions o;
  o.width_px = width_px;
  o.height_px = height_px;
  if (view == "top") o.view = post::PreviewView::Top;
  else if (view == "iso") o.view = post::PreviewView::Iso;
  else if (view == "both") o.view = post::PreviewView::Both;
  else throw InputError("view = " + view + ": must be one of top, iso, both");
  o.layer = layer;
  o.travel = travel;
  o.colouring = by_layer ? post::PreviewColouring::Layer : post::PreviewColouring::Feature;
  std::string png;
  {
    const post::PreviewScene scene = scene_of(r);
    py::gil_scoped_release release;
    png = post::render_png(scene, o);
  }
  return py::bytes(png);
}

// Every (path, text) written as one transaction (all or none), never over a protected input.
void write_files(const std::vector<std::pair<std::string, std::string>>& files,
                 const std::vector<std::string>& inputs) {
  slicer::OutputFiles out;
  for (const auto& input : inputs) out.protect_input(input);
  for (const auto& [path, text] : files) out.stage(path, text);
  out.commit();
}

}  // namespace

void bind_result(py::module_& m) {
  py::class_<RawResult, std::shared_ptr<RawResult>>(m, "RawResult")
      .def_readonly("name", &RawResult::name)
      .def_property_readonly("gcode", [](const RawResult& r) { return py::str(r.gcode); })
      .def_property_readonly("report_json", [](const RawResult& r) { return slicer::dump_json(r.report); })
      .def_readonly("summary_text", &RawResult::summary)
      .def_readonly("machine", &RawResult::machine)
      .def_readonly("files", &RawResult::files)
      .def("moves", &moves)
      .def("e", &e_values)
      .def("layer_z", &layer_z)
      .def("start", [](RawResult& r) {
             const slicer::Vec3 s = program_of(r)->start_mm;
             return std::vector<double>{s.x(), s.y(), s.z()};
           })
      .def("check_json", &check_json, py::call_guard<py::gil_scoped_release>())
      // The 3D viewer `strand preview -o x.html` writes (three.js inlined: about 0.6 MB).
      .def("preview_html", [](const RawResult& r, const std::string& title) {
             py::gil_scoped_release release;
             return post::render_viewer_html(
                 post::viewer_data_from_gcode(r.gcode, nullptr, slicer::kDefaultArcToleranceMm, title),
                 title);
           })
      // The light canvas page a job's preview.html is (a notebook's inline frame).
      .def("preview_page_html", [](const RawResult& r, const std::string& title) {
             const post::PreviewScene scene = scene_of(r);
             py::gil_scoped_release release;
             return post::render_html(scene, title);
           })
      .def("preview_png", &preview_png);
  m.def("write_files", &write_files, py::call_guard<py::gil_scoped_release>());
}

}  // namespace strand::python
