// Fuzz target: any bytes as G-code, read and checked as `strand check` does (against the
// delta; against a polargraph, with pen commands and Z lifts read and axes mapped to paper;
// without a machine, rules and pen from the file alone) and cut into a preview scene as
// `strand preview` does. RS274NGC files (parameters, expressions, O-word loops) are read with
// their work bounded; errors in them are InputError (seeds/gcode_fuzz/expressions.ngc).
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "machines/profile.h"
#include "postprocess/inspect/check.h"
#include "postprocess/preview/preview_scene.h"
#include "slicer/input_error.h"
#include "slicer/json_input.h"

namespace {

using namespace strand;

void check_against(std::string_view text, const machines::MachineProfile* machine, bool preview) {
  post::CheckOptions options;
  options.machine = machine;
  const post::CheckInput in = post::read_for_check(text, machine, std::nullopt);
  options.rules = in.rules;
  const post::CheckReport report = post::check_parsed(in.parsed, options);
  slicer::dump_json(post::to_json(report));  // as `strand check --json` prints it
  post::to_text(report);
  if (preview) post::preview_scene(in.parsed.program, 0.01);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const machines::MachineProfile delta = machines::load_profile("deltawasp-2040-clay");
  static const machines::MachineProfile plotter = machines::load_profile("polargraph");
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    check_against(text, &delta, true);
  } catch (const InputError&) {
  }
  try {
    check_against(text, &plotter, false);
  } catch (const InputError&) {
  }
  try {
    check_against(text, nullptr, false);  // rules and pen from the file alone
  } catch (const InputError&) {
  }
  return 0;
}
