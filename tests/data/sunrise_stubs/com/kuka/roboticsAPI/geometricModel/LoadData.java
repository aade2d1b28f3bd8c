package com.kuka.roboticsAPI.geometricModel;

import strandtest.Log;

public class LoadData {
  public void setMass(double kg) {
    Log.line("LOAD_MASS " + kg);
  }

  public void setCenterOfMass(double x, double y, double z) {
    Log.line("LOAD_COG " + x + " " + y + " " + z);
  }
}
