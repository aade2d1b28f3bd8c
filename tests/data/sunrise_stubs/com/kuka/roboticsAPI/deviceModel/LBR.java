package com.kuka.roboticsAPI.deviceModel;

import com.kuka.roboticsAPI.geometricModel.ObjectFrame;
import com.kuka.roboticsAPI.motionModel.Motion;

public class LBR {
  private final ObjectFrame flange = new ObjectFrame("Flange", null);

  public ObjectFrame getFlange() {
    return flange;
  }

  public void move(Motion motion) {
    motion.execute("LBR");
  }
}
