package com.kuka.roboticsAPI.motionModel;

import com.kuka.roboticsAPI.deviceModel.JointPosition;
import com.kuka.roboticsAPI.geometricModel.Frame;
import strandtest.Log;

public class PTP extends Motion {
  private final JointPosition joints;
  private final Frame frame;
  private double relative = 1.0;

  PTP(JointPosition joints, Frame frame) {
    this.joints = joints;
    this.frame = frame;
  }

  public PTP setJointVelocityRel(double relative) {
    this.relative = relative;
    return this;
  }

  @Override
  public void execute(String moved) {
    if (joints != null) {
      StringBuilder s = new StringBuilder("PTP_JOINTS " + moved + " " + relative);
      for (double q : joints.values) s.append(' ').append(q);
      Log.line(s.toString());
    } else {
      Log.line("PTP_FRAME " + moved + " " + frame.x + " " + frame.y + " " + frame.z + " " + frame.a
          + " " + frame.b + " " + frame.c + " " + relative);
    }
  }
}
