package com.kuka.roboticsAPI.geometricModel;

import com.kuka.roboticsAPI.geometricModel.math.Transformation;
import strandtest.Log;

public class Tool extends SceneGraphObject {
  private final LoadData load = new LoadData();

  public Tool(String name) {
    super(name);
  }

  public LoadData getLoadData() {
    return load;
  }

  // A child of the tool's root frame.
  public ObjectFrame addChildFrame(String name, Transformation t) {
    Log.line("FRAME " + name + " " + t.x + " " + t.y + " " + t.z + " " + t.a + " " + t.b + " " + t.c);
    return new ObjectFrame(name, t);
  }

  // A child of one of the tool's frames; logged with that frame's name last.
  public ObjectFrame addChildFrame(String name, ObjectFrame parent, Transformation t) {
    Log.line("FRAME " + name + " " + t.x + " " + t.y + " " + t.z + " " + t.a + " " + t.b + " " + t.c
        + " " + parent.getName());
    return new ObjectFrame(name, t);
  }

  // A frame of the tool (a template's frames as taught in the project), by its path.
  public ObjectFrame getFrame(String path) {
    Log.line("TOOL_FRAME " + getName() + " " + path);
    return new ObjectFrame(path, null);
  }

  public void attachTo(ObjectFrame parent) {
    Log.line("ATTACH " + getName() + " " + parent.getName());
  }
}
