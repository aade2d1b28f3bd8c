// Fuzz target: any bytes as an SVG drawing, imported and laid out on an XY plotter at its
// own size (no fit: hostile coordinates reach flattening and hatching as they are).
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "machines/profile.h"
#include "postprocess/plot/plot_layout.h"
#include "slicer/input_error.h"
#include "slicer/svg_import.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace strand;
  static const machines::MachineProfile machine = machines::load_profile("xy-plotter-servo");
  try {
    const slicer::SvgDrawing drawing =
        slicer::import_svg(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz.svg");
    post::layout_plot(drawing, machine, post::PlotOptions{});
  } catch (const InputError&) {
    // Refused with a message: the expected outcome for bad input.
  }
  return 0;
}
