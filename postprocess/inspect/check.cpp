// Check of a parsed G-code file: contacts and strands per layer, forbidden arcs, build
// volume, parse problems; the strand count comes from estimate(), contacts from crossings.
#include "postprocess/inspect/check.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "machines/gcode_format.h"
#include "machines/kinematics.h"
#include "machines/plotter_kinematics.h"
#include "postprocess/plan/estimate.h"

namespace strand::post {

using slicer::MoveKind;
using slicer::Vec2;
using slicer::Vec3;

bool CheckReport::ok() const {
  return crossing_count() == crossings_allowed && parse_issues.empty() &&
         arcs_forbidden_total == 0 && outside_volume_total == 0;
}

std::size_t CheckReport::crossing_count() const {
  std::size_t n = 0;
  for (const auto& l : layers) n += l.crossings.size();
  return n;
}

std::size_t CheckReport::touch_count() const {
  std::size_t n = 0;
  for (const auto& l : layers) n += l.touches.size();
  return n;
}

int CheckReport::line_of(std::size_t move) const {
  return move < move_lines.size() ? move_lines[move] : 0;
}

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

void check_moves(const ParsedGcode& parsed, const machines::MachineProfile& m, CheckReport& r) {
  const auto& moves = parsed.program.moves;
  Vec3 at = parsed.program.start_mm;
  for (std::size_t i = 0; i < moves.size(); ++i) {
    const auto& mv = moves[i];
    if (mv.kind == MoveKind::Raw || mv.kind == MoveKind::Dwell) continue;
    const int line = r.line_of(i);
    if (mv.is_arc && !m.arcs) {
      add_finding(r.arcs_forbidden, r.arcs_forbidden_total,
                  {line, i, mv.end_mm, "G2/G3 arc, but " + m.name + " does not accept arcs"});
    }
    if (auto why = machines::outside_reason(m.volume, mv.end_mm)) {
      add_finding(r.outside_volume, r.outside_volume_total, {line, i, mv.end_mm, *why});
    } else if (mv.is_arc) {
      for (const Vec2& p : arc_extremes(at.head<2>(), mv)) {
        const Vec3 q(p.x(), p.y(), mv.end_mm.z());
        if (auto bulge = machines::outside_reason(m.volume, q)) {
          add_finding(r.outside_volume, r.outside_volume_total, {line, i, q, *bulge});
          break;
        }
      }
    }
    at = mv.end_mm;
  }
}

// A pen plotter writes its own axes (cable lengths, R and theta); read them back to paper
// millimetres so contacts and reach are judged where the pen draws.
ParsedGcode to_paper(const ParsedGcode& parsed, const machines::Plotter& plotter) {
  ParsedGcode paper = parsed;
  auto map = [&](Vec3& p) {
    const Vec2 q = machines::to_paper(plotter.setup, p.head<2>());
    p.x() = q.x();
    p.y() = q.y();
  };
  map(paper.program.start_mm);
  for (auto& mv : paper.program.moves) map(mv.end_mm);
  return paper;
}

void check_reach(const ParsedGcode& paper, const machines::MachineProfile& m, CheckReport& r) {
  const auto& moves = paper.program.moves;
  for (std::size_t i = 0; i < moves.size(); ++i) {
    const auto& mv = moves[i];
    if (mv.kind != MoveKind::Deposit && mv.kind != MoveKind::Travel) continue;
    if (auto why = machines::unreachable_reason(m.plotter, mv.end_mm.head<2>())) {
      add_finding(r.outside_volume, r.outside_volume_total, {r.line_of(i), i, mv.end_mm, *why});
    }
  }
}

// Whether the rules let these two moves cross (see CheckRules).
bool crossing_allowed(const slicer::MotionProgram& p, const Contact& c, CheckRules rules) {
  if (rules == CheckRules::Plot) return true;
  if (rules == CheckRules::Diw) return false;
  return p.moves[c.move_a].feature != slicer::Feature::Wall ||
         p.moves[c.move_b].feature != slicer::Feature::Wall;
}

// One row per layer of the program; a row -1 only when deposits before the first layer
// have contacts.
void fill_layers(const ParsedGcode& parsed, const CheckOptions& o, CheckReport& r) {
  const CheckRules rules = r.rules.rules;
  const Estimate est = estimate(parsed.program);
  for (const auto& le : est.layers) r.layers.push_back({le.layer, le.z_mm, le.strands, {}, {}});
  const ContactReport contacts = find_contacts(parsed.program, o.arc_tolerance_mm, o.touch_mm);
  const bool before_first = std::any_of(contacts.crossings.begin(), contacts.crossings.end(),
                                        [](const Contact& c) { return c.layer < 0; }) ||
                            std::any_of(contacts.touches.begin(), contacts.touches.end(),
                                        [](const Contact& c) { return c.layer < 0; });
  if (before_first) r.layers.insert(r.layers.begin(), {-1, parsed.program.start_mm.z(), 0, {}, {}});
  auto row = [&](int layer) -> LayerCheck& {
    return r.layers[static_cast<std::size_t>(std::max(layer, -1) + (before_first ? 1 : 0))];
  };
  for (const auto& c : contacts.crossings) {
    row(c.layer).crossings.push_back(c);
    if (crossing_allowed(parsed.program, c, rules)) ++r.crossings_allowed;
  }
  for (const auto& c : contacts.touches) row(c.layer).touches.push_back(c);
}

std::string xy(const Vec2& p) {
  return "(" + machines::fmt_xyz(p.x()) + ", " + machines::fmt_xyz(p.y()) + ")";
}

std::string xyz(const Vec3& p) {
  return "(" + machines::fmt_xyz(p.x()) + ", " + machines::fmt_xyz(p.y()) + ", " +
         machines::fmt_xyz(p.z()) + ")";
}

nlohmann::json contact_json(const Contact& c, const CheckReport& r) {
  return {{"x_mm", c.at_mm.x()},
          {"y_mm", c.at_mm.y()},
          {"line_a", r.line_of(c.move_a)},
          {"line_b", r.line_of(c.move_b)}};
}

nlohmann::json finding_json(const Finding& f) {
  return {{"line", f.line},
          {"x_mm", f.at_mm.x()},
          {"y_mm", f.at_mm.y()},
          {"z_mm", f.at_mm.z()},
          {"what", f.what}};
}

}  // namespace

CheckReport check_parsed(const ParsedGcode& parsed, const CheckOptions& o) {
  CheckReport r;
  r.moves = parsed.program.moves.size();
  r.move_lines = parsed.move_lines;
  r.parse_issues = parsed.issues;
  r.notes = parsed.notes;
  r.rules = o.rules ? *o.rules : default_rules(o.machine, {});
  r.pen_drawing = r.rules.rules == CheckRules::Plot;
  if (o.machine && o.machine->plotter.enabled) {
    r.machine = o.machine->name;
    const ParsedGcode paper = to_paper(parsed, o.machine->plotter);
    fill_layers(paper, o, r);
    check_reach(paper, *o.machine, r);
    return r;
  }
  fill_layers(parsed, o, r);
  if (o.machine) {
    r.machine = o.machine->name;
    check_moves(parsed, *o.machine, r);
  }
  return r;
}

CheckReport check_gcode(std::string_view text, const CheckOptions& o) {
  CheckInput in = read_for_check(text, o.machine, o.rules);
  CheckOptions with_rules = o;
  with_rules.rules = in.rules;
  return check_parsed(in.parsed, with_rules);
}

nlohmann::json to_json(const CheckReport& r) {
  nlohmann::json layers = nlohmann::json::array();
  for (const auto& l : r.layers) {
    nlohmann::json cross = nlohmann::json::array(), touch = nlohmann::json::array();
    for (const auto& c : l.crossings) cross.push_back(contact_json(c, r));
    for (const auto& c : l.touches) touch.push_back(contact_json(c, r));
    layers.push_back({{"layer", l.layer},
                      {"z_mm", l.z_mm},
                      {"strands", l.strands},
                      {"crossings", cross},
                      {"touches", touch}});
  }
  nlohmann::json issues = nlohmann::json::array(), arcs = nlohmann::json::array(),
                 outside = nlohmann::json::array();
  nlohmann::json notes = nlohmann::json::array();
  for (const auto& i : r.parse_issues) issues.push_back({{"line", i.line}, {"what", i.what}});
  for (const auto& i : r.notes) notes.push_back({{"line", i.line}, {"what", i.what}});
  for (const auto& f : r.arcs_forbidden) arcs.push_back(finding_json(f));
  for (const auto& f : r.outside_volume) outside.push_back(finding_json(f));
  return {{"ok", r.ok()},
          {"machine", r.machine},
          {"rules", to_string(r.rules.rules)},
          {"rules_why", r.rules.why},
          {"pen_drawing", r.pen_drawing},
          {"moves", r.moves},
          {"layers", layers},
          {"crossings", r.crossing_count()},
          {"crossings_allowed", r.crossings_allowed},
          {"touches", r.touch_count()},
          {"notes", notes},
          {"parse_issues", issues},
          {"arcs_forbidden", arcs},
          {"arcs_forbidden_total", r.arcs_forbidden_total},
          {"outside_volume", outside},
          {"outside_volume_total", r.outside_volume_total}};
}

namespace {

constexpr std::size_t kTextListed = 20;  // problems listed per kind in the text report

std::string crossing_heading(const CheckReport& r) {
  const std::size_t n = r.crossing_count(), allowed = r.crossings_allowed;
  if (n == 0) return "";
  if (r.pen_drawing)
    return "strokes crossing (a drawing may cross itself; listed for review: " + std::to_string(n) +
           "):\n";
  if (allowed == 0) return "self-crossings (" + std::to_string(n) + "):\n";
  return "crossings (" + std::to_string(n) + ", " + std::to_string(allowed) +
         " allowed by fdm rules: infill may cross; " + std::to_string(n - allowed) +
         " between walls):\n";
}

void list_notes(const std::vector<ParseIssue>& list, std::string& out) {
  for (std::size_t i = 0; i < list.size() && i < kTextListed; ++i) {
    out += "  line " + std::to_string(list[i].line) + ": " + list[i].what + "\n";
  }
  if (list.size() > kTextListed)
    out += "  ... and " + std::to_string(list.size() - kTextListed) + " more\n";
}

std::string layer_range(int first, int last) {
  return first == last ? std::to_string(first) : std::to_string(first) + "-" + std::to_string(last);
}

// Consecutive layers with equal strands and contact counts share one row.
std::string layer_table(const CheckReport& r) {
  std::string out = "layers     z_mm             strands  crossings  touches\n";
  for (std::size_t b = 0; b < r.layers.size();) {
    const auto& L = r.layers[b];
    std::size_t e = b + 1;
    while (e < r.layers.size() && r.layers[e].strands == L.strands &&
           r.layers[e].crossings.size() == L.crossings.size() &&
           r.layers[e].touches.size() == L.touches.size()) {
      ++e;
    }
    const auto& last = r.layers[e - 1];
    char row[160];
    const std::string z =
        machines::fmt_xyz(L.z_mm) + (e - b > 1 ? "-" + machines::fmt_xyz(last.z_mm) : "");
    std::snprintf(row, sizeof row, "%-10s %-16s %7d  %9zu  %7zu\n",
                  layer_range(L.layer, last.layer).c_str(), z.c_str(), L.strands,
                  L.crossings.size(), L.touches.size());
    out += row;
    b = e;
  }
  return out;
}

void list_contacts(const CheckReport& r, bool crossings, std::string& out) {
  std::size_t listed = 0, total = 0;
  for (const auto& l : r.layers) {
    for (const auto& c : crossings ? l.crossings : l.touches) {
      if (listed++ < kTextListed) {
        out += std::string(crossings ? "  crossing" : "  touch") + " in layer " +
               std::to_string(l.layer) + " at " + xy(c.at_mm) + " mm: lines " +
               std::to_string(r.line_of(c.move_a)) + " and " + std::to_string(r.line_of(c.move_b)) +
               "\n";
      }
      ++total;
    }
  }
  if (total > kTextListed) out += "  ... and " + std::to_string(total - kTextListed) + " more\n";
}

void list_findings(const std::vector<Finding>& list, std::size_t total, std::string& out) {
  for (std::size_t i = 0; i < list.size() && i < kTextListed; ++i) {
    out += "  line " + std::to_string(list[i].line) + " at " + xyz(list[i].at_mm) +
           " mm: " + list[i].what + "\n";
  }
  if (total > kTextListed) out += "  ... and " + std::to_string(total - kTextListed) + " more\n";
}

}  // namespace

std::string to_text(const CheckReport& r) {
  std::string out = std::to_string(r.layers.size()) + " layers, " + std::to_string(r.moves) +
                    " moves" +
                    (r.machine.empty() ? ", no machine given (bounds and arcs not checked)"
                                       : ", machine " + r.machine) +
                    "\nrules " + to_string(r.rules.rules) + ": " + r.rules.why + "\n";
  out += layer_table(r);
  out += crossing_heading(r);
  list_contacts(r, true, out);
  if (r.arcs_forbidden_total > 0)
    out += "arcs the machine forbids (" + std::to_string(r.arcs_forbidden_total) + "):\n";
  list_findings(r.arcs_forbidden, r.arcs_forbidden_total, out);
  if (r.outside_volume_total > 0)
    out += "moves outside the build volume (" + std::to_string(r.outside_volume_total) + "):\n";
  list_findings(r.outside_volume, r.outside_volume_total, out);
  if (!r.parse_issues.empty())
    out += "problems in the file (" + std::to_string(r.parse_issues.size()) + "):\n";
  list_notes(r.parse_issues, out);
  if (!r.notes.empty()) out += "notes (" + std::to_string(r.notes.size()) + "):\n";
  list_notes(r.notes, out);
  if (r.touch_count() > 0)
    out += "touches (allowed, listed for review: " + std::to_string(r.touch_count()) + "):\n";
  list_contacts(r, false, out);
  out += r.ok() ? "check: OK\n" : "check: FAILED\n";
  return out;
}

}  // namespace strand::post
