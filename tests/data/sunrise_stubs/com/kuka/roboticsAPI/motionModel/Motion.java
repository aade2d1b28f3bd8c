package com.kuka.roboticsAPI.motionModel;

public abstract class Motion {
  public abstract void execute(String moved);
}
