// Contacts between deposited segments inside each layer: proper crossings (a filament
// over itself, which grows a bump layer after layer) and touches (end on a filament,
// collinear overlap). O(n log^2 n + k) per layer for n segments and k box overlaps.
#pragma once

#include <cstdint>
#include <vector>

#include "slicer/motion.h"

namespace strand::post {

struct Contact {
  int layer = 0;
  slicer::Vec2 at_mm = slicer::Vec2::Zero();
  std::size_t move_a = 0;  // indices into MotionProgram::moves
  std::size_t move_b = 0;
  int line_a = 0, line_b = 0;  // G-code lines of the two moves, when the search was told them
  bool walls = false;          // both moves are walls (FDM rules let any other pair cross)
  // The printheads (T<n>) of the two moves; different: two inks cross (issue 33).
  std::int16_t tool_a = 0, tool_b = 0;
  bool between_tools() const { return tool_a != tool_b; }
};

struct ContactReport {
  std::vector<Contact> crossings;
  std::vector<Contact> touches;
};

// The search fed one move at a time, in program order: only the current layer's segments are
// held. Each layer is searched when a move of another layer arrives (or at finish()), and its
// contacts are appended to `out`, sorted as find_contacts sorts them. Arcs are flattened with
// `arc_tolerance_mm`; segments closer than `touch_mm` touch.
class ContactStream {
 public:
  ContactStream(double arc_tolerance_mm, double touch_mm, const slicer::Vec3& start_mm);
  // `move` is the move's index in the whole program, `line` its G-code line (0: unknown).
  void add(const slicer::Move& mv, std::size_t move, int line, ContactReport& out);
  void finish(ContactReport& out);

  struct Seg {
    slicer::Vec2 a, b;
    std::size_t move;     // source move
    std::int64_t strand;  // strand id within the program
    std::int64_t index;   // position within its strand (consecutive pieces differ by 1)
    int line;
    bool wall;
    std::int16_t tool;  // the printhead that deposits it
  };

 private:
  void search_layer(ContactReport& out);

  double tol_, touch_;
  slicer::Vec3 at_;
  std::int64_t strand_ = -1, index_ = 0;
  bool depositing_ = false;
  int layer_ = -2;  // the layer whose segments segs_ holds; -2 before the first move
  std::vector<Seg> segs_;
};

// Arcs are flattened with `arc_tolerance_mm`; segments closer than `touch_mm` touch.
// Consecutive segments of one strand (sharing their joint) are not contacts.
ContactReport find_contacts(const slicer::MotionProgram& program, double arc_tolerance_mm,
                            double touch_mm);

}  // namespace strand::post
