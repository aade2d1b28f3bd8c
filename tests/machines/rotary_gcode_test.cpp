#include "machines/rotary_gcode.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "patterns/registry.h"
#include "postprocess/inspect/gcode_parser.h"
#include "postprocess/plan/produce_curved.h"
#include "slicer/units.h"
#include "tests/support/cli_runner.h"
#include "tests/support/sample_jobs.h"

namespace strand::machines {
namespace {

using slicer::Vec3;

post::CurvedProduced rotary_sample(const MachineProfile& m) {
  const auto j = nlohmann::json::parse(
      testing::slurp(testing::samples_dir() + "/scaffold-cylinder-rotary.json"));
  const auto* g = patterns::find_generator(j.at("generator"));
  const auto t = g->generate(slicer::resolve_params(g->table(), j.at("params")));
  return post::produce_curved(t, *slicer::substrate_from(j.at("substrate")), m, 0.01, "r.gcode");
}

// The contact on the workpiece for a nozzle position and A angle, as the header describes.
Vec3 contact(const Vec3& tip, double a_deg, const RotaryAxis& r) {
  const Vec3 rel = tip - r.axis_point_mm;
  return Eigen::AngleAxisd(-slicer::deg_to_rad(a_deg), r.axis_dir) * rel;
}

struct Timed {
  double length_mm = 0.0, minutes = 0.0;
};

// Surface length and firmware time of every deposit, reading F as the profile says.
std::vector<Timed> deposits(const std::string& gcode, const MachineProfile& m) {
  const auto parsed = post::parse_gcode(gcode);
  std::vector<Timed> out;
  Vec3 at = parsed.program.start_mm;
  double a = 0.0;
  for (std::size_t i = 0; i < parsed.program.moves.size(); ++i) {
    const auto& mv = parsed.program.moves[i];
    const double a_next = parsed.a_deg[i];
    if (mv.kind == slicer::MoveKind::Deposit) {
      const double xyz = (mv.end_mm - at).norm();
      const double f = mv.feed_mm_per_min;
      const double minutes =
          m.rotary.inverse_time ? 1.0 / f : (xyz > 0 ? xyz : std::abs(a_next - a)) / f;
      out.push_back(
          {(contact(mv.end_mm, a_next, m.rotary) - contact(at, a, m.rotary)).norm(), minutes});
    }
    at = mv.end_mm;
    a = a_next;
  }
  return out;
}

void expect_surface_speed(const MachineProfile& m) {
  const auto p = rotary_sample(m);
  const std::string& g = p.files.front().second;
  const double planned = 400.0;  // the sample's speed, mm/min, below every cap of the profile
  double len = 0.0, minutes = 0.0;
  int checked = 0;
  for (const auto& d : deposits(g, m)) {
    len += d.length_mm, minutes += d.minutes;
    if (d.length_mm < 0.2) continue;  // 0.001 mm rounding of shorter moves exceeds 1 %
    EXPECT_NEAR(d.length_mm / d.minutes, planned, planned * 0.01);
    ++checked;
  }
  EXPECT_GT(checked, 1000);
  EXPECT_NEAR(len / minutes, planned, planned * 0.002);
}

TEST(RotaryGcode, MarlinFeedsGiveThePlannedSurfaceSpeed) {
  expect_surface_speed(load_profile("marlin-rotary-a"));
}

TEST(RotaryGcode, InverseTimeFeedsGiveThePlannedSurfaceSpeed) {
  MachineProfile m = load_profile("marlin-rotary-a");
  m.firmware = Firmware::RepRap;
  m.rotary.inverse_time = true;
  expect_surface_speed(m);
  EXPECT_NE(rotary_sample(m).files.front().second.find("\nG93 "), std::string::npos);
}

TEST(RotaryGcode, HeaderLetsAReaderMapMovesBackOntoTheCylinder) {
  const auto p = rotary_sample(load_profile("marlin-rotary-a"));
  const std::string& g = p.files.front().second;
  for (const char* want : {"\n;ROTARY_AXIS:A\n", "\n;ROTARY_AXIS_DIR:1.000,0.000,0.000\n",
                           "\n;ROTARY_AXIS_POINT:20.000,100.000,60.000\n",
                           "\n;SUBSTRATE:cylinder radius=25.0000 length=60.0000\n", "\n;LAYER:0\n",
                           "\n;LAYER_CHANGE\n", "\n;TYPE:"}) {
    EXPECT_NE(g.find(want), std::string::npos) << want;
  }
  // Every deposit is on top of the cylinder, at its layer's radius.
  const auto parsed = post::parse_gcode(g);
  const RotaryAxis& r = load_profile("marlin-rotary-a").rotary;
  for (std::size_t i = 0; i < parsed.program.moves.size(); ++i) {
    const auto& mv = parsed.program.moves[i];
    if (mv.kind != slicer::MoveKind::Deposit) continue;
    const Vec3 rel = mv.end_mm - r.axis_point_mm;
    EXPECT_NEAR(rel.y(), 0.0, 1e-9) << "above the axis";
    const double layer_radius = 25.0 + (mv.layer + 1) * p.program.layers[0].height_mm;
    EXPECT_NEAR(rel.z(), layer_radius, 1.5e-3);
  }
}

}  // namespace
}  // namespace strand::machines
