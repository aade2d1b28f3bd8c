// The checks of one program fed in pieces: strand counts as estimate() counts them, contacts
// per layer (ContactStream), forbidden arcs, build volume or plotter reach per move.
#include "postprocess/inspect/check_stream.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "machines/kinematics.h"
#include "machines/plotter_kinematics.h"
#include "postprocess/plan/estimate.h"

namespace strand::post {

using slicer::MoveKind;
using slicer::Vec2;
using slicer::Vec3;

namespace {

// Points of an arc from `from` to its end that may lie farthest out: its four axis
// extremes and its point farthest from the origin (delta radius), when within the sweep.
std::vector<Vec2> arc_extremes(const Vec2& from, const slicer::Move& mv) {
  const Vec2 c = mv.center_mm, to = mv.end_mm.head<2>();
  const double r = (from - c).norm();
  const double sweep = std::abs(slicer::arc_sweep(c, from, to, mv.ccw));
  std::vector<Vec2> candidates = {c + Vec2(r, 0), c - Vec2(r, 0), c + Vec2(0, r), c - Vec2(0, r)};
  if (c.norm() > 0) candidates.push_back(c + r * c.normalized());
  std::vector<Vec2> out;
  for (const Vec2& p : candidates) {
    if (std::abs(slicer::arc_sweep(c, from, p, mv.ccw)) <= sweep) out.push_back(p);
  }
  return out;
}

void add_finding(std::vector<Finding>& list, std::size_t& total, Finding f) {
  if (list.size() < CheckReport::kMaxFindings) list.push_back(std::move(f));
  ++total;
}

// A pen plotter writes its own axes (cable lengths, R and theta); read them back to paper
// millimetres so contacts and reach are judged where the pen draws.
Vec3 paper(const machines::Plotter& plotter, const Vec3& p) {
  const Vec2 q = machines::to_paper(plotter.setup, p.head<2>());
  return {q.x(), q.y(), p.z()};
}

// Whether the rules let this crossing be (see CheckRules).
bool crossing_allowed(const Contact& c, CheckRules rules) {
  if (rules == CheckRules::Plot) return true;
  if (rules == CheckRules::Diw) return false;
  return !c.walls;
}

// A layer that deposits nothing (travel only, or only marked) is not a layer of the print:
// its row goes, and it is counted apart.
void drop_layers_without_deposit(CheckReport& r) {
  const auto empty = [](const LayerCheck& l) {
    return l.layer >= 0 && l.strands == 0 && l.crossings.empty() && l.touches.empty();
  };
  for (const auto& l : r.layers) {
    if (!empty(l)) continue;
    if (r.layers_without_deposit_index.size() < CheckReport::kMaxFindings)
      r.layers_without_deposit_index.push_back(l.layer);
    ++r.layers_without_deposit;
  }
  r.layers.erase(std::remove_if(r.layers.begin(), r.layers.end(), empty), r.layers.end());
}

}  // namespace

CheckStream::CheckStream(const CheckOptions& o) : o_(o) {
  if (o.machine && o.machine->plotter.enabled) plotter_ = o.machine;
  if (o.machine && !plotter_ && IdleHeadCheck(*o.machine).active()) idle_.emplace(*o.machine);
}

LayerCheck& CheckStream::row(int layer) {
  if (layer < 0) return before_first_;
  while (rows_.size() <= static_cast<std::size_t>(layer))
    rows_.push_back({static_cast<int>(rows_.size()), 0.0, 0, {}, {}, {}});
  return rows_[static_cast<std::size_t>(layer)];
}

void CheckStream::add(const slicer::MotionProgram& p, const std::vector<int>& move_lines,
                      std::size_t first_move) {
  const int layers = static_cast<int>(p.layers.size());
  if (layers > 0) row(layers - 1);  // every layer has its row, moves or not
  if (p.moves.empty()) return;
  if (!started_) {  // the program's start is known once it has a move
    started_ = true;
    at_ = plotter_ ? paper(plotter_->plotter, p.start_mm) : p.start_mm;
    contacts_.emplace(o_.arc_tolerance_mm, o_.touch_mm, at_);
  }
  for (std::size_t i = 0; i < p.moves.size(); ++i) {
    const int line = i < move_lines.size() ? move_lines[i] : 0;
    if (!plotter_) {
      add_move(p.moves[i], first_move + i, line, p);
      continue;
    }
    slicer::Move mv = p.moves[i];
    mv.end_mm = paper(plotter_->plotter, mv.end_mm);
    add_move(mv, first_move + i, line, p);
  }
  r_.moves += p.moves.size();
  take_contacts();
}

void CheckStream::add_move(const slicer::Move& mv, std::size_t move, int line, const slicer::MotionProgram& p) {
  r_.deposit_moves += mv.kind == MoveKind::Deposit;
  contacts_->add(mv, move, line, found_);
  bounds(mv, move, line);
  if (idle_) idle_heads(mv, move, line, p);
  strands(mv, static_cast<int>(p.layers.size()));  // last: it moves at_ on
}

// The file's xy are where the depositing nozzle is (its offset read from the header, or the
// firmware's), its z the carriage's: the tip is the profile's z offset higher.
void CheckStream::idle_heads(const slicer::Move& mv, std::size_t move, int line, const slicer::MotionProgram& p) {
  if (mv.kind != MoveKind::Deposit) return;
  const Vec3 up(0, 0, machines::tool_offset(*o_.machine, mv.tool).z());
  double h = 0.0;  // the layer's height: its ;HEIGHT:, else the step from the layer below
  if (mv.layer >= 0 && static_cast<std::size_t>(mv.layer) < p.layers.size()) {
    const auto k = static_cast<std::size_t>(mv.layer);
    h = p.layers[k].height_mm > 0 ? p.layers[k].height_mm : p.layers[k].z_mm - (k > 0 ? p.layers[k - 1].z_mm : 0.0);
  }
  idle_->add_move(at_, mv, up, h, move, line, o_.arc_tolerance_mm);
}

// As estimate() counts them: a deposit after a travel that moved, or in a new layer,
// starts a strand; deposits before the first layer count in none.
void CheckStream::strands(const slicer::Move& mv, int layers) {
  if (mv.layer != last_layer_) depositing_ = false;
  last_layer_ = mv.layer;
  if (mv.kind == MoveKind::Dwell || mv.kind == MoveKind::Raw) return;
  const double len = move_length(at_, mv);
  if (mv.kind == MoveKind::Deposit) {
    if (!depositing_ && mv.layer >= 0 && mv.layer < layers) {
      LayerCheck& r = row(mv.layer);
      ++r.strands;
      const auto k = static_cast<std::size_t>(std::max<int>(mv.tool, 0));
      if (r.strands_by_tool.size() <= k) r.strands_by_tool.resize(k + 1, 0);
      ++r.strands_by_tool[k];
    }
    depositing_ = true;
  } else if (len > 0) {
    depositing_ = false;
  }
  at_ = mv.end_mm;
}

// Forbidden arcs and the build volume (arc bulges included), or a plotter's reach.
void CheckStream::bounds(const slicer::Move& mv, std::size_t move, int line) {
  const machines::MachineProfile* m = o_.machine;
  if (!m) return;
  if (plotter_) {
    if (mv.kind != MoveKind::Deposit && mv.kind != MoveKind::Travel) return;
    if (auto why = machines::unreachable_reason(m->plotter, mv.end_mm.head<2>()))
      add_finding(r_.outside_volume, r_.outside_volume_total, {line, move, mv.end_mm, *why});
    return;
  }
  if (mv.kind == MoveKind::Raw || mv.kind == MoveKind::Dwell) return;
  if (mv.is_arc && !m->arcs) {
    add_finding(r_.arcs_forbidden, r_.arcs_forbidden_total,
                {line, move, mv.end_mm, "G2/G3 arc, but " + m->name + " does not accept arcs"});
  }
  if (auto why = machines::outside_reason(m->volume, mv.end_mm)) {
    add_finding(r_.outside_volume, r_.outside_volume_total, {line, move, mv.end_mm, *why});
  } else if (mv.is_arc) {
    for (const Vec2& p : arc_extremes(at_.head<2>(), mv)) {
      const Vec3 q(p.x(), p.y(), mv.end_mm.z());
      if (auto bulge = machines::outside_reason(m->volume, q)) {
        add_finding(r_.outside_volume, r_.outside_volume_total, {line, move, q, *bulge});
        break;
      }
    }
  }
}

void CheckStream::take_contacts() {
  for (auto& c : found_.crossings) row(c.layer).crossings.push_back(c);
  for (auto& c : found_.touches) row(c.layer).touches.push_back(c);
  found_.crossings.clear();
  found_.touches.clear();
}

CheckReport CheckStream::finish(const ParsedGcode& parsed, const RulesChoice& rules) {
  if (contacts_) contacts_->finish(found_);
  take_contacts();
  const auto& layers = parsed.program.layers;
  if (!layers.empty()) row(static_cast<int>(layers.size()) - 1);
  for (std::size_t i = 0; i < layers.size() && i < rows_.size(); ++i)
    rows_[i].z_mm = layers[i].z_mm;
  CheckReport r = std::move(r_);
  r.rules = rules;
  r.pen_drawing = rules.rules == CheckRules::Plot;
  if (o_.machine) r.machine = o_.machine->name;
  if (idle_ && !r.pen_drawing) {
    r.idle_heads_checked = true;
    r.idle_head_collisions = idle_->hit_count();
    r.idle_head_hits = idle_->hits();
  }
  r.parse_issues = parsed.issues;
  r.notes = parsed.notes;
  // A row -1 only when deposits before the first layer have contacts.
  if (!before_first_.crossings.empty() || !before_first_.touches.empty()) {
    before_first_.z_mm = parsed.program.start_mm.z();
    r.layers.push_back(std::move(before_first_));
  }
  for (auto& l : rows_) r.layers.push_back(std::move(l));
  rows_.clear();
  for (const auto& l : r.layers) {
    for (const auto& c : l.crossings) r.crossings_allowed += crossing_allowed(c, rules.rules);
  }
  drop_layers_without_deposit(r);
  return r;
}

namespace {

// One reading of the program, its pieces handed to the sink, under the given pen reading.
using Reading = std::function<ParsedGcode(const PenReading&, const PieceSink&)>;

// read_for_check and check_parsed in one pass: a drawing lifted by Z alone is read twice
// (the first reading finds the lowest drawing z), as parse_drawing reads it.
CheckReport check_reading(const Reading& read, std::string_view head, const CheckOptions& o) {
  const RulesChoice rules = o.rules ? *o.rules : default_rules(o.machine, head);
  const PenReading pen = o.machine ? pen_reading_from(*o.machine) : PenReading{};
  CheckOptions with_rules = o;
  with_rules.rules = rules;
  std::optional<CheckStream> stream(std::in_place, with_rules);
  const bool drawing = rules.rules == CheckRules::Plot;
  double low = std::numeric_limits<double>::infinity(), high = -low;
  const PieceSink sink = [&](const ParsedGcode& piece, std::size_t first_move) {
    stream->add(piece.program, piece.move_lines, first_move);
    if (!drawing) return;
    for (const slicer::Move& m : piece.program.moves) {
      if (m.kind != MoveKind::Deposit) continue;
      low = std::min(low, m.end_mm.z());
      high = std::max(high, m.end_mm.z());
    }
  };
  ParsedGcode parsed = read(pen, sink);
  if (drawing) {
    if (const auto by_z = pen_by_z(parsed, pen, low, high)) {
      stream.emplace(with_rules);
      parsed = read(by_z->pen, sink);
      parsed.notes.push_back(by_z->note);
    }
  }
  return stream->finish(parsed, rules_after_reading(rules, o.rules, o.machine, parsed));
}

}  // namespace

CheckReport check_gcode(std::string_view text, const CheckOptions& o) {
  return check_reading(
      [text](const PenReading& pen, const PieceSink& sink) {
        return parse_gcode_layers(text, pen, sink);
      },
      text, o);
}

CheckReport check_gcode_file(const GcodeFile& file, const GcodeScan& scan, const CheckOptions& o,
                             slicer::Progress* progress) {
  if (scan.has_o_words) return check_gcode(file.text(), o);
  const auto mib = [progress](std::uintmax_t bytes) {
    slicer::progress_step(progress, static_cast<std::size_t>(bytes >> 20));
  };
  const LineSource lines = [&](const std::function<void(std::string_view)>& each) {
    file.each_line(each, mib);
  };
  return check_reading(
      [&](const PenReading& pen, const PieceSink& sink) {
        return parse_gcode_layers(lines, scan, pen, sink);
      },
      scan.head, o);
}

}  // namespace strand::post
