// A slice by objects: --part values, tools by object, objects read and placed together, the
// overlap check, and the fill source that prints each object in its own tool.
#include "jobs/slice_objects.h"

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <limits>
#include <optional>
#include <utility>

#include "slicer/input_error.h"
#include "slicer/mesh_io.h"
#include "slicer/params.h"

namespace strand::jobs {

namespace {

constexpr int kMaxTool = 15;  // as postprocess/plan/tool_assignment
constexpr char kPartForm[] = "FILE:TOOL, TOOL a printhead 0 to 15 (e.g. --part a.stl:1)";
constexpr char kObjectForms[] =
    "objects (build item k in tool k) or objects=TOOL,... in build order (e.g. objects=1,0)";

// The text for a one-line message: control characters shown as '?', at most 120 characters.
std::string shown(const std::string& text) {
  std::string out = text.substr(0, 120);
  for (char& c : out) {
    if (static_cast<unsigned char>(c) < 0x20) c = '?';
  }
  return out;
}

// "1" -> 1 for a tool in [0, kMaxTool]; nullopt otherwise.
std::optional<int> tool_number(const std::string& text) {
  int v = -1;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || end != text.data() + text.size() || v < 0 || v > kMaxTool) return std::nullopt;
  return v;
}

std::string tools_text(const nlohmann::json& tools) {
  return shown(tools.is_string() ? tools.get<std::string>() : tools.dump());
}

// The tools of `count` objects as `tools` gives them (tools_by_object is true).
std::vector<int> object_tools(const nlohmann::json& tools, std::size_t count) {
  const std::string what = "slice.tools = " + tools_text(tools);
  std::vector<int> out;
  if (tools.is_string() && tools.get<std::string>() == "objects") {
    if (count > kMaxTool + 1) throw InputError(what + ": " + std::to_string(count) + " objects, more than the 16 tools; give objects=TOOL,...");
    for (std::size_t k = 0; k < count; ++k) out.push_back(static_cast<int>(k));
    return out;
  }
  std::vector<std::string> items;
  if (tools.is_string()) {
    const std::string list = tools.get<std::string>().substr(8);  // after "objects="
    for (std::size_t at = 0; at <= list.size();) {
      const auto next = std::min(list.find(',', at), list.size());
      items.push_back(list.substr(at, next - at));
      at = next + 1;
    }
  } else {
    for (const auto& t : tools.at("by_object")) items.push_back(t.is_number_integer() ? std::to_string(t.get<long long>()) : t.dump());
  }
  for (const auto& item : items) {
    const auto t = tool_number(item);
    if (!t) throw InputError(what + ": must be " + kObjectForms + ", each tool a whole number 0 to 15");
    out.push_back(*t);
  }
  if (out.size() != count) {
    throw InputError(what + ": " + std::to_string(out.size()) + " tool(s) for " + std::to_string(count) +
                     " object(s) (the file's build items, in order)");
  }
  return out;
}

// Each object's fill, its strokes tagged with the object's index in fill() and given the
// object's tool in layer_from(); the sums come from a source over all objects together.
class ObjectsFill final : public patterns::PartFillSource {
 public:
  ObjectsFill(std::vector<patterns::PartFill> objects, std::vector<int> tools, const patterns::RegionPattern& p,
              std::string order, FillCompletion complete)
      : tools_(std::move(tools)), given_(order == "given"), complete_(std::move(complete)) {
    record.generator = "slice";
    std::vector<std::vector<slicer::Region>> layers;
    patterns::PartFill whole;
    for (auto& o : objects) {
      layers.push_back(o.layers);
      whole.volume_mm3 += o.volume_mm3;
      whole.half_extent_mm = o.half_extent_mm;
      whole.perimeters = o.perimeters;
      objects_.push_back(patterns::part_fill_layers(std::move(o), p));
    }
    whole.layers = joined_layers(layers);
    whole_ = patterns::part_fill_layers(std::move(whole), p);
  }

  std::size_t layer_count() const override { return whole_->layer_count(); }
  const slicer::Region& region(std::size_t k) const override { return whole_->region(k); }

  patterns::LayerFill fill(std::size_t k) const override {
    patterns::LayerFill all;
    for (std::size_t i = 0; i < objects_.size(); ++i) {
      patterns::LayerFill f = objects_[i]->fill(k);
      if (complete_) complete_(objects_[i]->region(k), f);
      for (auto& s : f.strokes) {
        s.tool = static_cast<int>(i);  // the object, until layer_from gives its tool
        all.strokes.push_back(std::move(s));
      }
      all.regions += f.regions;
      all.pattern_strands += f.pattern_strands;
      all.pattern_length_mm += f.pattern_length_mm;
    }
    return all;
  }

  slicer::Layer layer_from(std::size_t k, patterns::LayerFill f) override {
    std::vector<std::vector<slicer::Stroke>> by_tool(kMaxTool + 1);
    std::vector<int> order;
    for (auto& s : f.strokes) {
      const int object = s.tool;
      s.tool = tools_[static_cast<std::size_t>(object)];
      by_tool[static_cast<std::size_t>(s.tool)].push_back(s);
    }
    for (std::size_t i = 0; i < tools_.size(); ++i) {
      const int t = tools_[i];
      if (!by_tool[static_cast<std::size_t>(t)].empty() && std::find(order.begin(), order.end(), t) == order.end()) order.push_back(t);
    }
    if (!given_) {
      const int current = tool_;
      std::sort(order.begin(), order.end(), [current](int x, int y) { return std::pair(x != current, x) < std::pair(y != current, y); });
    }
    slicer::Layer layer = whole_->layer_from(k, std::move(f));  // z, height and the sums
    layer.strokes.clear();
    for (int t : order) {
      for (auto& s : slicer::nearest_first(std::move(by_tool[static_cast<std::size_t>(t)]), at_)) layer.strokes.push_back(std::move(s));
      tool_ = t;
    }
    if (k + 1 == layer_count()) record.derived.update(whole_->record.derived);
    return layer;
  }

 private:
  std::vector<std::unique_ptr<patterns::PartFillSource>> objects_;
  std::unique_ptr<patterns::PartFillSource> whole_;
  std::vector<int> tools_;
  bool given_ = false;
  FillCompletion complete_;
  slicer::Vec2 at_ = slicer::Vec2::Zero();
  int tool_ = 0;  // the tool the machine holds (it starts with tool 0)
};

}  // namespace

SlicePart part_from_text(const std::string& text) {
  const auto colon = text.rfind(':');
  const auto tool = colon == std::string::npos ? std::nullopt : tool_number(text.substr(colon + 1));
  if (!tool || colon == 0) throw InputError("--part = " + shown(text) + ": must be " + kPartForm);
  return {text.substr(0, colon), *tool};
}

bool tools_by_object(const nlohmann::json& tools) {
  if (tools.is_string()) {
    const std::string& t = tools.get_ref<const std::string&>();
    return t == "objects" || t.starts_with("objects=");
  }
  return tools.is_object() && tools.size() == 1 && tools.contains("by_object") && tools.at("by_object").is_array();
}

bool slices_objects(const SliceSettings& s) { return !s.parts.empty() || tools_by_object(s.tools); }

void check_tool_order(const std::string& order) {
  if (order != "fewest-changes" && order != "given") {
    throw InputError("slice.tool-order = " + shown(order) + ": must be fewest-changes or given");
  }
}

std::vector<SliceObject> read_slice_objects(const SliceSettings& s) {
  std::vector<SliceObject> out;
  if (s.parts.size() > kMaxSliceObjects) {
    throw InputError("--part: " + std::to_string(s.parts.size()) + " parts, at most " + std::to_string(kMaxSliceObjects));
  }
  if (!s.parts.empty() && !s.tools.is_null() && (tools_by_object(s.tools) || (s.tools.is_string() && s.tools.get<std::string>().starts_with("layers=")) || (s.tools.is_object() && s.tools.contains("by_layer")))) {
    throw InputError("slice.tools = " + tools_text(s.tools) + ": --part gives each part its tool; add tools by feature only");
  }
  std::size_t triangles = 0;
  const auto count = [&](const slicer::Mesh& m, const std::string& name) {
    triangles += m.triangles.size();
    if (triangles > slicer::kMaxMeshTriangles) {
      throw InputError("mesh = " + name + ": more than " + std::to_string(slicer::kMaxMeshTriangles) + " triangles in all parts");
    }
  };
  for (const SlicePart& p : s.parts) {
    out.push_back({p.path, "--part = " + shown(p.path) + ":" + std::to_string(p.tool), slicer::read_mesh_file(p.path), p.tool});
    count(out.back().mesh, p.path);
  }
  if (!s.parts.empty()) return out;
  std::vector<slicer::Mesh> meshes = slicer::read_mesh_objects(s.part);
  if (meshes.size() > kMaxSliceObjects) {
    throw InputError("mesh = " + s.part + ": " + std::to_string(meshes.size()) + " build items, at most " +
                     std::to_string(kMaxSliceObjects) + " objects are sliced apart");
  }
  const std::vector<int> tools = object_tools(s.tools, meshes.size());
  const std::string name = s.part_name.empty() ? s.part : s.part_name;
  for (std::size_t k = 0; k < meshes.size(); ++k) {
    out.push_back({name + " object " + std::to_string(k), "slice.tools = " + tools_text(s.tools), std::move(meshes[k]), tools[k]});
  }
  return out;
}

void check_object_tools(const std::vector<SliceObject>& objects, const machines::MachineProfile& m) {
  const int count = machines::tool_count(m);
  for (const SliceObject& o : objects) {
    if (o.tool < count) continue;
    throw InputError(o.given + ": tool " + std::to_string(o.tool) + " (" + o.name + ") is not on machine " + m.name +
                     " (" + std::to_string(count) + " tool(s): 0 to " + std::to_string(count - 1) + ")");
  }
}

slicer::PreparedMesh prepare_objects(const slicer::Mesh& placed, std::vector<SliceObject>& objects,
                                     const slicer::PrepareOptions& options, slicer::Placement place,
                                     Eigen::Affine3d* rested) {
  std::vector<slicer::Mesh> like;
  for (const SliceObject& o : objects) like.push_back(o.mesh);
  std::vector<slicer::Mesh> pieces = slicer::split_mesh(placed, like);
  slicer::PreparedMesh all;
  for (std::size_t i = 0; i < objects.size(); ++i) {
    slicer::PreparedMesh p = slicer::prepare_mesh(pieces[i], options, "mesh = " + objects[i].name);
    for (const auto& c : p.changes) all.changes.push_back(objects[i].name + ": " + c);
    for (const auto& d : p.defects) all.defects.push_back(objects[i].name + ": " + d);
    if (i == 0) all.before = p.before;
    pieces[i] = std::move(p.mesh);
  }
  // Repairs may add triangles at the extremes: rest the objects on the bed again, together.
  all.mesh = slicer::place_mesh(slicer::merge_meshes(pieces), {1.0, slicer::Vec3::Zero(), place}, rested);
  pieces = slicer::split_mesh(all.mesh, pieces);
  for (std::size_t i = 0; i < objects.size(); ++i) objects[i].mesh = std::move(pieces[i]);
  return all;
}

void check_objects_apart(const std::vector<SliceObject>& objects,
                         const std::vector<std::vector<slicer::Region>>& layers, double layer_height_mm) {
  const std::size_t n = layers.empty() ? 0 : layers.front().size();
  for (std::size_t k = 0; k < n; ++k) {
    std::vector<std::pair<slicer::Vec2, slicer::Vec2>> box;
    for (const auto& object : layers) box.push_back(slicer::region_bounds(object[k]));
    for (std::size_t i = 0; i < layers.size(); ++i) {
      for (std::size_t j = i + 1; j < layers.size(); ++j) {
        if (layers[i][k].empty() || layers[j][k].empty()) continue;
        if ((box[i].second.array() < box[j].first.array()).any() || (box[j].second.array() < box[i].first.array()).any()) continue;
        const double shared = slicer::area_mm2(slicer::region_intersection(layers[i][k], layers[j][k]));
        if (shared <= kObjectOverlapMm2) continue;
        char where[160];
        std::snprintf(where, sizeof where, " overlap in layer %zu (z = %.3f mm, %.3f mm2 shared)", k,
                      (static_cast<double>(k) + 1.0) * layer_height_mm, shared);
        throw InputError("slice: " + objects[i].name + " and " + objects[j].name + where +
                         "; two inks may not print on each other: move the objects apart");
      }
    }
  }
}

std::vector<slicer::Region> joined_layers(const std::vector<std::vector<slicer::Region>>& layers) {
  std::vector<slicer::Region> out(layers.empty() ? 0 : layers.front().size());
  for (const auto& object : layers) {
    for (std::size_t k = 0; k < out.size() && k < object.size(); ++k) out[k].insert(out[k].end(), object[k].begin(), object[k].end());
  }
  return out;
}

std::unique_ptr<patterns::PartFillSource> objects_fill_layers(std::vector<patterns::PartFill> objects,
                                                              std::vector<int> tools,
                                                              const patterns::RegionPattern& p,
                                                              const std::string& order,
                                                              FillCompletion complete) {
  return std::make_unique<ObjectsFill>(std::move(objects), std::move(tools), p, order, std::move(complete));
}

}  // namespace strand::jobs
