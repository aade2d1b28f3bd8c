package com.kuka.roboticsAPI.applicationModel;

import com.kuka.roboticsAPI.geometricModel.ObjectFrame;
import com.kuka.roboticsAPI.geometricModel.SceneGraphObject;
import com.kuka.roboticsAPI.geometricModel.Tool;
import strandtest.Log;

public abstract class RoboticsAPIApplication {
  // Frames come back named by their path; a template comes back as a Tool of that name.
  private final IApplicationData data = new IApplicationData() {
    @Override
    public ObjectFrame getFrame(String path) {
      Log.line("APP_FRAME " + path);
      return new ObjectFrame(path, null);
    }

    @Override
    @SuppressWarnings("unchecked")
    public <T extends SceneGraphObject> T createFromTemplate(String templateName) {
      Log.line("TEMPLATE " + templateName);
      return (T) new Tool(templateName);
    }
  };

  public void initialize() {}

  public abstract void run() throws Exception;

  public IApplicationData getApplicationData() {
    return data;
  }
}
