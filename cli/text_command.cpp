// `strand text "STRING" --size MM -o OUT.svg|OUT.gcode`: lettering for specimens and
// drawings, in a single-stroke Hershey font or an installed outline font, written as an
// SVG (to place in a drawing) or plotted straight to pen G-code.
#include <iostream>
#include <memory>
#include <utility>

#include "cli/commands.h"
#include "cli/param_flags.h"
#include "jobs/plot_pipeline.h"
#include "slicer/file_io.h"
#include "slicer/input_error.h"
#include "slicer/json_input.h"
#include "slicer/svg_export.h"
#include "slicer/text_layout.h"

namespace strand::cli {

using jobs::PlotRequest;
using jobs::PlotResult;
using jobs::draw_text_into;
using jobs::plot_drawing;

namespace {

const slicer::ParamTable& text_table() {
  using slicer::ParamType;
  static const slicer::ParamTable kTable{
      "text",
      {
          {"size", ParamType::Number, "mm", "font size (the em; capitals of the Hershey simplex fonts are 0.66 of it; at least 0.1 mm: smaller letters collapse at the output's 0.001 mm steps)", 0.1, false, 1000.0, false, 5.0},
          {"font", ParamType::Text, "", "hershey:NAME (single stroke: futural, rowmans, scripts, timesr, ...) or an installed font family (outline, filled)", std::nullopt, false, std::nullopt, false, "hershey:futural"},
          {"anchor", ParamType::Text, "", "which end of each line sits at the origin", std::nullopt, false, std::nullopt, false, "start", "", {"start", "middle", "end"}},
          {"line-spacing", ParamType::Number, "", "distance between lines (\\n in STRING) in font sizes", 0.5, false, 10.0, false, 1.25},
          {"fill", ParamType::Text, "", "outline fonts in G-code: outline plus hatch or rings, outline only", std::nullopt, false, std::nullopt, false, "hatch", "", {"hatch", "concentric", "outline"}},
          {"offset", ParamType::NumberList, "mm", "G-code: X,Y shift from the centre of the drawable area", std::nullopt, false, std::nullopt, false, nlohmann::json::array({0, 0})},
      }};
  return kTable;
}

// Characters of the string (a label or a few lines: this is 10 pages); a drawing's <text>
// may hold up to slicer::kMaxSvgTextChars.
constexpr std::size_t kMaxTextChars = 20'000;

struct TextArgs {
  std::string text, output, report, machine = "xy-plotter-servo";
  ParamFlags flags;
};

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// The string as an SVG text in mm: one chunk per line ("\n" typed or a real newline).
slicer::SvgText text_element(const std::string& text, const nlohmann::json& v) {
  slicer::TextStyle style;
  style.font_size = v.at("size").get<double>();
  const std::string anchor = v.at("anchor").get<std::string>();
  style.anchor = anchor == "middle" ? slicer::TextAnchor::Middle : anchor == "end" ? slicer::TextAnchor::End : slicer::TextAnchor::Start;
  slicer::SvgText t;
  t.filled = true;
  t.fill_color = "#000000";
  std::string s = text;
  for (std::size_t at = s.find("\\n"); at != std::string::npos; at = s.find("\\n", at + 1)) s.replace(at, 2, "\n");
  const std::u32string chars = slicer::utf8_to_u32(s);
  if (chars.size() > kMaxTextChars) {
    throw InputError("text: the string has " + std::to_string(chars.size()) +
                     " characters (at most " + std::to_string(kMaxTextChars) + ")");
  }
  bool line_start = true;
  int line = 0;
  for (char32_t c : chars) {
    if (c == U'\n') {
      line_start = true;
      ++line;
      continue;
    }
    slicer::TextChar tc;
    tc.code = c;
    tc.style = style;
    if (line_start) {
      tc.x = 0.0;
      tc.y = line * v.at("line-spacing").get<double>() * style.font_size;
    }
    line_start = false;
    t.chars.push_back(tc);
  }
  if (t.chars.empty()) throw InputError("text: the string is empty");
  return t;
}

int run_text(const TextArgs& a) {
  const nlohmann::json v = slicer::resolve_params(text_table(), given_params(text_table(), a.flags));
  const bool svg = ends_with(a.output, ".svg"), gcode = ends_with(a.output, ".gcode");
  if (!svg && !gcode) throw InputError("text.output = " + a.output + ": must end in .svg or .gcode");
  slicer::TextOptions to;
  to.font = v.at("font").get<std::string>();
  to.mode = slicer::hershey_name(to.font).empty() ? slicer::TextMode::Outline : slicer::TextMode::Hershey;
  PlotRequest r;
  r.input = "text \"" + a.text + "\"";
  r.parameters = v;
  r.drawing.texts.push_back(text_element(a.text, v));
  draw_text_into(r, to);
  if (r.drawing.shapes.empty()) throw InputError("text: nothing to draw (the font has no glyph for any character)");
  std::string out, summary;
  slicer::OutputFiles files;
  if (svg) {
    out = slicer::write_svg({{"m1", "text", r.drawing.shapes}}, 0.1 * v.at("size").get<double>(), 0.3);
    summary = "  " + r.notes.front().first + std::string(11, ' ') + r.notes.front().second + "\n";
  } else {
    r.options.fill = post::fill_style_from_string(v.at("fill").get<std::string>());
    r.options.offset_mm = slicer::Vec2(v["offset"][0].get<double>(), v["offset"][1].get<double>());
    const machines::MachineProfile m = machines::load_profile(a.machine);
    PlotResult p = plot_drawing(std::move(r), m);
    out = p.gcode;
    summary = p.summary;
    p.report["gcode"] = a.output;
    if (!a.report.empty()) files.stage(a.report, slicer::dump_json(p.report) + "\n");
  }
  files.stage(a.output, out);
  files.commit();
  std::cout << "text -> " << a.output << (gcode ? " (" + a.machine + ")" : "") << "\n" << summary;
  return 0;
}

}  // namespace

void add_text_command(CLI::App& app, Action& action) {
  auto a = std::make_shared<TextArgs>();
  CLI::App* sub = app.add_subcommand("text", "lettering -> SVG or pen plotter G-code");
  sub->add_option("string", a->text, "the text; \\n starts a new line")->required();
  a->output = "text.svg";
  sub->add_option("-o,--output", a->output, "OUT.svg (paths in mm) or OUT.gcode (plotted on --machine); default text.svg");
  sub->add_option("--machine", a->machine, "plotter profile for G-code output (default xy-plotter-servo)");
  sub->add_option("--report", a->report, "G-code output: write a JSON report here");
  add_param_flags(sub, text_table(), a->flags);
  sub->callback([&action, a] { action = [a] { return run_text(*a); }; });
}

}  // namespace strand::cli
