// The comments a G-code reader takes data from: layer markers and heights, feature roles
// and widths, pens and their colours, printheads' offsets (gcode_reader.h).
#include <charconv>
#include <cmath>

#include "postprocess/inspect/gcode_reader.h"
#include "postprocess/inspect/gcode_text.h"

namespace strand::post {

namespace gcode {

void Reader::comment(std::string_view c, int) {
  if (starts_with(trim(c), "extruder_offset = ")) {
    tool_offsets(trim(c).substr(18));
    return;
  }
  if (starts_with(c, "LAYER_CHANGE")) {
    new_layer(std::nullopt);
  } else if (starts_with(c, "LAYER:")) {
    if (!marker_pending_) new_layer(std::nullopt);
    marker_pending_ = false;
  } else if (starts_with(c, "Z:") && !out_.program.layers.empty()) {
    double z = 0;
    std::from_chars(c.data() + 2, c.data() + c.size(), z);
    out_.program.layers.back().z_mm = z;
    layer_z_known_ = true;
  } else if (starts_with(c, "HEIGHT:") && !out_.program.layers.empty()) {
    double h = 0;
    std::from_chars(c.data() + 7, c.data() + c.size(), h);
    out_.program.layers.back().height_mm = h;
  } else if (starts_with(c, "TYPE:")) {
    feature_ = feature_from_role(c.substr(5));
  } else if (starts_with(c, "FEATURE:")) {
    feature_ = feature_from_comment(trim(c.substr(8)), feature_);
  } else if (starts_with(c, "WIDTH:")) {
    std::from_chars(c.data() + 6, c.data() + c.size(), width_);
  } else if (starts_with(c, "PEN:")) {  // Strand's pen G-code: pen k from here on
    int k = 0;
    const auto r = std::from_chars(c.data() + 4, c.data() + c.size(), k);
    if (r.ec == std::errc() && k >= 1 && k <= kMaxPens) tool_ = static_cast<std::int16_t>(k - 1);
  } else {
    pen_colour(trim(c));
  }
}

// "0x0,35x0": per printhead x and y, mm; at most 64 heads, anything unreadable ignored whole.
void Reader::tool_offsets(std::string_view c) {
  std::vector<slicer::Vec2> offsets;
  while (!c.empty() && offsets.size() < 64) {
    const auto comma = c.find(',');
    const std::string_view item = c.substr(0, comma);
    const auto x = item.find('x');
    double a = 0, b = 0;
    if (x == std::string_view::npos) return;
    const auto ra = std::from_chars(item.data(), item.data() + x, a);
    const auto rb = std::from_chars(item.data() + x + 1, item.data() + item.size(), b);
    if (ra.ec != std::errc() || rb.ec != std::errc() || !std::isfinite(a) || !std::isfinite(b) || std::abs(a) > 1e4 ||
        std::abs(b) > 1e4) {
      return;
    }
    offsets.emplace_back(a * scale_, b * scale_);
    if (comma == std::string_view::npos) break;
    c.remove_prefix(comma + 1);
  }
  tool_offsets_ = std::move(offsets);
}

void Reader::pen_colour(std::string_view c) {
  if (!starts_with(c, "pen ")) return;
  int k = 0;
  const auto r = std::from_chars(c.data() + 4, c.data() + c.size(), k);
  if (r.ec != std::errc() || k < 1 || k > kMaxPens) return;
  const std::string_view rest = c.substr(static_cast<std::size_t>(r.ptr - c.data()));
  if (!starts_with(rest, " colour: #") || rest.size() != 16) return;
  const std::string_view hex = rest.substr(10);
  if (hex.find_first_not_of("0123456789abcdefABCDEF") != std::string_view::npos) return;
  auto& colours = out_.pen_colours;
  if (colours.size() < static_cast<std::size_t>(k)) colours.resize(static_cast<std::size_t>(k));
  colours[static_cast<std::size_t>(k - 1)] = "#" + std::string(hex);
}

}  // namespace gcode

}  // namespace strand::post
