// Named geometric tolerances with their purpose. User-visible ones (arc chord error) are
// parameters; these are internal thresholds only.
#pragma once

namespace strand::slicer {

// Two points closer than this are the same point (joining strokes, closing loops), mm.
// Well below the 0.001 mm G-code resolution.
inline constexpr double kSamePointMm = 1e-6;
// Coordinates parsed back from G-code are rounded to 0.001 mm; geometry checks on parsed
// files treat distances below this as contact, mm.
inline constexpr double kGcodeResolutionMm = 1e-3;
// Arcs shorter than this sweep are emitted as a straight line, rad.
inline constexpr double kMinArcSweepRad = 1e-9;
// Default chord error when segmenting arcs for machines without G2/G3, mm (issue 2).
inline constexpr double kDefaultArcToleranceMm = 0.01;
// Slack allowed on build-volume checks so that a part placed exactly on the edge passes, mm.
inline constexpr double kBoundsSlackMm = 1e-6;

}  // namespace strand::slicer
