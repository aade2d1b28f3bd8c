package com.kuka.roboticsAPI.motionModel;

public class MotionBatch extends Motion {
  private final Motion[] motions;

  public MotionBatch(Motion... motions) {
    this.motions = motions.clone();
  }

  @Override
  public void execute(String moved) {
    for (Motion m : motions) m.execute(moved);
  }
}
