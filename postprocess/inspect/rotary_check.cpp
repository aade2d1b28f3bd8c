// Rotary G-code mapped back onto its cylinder through the header's axis and substrate lines,
// and held to what the writer promises (machines/rotary_gcode.h): ;LAYER:n numbered 0, 1, ...;
// deposits on the offset surface the layer's ;Z: names; the same ink per mm on the cylinder
// within a layer (a deleted, swapped or turned move changes the distance, not its E); feeds
// that give the planned surface speed (deposits per feature at the job's speed, travels at
// the machine's travel or lift feed).
#include <algorithm>
#include <charconv>
#include <cmath>
#include <map>
#include <optional>

#include "machines/gcode_format.h"
#include "machines/kinematics.h"
#include "postprocess/inspect/pose_check.h"
#include "slicer/input_error.h"
#include "slicer/params.h"
#include "slicer/tolerances.h"
#include "slicer/units.h"

namespace strand::post {

using machines::fmt_fixed;
using slicer::Vec3;

namespace {

// What the comments and modes of a rotary file say beyond the axis header.
struct RotaryComments {
  std::vector<std::pair<int, long long>> layer_marks;  // (line, n) of ;LAYER:n
  std::string machine;                                 // "; machine: NAME (...)"
  std::optional<double> speed_mm_per_min;              // "; param speed = S"
  std::map<std::string, double> speed_factors;         // "; param infill-speed-factor = f"
  bool inverse_time = false;                           // a G93 line
  // "; substrate: ... wrap patch, arc length at surface": the pattern is centred on u = 0
  // with u = turn x substrate radius (postprocess/plan/cylinder_placement.h).
  bool centred_patch = false;
};

bool starts_with(std::string_view s, std::string_view p) { return s.substr(0, p.size()) == p; }

std::optional<double> number_after(std::string_view s, std::size_t at) {
  double v = 0.0;
  while (at < s.size() && s[at] == ' ') ++at;
  if (at >= s.size()) return std::nullopt;
  const auto r = std::from_chars(s.data() + at, s.data() + s.size(), v);
  if (r.ec != std::errc() || !std::isfinite(v)) return std::nullopt;
  return v;
}

RotaryComments read_comments(std::string_view text) {
  RotaryComments c;
  int line_no = 0;
  for (std::size_t pos = 0; pos <= text.size();) {
    std::size_t nl = text.find('\n', pos);
    if (nl == std::string_view::npos) nl = text.size();
    std::string_view line = text.substr(pos, nl - pos);
    pos = nl + 1;
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (starts_with(line, "G93")) c.inverse_time = true;
    if (line.empty() || line[0] != ';') continue;
    if (starts_with(line, ";LAYER:")) {
      long long n = -1;
      const auto r = std::from_chars(line.data() + 7, line.data() + line.size(), n);
      c.layer_marks.push_back({line_no, r.ec == std::errc() ? n : -1});
    } else if (starts_with(line, "; substrate: cylinder") &&
               line.find("wrap patch, arc length at surface") != std::string_view::npos) {
      c.centred_patch = true;
    } else if (starts_with(line, "; machine: ") && c.machine.empty()) {
      const std::string_view rest = line.substr(11);
      c.machine = std::string(rest.substr(0, rest.find(' ')));
    } else if (starts_with(line, "; param speed = ")) {
      c.speed_mm_per_min = number_after(line, 16);
    } else if (starts_with(line, "; param ")) {
      const std::string_view rest = line.substr(8);
      const std::size_t key_end = rest.find("-speed-factor = ");
      if (key_end == std::string_view::npos) continue;
      if (auto f = number_after(rest, key_end + 16))
        c.speed_factors[std::string(rest.substr(0, key_end))] = *f;
    }
  }
  return c;
}

// ;Z: then ;LAYER: per layer in the writer's block: pair them up in order (NaN: none given).
std::vector<double> layer_z(std::string_view text) {
  std::vector<double> out;
  double pending = std::nan("");
  for (std::size_t pos = 0; pos <= text.size();) {
    std::size_t nl = text.find('\n', pos);
    if (nl == std::string_view::npos) nl = text.size();
    const std::string_view line = text.substr(pos, nl - pos);
    pos = nl + 1;
    if (starts_with(line, ";LAYER_CHANGE")) pending = std::nan("");
    if (starts_with(line, ";Z:")) pending = number_after(line, 3).value_or(std::nan(""));
    if (starts_with(line, ";LAYER:")) {
      out.push_back(pending);
      pending = std::nan("");
    }
  }
  return out;
}

// The machine whose feeds the file was planned with: the one given, else a shipped rotary
// profile the header names (a bare name only: never a path from inside a file).
std::optional<machines::MachineProfile> planning_machine(const machines::MachineProfile* given,
                                                         const std::string& named) {
  if (given) return given->rotary.enabled ? std::optional(*given) : std::nullopt;
  if (named.empty() || named.size() > 64) return std::nullopt;
  for (char ch : named) {
    if (!((ch >= 'a' && ch <= 'z') || (ch >= '0' && ch <= '9') || ch == '-')) return std::nullopt;
  }
  try {
    auto m = machines::load_profile(named);
    if (m.rotary.enabled) return m;
  } catch (const InputError&) {
  }
  return std::nullopt;
}

double median_of(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

// One move on the cylinder: from the previous sample to this one.
struct RotaryMove {
  std::size_t line = 0;
  bool deposit = false;
  slicer::Feature feature = slicer::Feature::Infill;
  int layer = 0;
  double surface_mm = 0.0;      // contact distance on the workpiece
  double e = 0.0;               // E advanced
  double speed_mm_per_s = 0.0;  // surface speed the feed gives; 0 when it gives none
};

// Files round positions and A to 0.001 and F to 0.001: a distance is off by up to this, mm.
constexpr double kRoundingMm = 2e-3;

bool deviates(double value, double reference, double len_mm) {
  return std::abs(value - reference) >
         (slicer::kSpeedDeviation + kRoundingMm / len_mm) * std::abs(reference);
}

std::vector<RotaryMove> rotary_moves(const ParsedGcode& parsed,
                                     const std::vector<CylinderSample>& samples,
                                     bool inverse_time) {
  std::vector<RotaryMove> out;
  std::size_t k = 0;  // index into samples
  const auto& moves = parsed.program.moves;
  std::optional<std::size_t> prev;  // index of the previous deposit/travel move
  for (std::size_t i = 0; i < moves.size(); ++i) {
    const auto& mv = moves[i];
    if (mv.kind != slicer::MoveKind::Deposit && mv.kind != slicer::MoveKind::Travel) continue;
    const std::size_t s = k++;
    if (!prev) {
      prev = i;
      continue;  // from wherever the machine was: nothing to measure
    }
    RotaryMove m;
    m.line = static_cast<std::size_t>(parsed.move_lines[i]);
    m.deposit = mv.kind == slicer::MoveKind::Deposit;
    m.feature = mv.feature;
    m.layer = mv.layer;
    m.surface_mm = (samples[s].p_mm - samples[s - 1].p_mm).norm();
    m.e = parsed.e_step.empty() ? 0.0 : parsed.e_step[i];
    const double xyz = (mv.end_mm - moves[*prev].end_mm).norm();
    const double da = parsed.a_deg.empty() ? 0.0 : std::abs(parsed.a_deg[i] - parsed.a_deg[*prev]);
    const double f = mv.feed_mm_per_min;
    double minutes = 0.0;
    if (f > 0) minutes = inverse_time ? 1.0 / f : (xyz > 0 ? xyz : da) / f;
    if (minutes > 0) m.speed_mm_per_s = m.surface_mm / (minutes * 60.0);
    out.push_back(m);
    prev = i;
  }
  return out;
}

// Ink per mm on the cylinder is the layer's bead section: the same for every deposit of it.
void check_ink(const std::vector<RotaryMove>& moves, PoseCheckReport& r) {
  std::map<int, std::vector<double>> per_layer;
  for (const auto& m : moves) {
    if (m.deposit && m.surface_mm >= slicer::kSpeedCheckMinMm)
      per_layer[m.layer].push_back(m.e / m.surface_mm);
  }
  std::map<int, double> reference;
  for (auto& [layer, v] : per_layer) reference[layer] = median_of(v);
  for (const auto& m : moves) {
    if (!m.deposit) continue;
    const double ref = reference.count(m.layer) ? reference[m.layer] : 0.0;
    // Below the check length only gross disagreement counts (E for twice the distance).
    if (m.surface_mm < slicer::kSpeedCheckMinMm) {
      if (ref > 0 && m.e > 0 && m.surface_mm > 1e-9 &&
          std::abs(m.e - ref * m.surface_mm) > 0.5 * ref * slicer::kSpeedCheckMinMm)
        r.extrusion.add(m.line, "E " + fmt_fixed(m.e, 5) + " over " + fmt_fixed(m.surface_mm, 4) +
                                    " mm on the cylinder; the layer deposits " + fmt_fixed(ref, 5) +
                                    " per mm");
      continue;
    }
    if (deviates(m.e / m.surface_mm, ref, m.surface_mm)) {
      r.extrusion.add(m.line, "E " + fmt_fixed(m.e, 5) + " over " + fmt_fixed(m.surface_mm, 4) +
                                  " mm on the cylinder (" + fmt_fixed(m.e / m.surface_mm, 5) +
                                  " per mm); the layer deposits " + fmt_fixed(ref, 5) +
                                  " per mm (a moved, deleted or swapped line?)");
    }
  }
}

// Deposits: one surface speed per feature, the planned one when the job's speed and the
// machine are known. Travels: the machine's travel or lift feed.
void check_feeds(const std::vector<RotaryMove>& moves, const RotaryComments& c,
                 const std::optional<machines::MachineProfile>& m, PoseCheckReport& r) {
  std::map<slicer::Feature, std::vector<double>> per_feature;
  std::map<slicer::Feature, std::size_t> first_line;
  std::vector<double> ink;
  for (const auto& mv : moves) {
    if (!mv.deposit || mv.surface_mm < slicer::kSpeedCheckMinMm) continue;
    per_feature[mv.feature].push_back(mv.speed_mm_per_s);
    first_line.emplace(mv.feature, mv.line);
    if (mv.layer == 0) ink.push_back(mv.e / mv.surface_mm);
  }
  std::map<slicer::Feature, double> planned;
  for (auto& [f, v] : per_feature) planned[f] = median_of(v);
  if (m && c.speed_mm_per_min) {
    for (auto& [f, median] : planned) {
      double factor = 1.0;
      const auto given = c.speed_factors.find(slicer::to_string(f));
      if (given != c.speed_factors.end()) {
        factor = given->second;
      } else if (auto pf = m->speed_factors.find(f); pf != m->speed_factors.end()) {
        factor = pf->second;
      }
      double v = slicer::mm_per_min_to_mm_per_s(
          std::min(*c.speed_mm_per_min * factor, m->limits.max_feed_mm_per_min));
      const double area = median_of(ink) * m->deposition.mm3_per_e;
      const double q_max = m->limits.max_volumetric_flow_mm3_per_s;
      if (m->deposition.model == machines::DepositionModel::EVolumetric && q_max > 0 && area > 0)
        v = std::min(v, q_max / area);
      if (std::abs(median - v) > slicer::kSpeedDeviation * v) {
        r.speed.add(first_line[f], slicer::to_string(f) + " deposits move at " +
                                       fmt_fixed(median, 3) + " mm/s on the cylinder, planned " +
                                       fmt_fixed(v, 3) + " mm/s (the job's speed " +
                                       slicer::short_number(*c.speed_mm_per_min) +
                                       " mm/min on machine " + m->name + ")");
      }
      median = v;
    }
  }
  const double travel = m ? slicer::mm_per_min_to_mm_per_s(m->limits.travel_feed_mm_per_min) : 0;
  const double lift = m ? slicer::mm_per_min_to_mm_per_s(m->limits.z_feed_mm_per_min) : 0;
  for (const auto& mv : moves) {
    if (mv.surface_mm < slicer::kSpeedCheckMinMm) continue;
    if (!(mv.speed_mm_per_s > 0)) {
      r.speed.add(mv.line, "no feed for a move of " + fmt_fixed(mv.surface_mm, 4) + " mm");
      continue;
    }
    if (mv.deposit) {
      const double v = planned[mv.feature];
      if (deviates(mv.speed_mm_per_s, v, mv.surface_mm)) {
        r.speed.add(mv.line, "deposits at " + fmt_fixed(mv.speed_mm_per_s, 3) +
                                 " mm/s on the cylinder, planned " + fmt_fixed(v, 3) + " mm/s");
      }
    } else if (m && deviates(mv.speed_mm_per_s, travel, mv.surface_mm) &&
               deviates(mv.speed_mm_per_s, lift, mv.surface_mm)) {
      r.speed.add(mv.line, "travels at " + fmt_fixed(mv.speed_mm_per_s, 3) +
                               " mm/s on the cylinder; the machine travels at " +
                               fmt_fixed(travel, 3) + " and lifts at " + fmt_fixed(lift, 3) +
                               " mm/s");
    }
  }
}

// ;LAYER:n numbered 0, 1, 2, ... and, with the machine known, each layer's deposits at the
// radius its ;Z: names: the writer's ;Z: is the layer's first point, backed off by the
// machine's lift above the layer's offset surface.
void check_layers(const RotaryComments& c, const std::vector<double>& z, const RotaryHeader& h,
                  const std::optional<machines::MachineProfile>& m, PoseCheckReport& r) {
  for (std::size_t k = 0; k < c.layer_marks.size(); ++k) {
    const auto [line, n] = c.layer_marks[k];
    if (n != static_cast<long long>(k)) {
      r.numbering.add(static_cast<std::size_t>(line),
                      ";LAYER:" + std::to_string(n) + " is the file's layer " + std::to_string(k) +
                          ": layers are numbered 0, 1, 2, ...");
    }
  }
  if (!m) return;
  for (const auto& l : r.layers) {
    if (l.layer < 0 || static_cast<std::size_t>(l.layer) >= z.size() ||
        static_cast<std::size_t>(l.layer) >= c.layer_marks.size() || std::isnan(z[l.layer]))
      continue;
    const double expected = z[l.layer] - h.axis_point_mm.z() - m->rotary.lift_mm;
    if (l.strands > 0 && std::abs(l.radius_mm - expected) > slicer::kOffSurfaceMm) {
      r.off_surface.add(static_cast<std::size_t>(c.layer_marks[l.layer].first),
                        "layer " + std::to_string(l.layer) + " deposits at radius " +
                            fmt_fixed(l.radius_mm, 4) + " mm; its ;Z: puts them at " +
                            fmt_fixed(expected, 4) + " mm from the axis (" +
                            fmt_fixed(m->rotary.lift_mm, 3) + " mm below its first point)");
    }
  }
}

// A patch is centred on u = 0 (the line under the nozzle at A = 0): every A shifted alike
// moves the whole pattern off it. Within half a millimetre (sampled arcs, rounding).
void check_centre(const std::vector<CylinderSample>& samples, const RotaryHeader& h,
                  PoseCheckReport& r) {
  constexpr double kCentreMm = 0.5;
  double lo = 1e300, hi = -1e300;
  std::size_t first = 0;
  for (const auto& s : samples) {
    if (!s.extrude) continue;
    const double u = std::atan2(s.p_mm.y(), s.p_mm.x()) * h.radius_mm;
    if (lo > hi) first = s.source;
    lo = std::min(lo, u), hi = std::max(hi, u);
  }
  if (lo > hi) return;
  const double centre = (lo + hi) / 2.0;
  if (std::abs(centre) > kCentreMm) {
    r.off_surface.add(first, "the pattern's centre is " + fmt_fixed(centre, 3) + " mm (" +
                                 fmt_fixed(slicer::rad_to_deg(centre / h.radius_mm), 3) +
                                 " deg of A) around from u = 0, where the header's placement "
                                 "centres a patch (A shifted?)");
  }
}

}  // namespace

PoseCheckReport check_rotary_gcode(std::string_view text, const std::string& file,
                                   const machines::MachineProfile* machine) {
  const RotaryHeader h = read_rotary_header(text, file);
  const ParsedGcode parsed = parse_gcode(text);
  const std::vector<CylinderSample> samples = rotary_samples(parsed, h);
  if (samples.empty())
    throw InputError("input = " + file + ": no moves (a rotary G-code moves the nozzle)");
  const RotaryComments comments = read_comments(text);
  PoseCheckReport r;
  r.kind = "rotary G-code";
  r.machine = machine ? machine->name : "";
  r.rows = parsed.program.moves.size();
  for (const auto& issue : parsed.issues)
    r.parse.add(static_cast<std::size_t>(issue.line), issue.what);
  for (std::size_t i = 0; i < parsed.program.moves.size(); ++i) {
    const auto& mv = parsed.program.moves[i];
    const std::size_t line = static_cast<std::size_t>(parsed.move_lines[i]);
    if (mv.kind == slicer::MoveKind::Deposit) {
      // The nozzle points straight down: a deposit must be on top of the cylinder.
      const Vec3 rel = mv.end_mm - h.axis_point_mm;
      const Vec3 radial = rel - rel.dot(h.axis_dir) * h.axis_dir;
      const double angle = slicer::rad_to_deg(
          std::acos(std::clamp(radial.normalized().dot(Vec3::UnitZ()), -1.0, 1.0)));
      if (angle > slicer::kPoseNormalDeg)
        r.normals.add(line,
                      "the nozzle is " + fmt_fixed(angle, 3) + " deg off the top of the cylinder");
    }
    if (machine && (mv.kind == slicer::MoveKind::Deposit || mv.kind == slicer::MoveKind::Travel)) {
      if (auto why = machines::outside_reason(machine->volume, mv.end_mm))
        r.outside.add(line, *why);
    }
  }
  check_on_cylinder(samples, slicer::kGcodeResolutionMm, r);
  if (comments.centred_patch) check_centre(samples, h, r);
  const auto planned_on = planning_machine(machine, comments.machine);
  check_layers(comments, layer_z(text), h, planned_on, r);
  const std::vector<RotaryMove> moves = rotary_moves(parsed, samples, comments.inverse_time);
  check_ink(moves, r);
  check_feeds(moves, comments, planned_on, r);
  return r;
}

}  // namespace strand::post
