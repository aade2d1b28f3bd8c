// Seams for a scaffold layer's dead ends. A serpentine of whole chords joined along the
// boundary enters a lobe (a cow's leg below its body, a gear's tooth) and cannot come back
// out, so a second lobe beside it becomes a strand of its own. A seam is a slit one gap
// wide cut down the middle of a lobe's chords, inside the fill boundary: the lobe becomes
// a ring round it, filled down one half and back up the other ("there and back"), with
// the joins between the half chords running along the slit's two sides. A lobe narrower
// than a pitch is printed round its edge instead (its chords left out: round_lobe).
#pragma once

#include <vector>

#include "patterns/region_clip.h"
#include "slicer/region.h"

namespace strand::patterns {

struct SeamOptions {
  double nozzle_mm = 0.0;    // bead width: the narrowest slit
  double pitch_mm = 0.0;     // line spacing: rows are this far apart
  double min_half_mm = 0.0;  // a cut chord's halves are kept at least this long
};

// One way to let a serpentine out of a cell again: a slit cut out of the fill, or (drop)
// where the cell's chords are left out, so the join along the ring runs round the lobe and
// back, out along one side and in along the other, as a perimeter would.
struct CellCut {
  slicer::Region region;
  bool drop = false;
};

struct LobeSeams {
  std::vector<std::vector<CellCut>> cells;  // per cell, its cuts (at least two)
  std::size_t dead_ends = 0;                // cells[0, dead_ends): at a dead end
  // Per pair of dead ends, the cells off the path between them (longest path first): with
  // those cut, one strand may run from one dead end to the other, there and back into every
  // branch off its way.
  std::vector<std::vector<std::size_t>> spines;
};

// Candidate slits for `pieces` (one scaffold layer's parallel chords, `order` the line
// index, clipped to `fill`, the region whose boundary the joins follow), one list per cell of
// the chords (a run of rows with one chord each, every chord overlapping only its neighbours
// in the rows beside it), each slit as wide as a gap where the cell's chords leave min_half
// beside it, at least a nozzle. Variants 0 and 1 cut every chord of the cell, kept a tenth
// and half a nozzle inside the ring (a chord close to the lobe's tip is cut only by the
// first); then the chords long enough to halve, and those with the first or last left whole;
// last, for a cell whose chords are all at most a pitch long, the drop (a cell too narrow to
// halve has only that, twice). Cells at a dead end (no chord beyond one of their ends) come first,
// in row order. None when the pieces are not parallel straight chords. Deterministic.
LobeSeams lobe_seams(const slicer::Region& fill, const std::vector<FillPiece>& pieces,
                     const SeamOptions& options);

// The pieces whose midpoints lie in `drop` (one cell's CellCut with drop set) replaced by one
// piece along their ring round the lobe, from the first of their ends to the last the way no
// other piece ends, its feature the first one's: the lobe's edge, out along one side and back
// along the other, printed as a piece so it cannot be left out. False, `pieces` unchanged,
// when none lies there, their ends are not all on one ring, or another piece ends among them.
bool round_lobe(const RingSet& rs, const slicer::Region& drop, std::vector<FillPiece>& pieces);

}  // namespace strand::patterns
