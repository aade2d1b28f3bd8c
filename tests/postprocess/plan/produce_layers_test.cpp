// The layer-by-layer job (produce_layers) writes the bytes of the whole program planned at
// once (plan + produce_program): every generator's sample on every flat DIW profile, the
// preview copy included, kept in memory or streamed with its head given last.
#include <gtest/gtest.h>

#include <sstream>

#include "machines/builtin_profiles.h"
#include "patterns/registry.h"
#include "postprocess/plan/produce.h"
#include "slicer/input_error.h"
#include "tests/support/sample_jobs.h"

namespace strand::post {
namespace {

bool is_flat_diw(const machines::MachineProfile& m) {
  return !m.plotter.enabled && !m.robot.enabled && !m.rotary.enabled;
}

nlohmann::json sample_values(const patterns::GeneratorSpec& g) {
  const auto it = testing::sample_params().find(g.name);
  EXPECT_NE(it, testing::sample_params().end()) << g.name << " has no sample job";
  nlohmann::json params = it == testing::sample_params().end() ? nlohmann::json::object() : it->second;
  params.erase("height");
  params["layers"] = 6;  // several layers of each alternation, quickly
  return slicer::resolve_params(g.table(), params);
}

TEST(ProduceLayers, TheSameBytesAsTheWholeToolpathForEveryGeneratorAndPrinter) {
  int compared = 0;
  for (const auto& b : machines::builtin_profiles()) {
    const machines::MachineProfile m = machines::load_profile(b.name);
    if (!is_flat_diw(m)) continue;
    for (const auto& g : patterns::generators()) {
      SCOPED_TRACE(g.name + " on " + m.name);
      const nlohmann::json values = sample_values(g);
      const slicer::Toolpath whole = g.generate(values);
      const PlanOptions o = plan_options_from(whole, 0.01);
      Produced expected;
      try {
        expected = produce_program(whole, plan(whole, m, o), m, o, "x.gcode", true);
      } catch (const InputError& e) {
        // A part too big for this bed is refused the same way, layer by layer.
        auto source = g.layers(values);
        ProduceOptions po;
        EXPECT_THROW(produce_layers(*source, m, o, po), InputError) << e.what();
        continue;
      }
      auto source = g.layers(values);
      ProduceOptions po;
      po.gcode_path = "x.gcode";
      po.viewer_e = true;
      po.keep_program = true;
      const Produced in_memory = produce_layers(*source, m, o, po);
      EXPECT_EQ(in_memory.gcode, expected.gcode);
      EXPECT_EQ(in_memory.viewer_gcode, expected.viewer_gcode);
      EXPECT_EQ(in_memory.report.dump(), expected.report.dump());
      EXPECT_EQ(in_memory.summary, expected.summary);
      EXPECT_TRUE(in_memory.program == expected.program) << "the kept program is the whole one";

      std::ostringstream body, viewer_body;
      po.streams = {&body, &viewer_body};
      po.keep_program = false;
      auto again = g.layers(values);
      const Produced streamed = produce_layers(*again, m, o, po);
      EXPECT_TRUE(streamed.gcode.empty() && streamed.viewer_gcode.empty());
      EXPECT_TRUE(streamed.program.moves.empty()) << "nothing of the program is kept";
      EXPECT_EQ(streamed.gcode_head + body.str(), expected.gcode);
      EXPECT_EQ(streamed.viewer_gcode_head + viewer_body.str(), expected.viewer_gcode);
      EXPECT_TRUE(streamed.gcode_head.starts_with("; Strand " + g.name));
      EXPECT_TRUE(body.str().find(";LAYER:5\n") != std::string::npos);
      ++compared;
    }
  }
  EXPECT_GE(compared, 20) << "every generator on at least four printers";
}

// A sliced part can have empty layers (a sphere cap's first): the start position, the
// estimates and the file are still those of the whole program. Found by comparing slices of
// samples/meshes/sphere-cap.stl before and after the pipeline: the first empty layer gave
// the estimates a start at the origin.
TEST(ProduceLayers, EmptyLayersFirstAndBetweenChangeNothing) {
  slicer::Toolpath t;
  t.generator = "test";
  t.parameters = nlohmann::json::object();
  t.derived = nlohmann::json::object();
  auto stroke = [](double x) {
    slicer::Stroke s;
    s.start_mm = slicer::Vec2(x, 0);
    s.segments = {slicer::line_to(slicer::Vec2(x + 10, 0), slicer::Feature::Infill),
                  slicer::arc_to(slicer::Vec2(x + 10, 6), slicer::Vec2(x + 10, 3), true, slicer::Feature::Wall)};
    s.width_mm = 0.8;
    s.height_mm = 0.6;
    return s;
  };
  t.layers = {{0.6, 0.6, {}}, {1.2, 0.6, {stroke(-20), stroke(5)}}, {1.8, 0.6, {}}, {2.4, 0.6, {stroke(-10)}}};
  for (const char* name : {"deltawasp-2040-clay", "deltawasp-2040-clay-valve", "marlin-xyz-200"}) {
    SCOPED_TRACE(name);
    const machines::MachineProfile m = machines::load_profile(name);
    const PlanOptions o = plan_options_from(t, 0.01);
    const Produced whole = produce_program(t, plan(t, m, o), m, o, "x.gcode", true);
    slicer::ToolpathLayers source(t);
    ProduceOptions po;
    po.gcode_path = "x.gcode";
    po.viewer_e = true;
    const Produced layers = produce_layers(source, m, o, po);
    EXPECT_EQ(layers.gcode, whole.gcode);
    EXPECT_EQ(layers.viewer_gcode, whole.viewer_gcode);
    EXPECT_EQ(layers.report.dump(), whole.report.dump());
    EXPECT_GT(whole.report.at("totals").at("travel_length_mm").get<double>(), 0.0);
  }
}

// Layers are asked for one at a time, in order, each once: the source never has to hold
// the stack, and the planner has planned layer k - 1 before layer k is made.
class CountingLayers final : public slicer::LayerSource {
 public:
  CountingLayers(std::unique_ptr<slicer::LayerSource> inner, std::vector<std::size_t>& asked)
      : inner_(std::move(inner)), asked_(asked) {
    record = inner_->record;
  }
  std::size_t layer_count() const override { return inner_->layer_count(); }
  slicer::Layer layer(std::size_t index) override {
    asked_.push_back(index);
    return inner_->layer(index);
  }

 private:
  std::unique_ptr<slicer::LayerSource> inner_;
  std::vector<std::size_t>& asked_;
};

TEST(ProduceLayers, AsksForEachLayerOnceInOrder) {
  const auto* g = patterns::find_generator("scaffold");
  ASSERT_NE(g, nullptr);
  std::vector<std::size_t> asked;
  CountingLayers source(g->layers(sample_values(*g)), asked);
  const machines::MachineProfile m = machines::load_profile("deltawasp-2040-clay");
  produce_layers(source, m, plan_options_from(source.record, 0.01), {});
  ASSERT_EQ(asked.size(), 6u);
  for (std::size_t k = 0; k < asked.size(); ++k) EXPECT_EQ(asked[k], k);
}

}  // namespace
}  // namespace strand::post
