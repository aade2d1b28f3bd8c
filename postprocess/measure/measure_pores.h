// `strand measure --test pore`: every pore of a printed pore test (patterns/pore_test.h)
// measured in a photo: its open area A, perimeter L and Pr = L^2 / (16 A) (Ouyang et al.
// 2016: 1 for a square pore, pi/4 = 0.785 for a round one, lower still for irregular ones).
#pragma once

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <string>

#include "postprocess/measure/measure_setup.h"

namespace strand::post::measure {

// Measures the photo against a pore-test report (its derived pores, fiducials, pitch_mm and
// nozzle_mm). Per pore, in a window of one pitch round its centre: the bed level in the
// middle, the ink level on the four filament crossings, the open region where the photo is
// nearer the bed than the ink (the part connected to the centre), its outline traced at that
// half level on a 4x finer grid. A pore whose open region reaches the window's edge (a
// filament missing) or that is filled with ink gets "pr": null and its "status".
// InputError: a report of another test, marks not found, contrast too low.
Measured measure_pores(const cv::Mat& photo, const nlohmann::json& report, const std::string& what);

}  // namespace strand::post::measure
