package com.kuka.roboticsAPI.motionModel;

import com.kuka.roboticsAPI.geometricModel.Frame;
import strandtest.Log;

public class LIN extends Motion {
  private final Frame target;
  private double velocity = -1.0;
  private double blending = -1.0;
  private double acceleration = -1.0;

  LIN(Frame target) {
    this.target = target;
  }

  public LIN setCartVelocity(double mmPerS) {
    velocity = mmPerS;
    return this;
  }

  public LIN setBlendingCart(double mm) {
    blending = mm;
    return this;
  }

  public LIN setCartAcceleration(double mmPerS2) {
    acceleration = mmPerS2;
    return this;
  }

  @Override
  public void execute(String moved) {
    Log.line("LIN " + moved + " " + target.parent.getName() + " " + target.x + " " + target.y + " "
        + target.z + " " + target.a + " " + target.b + " " + target.c + " " + velocity + " "
        + blending + (acceleration > 0 ? " " + acceleration : ""));
  }
}
