package strandtest;

public final class Log {
  private Log() {}

  public static void line(String text) {
    System.out.println(text);
  }
}
