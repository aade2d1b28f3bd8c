package strandtest;

import java.lang.reflect.Field;
import java.lang.reflect.Modifier;
import javax.inject.Inject;

// Runs a generated application: `Main CLASS run` injects its fields, then calls initialize()
// and run(); `Main CLASS constants` prints its static String constants, NAME=VALUE with every
// character outside printable ASCII as \\uXXXX.
public final class Main {
  public static void main(String[] args) throws Exception {
    Class<?> c = Class.forName("application." + args[0]);
    if (args[1].equals("constants")) {
      for (Field f : c.getDeclaredFields()) {
        if (Modifier.isStatic(f.getModifiers()) && f.getType() == String.class) {
          f.setAccessible(true);
          Log.line(f.getName() + "=" + shown((String) f.get(null)));
        }
      }
      return;
    }
    Object app = c.getDeclaredConstructor().newInstance();
    for (Field f : c.getDeclaredFields()) {
      if (f.isAnnotationPresent(Inject.class)) {
        f.setAccessible(true);
        f.set(app, f.getType().getDeclaredConstructor().newInstance());
      }
    }
    c.getMethod("initialize").invoke(app);
    c.getMethod("run").invoke(app);
  }

  private static String shown(String s) {
    StringBuilder out = new StringBuilder();
    for (char ch : s.toCharArray()) {
      if (ch >= 0x20 && ch <= 0x7e && ch != '\\') {
        out.append(ch);
      } else {
        out.append(String.format("\\u%04x", (int) ch));
      }
    }
    return out.toString();
  }
}
