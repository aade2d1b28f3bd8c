// Fuzz target: any bytes as an image for `strand trace`: decoded (stb_image, libnetpbm) and,
// when small, traced with potrace into two levels and laid out as `plot --trace` would.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "machines/profile.h"
#include "postprocess/plot/plot_layout.h"
#include "slicer/image.h"
#include "slicer/input_error.h"
#include "slicer/trace.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace strand;
  static const machines::MachineProfile machine = machines::load_profile("xy-plotter-servo");
  try {
    const slicer::GreyImage image =
        slicer::decode_image(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz");
    // Decoding is what hostile bytes reach; tracing a large legal image is slow, not wrong.
    if (static_cast<long>(image.width) * image.height > 256L * 256) return 0;
    slicer::TraceOptions options;
    options.levels = 2;
    const slicer::Trace trace = slicer::trace_image(image, options);
    slicer::SvgDrawing drawing;
    for (const auto& level : trace.levels) {
      slicer::SvgShape shape;
      shape.element = "path";
      shape.paths = level.paths;
      shape.filled = true;
      shape.evenodd = true;
      shape.fill_color = "#000000";
      if (!shape.paths.empty()) drawing.shapes.push_back(shape);
    }
    post::PlotOptions plot;
    plot.fit_mm = slicer::Vec2(100, 100);
    if (!drawing.shapes.empty()) post::layout_plot(drawing, machine, plot);
  } catch (const InputError&) {
    // Refused with a message: the expected outcome for bad input.
  }
  return 0;
}
