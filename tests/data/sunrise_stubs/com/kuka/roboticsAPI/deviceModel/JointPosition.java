package com.kuka.roboticsAPI.deviceModel;

public class JointPosition {
  public final double[] values;

  public JointPosition(double... values) {
    this.values = values.clone();
  }
}
