// Tool assignment: parsing the two forms, cutting strokes where the tool changes, grouping.
#include "postprocess/plan/tool_assignment.h"

#include <algorithm>
#include <charconv>
#include <utility>

#include "slicer/input_error.h"

namespace strand::post {

namespace {

constexpr int kMaxTool = 15;
constexpr std::size_t kMaxLayerCycle = 64;
constexpr char kForms[] = "FEATURE=TOOL,... (e.g. node=1,ligament=0) or layers=TOOL,... (e.g. layers=0,1)";

int tool_index(const std::string& text, const std::string& what) {
  int v = -1;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || end != text.data() + text.size() || v < 0 || v > kMaxTool) {
    throw InputError(what + ": tool " + text.substr(0, 40) + " must be a whole number 0 to " + std::to_string(kMaxTool));
  }
  return v;
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::size_t at = 0;
  while (true) {
    const auto next = s.find(sep, at);
    out.push_back(s.substr(at, next == std::string::npos ? std::string::npos : next - at));
    if (next == std::string::npos) return out;
    at = next + 1;
  }
}

void set_feature(ToolAssignment& a, const std::string& name, int tool, const std::string& what) {
  slicer::Feature f{};
  try {
    f = slicer::feature_from_string(name);
  } catch (const InputError&) {
    throw InputError(what + ": " + name.substr(0, 40) + " is not a feature (infill, wall, ligament, node, grip, frame, link)");
  }
  if (!a.by_feature.emplace(f, tool).second) throw InputError(what + ": " + name + " is given twice");
}

}  // namespace

int ToolAssignment::highest() const {
  int h = -1;
  for (const auto& [f, t] : by_feature) h = std::max(h, t);
  for (int t : by_layer) h = std::max(h, t);
  return h;
}

ToolAssignment tool_assignment_from_text(const std::string& text, const std::string& what) {
  const std::string w = what + " = " + text.substr(0, 80);
  if (text.empty() || text.size() > 400) throw InputError(w + ": must be " + kForms);
  ToolAssignment a;
  if (text.starts_with("layers=")) {
    for (const auto& t : split(text.substr(7), ',')) a.by_layer.push_back(tool_index(t, w));
    if (a.by_layer.size() > kMaxLayerCycle) throw InputError(w + ": at most 64 layers in the cycle");
    return a;
  }
  for (const auto& item : split(text, ',')) {
    const auto eq = item.find('=');
    if (eq == std::string::npos) throw InputError(w + ": must be " + kForms);
    set_feature(a, item.substr(0, eq), tool_index(item.substr(eq + 1), w), w);
  }
  return a;
}

ToolAssignment tool_assignment_from_json(const nlohmann::json& j, const std::string& what) {
  if (j.is_string()) return tool_assignment_from_text(j.get<std::string>(), what);
  const bool feature = j.is_object() && j.size() == 1 && j.contains("by_feature") && j.at("by_feature").is_object();
  const bool layer = j.is_object() && j.size() == 1 && j.contains("by_layer") && j.at("by_layer").is_array();
  if (!feature && !layer) {
    throw InputError(what + ": must be {\"by_feature\": {\"node\": 1, ...}} or {\"by_layer\": [0, 1]}");
  }
  ToolAssignment a;
  auto index = [&](const nlohmann::json& v) {
    if (!v.is_number_integer()) throw InputError(what + ": tools are whole numbers 0 to " + std::to_string(kMaxTool));
    return tool_index(std::to_string(v.get<long long>()), what);
  };
  if (feature) {
    for (const auto& [name, t] : j.at("by_feature").items()) set_feature(a, name, index(t), what);
  } else {
    if (j.at("by_layer").empty() || j.at("by_layer").size() > kMaxLayerCycle) {
      throw InputError(what + ".by_layer: 1 to 64 tools");
    }
    for (const auto& t : j.at("by_layer")) a.by_layer.push_back(index(t));
  }
  return a;
}

std::vector<slicer::Stroke> assign_tools(const std::vector<slicer::Stroke>& strokes, const ToolAssignment& a,
                                         int layer_index, int current) {
  std::vector<slicer::Stroke> cut;
  cut.reserve(strokes.size());
  for (const auto& s : strokes) {
    if (!a.by_layer.empty()) {
      cut.push_back(s);
      cut.back().tool = a.by_layer[static_cast<std::size_t>(layer_index) % a.by_layer.size()];
      continue;
    }
    auto tool_of = [&](const slicer::Segment& seg) {
      const auto it = a.by_feature.find(seg.feature);
      return it == a.by_feature.end() ? s.tool : it->second;
    };
    // The stroke without its segments, copied for each piece (copying the stroke itself for
    // each cut made a long strand cut at every node quadratic: minutes for a big lattice).
    slicer::Stroke blank = s;
    blank.segments = {};
    slicer::Stroke piece = blank;
    for (const auto& seg : s.segments) {
      const int t = tool_of(seg);
      if (!piece.segments.empty() && t != piece.tool) {
        const slicer::Vec2 at = piece.end_mm();
        cut.push_back(std::move(piece));
        piece = blank;
        piece.start_mm = at;
      }
      piece.tool = t;
      piece.segments.push_back(seg);
    }
    if (!piece.segments.empty()) cut.push_back(std::move(piece));
  }
  std::vector<int> order;
  for (const auto& s : cut) {
    if (std::find(order.begin(), order.end(), s.tool) == order.end()) order.push_back(s.tool);
  }
  std::sort(order.begin(), order.end(), [current](int x, int y) { return std::pair(x != current, x) < std::pair(y != current, y); });
  std::vector<slicer::Stroke> out;
  out.reserve(cut.size());
  for (int t : order) {
    for (auto& s : cut) {
      if (s.tool == t) out.push_back(std::move(s));
    }
  }
  return out;
}

}  // namespace strand::post
