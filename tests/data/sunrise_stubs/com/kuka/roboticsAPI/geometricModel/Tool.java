package com.kuka.roboticsAPI.geometricModel;

import com.kuka.roboticsAPI.geometricModel.math.Transformation;
import strandtest.Log;

public class Tool extends ObjectFrame {
  private final LoadData load = new LoadData();

  public Tool(String name) {
    super(name, null);
  }

  public LoadData getLoadData() {
    return load;
  }

  public ObjectFrame addChildFrame(String name, Transformation t) {
    Log.line("FRAME " + name + " " + t.x + " " + t.y + " " + t.z + " " + t.a + " " + t.b + " " + t.c);
    return new ObjectFrame(name, t);
  }

  public void attachTo(ObjectFrame parent) {
    Log.line("ATTACH " + getName() + " " + parent.getName());
  }
}
