// The pose CSV of a robot cell: one row per pose of the program, header fixed as
//   index,t_s,x_mm,y_mm,z_mm,qw,qx,qy,qz,speed_mm_s,extrude,layer,lap,feature,px_mm,py_mm,pz_mm,nx,ny,nz
// x, q: the workpiece frame's origin and orientation (unit quaternion, w first) in the robot
// base frame; p, n: the contact point (the nozzle tip) and the outward surface normal in the
// workpiece frame; speed and extrude describe the motion from the previous row to this one;
// feature is the deposit's role, or "travel" when nothing is deposited. Strand writes it and
// `strand check` reads it back (from any source that keeps the header).
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "slicer/pose_program.h"

namespace strand::machines {

inline constexpr const char* kPoseCsvHeader =
    "index,t_s,x_mm,y_mm,z_mm,qw,qx,qy,qz,speed_mm_s,extrude,layer,lap,feature,px_mm,py_mm,pz_mm,"
    "nx,ny,nz";

std::string write_pose_csv(const slicer::PoseProgram& program);

// Rows back as pose points (uv, offset and turn left at zero: the reader does not know the
// substrate). Throws InputError naming the file and line of the first malformed row.
std::vector<slicer::PosePoint> read_pose_csv(std::string_view text, const std::string& file);

}  // namespace strand::machines
