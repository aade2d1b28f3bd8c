// `strand check` on a pose CSV: the vendor programs beside it read back (URScript movel
// targets and speeds with their set_tcp, KRL LIN frames and $VEL.CP, RAPID MoveL robtargets and
// speeddata, the Sunrise application's contact radii and whether it scales its speeds) and
// their motions compared with the CSV's time line: per program the worst ratio of the contact
// point's speed to the row's planned speed and the worst lap against the extruder's time, so a
// program edited by hand shows its contact-speed error before printing (issue 37).
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "machines/contact_speed.h"
#include "machines/profile.h"
#include "slicer/pose_program.h"

namespace strand::post {

struct ProgramSpeed {
  std::string program;  // "URScript", "KRL", "Sunrise", "RAPID"
  std::string file;     // the program beside the CSV
  bool read = false;    // false: the file is not there (or could not be read: see problem)
  std::string problem;
  machines::ContactSpeedFigures figures;

  // Within 2 % of the time line (contact speed and every lap).
  bool ok() const;
};

// The programs the cell writes beside `csv_file`, read back against `rows`.
std::vector<ProgramSpeed> check_program_speeds(const std::vector<slicer::PosePoint>& rows,
                                               const std::string& csv_file,
                                               const machines::MachineProfile& m);

nlohmann::json program_speeds_json(const std::vector<ProgramSpeed>& speeds);
std::string program_speeds_text(const std::vector<ProgramSpeed>& speeds);

}  // namespace strand::post
