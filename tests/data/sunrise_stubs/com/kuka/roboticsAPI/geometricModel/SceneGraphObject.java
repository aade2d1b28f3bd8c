package com.kuka.roboticsAPI.geometricModel;

// Base of the objects of the scene graph (tools, workpieces).
public abstract class SceneGraphObject {
  private final String name;

  protected SceneGraphObject(String name) {
    this.name = name;
  }

  public String getName() {
    return name;
  }
}
