// Plotter kinematics: paper millimetres <-> the machine's axes (cable lengths, R and theta
// screws), where a point can be drawn, and how finely a straight paper segment must be cut
// so that the firmware's linear interpolation in its own axes stays close to it.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "machines/plotter_profile.h"

namespace strand::machines {

using slicer::Vec2;

// Paper frame: y grows downwards for polargraph and R-theta (as in SVG), upwards for XY.
bool paper_y_down(PlotterKind k);

// Paper point -> G-code X/Y. Inverse of to_paper within floating-point error.
Vec2 to_axes(const PlotterSetup& s, const Vec2& paper_mm);
Vec2 to_paper(const PlotterSetup& s, const Vec2& axes);

// Cable tensions of a polargraph divided by the gondola's weight {left, right}; static
// equilibrium of a point gondola hanging at the attachment point.
std::pair<double, double> cable_tension(const PlotterSetup& s, const Vec2& paper_mm);
// Paper mm moved per mm of axis travel in the worst direction (1 / smallest singular value of
// the axes' Jacobian): how much a motor step is magnified on the paper.
double resolution_loss(const PlotterSetup& s, const Vec2& paper_mm);

// nullopt if the pen can draw at p; otherwise the reason ("left cable tension 0.41 x the
// gondola weight < 0.5", "x 430 mm > 420 mm").
std::optional<std::string> unreachable_reason(const Plotter& p, const Vec2& paper_mm);

// The rectangle drawings are fitted into: the paper area, and for a polargraph the largest
// rectangle centred below the motors where tension and resolution limits hold. {min, max}.
std::pair<Vec2, Vec2> drawable_area(const Plotter& p);

// Worst paper error of one emitted point from writing its axes with `decimals` digits and
// from the motors' step size, mm.
double rounding_error_mm(const PlotterSetup& s, const Vec2& paper_mm, int decimals);

// Points after `a` (ending with b) on the paper segment a-b such that moving linearly in
// axis space between consecutive points never leaves the segment by more than tolerance_mm
// (checked on 7 interior samples per piece with a 10 % margin; pieces are halved until it
// holds). XY machines return {b}.
std::vector<Vec2> split_for_axes(const PlotterSetup& s, const Vec2& a, const Vec2& b,
                                 double tolerance_mm);

}  // namespace strand::machines
