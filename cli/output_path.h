// Default output names: every command that writes one file names it after its input, in the
// current directory, so `strand plot drawing.svg` writes drawing.gcode and `strand preview
// part.gcode` writes part-preview.png. The output never replaces the input: the commands stage
// their files with slicer::OutputFiles::protect_input, which refuses that (exit 2).
#pragma once

#include <string>

namespace strand::cli {

// The input's file name without directory and extension, plus `suffix`:
// ("drawings/cat.svg", ".gcode") -> "cat.gcode", ("part.gcode", "-preview.png") ->
// "part-preview.png". An input without a stem (".", "/") gives "strand" + suffix.
std::string output_from_input(const std::string& input, const std::string& suffix);

}  // namespace strand::cli
