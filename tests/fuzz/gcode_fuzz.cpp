// Fuzz target: any bytes as G-code, parsed, checked (contacts, bounds on the delta) and cut
// into a preview scene, as `strand check` and `strand preview` do.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "machines/profile.h"
#include "postprocess/inspect/check.h"
#include "postprocess/preview/preview_scene.h"
#include "slicer/input_error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace strand;
  static const machines::MachineProfile machine = machines::load_profile("deltawasp-2040-clay");
  try {
    const post::ParsedGcode parsed =
        post::parse_gcode(std::string_view(reinterpret_cast<const char*>(data), size));
    post::CheckOptions options;
    options.machine = &machine;
    const post::CheckReport report = post::check_parsed(parsed, options);
    post::to_json(report).dump();
    post::to_text(report);
    post::preview_scene(parsed.program, 0.01);
  } catch (const InputError&) {
  }
  return 0;
}
