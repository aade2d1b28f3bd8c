// Ink profiles (issue 32): `strand calibrate` fits the width model to photo measurements
// and writes materials/NAME.json; `--material NAME` on a generator reads one back.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "slicer/params.h"

namespace strand::jobs {

// width = a * flow^p * speed^q (speed in mm/min), fitted by least squares on the logarithms.
struct WidthModel {
  double a = 0.0;
  double p = 0.0;
  double q = 0.0;
  double rms_mm = 0.0;  // residual of the fitted widths, mm
  int points = 0;
  double width_mm(double flow, double speed_mm_per_min) const;
};

// Lines whose ink covers less than this share of their length are left out of the fit.
inline constexpr double kLeastCoverage = 0.5;

// Fits the model to the "lines" of `strand measure --test lines` outputs; InputError when
// fewer than 4 lines, or fewer than 2 distinct flows or speeds, remain.
WidthModel fit_width_model(const std::vector<nlohmann::json>& measurements);

// The profile `strand calibrate` writes: the model, the speed and flow that lay a bead as
// wide as the nozzle (flow 1 when that speed lies within the measured speeds, else the
// nearest measured speed with the flow that makes up the rest), the layer height, and the
// measurement files it came from.
nlohmann::json ink_profile(const std::string& name, const std::vector<nlohmann::json>& measurements,
                           const std::vector<std::string>& sources);

// Reads the measurement files, fits, writes the profile atomically to `out_path`; returns it.
// At least one lines measurement is needed for the fit. Among the others:
//  - fusion measurements set min_spacing_without_fusion_mm: the widest of their closest
//    separate spacings, so filaments that far apart stayed separate on every print;
//  - collapse measurements set min_gap_without_collapse_mm, the gap the ink spans without
//    collapse: per print its widest_spanned_gap_mm (the widest gap that spans, Cf >= 90 %,
//    with every narrower gap spanning too), and the smallest of these over the prints, so
//    every print spanned it; 0 when a print spanned not even its narrowest gap.
// Without such measurements the key is null (not measured).
nlohmann::json calibrate_files(const std::vector<std::string>& paths, const std::string& out_path);

// A profile by name: NAME.json in ./materials, then in the user's
// $XDG_CONFIG_HOME/strand/materials (or ~/.config/strand/materials); or a path ending .json.
// InputError "material = NAME: ..." when missing or malformed.
nlohmann::json load_ink_profile(const std::string& name_or_path);

// Fills the generator values the profile sets (speed, layer-height) unless given, for the
// keys `table` has; returns the summary the job report records under "material".
// InputError when the profile's nozzle differs from the given --nozzle by more than 1 %.
nlohmann::json apply_ink_profile(const nlohmann::json& profile, const std::string& name,
                                 const slicer::ParamTable& table, nlohmann::json& given);

}  // namespace strand::jobs
