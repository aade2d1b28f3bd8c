// Erase pattern for the wall robot: horizontal sweeps of the heated disc over a rectangle,
// one disc diameter apart, stopping every diameter to dwell at erase temperature.
#pragma once

#include <string>
#include <vector>

#include "machines/profile.h"

namespace strand::machines {

// The rectangle is in the paper frame; the marker is driven so that the disc (marker +
// erase.offset_mm) covers it. Throws InputError if the machine cannot erase or a sweep point
// is out of reach.
std::string emit_erase_gcode(const MachineProfile& m, const slicer::Vec2& lo_mm,
                             const slicer::Vec2& hi_mm, const std::vector<std::string>& header);

}  // namespace strand::machines
