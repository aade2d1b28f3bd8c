// `strand measure --test collapse`: every gap of a printed collapse test
// (patterns/collapse_test.h) measured in a side photo: how far the filament across the
// pillars sags into it, as Ribeiro et al.'s collapse area factor (Biofabrication 2017), and a
// class, spans, collapsed or broken.
#pragma once

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <string>

#include "postprocess/measure/measure_setup.h"

namespace strand::post::measure {

// A gap keeps at least this collapse area factor (%): class "spans". Below, "collapsed".
inline constexpr double kSpansAreaFactorPct = 90.0;
// The filament is missing over more than this share of a gap: class "broken".
inline constexpr double kBrokenShare = 0.5;

// Measures a side photo against a collapse-test report (its derived gaps, pillar_mm,
// pillar_height_mm, filament_z_mm and nozzle_mm): the photo rectified onto the filament's
// upright plane from the pillars (collapse_side_view.h), then per column of each gap the
// filament's underside z(x), the topmost ink below the pillar tops (0 where it lies on the
// bed or is missing). The collapse area factor Cf = 100 * (area under the underside) / (gap x
// pillar height): 100 % for a straight span, 0 % for a filament on the bed. InputError: a
// report of another test, and whatever the side view refuses.
Measured measure_collapse(const cv::Mat& photo, const nlohmann::json& report, const std::string& what);

}  // namespace strand::post::measure
