package com.kuka.roboticsAPI.geometricModel;

public class World {
  public static final World Current = new World();
  private final ObjectFrame root = new ObjectFrame("World", null);

  public ObjectFrame getRootFrame() {
    return root;
  }
}
