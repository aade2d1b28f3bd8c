package com.kuka.roboticsAPI.applicationModel;

import com.kuka.roboticsAPI.geometricModel.ObjectFrame;
import com.kuka.roboticsAPI.geometricModel.SceneGraphObject;

// The project's data (frames taught in the application data, object templates).
public interface IApplicationData {
  ObjectFrame getFrame(String path);

  <T extends SceneGraphObject> T createFromTemplate(String templateName);
}
