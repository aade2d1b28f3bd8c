// Fuzz target: any bytes as the curved-substrate files `strand check` and `strand preview`
// read — a robot cell's pose CSV and a rotary printer's 4-axis G-code — checked against their
// shipped machines (and, for rotary files, against the machine their header names) and cut
// into preview samples. A tampered file must fail with reasons, never crash or hang.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "machines/profile.h"
#include "postprocess/inspect/curved_files.h"
#include "postprocess/inspect/pose_check.h"
#include "slicer/input_error.h"
#include "slicer/json_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace strand;
  static const machines::MachineProfile robot = machines::load_profile("kuka-iiwa14-wasp-cylinder");
  static const machines::MachineProfile rotary = machines::load_profile("marlin-rotary-a");
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const post::PoseCheckReport report = post::is_rotary_gcode(text)
                                             ? post::check_rotary_gcode(text, "fuzz.gcode", &rotary)
                                             : post::check_pose_csv(text, "fuzz.csv", robot);
    slicer::dump_json(post::to_json(report));  // as `strand check --json` prints it
    post::to_text(report);
  } catch (const InputError&) {
  }
  if (post::is_rotary_gcode(text)) {
    try {
      post::to_text(post::check_rotary_gcode(text, "fuzz.gcode", nullptr));
    } catch (const InputError&) {
    }
  }
  try {
    post::read_curved_part(text, post::is_rotary_gcode(text) ? "fuzz.gcode" : "fuzz.csv");
  } catch (const InputError&) {
  }
  return 0;
}
