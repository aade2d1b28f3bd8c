// `strand check` one layer at a time: the checks of check.h fed piece by piece (each layer of
// a file as it is read, or a whole parsed program), keeping per layer only its row (strands,
// contacts) and of the other findings the first CheckReport::kMaxFindings, so memory stays
// flat in the file's size.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "postprocess/inspect/check.h"
#include "postprocess/inspect/gcode_file.h"
#include "postprocess/plan/idle_heads.h"
#include "slicer/progress_listener.h"

namespace strand::post {

class CheckStream {
 public:
  // `o.rules` settled before the reading (finish() takes the final choice: a pen servo may
  // still make a diw reading a drawing).
  explicit CheckStream(const CheckOptions& o);
  // The next moves of the program, in order: program.moves[i] is move first_move + i of the
  // whole program, read from move_lines[i] (0 when not given); program.layers lists at
  // least the layers these moves are in, program.start_mm the program's start.
  void add(const slicer::MotionProgram& program, const std::vector<int>& move_lines,
           std::size_t first_move);
  // Once every move is in: `parsed` gives the final layers, start, issues and notes.
  CheckReport finish(const ParsedGcode& parsed, const RulesChoice& rules);

 private:
  void add_move(const slicer::Move& mv, std::size_t move, int line, const slicer::MotionProgram& p);
  void strands(const slicer::Move& mv, int layers);
  void bounds(const slicer::Move& mv, std::size_t move, int line);
  void idle_heads(const slicer::Move& mv, std::size_t move, int line, const slicer::MotionProgram& p);
  void take_contacts();
  LayerCheck& row(int layer);

  CheckOptions o_;
  const machines::MachineProfile* plotter_ = nullptr;  // the machine, when a plotter
  bool started_ = false;
  slicer::Vec3 at_ = slicer::Vec3::Zero();  // where the last move ended (paper for plotters)
  bool depositing_ = false;                 // the strand count's state, as estimate()'s
  int last_layer_ = -2;
  std::optional<ContactStream> contacts_;
  std::optional<IdleHeadCheck> idle_;  // a machine with heads at several places
  ContactReport found_;  // contacts of the layers searched, until placed in their rows
  std::vector<LayerCheck> rows_;
  LayerCheck before_first_{-1, 0.0, 0, {}, {}};
  CheckReport r_;
};

// check_gcode on the file, read line by line: a first pass scans it (GcodeScan), then each
// layer is checked as it is read and dropped. An RS274NGC program with O-words is read whole
// (its loops jump back); `progress` hears the MiB read.
CheckReport check_gcode_file(const GcodeFile& file, const GcodeScan& scan, const CheckOptions& o,
                             slicer::Progress* progress = nullptr);

}  // namespace strand::post
