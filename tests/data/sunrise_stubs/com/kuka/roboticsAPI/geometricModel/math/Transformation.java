package com.kuka.roboticsAPI.geometricModel.math;

public class Transformation {
  public final double x, y, z, a, b, c;

  private Transformation(double x, double y, double z, double a, double b, double c) {
    this.x = x;
    this.y = y;
    this.z = z;
    this.a = a;
    this.b = b;
    this.c = c;
  }

  public static Transformation ofRad(double x, double y, double z, double a, double b, double c) {
    return new Transformation(x, y, z, a, b, c);
  }
}
