// `strand measure --test fusion`: every pair of neighbouring filaments of a printed fusion
// test (patterns/fusion_test.h) measured in a photo: how much of the measured zone between
// them is fused (ink bridging the gap), and a class, fused or separate (Ribeiro et al. 2017).
#pragma once

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <string>

#include "postprocess/measure/measure_setup.h"

namespace strand::post::measure {

// A pair is fused over at least this share of its measured zone: class "fused".
inline constexpr double kFusedShare = 0.1;

// Measures the photo against a fusion-test report (its derived spacings, fiducials and
// nozzle_mm). At stations along the mid-line between two filaments, the ink's contrast
// against the bed (taken beside the meander at the same height, so uneven light cancels) over
// the full contrast on the filaments; a station is fused when that share stays above one half
// across the middle half of the gap. InputError: a report of another test, marks not found,
// contrast too low.
Measured measure_fusion(const cv::Mat& photo, const nlohmann::json& report, const std::string& what);

}  // namespace strand::post::measure
