// Building the viewer's layer blocks from a G-code reading or a 3D scene.
#include "postprocess/preview/viewer_data.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "postprocess/inspect/gcode_parser.h"
#include "postprocess/plan/arc_segmentation.h"
#include "postprocess/plan/estimate.h"
#include "slicer/input_error.h"

namespace strand::post {

using slicer::MoveKind;
using slicer::Vec3;

namespace {

constexpr int kFeatureCount = static_cast<int>(slicer::Feature::Pen) + 1;

// One layer's segments as parallel arrays until its block is written.
struct BlockBuilder {
  std::vector<float> pos, feed, flow;
  std::vector<std::uint32_t> line;
  std::vector<std::uint8_t> kind, tool;

  std::size_t size() const { return kind.size(); }
  void add(const ViewerSegment& s) {
    for (const Vec3* p : {&s.from_mm, &s.to_mm})
      for (int a = 0; a < 3; ++a) pos.push_back(static_cast<float>((*p)[a]));
    feed.push_back(s.feed_mm_per_min);
    flow.push_back(s.e_per_mm);
    line.push_back(s.line);
    kind.push_back(s.kind);
    tool.push_back(s.tool);
  }
  template <class T>
  static void put(std::string& out, const std::vector<T>& v) {  // little-endian hosts only
    static_assert(std::endian::native == std::endian::little);
    out.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
  }
  void write_to(std::string& out) {
    const std::size_t start = out.size();
    put(out, pos), put(out, feed), put(out, flow), put(out, line), put(out, kind), put(out, tool);
    out.resize(start + viewer_block_bytes(size()), '\0');
    *this = {};
  }
};

struct Bounds {
  bool any = false;
  Vec3 lo = Vec3::Zero(), hi = Vec3::Zero();
  void grow(const Vec3& p) {
    lo = any ? lo.cwiseMin(p) : p;
    hi = any ? hi.cwiseMax(p) : p;
    any = true;
  }
};

// Collects segments layer after layer: a segment of an earlier layer than the open one (a
// move before the first layer, a file going back) stays in the open layer's block.
class Collector {
 public:
  explicit Collector(ViewerData& d) : d_(d) {}
  void add(int layer, const ViewerSegment& s, bool counts_as_move) {
    open(std::max(layer, 0));
    block_.add(s);
    ViewerLayer& l = d_.layers.back();
    ++l.segments;
    if (counts_as_move) ++l.moves;
    const bool travel = s.kind & kViewerTravelBit;
    if (!travel) {
      deposits_.grow(s.from_mm), deposits_.grow(s.to_mm);
      d_.max_feed_mm_per_min = std::max<double>(d_.max_feed_mm_per_min, s.feed_mm_per_min);
      d_.max_e_per_mm = std::max<double>(d_.max_e_per_mm, s.e_per_mm);
      d_.max_tool = std::max<int>(d_.max_tool, s.tool);
      d_.pens = d_.pens || s.kind == static_cast<int>(slicer::Feature::Pen);
    }
    all_.grow(s.from_mm), all_.grow(s.to_mm);
  }
  void finish() {
    if (d_.layers.empty()) throw InputError("input = " + d_.source + ": no moves to draw");
    block_.write_to(d_.blocks);
    const Bounds& b = deposits_.any ? deposits_ : all_;
    d_.min_mm = b.lo, d_.max_mm = b.hi;
  }

 private:
  void open(int layer) {
    while (static_cast<int>(d_.layers.size()) <= layer) {
      if (!d_.layers.empty()) block_.write_to(d_.blocks);
      ViewerLayer l;
      l.offset = d_.blocks.size();
      d_.layers.push_back(l);
    }
  }
  ViewerData& d_;
  BlockBuilder block_;
  Bounds deposits_, all_;
};

std::uint8_t kind_of(slicer::Feature f, bool travel) {
  return static_cast<std::uint8_t>(static_cast<int>(f) | (travel ? kViewerTravelBit : 0));
}

std::uint8_t tool_of(int tool) { return static_cast<std::uint8_t>(std::clamp(tool, 0, 255)); }

// {"v": [x, y, z, ...], "t": [i, j, k, ...]}; `rounded`: to 0.1 um (a part of a few hundred
// thousand triangles travels in half the text).
nlohmann::json mesh_json(const slicer::TriangleMesh& m, bool rounded) {
  nlohmann::json v = nlohmann::json::array(), t = nlohmann::json::array();
  for (const auto& p : m.vertices_mm) {
    for (int k = 0; k < 3; ++k) v.push_back(rounded ? std::round(p[k] * 1e4) / 1e4 : p[k]);
  }
  for (const auto& f : m.triangles) t.push_back(f[0]), t.push_back(f[1]), t.push_back(f[2]);
  return {{"v", v}, {"t", t}};
}

}  // namespace

std::size_t viewer_block_bytes(std::size_t segments) {
  return (segments * kViewerSegmentBytes + 3) / 4 * 4;
}

ViewerData viewer_data_from_gcode(std::string_view text, const machines::MachineProfile* machine,
                                  double arc_tolerance_mm, const std::string& source) {
  ViewerData d;
  d.source = source;
  d.trapezoid_time = machine != nullptr;
  Collector c(d);
  EstimateStream estimate(machine);
  std::vector<double> e_by_layer;
  bool started = false;
  Vec3 at = Vec3::Zero();
  const auto sink = [&](const ParsedGcode& piece, std::size_t) {
    const slicer::MotionProgram& p = piece.program;
    estimate.add(p);
    if (!started && !p.moves.empty()) at = p.start_mm, started = true;
    for (std::size_t i = 0; i < p.moves.size(); ++i) {
      const slicer::Move& mv = p.moves[i];
      if (mv.kind == MoveKind::Dwell || mv.kind == MoveKind::Raw) continue;
      const double de = i < piece.e_step.size() ? piece.e_step[i] : 0.0;
      const std::size_t layer = static_cast<std::size_t>(std::max(mv.layer, 0));
      if (e_by_layer.size() <= layer) e_by_layer.resize(layer + 1, 0.0);
      e_by_layer[layer] += de;
      const bool travel = mv.kind != MoveKind::Deposit;
      const double len = move_length(at, mv);
      ViewerSegment s;
      s.feed_mm_per_min = static_cast<float>(mv.feed_mm_per_min);
      s.e_per_mm = travel || len <= 0 ? 0.0f : static_cast<float>(std::max(de, 0.0) / len);
      s.line = i < piece.move_lines.size() ? static_cast<std::uint32_t>(std::max(piece.move_lines[i], 0)) : 0;
      s.kind = kind_of(mv.feature, travel);
      s.tool = tool_of(mv.tool);
      std::vector<Vec3> ends;
      if (mv.is_arc) {
        const auto pts = segment_arc(at.head<2>(), mv.center_mm, mv.end_mm.head<2>(), mv.ccw, arc_tolerance_mm);
        for (std::size_t k = 0; k < pts.size(); ++k) {
          const double f = static_cast<double>(k + 1) / static_cast<double>(pts.size());
          ends.emplace_back(pts[k].x(), pts[k].y(), at.z() + f * (mv.end_mm.z() - at.z()));
        }
      } else {
        ends.push_back(mv.end_mm);
      }
      for (std::size_t k = 0; k < ends.size(); ++k) {
        s.from_mm = k == 0 ? at : ends[k - 1];
        s.to_mm = ends[k];
        c.add(mv.layer, s, k == 0);
      }
      at = mv.end_mm;
    }
  };
  const ParsedGcode parsed = parse_gcode_layers(text, {}, sink);
  d.pen_colours = parsed.pen_colours;
  c.finish();
  const Estimate e = estimate.finish();
  for (std::size_t i = 0; i < d.layers.size(); ++i) {
    ViewerLayer& l = d.layers[i];
    if (i < parsed.program.layers.size()) l.z_mm = parsed.program.layers[i].z_mm;
    if (i < e_by_layer.size()) l.e = e_by_layer[i];
    if (i >= e.layers.size()) continue;
    const LayerEstimate& le = e.layers[i];
    l.strands = le.strands;
    l.deposit_length_mm = le.deposit_length_mm;
    l.travel_length_mm = le.travel_length_mm;
    l.time_s = machine ? le.time_trapezoid_s : le.time_naive_s;
  }
  return d;
}

ViewerData viewer_data_from_scene(const PreviewScene& scene, const std::string& source) {
  ViewerData d;
  d.source = source;
  d.layer_value = scene.layer_value;
  d.substrate = scene.substrate;
  d.bead_width_mm = scene.bead_width_mm;
  d.pen_colours = scene.pen_colours;
  Collector c(d);
  for (const PreviewPath& path : scene.paths) {
    ViewerSegment s;
    s.kind = kind_of(path.feature, path.travel);
    s.tool = tool_of(path.tool);
    double length = 0.0;
    for (std::size_t k = 1; k < path.points_mm.size(); ++k) {
      s.from_mm = path.points_mm[k - 1];
      s.to_mm = path.points_mm[k];
      length += (s.to_mm - s.from_mm).norm();
      c.add(path.layer, s, true);
    }
    const std::size_t layer = static_cast<std::size_t>(std::max(path.layer, 0));
    if (layer < d.layers.size() && !path.travel) {
      ++d.layers[layer].strands;
      d.layers[layer].deposit_length_mm += length;
    } else if (layer < d.layers.size()) {
      d.layers[layer].travel_length_mm += length;
    }
  }
  c.finish();
  for (std::size_t i = 0; i < d.layers.size() && i < scene.layer_z_mm.size(); ++i)
    d.layers[i].z_mm = scene.layer_z_mm[i];
  return d;
}

nlohmann::json viewer_index(const ViewerData& d) {
  using nlohmann::json;
  json layers = json::array();
  std::size_t segments = 0;
  for (const ViewerLayer& l : d.layers) {
    layers.push_back({{"z", l.z_mm}, {"segments", l.segments}, {"moves", l.moves}, {"offset", l.offset},
                      {"bytes", viewer_block_bytes(l.segments)}, {"strands", l.strands},
                      {"deposit_length_mm", l.deposit_length_mm}, {"travel_length_mm", l.travel_length_mm},
                      {"time_s", l.time_s}, {"e", l.e}});
    segments += l.segments;
  }
  json features = json::array(), colours = json::array();
  for (int f = 0; f < kFeatureCount; ++f) {
    features.push_back(slicer::to_string(static_cast<slicer::Feature>(f)));
    colours.push_back(hex_colour(feature_colour(static_cast<slicer::Feature>(f))));
  }
  json j = {{"version", 1},
            {"source", d.source},
            {"layers", layers},
            {"segments", segments},
            {"bounds", {{"min", {d.min_mm.x(), d.min_mm.y(), d.min_mm.z()}}, {"max", {d.max_mm.x(), d.max_mm.y(), d.max_mm.z()}}}},
            {"features", features},
            {"feature_colours", colours},
            {"feed_max", d.max_feed_mm_per_min},
            {"flow_max", d.max_e_per_mm},
            {"bead_width_mm", d.bead_width_mm},
            {"layer_value", d.layer_value},
            {"time", d.trapezoid_time ? "trapezoid" : "naive"}};
  if (d.pens) {
    PreviewScene pens;
    pens.pen_colours = d.pen_colours;
    PreviewPath pen;
    pen.feature = slicer::Feature::Pen;
    for (pen.tool = 0; pen.tool <= d.max_tool; ++pen.tool) {
      const PreviewKey k = deposit_key(pens, pen);
      j["pens"].push_back({{"name", k.name}, {"colour", hex_colour(k.colour)}});
    }
  }
  if (!d.substrate.vertices_mm.empty()) j["substrate"] = mesh_json(d.substrate, false);
  if (!d.part.vertices_mm.empty()) j["part"] = mesh_json(d.part, true);
  if (!d.part_note.empty()) j["part_note"] = d.part_note;
  return j;
}

std::string_view viewer_blocks(const ViewerData& d, std::size_t from, std::size_t to) {
  const std::size_t begin = d.layers.at(from).offset;
  const std::size_t end = d.layers.at(to).offset + viewer_block_bytes(d.layers.at(to).segments);
  return std::string_view(d.blocks).substr(begin, end - begin);
}

std::vector<ViewerSegment> decode_viewer_block(std::string_view b, std::size_t n) {
  if (b.size() < viewer_block_bytes(n)) throw std::invalid_argument("viewer block shorter than its segments");
  std::vector<ViewerSegment> out(n);
  const auto read = [&b](std::size_t at, auto& value) { std::memcpy(&value, b.data() + at, sizeof value); };
  for (std::size_t i = 0; i < n; ++i) {
    ViewerSegment& s = out[i];
    float p[6];
    read(i * 24, p);
    s.from_mm = Vec3(p[0], p[1], p[2]);
    s.to_mm = Vec3(p[3], p[4], p[5]);
    read(n * 24 + i * 4, s.feed_mm_per_min);
    read(n * 28 + i * 4, s.e_per_mm);
    read(n * 32 + i * 4, s.line);
    read(n * 36 + i, s.kind);
    read(n * 37 + i, s.tool);
  }
  return out;
}

}  // namespace strand::post
