// The workbench's drawings: the /draw page and POST /api/plot (Api::State::route_plot), a
// multipart upload (an SVG, an image to trace, or the page's canvas as SVG) plotted for a pen
// plotter exactly as `strand plot` plots it, on the worker pool, optionally kept in the gallery.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "serve/api.h"

namespace strand::serve {

// One plot as the form asks for it: fields file (an SVG or an image) or svg (SVG text),
// machine, name, mirror, order, and the flags of `strand plot` and `strand trace` by their
// long names, each converted as the command line converts them.
struct PlotForm {
  std::string drawing;                // the SVG text or the image's bytes
  std::string input = "drawing.svg";  // the server's name for it (.svg, .png, .jpg, .img)
  bool image = false;                 // traced (the trace flags apply) rather than imported
  std::string machine = "xy-plotter-servo";
  std::string name;  // "" = not kept in the gallery
  bool mirror = false, order = true;
  nlohmann::json plot_given = nlohmann::json::object();   // plot flags, parsed, unresolved
  nlohmann::json trace_given = nlohmann::json::object();  // trace flags, parsed, unresolved
  nlohmann::json fields = nlohmann::json::object();       // options as written, for "open to edit"
};

// Throws InputError naming the first bad field ("plot.tolerance = 99: must be in ..."), or
// HttpError 413 past kMaxUploadBytes. The client's file name is read by nothing.
PlotForm read_plot_form(const Request& r);

}  // namespace strand::serve
