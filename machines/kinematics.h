// Build-volume geometry: does a point lie inside, and if not, which dimension fails.
#pragma once

#include <optional>
#include <string>

#include "machines/profile.h"

namespace strand::machines {

// nullopt when p is inside the volume; otherwise "radius 104.2 mm > 100 mm" or
// "x 210.5 mm > 200 mm", naming the dimension that failed.
std::optional<std::string> outside_reason(const BuildVolume& v, const Vec3& p_mm);

}  // namespace strand::machines
