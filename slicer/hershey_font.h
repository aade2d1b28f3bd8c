// Single-stroke Hershey fonts (Debian's hershey-fonts-data, read with libhersheyfont): the
// lettering plotters want, one pen line per stroke instead of an outline to fill.
#pragma once

#include <string>
#include <vector>

#include "slicer/font.h"

namespace strand::slicer {

// Hershey units in one em. The fonts are drawn on a 32-unit body (capitals 21 units tall
// in the simplex romans, so a 10 mm font size gives 6.6 mm capitals).
inline constexpr double kHersheyUnitsPerEm = 32.0;

// The fonts hershey-fonts-data ships ("futural", "rowmans", "scripts", ...).
const std::vector<std::string>& hershey_font_names();

// Loads the printable ASCII glyphs of a Hershey font by name ("futural"). Throws InputError
// naming the font and the installed ones when it is unknown or not installed.
Font load_hershey_font(const std::string& name);

}  // namespace strand::slicer
