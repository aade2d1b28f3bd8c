// Missing-rib geometry: the node grid with its bent ribs, the outward ribs of the boundary
// nodes and the frame pieces that pair their ends, built as a RibNetwork and traversed as
// one non-crossing closed strand per layer.
#include "patterns/missing_rib.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "patterns/rib_network.h"
#include "patterns/wrap_fit.h"
#include "slicer/units.h"

namespace strand::patterns {

using slicer::Feature;
using slicer::Vec2;

namespace {

// A rib end on the frame, with the node it belongs to and the frame side it lies on
// (0 bottom, 1 right, 2 top, 3 left: counter-clockwise).
struct FrameTip {
  Vec2 at_mm;
  int node = 0;
  int side = 0;
};

class Builder {
 public:
  Builder(const MissingRibParams& p, const MissingRibGeometry& g) : p_(p), g_(g) {
    theta_ = slicer::deg_to_rad(p.angle_deg);
    half_x_ = g.frame_width_mm / 2;
    half_y_ = g.frame_depth_mm / 2;
  }

  RibNetwork build() {
    std::vector<FrameTip> tips = frame_tips();
    std::vector<int> tip_vertex;
    for (const auto& t : tips) tip_vertex.push_back(net_.add_vertex(t.at_mm));  // strand starts on the frame
    nodes_.resize(static_cast<std::size_t>((p_.rows + 1) * (p_.cols + 1)));
    for (int i = 0; i <= p_.rows; ++i) {
      for (int j = 0; j <= p_.cols; ++j) nodes_[index(i, j)] = net_.add_vertex(node_at(i, j));
    }
    for (int i = 0; i <= p_.rows; ++i) {
      for (int j = 0; j <= p_.cols; ++j) {
        if (j < p_.cols) bent_rib(i, j, 0, nodes_[index(i, j + 1)]);
        if (i < p_.rows) bent_rib(i, j, 1, nodes_[index(i + 1, j)]);
      }
    }
    for (std::size_t k = 0; k < tips.size(); ++k) {
      net_.add_edge(nodes_[static_cast<std::size_t>(tips[k].node)], tip_vertex[k], Feature::Ligament);
    }
    for (std::size_t k = 0; k + 1 < tips.size(); k += 2) frame_piece(tips[k], tips[k + 1], tip_vertex[k], tip_vertex[k + 1]);
    return net_;
  }

 private:
  std::size_t index(int i, int j) const { return static_cast<std::size_t>(i * (p_.cols + 1) + j); }
  Vec2 node_at(int i, int j) const {
    return Vec2((j - p_.cols / 2.0) * g_.pitch_mm, (i - p_.rows / 2.0) * g_.pitch_mm);
  }
  // Rotation of node (i, j): +theta and -theta alternate like a checkerboard.
  double rotation(int i, int j) const { return (i + j) % 2 == 0 ? theta_ : -theta_; }
  // End of arm k (0 east, 1 north, 2 west, 3 south) of node (i, j).
  Vec2 arm_end(int i, int j, int k) const {
    const double a = rotation(i, j) + k * slicer::kPi / 2;
    return node_at(i, j) + p_.rib_mm * Vec2(std::cos(a), std::sin(a));
  }

  // Node (i, j) to its neighbour along arm k (east or north), through the bend.
  void bent_rib(int i, int j, int k, int neighbour) {
    const int bend = net_.add_vertex(arm_end(i, j, k));
    net_.add_edge(nodes_[index(i, j)], bend, Feature::Ligament);
    net_.add_edge(bend, neighbour, Feature::Ligament);
  }

  // Outward arms of the boundary nodes, counter-clockwise from the bottom-left corner.
  std::vector<FrameTip> frame_tips() const {
    std::vector<FrameTip> out;
    auto add = [&](int i, int j, int arm, int side) {
      out.push_back({on_frame(arm_end(i, j, arm), side), i * (p_.cols + 1) + j, side});
    };
    for (int j = 0; j <= p_.cols; ++j) add(0, j, 3, 0);
    for (int i = 0; i <= p_.rows; ++i) add(i, p_.cols, 0, 1);
    for (int j = p_.cols; j >= 0; --j) add(p_.rows, j, 1, 2);
    for (int i = p_.rows; i >= 0; --i) add(i, 0, 2, 3);
    return out;
  }

  // Arm ends land on the frame (half a pitch out) by construction; snap away rounding.
  Vec2 on_frame(Vec2 q, int side) const {
    if (side == 0) q.y() = -half_y_;
    if (side == 1) q.x() = half_x_;
    if (side == 2) q.y() = half_y_;
    if (side == 3) q.x() = -half_x_;
    return q;
  }

  // Frame from tip a to tip b, counter-clockwise, around the corners in between.
  void frame_piece(const FrameTip& a, const FrameTip& b, int va, int vb) {
    const Vec2 corners[4] = {Vec2(half_x_, -half_y_), Vec2(half_x_, half_y_), Vec2(-half_x_, half_y_),
                             Vec2(-half_x_, -half_y_)};
    int from = va;
    for (int s = a.side; s < b.side; ++s) {
      const int c = net_.add_vertex(corners[s]);
      net_.add_edge(from, c, Feature::Frame);
      from = c;
    }
    net_.add_edge(from, vb, Feature::Frame);
  }

  const MissingRibParams& p_;
  const MissingRibGeometry& g_;
  double theta_ = 0.0;
  double half_x_ = 0.0;
  double half_y_ = 0.0;
  RibNetwork net_;
  std::vector<int> nodes_;
};

}  // namespace

MissingRibGeometry missing_rib_geometry(const MissingRibParams& p) {
  MissingRibGeometry g;
  const double theta = slicer::deg_to_rad(p.angle_deg);
  g.pitch_mm = 2.0 * p.rib_mm * std::cos(theta);
  g.frame_width_mm = (p.cols + 1) * g.pitch_mm;
  g.frame_depth_mm = (p.rows + 1) * g.pitch_mm;
  g.width_mm = g.frame_width_mm + p.nozzle_mm;
  g.depth_mm = g.frame_depth_mm + p.nozzle_mm;
  g.height_mm = p.layers * p.layer_height_mm;
  g.min_clearance_mm = std::min(p.rib_mm * (std::cos(theta) - std::sin(theta)),
                                (p.rib_mm - p.node_gap_mm / std::sqrt(2.0)) * std::cos(theta));
  return g;
}

namespace {

// Header and report figures, from the strands actually laid down.
nlohmann::json missing_rib_report(const MissingRibParams& p, const MissingRibGeometry& g, const RibNetwork& net,
                                  const std::vector<slicer::Stroke>& strands) {
  double per_layer = 0.0;
  for (const auto& s : strands) per_layer += slicer::stroke_length(s);
  const double area = slicer::bead_area_mm2(p.nozzle_mm, p.layer_height_mm);
  const double density = per_layer * p.layers * area / (g.width_mm * g.depth_mm * g.height_mm);
  int ribs = 0;
  for (const auto& e : net.edges) ribs += e.feature == Feature::Ligament;
  return {
      {"footprint_mm", {g.width_mm, g.depth_mm}},
      {"height_mm", g.height_mm},
      {"layers", p.layers},
      {"layer_height_mm", p.layer_height_mm},
      {"rib_mm", p.rib_mm},
      {"rib_printed_mm", p.rib_mm - p.node_gap_mm / std::sqrt(2.0)},
      {"angle_deg", p.angle_deg},
      {"pitch_mm", g.pitch_mm},
      {"nodes", (p.rows + 1) * (p.cols + 1)},
      {"ribs_per_layer", ribs},
      {"min_clearance_mm", g.min_clearance_mm},
      {"node_gap_mm", p.node_gap_mm},
      {"filament_length_per_layer_mm", per_layer},
      {"filament_length_mm", per_layer * p.layers},
      {"bead_area_mm2", area},
      {"relative_density", density},
      {"porosity", 1.0 - density},
      {"porosity_formula", "1 - (filament length * bead area) / (width * depth * height), frame included"},
      {"strands_per_layer", strands.size()},
      {"strands_why",
       "frame pieces pair the outward rib ends so every vertex has even degree; passes turn into a "
       "neighbouring rib at each node (corner cut node-gap from the opposite pass) and circuits "
       "are merged at nodes: one closed strand"},
  };
}

// The network's strands, the same in every layer, and the report.
std::unique_ptr<slicer::LayerSource> stacked(const MissingRibParams& p, const MissingRibGeometry& g,
                                             const RibNetwork& net) {
  std::vector<slicer::Stroke> strands = non_crossing_circuits(net, p.node_gap_mm);
  for (auto& s : strands) {
    s.width_mm = p.nozzle_mm;
    s.height_mm = p.layer_height_mm;
  }
  nlohmann::json report = missing_rib_report(p, g, net, strands);
  auto t = std::make_unique<slicer::RepeatedLayers>(std::vector<std::vector<slicer::Stroke>>{std::move(strands)},
                                                    static_cast<std::size_t>(std::max(p.layers, 0)),
                                                    p.layer_height_mm);
  t->record.generator = "missing-rib";
  t->record.derived = std::move(report);
  return t;
}

// The lattice wrapped round a cylinder: `around` nodes per row (even, so the rotations
// alternate across the seam too), east ribs crossing the seam to the first node's copy one
// period on, outward ribs only at the two ends, and frame pieces pairing neighbouring tips
// at each end along a line half a pitch outside the end rows.
class RingBuilder {
 public:
  RingBuilder(const MissingRibParams& p, const MissingRibGeometry& g, int around)
      : p_(p), around_(around), pitch_(g.pitch_mm), theta_(slicer::deg_to_rad(p.angle_deg)) {
    net_.period_mm = around * g.pitch_mm;
    half_y_ = g.frame_depth_mm / 2;
  }

  RibNetwork build() {
    std::vector<int> tips[2];  // bottom, top; in order of x
    for (int end = 0; end < 2; ++end) {
      const int i = end == 0 ? 0 : p_.rows;
      for (int j = 0; j < around_; ++j) {
        Vec2 q = arm_end(i, j, end == 0 ? 3 : 1);
        q.y() = end == 0 ? -half_y_ : half_y_;  // on the frame by construction; snap rounding
        tips[end].push_back(net_.add_vertex(q));  // strands start on the frame
      }
    }
    for (int i = 0; i <= p_.rows; ++i) {
      for (int j = 0; j < around_; ++j) net_.add_vertex(node_at(i, j));
    }
    for (int i = 0; i <= p_.rows; ++i) {
      for (int j = 0; j < around_; ++j) {
        bent_rib(i, j, 0, node(i, (j + 1) % around_), j + 1 == around_ ? 1 : 0);
        if (i < p_.rows) bent_rib(i, j, 1, node(i + 1, j), 0);
      }
    }
    for (int end = 0; end < 2; ++end) {
      const int i = end == 0 ? 0 : p_.rows;
      for (int j = 0; j < around_; ++j) {
        net_.add_edge(node(i, j), tips[end][static_cast<std::size_t>(j)], Feature::Ligament);
      }
      for (std::size_t j = 0; j + 1 < tips[end].size(); j += 2) {
        net_.add_edge(tips[end][j], tips[end][j + 1], Feature::Frame);
      }
    }
    return net_;
  }

 private:
  int node(int i, int j) const { return 2 * around_ + i * around_ + j; }
  Vec2 node_at(int i, int j) const {
    return Vec2((j + 0.5) * pitch_ - net_.period_mm / 2, (i - p_.rows / 2.0) * pitch_);
  }
  Vec2 arm_end(int i, int j, int k) const {
    const double a = ((i + j) % 2 == 0 ? theta_ : -theta_) + k * slicer::kPi / 2;
    return node_at(i, j) + p_.rib_mm * Vec2(std::cos(a), std::sin(a));
  }
  void bent_rib(int i, int j, int k, int neighbour, int wrap) {
    const int bend = net_.add_vertex(arm_end(i, j, k));
    net_.add_edge(node(i, j), bend, Feature::Ligament);
    net_.add_edge(bend, neighbour, Feature::Ligament, wrap);
  }

  const MissingRibParams& p_;
  int around_ = 0;
  double pitch_ = 0.0, theta_ = 0.0, half_y_ = 0.0;
  RibNetwork net_;
};

}  // namespace

std::unique_ptr<slicer::LayerSource> missing_rib_layers(const MissingRibParams& p) {
  const MissingRibGeometry g = missing_rib_geometry(p);
  return stacked(p, g, Builder(p, g).build());
}

slicer::Toolpath generate_missing_rib(const MissingRibParams& p) { return slicer::collect(*missing_rib_layers(p)); }

slicer::Toolpath generate_missing_rib_wrapped(const MissingRibParams& given, double period_mm) {
  MissingRibParams p = given;
  const double c = std::cos(slicer::deg_to_rad(p.angle_deg));
  const WrapFit fit =
      fit_around("missing-rib", period_mm, 2 * p.rib_mm * c,
                 {4, 2, 500, 2 * missing_rib_min_rib_mm(p) * c,
                  "an even number: the node rotations alternate round the cylinder"});
  p.rib_mm = fit.cell_mm / (2 * c);
  p.cols = fit.cells;
  MissingRibGeometry g = missing_rib_geometry(p);
  g.frame_width_mm = g.width_mm = period_mm;
  slicer::Toolpath t = slicer::collect(*stacked(p, g, RingBuilder(p, g, fit.cells).build()));
  t.derived["nodes"] = (p.rows + 1) * fit.cells;
  add_wrap_report(t.derived, fit, "node pitch (the rib adjusted at the same angle)");
  return t;
}

}  // namespace strand::patterns
