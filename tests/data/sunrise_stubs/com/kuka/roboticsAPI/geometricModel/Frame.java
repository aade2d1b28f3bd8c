package com.kuka.roboticsAPI.geometricModel;

public class Frame {
  public final ObjectFrame parent;
  public final double x, y, z, a, b, c;

  public Frame(ObjectFrame parent, double x, double y, double z, double a, double b, double c) {
    this.parent = parent;
    this.x = x;
    this.y = y;
    this.z = z;
    this.a = a;
    this.b = b;
    this.c = c;
  }
}
