package com.kuka.roboticsAPI.motionModel;

import com.kuka.roboticsAPI.deviceModel.JointPosition;
import com.kuka.roboticsAPI.geometricModel.Frame;

public final class BasicMotions {
  private BasicMotions() {}

  public static LIN lin(Frame target) {
    return new LIN(target);
  }

  public static PTP ptp(Frame target) {
    return new PTP(null, target);
  }

  public static PTP ptp(JointPosition joints) {
    return new PTP(joints, null);
  }
}
