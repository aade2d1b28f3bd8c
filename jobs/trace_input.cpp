// Trace flags, tracing a file into pen layers, and those layers as a drawing.
#include "jobs/trace_input.h"

#include <charconv>
#include <cmath>
#include <cstdio>

#include "machines/gcode_format.h"
#include "slicer/file_io.h"
#include "slicer/image.h"
#include "slicer/input_error.h"

namespace strand::jobs {

const slicer::ParamTable& trace_table() {
  using slicer::ParamType;
  static const slicer::ParamTable kTable{
      "trace",
      {
          {"threshold", ParamType::Text, "",
           "grey (0 black .. 1 white) below which a pixel is ink, or adaptive (10 % darker than "
           "its neighbourhood)",
           std::nullopt, false, std::nullopt, false, nullptr,
           "Otsu's threshold of the image, 0.45 after --highpass"},
          {"highpass", ParamType::Number, "px",
           "subtract a Gaussian blur of this radius first, removing uneven lighting (mkbitmap -f; "
           "0 off)",
           0.0, false, 1000.0, false, 0.0},
          {"blur", ParamType::Number, "px",
           "then blur with a Gaussian of this radius (mkbitmap -b; 0 off)", 0.0, false, 1000.0,
           false, 0.0},
          {"upscale", ParamType::Integer, "",
           "then interpolate each pixel into N x N before the threshold (mkbitmap -s)", 1.0, false,
           8.0, false, 1},
          {"levels", ParamType::Integer, "",
           "pen layers: level k holds pixels darker than threshold * (N+1-k)/N, on pen k", 1.0,
           false, 8.0, false, 1},
          {"turdsize", ParamType::Integer, "px", "speckles up to this area are dropped", 0.0, false,
           1e6, false, 2},
          {"alphamax", ParamType::Number, "",
           "corner threshold: 0 polygons, 1.334 no corners (smoother curves)", 0.0, false, 1.3334,
           false, 1.0},
          {"opttolerance", ParamType::Number, "px",
           "curve joining tolerance, 0 keeps every potrace segment", 0.0, false, 10.0, false, 0.2},
          {"pixel-size", ParamType::Number, "mm",
           "size of one image pixel in the drawing (at least 10 steps of the output's 0.001 mm, "
           "so curves inside a pixel survive rounding)",
           0.01, false, 100.0, false, 0.25},
      }};
  return kTable;
}

slicer::TraceOptions trace_options(const nlohmann::json& v) {
  slicer::TraceOptions o;
  if (v.contains("threshold")) {
    const std::string t = v.at("threshold").is_string() ? v.at("threshold").get<std::string>()
                                                        : v.at("threshold").dump();
    if (t == "adaptive") {
      o.adaptive = true;
    } else {
      double g = 0.0;
      const auto r = std::from_chars(t.data(), t.data() + t.size(), g);
      if (r.ec != std::errc() || r.ptr != t.data() + t.size() || !(g > 0.0 && g <= 1.0)) {
        throw InputError("trace.threshold = " + t.substr(0, 40) +
                         ": must be a grey in (0, 1] or adaptive");
      }
      o.threshold = g;
    }
  }
  o.highpass_px = v.at("highpass").get<double>();
  o.blur_px = v.at("blur").get<double>();
  o.upscale = v.at("upscale").get<int>();
  o.levels = v.at("levels").get<int>();
  o.turdsize = v.at("turdsize").get<int>();
  o.alphamax = v.at("alphamax").get<double>();
  o.opttolerance = v.at("opttolerance").get<double>();
  o.pixel_mm = v.at("pixel-size").get<double>();
  return o;
}

TracedImage trace_file(const std::string& path, const slicer::TraceOptions& o,
                       slicer::Progress* progress) {
  return trace_bytes(slicer::read_file(path), path, o, progress);
}

TracedImage trace_bytes(const std::string& bytes, const std::string& label, const slicer::TraceOptions& o,
                        slicer::Progress* progress) {
  slicer::progress_phase(progress, "decoding");
  const slicer::GreyImage image = slicer::decode_image(bytes, label);
  TracedImage t;
  slicer::progress_phase(progress, "tracing");
  t.trace = slicer::trace_image(image, o);
  std::string greys, counts;
  for (std::size_t k = 0; k < t.trace.levels.size(); ++k) {
    const auto& level = t.trace.levels[k];
    const int g =
        static_cast<int>(std::lround(level.threshold * 255.0 / 2.0));  // mid-grey of the band
    char colour[8];
    std::snprintf(colour, sizeof colour, "#%02x%02x%02x", g, g, g);
    slicer::SvgShape s;
    s.element = "path";
    s.paths = level.paths;
    s.filled = true;
    s.evenodd = true;
    s.fill_color = colour;
    const std::string n = std::to_string(k + 1);
    if (!s.paths.empty()) t.layers.push_back({"m" + n, "level " + n, {s}});
    greys += (k ? ", " : "") + machines::fmt_fixed(level.threshold, 2);
    counts += (k ? " + " : "") + std::to_string(level.paths.size());
  }
  t.summary = std::to_string(t.trace.levels.size()) + " level(s) below grey " + greys + ": " +
              counts + " outline(s), " + std::to_string(image.width) + " x " +
              std::to_string(image.height) + " px";
  return t;
}

slicer::SvgDrawing drawing_of(const std::vector<slicer::SvgLayer>& layers,
                              const slicer::Vec2& size_mm) {
  slicer::SvgDrawing d;
  d.page_mm = size_mm;
  for (const auto& l : layers) {
    for (auto s : l.shapes) {
      s.group_ids = {l.id};
      s.layer_labels = {l.label};
      d.shapes.push_back(std::move(s));
    }
  }
  return d;
}

}  // namespace strand::jobs
