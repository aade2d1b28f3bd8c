// strand_slice_compare: what a slicer's G-code puts where the part is, for the side-by-side
// bench with PrusaSlicer (tests/bench/slice_vs_prusaslicer.py). Any slicer's file is read with
// Strand's own G-code reader and held against the part's sections from Strand's mesh slicer,
// so both tools are measured by the same rules.
//
//   strand_slice_compare place MESH WxDxH OUT.stl
//     The mesh scaled and placed as `strand slice MESH --scale-to-fit WxDxH` places it
//     (bounding-box centre at x = y = 0, resting on z = 0), as a binary STL for the other
//     slicer. Prints the placed size; the driver checks it against Strand's report.
//   strand_slice_compare measure PLACED.stl GCODE LAYER_MM NOZZLE_MM CX,CY
//     One JSON line of figures for GCODE, whose part centre is (CX, CY) in its own frame:
//     layers with material, those without deposit, strands per layer, deposit inside.
//
// Definitions (docs/slicing.md, "Side by side with PrusaSlicer"):
// - layer k is the mesh's section at z = (k + 0.5) * LAYER_MM, k < ceil(height / LAYER_MM);
//   it has material when the section is at least half a bead wide somewhere (it survives an
//   inward offset of a quarter nozzle): narrower slivers are not printable by either tool.
// - a deposit belongs to layer round(z / LAYER_MM) - 1 (both tools print layer k at its top,
//   z = (k + 1) * LAYER_MM).
// - a strand is a run of deposits between moves without deposit that change the position
//   (travels, z lifts): every start and stop of the ink.
// - deposit inside: the share of the deposited XY length within half a nozzle of the
//   layer's section (clipped exactly against the grown section's rings).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <map>
#include <string>
#include <vector>

#include "patterns/region_clip.h"
#include "postprocess/inspect/gcode_parser.h"
#include "slicer/file_io.h"
#include "slicer/mesh.h"
#include "slicer/mesh_io.h"
#include "slicer/mesh_slicer.h"
#include "slicer/region.h"

namespace {

using strand::slicer::Vec2;
using strand::slicer::Vec3;

int usage() {
  std::fprintf(stderr,
               "usage: strand_slice_compare place MESH WxDxH OUT.stl\n"
               "       strand_slice_compare measure PLACED.stl GCODE LAYER_MM NOZZLE_MM CX,CY\n");
  return 2;
}

// "30x30x30" -> (30, 30, 30); "100,100" -> (100, 100). Empty on a malformed text.
std::vector<double> numbers(const std::string& text, char sep) {
  std::vector<double> v;
  std::size_t at = 0;
  while (at <= text.size()) {
    const std::size_t end = std::min(text.find(sep, at), text.size());
    const std::string part = text.substr(at, end - at);
    char* stop = nullptr;
    const double x = std::strtod(part.c_str(), &stop);
    if (part.empty() || *stop != '\0' || !std::isfinite(x)) return {};
    v.push_back(x);
    at = end + 1;
  }
  return v;
}

int place(const std::string& mesh_path, const std::string& box_text, const std::string& out) {
  namespace sl = strand::slicer;
  const std::vector<double> box = numbers(box_text, 'x');
  if (box.size() != 3 || *std::min_element(box.begin(), box.end()) <= 0.0) {
    std::fprintf(stderr, "strand_slice_compare: box = %s: must be WxDxH in mm, each > 0\n",
                 box_text.c_str());
    return 2;
  }
  sl::Mesh m = sl::place_mesh(sl::read_mesh_file(mesh_path), {});
  // The largest uniform scale that fits the box, as --scale-to-fit takes it.
  const Vec3 size = sl::bounds(m).size_mm();
  double scale = HUGE_VAL;
  for (int a = 0; a < 3; ++a)
    if (size[a] > 0.0) scale = std::min(scale, box[a] / size[a]);
  m = sl::place_mesh(std::move(m), {scale, Vec3::Zero(), sl::Placement::Center});
  sl::write_file_atomic(out, sl::binary_stl_bytes(m));
  const Vec3 placed = sl::bounds(m).size_mm();
  std::printf("{\"scale\": %.9g, \"size_mm\": [%.6f, %.6f, %.6f]}\n", scale, placed.x(),
              placed.y(), placed.z());
  return 0;
}

// What one layer of a file holds.
struct LayerFigures {
  double deposit_mm = 0.0;
  double inside_mm = 0.0;
  int strands = 0;
};

// The sections a deposit is held against: grown by half a nozzle, as ring sets for clipping.
struct Sections {
  std::vector<bool> material;
  std::vector<strand::patterns::RingSet> grown;
};

Sections sections_of(const strand::slicer::Mesh& m, double layer_mm, double nozzle_mm) {
  namespace sl = strand::slicer;
  const double height_mm = sl::bounds(m).size_mm().z();
  const int layers = std::max(1, static_cast<int>(std::ceil(height_mm / layer_mm - 1e-9)));
  const std::vector<sl::Region> regions = sl::slice_layers(m, layer_mm, layers);
  Sections s;
  for (const sl::Region& r : regions) {
    s.material.push_back(!sl::offset_region(r, -0.25 * nozzle_mm).empty());
    s.grown.push_back(strand::patterns::ring_set(sl::rings_of(sl::offset_region(r, 0.5 * nozzle_mm))));
  }
  return s;
}

// Per layer index (beyond the sections too: a deposit above the part is all outside).
std::map<int, LayerFigures> measure_file(const strand::post::ParsedGcode& g, const Sections& s,
                                         double layer_mm, const Vec2& center) {
  namespace sl = strand::slicer;
  namespace pt = strand::patterns;
  std::map<int, LayerFigures> out;
  std::map<int, std::vector<pt::PatternLine>> lines;  // each layer's deposits, as runs
  Vec3 at = g.program.start_mm;
  bool in_strand = false;
  int strand_layer = 0;
  for (const sl::Move& mv : g.program.moves) {
    if (mv.kind == sl::MoveKind::Raw || mv.kind == sl::MoveKind::Dwell) continue;
    const Vec3 from = at;
    at = mv.end_mm;
    if (mv.kind == sl::MoveKind::Travel) {
      if ((at - from).norm() > 1e-9) in_strand = false;
      continue;
    }
    const int k = static_cast<int>(std::lround(at.z() / layer_mm)) - 1;
    LayerFigures& f = out[k];
    const Vec2 a = from.head<2>() - center, b = at.head<2>() - center;
    f.deposit_mm += (b - a).norm();
    if (!in_strand || strand_layer != k) {
      ++f.strands;
      lines[k].push_back({});
      lines[k].back().points.push_back(a);
      in_strand = true;
      strand_layer = k;
    }
    lines[k].back().points.push_back(b);
  }
  for (auto& [k, runs] : lines) {
    if (k < 0 || k >= static_cast<int>(s.grown.size())) continue;
    for (pt::PatternLine& run : runs) {
      run.features.assign(run.points.size() - 1, sl::Feature::Infill);
    }
    for (const pt::FillPiece& piece : pt::clip_to_rings(s.grown[k], runs)) {
      const auto& p = piece.line.points;
      for (std::size_t i = 1; i < p.size(); ++i) out[k].inside_mm += (p[i] - p[i - 1]).norm();
    }
  }
  return out;
}

int measure(const std::string& mesh_path, const std::string& gcode_path, double layer_mm,
            double nozzle_mm, const std::string& center_text) {
  namespace sl = strand::slicer;
  const std::vector<double> c = numbers(center_text, ',');
  if (c.size() != 2 || !(layer_mm > 0.0) || !(nozzle_mm > 0.0)) return usage();
  const Sections s = sections_of(sl::read_mesh_file(mesh_path), layer_mm, nozzle_mm);
  const strand::post::ParsedGcode g = strand::post::parse_gcode(sl::read_file(gcode_path));
  const std::map<int, LayerFigures> layers = measure_file(g, s, layer_mm, Vec2(c[0], c[1]));

  int material = 0, strands_max = 0, strand_layers = 0;
  long strands_total = 0;
  double deposit_mm = 0.0, inside_mm = 0.0;
  std::string empty;  // layers with material and no deposit
  for (int k = 0; k < static_cast<int>(s.material.size()); ++k) {
    if (!s.material[k]) continue;
    ++material;
    const auto it = layers.find(k);
    if (it == layers.end() || it->second.deposit_mm <= 0.0)
      empty += (empty.empty() ? "" : ", ") + std::to_string(k);
  }
  for (const auto& [k, f] : layers) {
    deposit_mm += f.deposit_mm;
    inside_mm += f.inside_mm;
    if (f.strands == 0) continue;
    strands_max = std::max(strands_max, f.strands);
    strands_total += f.strands;
    ++strand_layers;
  }
  const int empty_count = empty.empty() ? 0 : static_cast<int>(std::count(empty.begin(), empty.end(), ',')) + 1;
  std::printf(
      "{\"layers\": %zu, \"material_layers\": %d, \"empty_material_layers\": %d, "
      "\"empty_layer_indices\": [%s], \"deposit_layers\": %d, \"strands\": %ld, "
      "\"strands_max\": %d, \"strands_mean\": %.3f, \"deposit_mm\": %.3f, "
      "\"inside_pct\": %.3f, \"parse_issues\": %zu}\n",
      s.material.size(), material, empty_count, empty.c_str(), strand_layers, strands_total,
      strands_max, strand_layers ? static_cast<double>(strands_total) / strand_layers : 0.0,
      deposit_mm, deposit_mm > 0.0 ? 100.0 * inside_mm / deposit_mm : 0.0, g.issues.size());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const std::vector<std::string> a(argv + 1, argv + argc);
    if (a.size() == 4 && a[0] == "place") return place(a[1], a[2], a[3]);
    if (a.size() == 6 && a[0] == "measure")
      return measure(a[1], a[2], std::atof(a[3].c_str()), std::atof(a[4].c_str()), a[5]);
    return usage();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "strand_slice_compare: %s\n", e.what());
    return 2;
  }
}
