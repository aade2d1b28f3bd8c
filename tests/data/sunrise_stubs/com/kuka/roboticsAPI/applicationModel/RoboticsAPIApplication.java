package com.kuka.roboticsAPI.applicationModel;

public abstract class RoboticsAPIApplication {
  public void initialize() {}

  public abstract void run() throws Exception;
}
