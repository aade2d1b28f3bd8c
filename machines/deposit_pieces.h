// How the emitter writes one deposit move: as one G2/G3 or G1, as G1 chords where the firmware
// has no arcs (or would misdraw the rounded numbers), and cut so no move pushes more E than
// the firmware's EXTRUDE_MAXLENGTH.
#pragma once

#include <vector>

#include "machines/profile.h"
#include "slicer/motion.h"

namespace strand::machines {

struct PiecePlan {
  int n = 1;            // pieces the deposit is written as
  bool chords = false;  // an arc written as G1 chords
};

// The pieces of `mv` starting at `from` on machine `m`; `limit_e`: the file carries the
// machine's real E words (not the viewer copy's volumes), so E per move is bounded.
PiecePlan piece_plan(const slicer::Vec3& from, const slicer::Move& mv, const MachineProfile& m,
                     bool limit_e);

// `mv` cut as `plan` says (equal fractions; volumes shared by length); chords lose is_arc.
std::vector<slicer::Move> deposit_pieces(const slicer::Vec3& from, const slicer::Move& mv,
                                         const PiecePlan& plan);

}  // namespace strand::machines
