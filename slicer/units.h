// Unit conversions: the only place where degrees, seconds, inches and mL meet mm and minutes.
#pragma once

namespace strand::slicer {

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kTwoPi = 2.0 * kPi;

constexpr double deg_to_rad(double deg) { return deg * kPi / 180.0; }
constexpr double rad_to_deg(double rad) { return rad * 180.0 / kPi; }
// Feeds are mm/min everywhere (G-code F); planners that integrate motion work in mm/s.
constexpr double mm_per_min_to_mm_per_s(double f) { return f / 60.0; }
constexpr double mm_per_s_to_mm_per_min(double v) { return v * 60.0; }
constexpr double mm3_to_ml(double mm3) { return mm3 / 1000.0; }
constexpr double kMmPerInch = 25.4;
constexpr double kMmPerCm = 10.0;
constexpr double kMmPerM = 1000.0;

}  // namespace strand::slicer
