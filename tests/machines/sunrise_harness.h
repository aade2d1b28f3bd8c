// The Sunrise test harness: the shipped KUKA profile with changed values, and the written
// application compiled with javac against stand-in RoboticsAPI classes (tests/data/
// sunrise_stubs) and run (tests/machines/sunrise_writer_test.cpp, sunrise_hostile_test.cpp).
#pragma once

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "machines/builtin_profiles.h"
#include "tests/support/cli_runner.h"

namespace strand::machines::sunrise_test {

inline const std::string kStubs = std::string(STRAND_SOURCE_DIR) + "/tests/data/sunrise_stubs";

inline std::string quoted(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

struct Shell {
  int exit_code;
  std::string out;
};

inline Shell shell(const std::string& command) {
  const std::string log = testing::fresh_dir("sh") + "/out";
  const int rc = std::system((command + " > " + quoted(log) + " 2>&1").c_str());
  return {WEXITSTATUS(rc), testing::slurp(log)};
}

// A copy of the shipped KUKA profile with some values changed, written into `dir`.
inline std::string profile_with(const std::string& dir, const nlohmann::json& sunrise,
                                const std::string& name = "kuka-test-cell") {
  nlohmann::json j;
  for (const auto& b : builtin_profiles())
    if (std::string(b.name) == "kuka-iiwa14-wasp-cylinder") j = nlohmann::json::parse(b.json);
  j["name"] = name;
  for (const auto& [k, v] : sunrise.items()) j["robot"]["sunrise"][k] = v;
  const std::string path = dir + "/cell.json";
  std::ofstream(path) << j.dump(2);
  return path;
}

// Compiles `java_file` (class `cls`) with the stubs and an I/O group stand-in; "" on success,
// javac's messages otherwise.
// The I/O group stand-in logs the lap signal and answers the ready input with alternating
// levels (a real extruder answers once it is parked), logging each read.
inline std::string compile(const std::string& dir, const std::string& java_file,
                           const std::string& io_group = "ExtruderIO",
                           const std::string& signal = "LapStart",
                           const std::string& ready = "ExtruderReady") {
  const std::string gen = dir + "/gen/com/kuka/generated/ioAccess";
  std::filesystem::create_directories(gen);
  std::ofstream(gen + "/" + io_group + "IOGroup.java")
      << "package com.kuka.generated.ioAccess;\npublic class " << io_group
      << "IOGroup {\n  private boolean next = false;\n  public void set" << signal
      << "(boolean level) { strandtest.Log.line(\"SIGNAL \" + level); }\n  public boolean get"
      << ready << "() { next = !next; strandtest.Log.line(\"READY \" + next); return next; }\n}\n";
  const Shell r =
      shell("cd " + quoted(dir) + " && javac -encoding UTF-8 -nowarn -d classes $(find " +
            quoted(kStubs) + " gen -name '*.java') " + quoted(java_file));
  return r.exit_code == 0 ? "" : r.out;
}

inline Shell run_java(const std::string& dir, const std::string& cls, const std::string& mode) {
  return shell("cd " + quoted(dir) + " && java -cp classes strandtest.Main " + cls + " " + mode);
}

}  // namespace strand::machines::sunrise_test
