// Workpiece poses from the holder geometry.
#include "machines/workpiece_pose.h"

#include <cassert>

#include "slicer/units.h"

namespace strand::machines {

Holder holder_of(const MachineProfile& m) {
  assert(m.robot.enabled || m.rotary.enabled);
  Holder h;
  if (m.robot.enabled) {
    h.fixed_tip = true;
    h.anchor_mm = m.robot.nozzle_tip_mm;
    h.nozzle_axis = m.robot.nozzle_axis;
    h.axis_dir = m.robot.substrate_axis;
  } else {
    h.fixed_tip = false;
    h.anchor_mm = m.rotary.axis_point_mm;
    h.nozzle_axis = -Vec3::UnitZ();
    h.axis_dir = m.rotary.axis_dir;
  }
  return h;
}

WorkpiecePose workpiece_pose(const Holder& h, const Vec3& p, double turn_rad) {
  // At turn 0 the workpiece x axis (u = 0) faces the nozzle: columns of the reference
  // rotation are the images of the workpiece x, y, z axes.
  const Vec3 up = -h.nozzle_axis;
  Eigen::Matrix3d ref;
  ref.col(0) = up;
  ref.col(2) = h.axis_dir;
  ref.col(1) = h.axis_dir.cross(up);
  WorkpiecePose w;
  w.rotation = ref * Eigen::AngleAxisd(-turn_rad, Vec3::UnitZ()).toRotationMatrix();
  if (h.fixed_tip) {
    w.tip_mm = h.anchor_mm;
    w.origin_mm = h.anchor_mm - w.rotation * p;
  } else {
    w.origin_mm = h.anchor_mm;
    w.tip_mm = h.anchor_mm + w.rotation * p;
  }
  return w;
}

Eigen::Isometry3d workpiece_in_flange(const RobotCell& cell) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translate(Vec3(0.0, 0.0, cell.mount_mm));
  t.rotate(Eigen::AngleAxisd(slicer::deg_to_rad(cell.mount_rotation_deg), Vec3::UnitZ()));
  return t;
}

Eigen::Vector4d quaternion_wxyz(const Eigen::Matrix3d& r) {
  Eigen::Quaterniond q(r);
  q.normalize();
  if (q.w() < 0) q.coeffs() *= -1.0;
  return Eigen::Vector4d(q.w(), q.x(), q.y(), q.z());
}

Eigen::Matrix3d rotation_of(const Eigen::Vector4d& wxyz) {
  return Eigen::Quaterniond(wxyz[0], wxyz[1], wxyz[2], wxyz[3]).normalized().toRotationMatrix();
}

}  // namespace strand::machines
