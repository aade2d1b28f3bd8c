// The check's report: the whole-program entry points (over check_stream.h) and the report as
// JSON and text.
#include "postprocess/inspect/check.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "machines/gcode_format.h"
#include "postprocess/inspect/check_stream.h"

namespace strand::post {

using slicer::MoveKind;
using slicer::Vec2;
using slicer::Vec3;

bool CheckReport::ok() const {
  return crossing_count() == crossings_allowed && parse_issues.empty() &&
         arcs_forbidden_total == 0 && outside_volume_total == 0 && idle_head_collisions == 0 &&
         !(deposit_moves == 0 && rules.rules == CheckRules::Diw);
}

std::size_t CheckReport::crossing_count() const {
  std::size_t n = 0;
  for (const auto& l : layers) n += l.crossings.size();
  return n;
}

std::size_t CheckReport::crossings_between_tools() const {
  std::size_t n = 0;
  for (const auto& l : layers) n += std::count_if(l.crossings.begin(), l.crossings.end(), [](const Contact& c) { return c.between_tools(); });
  return n;
}

std::size_t CheckReport::touch_count() const {
  std::size_t n = 0;
  for (const auto& l : layers) n += l.touches.size();
  return n;
}

int CheckReport::line_of(std::size_t move) const {
  for (const auto& l : layers) {
    for (const auto* list : {&l.crossings, &l.touches}) {
      for (const Contact& c : *list) {
        if (c.move_a == move) return c.line_a;
        if (c.move_b == move) return c.line_b;
      }
    }
  }
  for (const auto* list : {&arcs_forbidden, &outside_volume}) {
    for (const Finding& f : *list) {
      if (f.move == move) return f.line;
    }
  }
  return 0;
}

namespace {

std::string xy(const Vec2& p) {
  return "(" + machines::fmt_xyz(p.x()) + ", " + machines::fmt_xyz(p.y()) + ")";
}

std::string xyz(const Vec3& p) {
  return "(" + machines::fmt_xyz(p.x()) + ", " + machines::fmt_xyz(p.y()) + ", " +
         machines::fmt_xyz(p.z()) + ")";
}

// A crossing or touch; between two printheads' strands (not pens), with their tools.
nlohmann::json contact_json(const Contact& c, bool pen_drawing) {
  nlohmann::json j = {{"x_mm", c.at_mm.x()}, {"y_mm", c.at_mm.y()}, {"line_a", c.line_a}, {"line_b", c.line_b}};
  if (c.between_tools() && !pen_drawing) j["tools"] = {c.tool_a, c.tool_b};
  return j;
}

// A file printed by several printheads (strands of more than one tool in a layer).
bool several_tools(const CheckReport& r) {
  return std::any_of(r.layers.begin(), r.layers.end(), [](const LayerCheck& l) { return l.strands_by_tool.size() > 1; });
}

nlohmann::json idle_hit_json(const IdleHeadHit& h) {
  return {{"layer", h.layer},         {"tool", h.tool},
          {"active_tool", h.active_tool}, {"x_mm", h.tip_mm.x()},
          {"y_mm", h.tip_mm.y()},     {"tip_z_mm", h.tip_mm.z()},
          {"bead_top_mm", h.bead_top_mm}, {"line", h.line}};
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
  const RulesChoice rules = o.rules ? *o.rules : default_rules(o.machine, {});
  CheckOptions with_rules = o;
  with_rules.rules = rules;
  CheckStream stream(with_rules);
  stream.add(parsed.program, parsed.move_lines, 0);
  return stream.finish(parsed, rules);
}

nlohmann::json to_json(const CheckReport& r) {
  nlohmann::json layers = nlohmann::json::array();
  for (const auto& l : r.layers) {
    nlohmann::json cross = nlohmann::json::array(), touch = nlohmann::json::array();
    for (const auto& c : l.crossings) cross.push_back(contact_json(c, r.pen_drawing));
    for (const auto& c : l.touches) touch.push_back(contact_json(c, r.pen_drawing));
    layers.push_back({{"layer", l.layer},
                      {"z_mm", l.z_mm},
                      {"strands", l.strands},
                      {"crossings", cross},
                      {"touches", touch}});
    if (l.strands_by_tool.size() > 1) layers.back()["strands_by_tool"] = l.strands_by_tool;
  }
  nlohmann::json by_tool;  // several printheads: their crossings with each other
  if (several_tools(r) && !r.pen_drawing) by_tool = {{"crossings_between_tools", r.crossings_between_tools()}};
  nlohmann::json issues = nlohmann::json::array(), arcs = nlohmann::json::array(),
                 outside = nlohmann::json::array();
  nlohmann::json notes = nlohmann::json::array();
  for (const auto& i : r.parse_issues) issues.push_back({{"line", i.line}, {"what", i.what}});
  for (const auto& i : r.notes) notes.push_back({{"line", i.line}, {"what", i.what}});
  for (const auto& f : r.arcs_forbidden) arcs.push_back(finding_json(f));
  for (const auto& f : r.outside_volume) outside.push_back(finding_json(f));
  nlohmann::json out = {{"ok", r.ok()},
                        {"machine", r.machine},
                        {"rules", to_string(r.rules.rules)},
                        {"rules_why", r.rules.why},
                        {"pen_drawing", r.pen_drawing},
                        {"moves", r.moves},
                        {"deposit_moves", r.deposit_moves},
                        {"layers", layers},
                        {"layers_without_deposit", r.layers_without_deposit},
                        {"layers_without_deposit_index", r.layers_without_deposit_index},
                        {"crossings", r.crossing_count()},
                        {"crossings_allowed", r.crossings_allowed},
                        {"touches", r.touch_count()},
                        {"notes", notes},
                        {"parse_issues", issues},
                        {"arcs_forbidden", arcs},
                        {"arcs_forbidden_total", r.arcs_forbidden_total},
                        {"outside_volume", outside},
                        {"outside_volume_total", r.outside_volume_total}};
  if (by_tool.is_object()) out.update(by_tool);
  if (r.idle_heads_checked) {  // a machine with heads at several places
    out["idle_head_collisions"] = r.idle_head_collisions;
    out["idle_head_collision_list"] = nlohmann::json::array();
    for (const auto& h : r.idle_head_hits) out["idle_head_collision_list"].push_back(idle_hit_json(h));
  }
  return out;
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
    while (e < r.layers.size() && r.layers[e].strands == L.strands && r.layers[e].strands_by_tool == L.strands_by_tool &&
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
    if (L.strands_by_tool.size() > 1 && r.rules.rules != CheckRules::Plot) {  // several printheads: each one's
      out.pop_back();
      out += "  by tool";
      for (std::size_t k = 0; k < L.strands_by_tool.size(); ++k) out += " T" + std::to_string(k) + ":" + std::to_string(L.strands_by_tool[k]);
      out += "\n";
    }
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
               std::to_string(c.line_a) + " and " + std::to_string(c.line_b) +
               (c.between_tools() && !r.pen_drawing ? " (T" + std::to_string(c.tool_a) + " and T" + std::to_string(c.tool_b) + ": two inks)" : "") +
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

// An idle head's tip down on the beads: where, which heads, how high.
void list_idle_heads(const CheckReport& r, std::string& out) {
  if (!r.idle_heads_checked) return;
  if (r.idle_head_collisions == 0) {
    out += "idle heads: clear of the print over every deposit\n";
    return;
  }
  out += "idle heads dragging through the print (" + std::to_string(r.idle_head_collisions) +
         "; give the idle head an idle_lift_mm, or a part the idle head stays outside of):\n";
  for (std::size_t i = 0; i < r.idle_head_hits.size() && i < kTextListed; ++i) {
    const IdleHeadHit& h = r.idle_head_hits[i];
    out += "  layer " + std::to_string(h.layer) + ": T" + std::to_string(h.tool) + " idle at " + xyz(h.tip_mm) +
           " mm, beads up to z " + machines::fmt_xyz(h.bead_top_mm) + " under it, while T" +
           std::to_string(h.active_tool) + " deposits (line " + std::to_string(h.line) + ")\n";
  }
  if (r.idle_head_collisions > r.idle_head_hits.size())
    out += "  ... and " + std::to_string(r.idle_head_collisions - r.idle_head_hits.size()) + " more\n";
}

// "2 layers with moves but no deposit, not counted as layers: 5, 6" and, for a file that
// deposits nothing, the line that says so (a failure under the diw rules).
std::string without_deposit_text(const CheckReport& r) {
  std::string out;
  if (r.layers_without_deposit > 0) {
    const bool one = r.layers_without_deposit == 1;
    out += std::to_string(r.layers_without_deposit) +
           (one ? " layer with moves but no deposit, not counted as a layer: "
                : " layers with moves but no deposit, not counted as layers: ");
    const auto& index = r.layers_without_deposit_index;
    for (std::size_t i = 0; i < index.size() && i < kTextListed; ++i)
      out += (i ? ", " : "") + std::to_string(index[i]);
    out += r.layers_without_deposit > kTextListed ? ", ...\n" : "\n";
  }
  if (r.deposit_moves == 0) {
    out += "no deposit: not one of the " + std::to_string(r.moves) +
           " moves deposits (no E growing, no pen down)" +
           (r.rules.rules == CheckRules::Diw ? "" : " (said, not failed, under " +
                                                        to_string(r.rules.rules) + " rules)") +
           "\n";
  }
  return out;
}

}  // namespace

std::string to_text(const CheckReport& r) {
  std::string out = std::to_string(r.layers.size()) + " layers, " + std::to_string(r.moves) +
                    " moves" +
                    (r.machine.empty() ? ", no machine given (bounds and arcs not checked)"
                                       : ", machine " + r.machine) +
                    "\nrules " + to_string(r.rules.rules) + ": " + r.rules.why + "\n";
  out += without_deposit_text(r);
  out += layer_table(r);
  out += crossing_heading(r);
  if (r.crossings_between_tools() > 0 && !r.pen_drawing)
    out += "  of which between printheads (two inks): " + std::to_string(r.crossings_between_tools()) + "\n";
  list_contacts(r, true, out);
  if (r.arcs_forbidden_total > 0)
    out += "arcs the machine forbids (" + std::to_string(r.arcs_forbidden_total) + "):\n";
  list_findings(r.arcs_forbidden, r.arcs_forbidden_total, out);
  if (r.outside_volume_total > 0)
    out += "moves outside the build volume (" + std::to_string(r.outside_volume_total) + "):\n";
  list_findings(r.outside_volume, r.outside_volume_total, out);
  list_idle_heads(r, out);
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
