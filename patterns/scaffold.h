// Log-pile scaffold (thesis, appendix "scaffold.m"): parallel filaments rotated per layer,
// each layer one continuous serpentine whose U-turns lie outside the footprint.
#pragma once

#include <nlohmann/json.hpp>
#include <memory>
#include <optional>
#include <vector>

#include "slicer/layer_source.h"
#include "slicer/params.h"
#include "slicer/toolpath.h"

namespace strand::patterns {

enum class GradeAxis { None, X, Y, Z };

// `--gap a..b --grade x` (linear from a at the low edge to b at the high edge) or
// `--gap a,b,c --grade x` (equal zones of one gap each). The gap after a filament is the
// grade's value where that gap starts (its low edge along the axis; for z, the layer's
// bottom), so a gap is the schedule's value at one known place.
struct GapGrade {
  GradeAxis axis = GradeAxis::None;
  bool linear = false;
  std::vector<double> gaps_mm;  // linear: {from, to}; zones: one per zone

  // The gap at `fraction` of the graded length (clamped to [0, 1]).
  double at(double fraction) const;
  double mean_mm() const;
  // Zones the report gives porosity for: one per listed value; 4 equal ones for a..b.
  int zone_count() const { return linear ? 4 : static_cast<int>(gaps_mm.size()); }
};

// One entry of a job file's "schedule": layers first..last (0-based) take the values given.
struct ScheduleEntry {
  int first = 0;
  int last = 0;
  std::optional<double> speed_mm_per_min;
  std::optional<double> flow;   // bead section relative to a nozzle-wide bead
  std::optional<double> gap_mm;
  std::optional<double> angle_deg;
};

struct ScaffoldParams {
  double nozzle_mm = 0.84;        // filament diameter d
  double pitch_mm = 2.44;         // centre-to-centre spacing = gap + d
  double width_mm = 36.0;         // requested footprint along x
  double depth_mm = 36.0;         // requested footprint along y
  int layers = 15;
  double layer_height_mm = 0.7392;  // 0.88 d by default
  double overhang_mm = 0.84;      // how far U-turns stick out of the footprint
  std::vector<double> angles_deg = {0.0, 90.0};
  double speed_mm_per_min = 250.0;
  GapGrade grade;                       // axis None: every gap is pitch - nozzle
  bool stagger = false;                 // every second layer of a direction offset half a pitch
  std::vector<ScheduleEntry> schedule;  // sorted, not overlapping
};

// Sizes derived from the parameters, computed in one place.
// --size is rounded to the nearest whole number of pitches: a side holding N filaments
// measures (N - 1) * pitch + nozzle, edge to edge, with N >= 2.
struct ScaffoldGeometry {
  int filaments_x = 0;            // filaments laid along y, spread across x
  int filaments_y = 0;            // filaments laid along x, spread across y
  double width_mm = 0.0;          // actual footprint, edge to edge of the outer filaments
  double depth_mm = 0.0;
  double height_mm = 0.0;         // layers * layer height
  double link_clearance_mm = 0.0; // layer links run this far outside the U-turns
};

ScaffoldGeometry scaffold_geometry(const ScaffoldParams& p);
// The report keys both layouts share: footprint (`width_mm` x depth), filaments per layer,
// layer stack, pitch, gap, overhang, bead area and porosity from the filament length laid
// inside the footprint over all layers.
nlohmann::json scaffold_report(const ScaffoldParams& p, const ScaffoldGeometry& g, double width_mm,
                               const nlohmann::json& filaments_per_layer, double inside_length_mm);
// Layers centred on (0, 0); layer k at z = (k + 1) * layer height, made one at a time.
std::unique_ptr<slicer::LayerSource> scaffold_layers(const ScaffoldParams& p);
slicer::Toolpath generate_scaffold(const ScaffoldParams& p);
// `--wrap full` round a circumference `period_mm` (x, periodic; the width is ignored, the
// depth is the length along the axis): layers at 90 deg lay a whole number of lines along
// the axis (pitch adjusted to fit, at least 3, each at least a nozzle apart) in a serpentine
// with U-turns beyond the ends; layers at 0 deg one helix of lead = pitch. Other angles are
// an InputError naming scaffold.angles.
slicer::Toolpath generate_scaffold_wrapped(const ScaffoldParams& p, double period_mm);

// Parameter table (CLI flags and job keys) and the checked conversion from its values.
const slicer::ParamTable& scaffold_table();
ScaffoldParams scaffold_params_from(const nlohmann::json& values);

}  // namespace strand::patterns
