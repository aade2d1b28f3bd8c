// What every call of the Python module returns, before the Python layer (strand/_result.py)
// wraps it: the file text, the report, and the program behind the NumPy views.
#pragma once

#include <pybind11/pybind11.h>

#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "slicer/motion.h"
#include "slicer/progress_listener.h"

namespace strand::python {

namespace py = pybind11;

struct RawResult {
  std::string name;     // the default output file name: "scaffold.gcode", "part.csv"
  std::string gcode;    // the main file's text (a robot cell: its pose CSV)
  nlohmann::json report = nlohmann::json::object();
  std::string summary;  // the CLI's summary text
  std::string machine;  // profile name or path, for check(); empty: none
  double arc_tolerance_mm = 0.01;
  // Every file the job writes, name -> text, in the CLI's order (one for flat jobs).
  std::vector<std::pair<std::string, std::string>> files;
  // Held by the NumPy views too (they outlive the result); null until first asked for when
  // the job did not keep it (plots, curved jobs): then read back from `gcode`.
  std::shared_ptr<const slicer::MotionProgram> program;
  std::vector<int> move_lines;  // read back from `gcode`: each move's line (1-based)
  bool has_e = false;           // ... and the file has E words
};

// Reports phases to an optional Python callable (phase, done, steps) and turns Ctrl-C into
// KeyboardInterrupt: each call takes the GIL, runs the signal handlers and throws
// py::error_already_set when one raised, which unwinds the job (nothing is written).
class PyProgress : public slicer::Progress {
 public:
  explicit PyProgress(py::object callback) : callback_(std::move(callback)) {}
  void phase(const std::string& name, std::size_t steps) override;
  void step(std::size_t done) override;

 private:
  void notify(std::size_t done);
  py::object callback_;
  std::string phase_;
  std::size_t steps_ = 0;
};

// Binds RawResult (moves, layers, check, previews) into `m`.
void bind_result(py::module_& m);

}  // namespace strand::python
