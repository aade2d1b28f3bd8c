// Time left while a file streams to a machine, for `strand send`'s bar and the workbench's
// queue alike: seconds still to run after each file line, from the file's own moves.
#pragma once

#include <map>
#include <string>

namespace strand::jobs {

// Seconds still to run after each line that moves or dwells (distance / feed plus dwells).
std::map<int, double> time_left_after(const std::string& gcode_text);

// The time left once `line` is acknowledged: the entry of the last moving line up to it (the
// whole file's time before the first one); 0 for a file without moves.
double time_left_at(const std::map<int, double>& left, int line);

}  // namespace strand::jobs
