package com.kuka.roboticsAPI.geometricModel;

import com.kuka.roboticsAPI.geometricModel.math.Transformation;
import com.kuka.roboticsAPI.motionModel.Motion;

public class ObjectFrame {
  private final String name;
  private final Transformation offset;

  public ObjectFrame(String name, Transformation offset) {
    this.name = name;
    this.offset = offset;
  }

  public String getName() {
    return name;
  }

  public Transformation getOffset() {
    return offset;
  }

  public void move(Motion motion) {
    motion.execute(name);
  }

  public void moveAsync(Motion motion) {
    motion.execute(name);
  }
}
