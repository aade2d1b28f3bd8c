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
// Curved substrates (issue 11). A pose puts its contact point on the nozzle tip within this
// (R p + x = tip), mm; and its normal against the nozzle axis within kPoseNormalDeg, deg.
inline constexpr double kPoseTipMm = 0.01;
inline constexpr double kPoseNormalDeg = 0.1;
// A deposit lies on its layer's offset surface when its radius is within this of the
// layer's median deposit radius, mm (files round to 0.001 mm).
inline constexpr double kOffSurfaceMm = 0.01;
// Planned and actual speed may differ by this fraction (rounding of times and positions).
inline constexpr double kSpeedDeviation = 0.01;
// Segments shorter than this are not speed-checked: the file's rounding dominates them, mm.
inline constexpr double kSpeedCheckMinMm = 0.05;

// A slicing plane that passes exactly through a mesh vertex is moved up by this much, so
// every contour is a simple closed curve, mm (far below any layer height).
inline constexpr double kSliceNudgeMm = 1e-7;
// Clipper works on integers: coordinates are scaled by this many units per mm (0.01 um).
inline constexpr double kClipperUnitsPerMm = 1e5;
// Round joins of region offsets deviate from the true arc by at most this, mm.
inline constexpr double kOffsetArcToleranceMm = 0.005;

}  // namespace strand::slicer
