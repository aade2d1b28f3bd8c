// Fuzz target: any bytes as an SVG drawing (style sheets and text included), imported, its
// text laid out in the Hershey font, and laid out on an XY plotter at its own size (no fit:
// hostile coordinates reach flattening and hatching as they are).
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "machines/profile.h"
#include "postprocess/plot/plot_layout.h"
#include "slicer/input_error.h"
#include "slicer/svg_import.h"
#include "slicer/text_layout.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace strand;
  static const machines::MachineProfile machine = machines::load_profile("xy-plotter-servo");
  try {
    slicer::SvgDrawing drawing =
        slicer::import_svg(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.svg");
    for (auto& s : slicer::layout_text(drawing.texts, slicer::TextOptions{}).shapes)
      drawing.shapes.push_back(std::move(s));
    post::layout_plot(drawing, machine, post::PlotOptions{});
  } catch (const InputError&) {
    // Refused with a message: the expected outcome for bad input.
  }
  return 0;
}
