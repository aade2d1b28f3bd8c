// Lattice checks on parsed G-code (tests only).
#include "tests/support/lattice_checks.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "machines/profile.h"
#include "postprocess/inspect/crossings.h"
#include "postprocess/plan/estimate.h"
#include "postprocess/plan/produce.h"
#include "slicer/input_error.h"
#include "tests/support/gcode_view.h"

namespace strand::testing {

EmittedPart emit_on_delta(const slicer::ParamTable& table,
                          slicer::Toolpath (*make)(const nlohmann::json&), const nlohmann::json& given) {
  EmittedPart e;
  e.toolpath = make(slicer::resolve_params(table, given));
  const auto m = machines::load_profile("deltawasp-2040-clay");
  e.gcode = post::produce(e.toolpath, m, post::plan_options_from(e.toolpath, 0.01), "x.gcode").gcode;
  e.parsed = post::parse_gcode(e.gcode);
  return e;
}

std::string input_error_of(const slicer::ParamTable& table,
                           slicer::Toolpath (*make)(const nlohmann::json&), const nlohmann::json& given) {
  try {
    emit_on_delta(table, make, given);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

std::pair<slicer::Vec2, slicer::Vec2> deposit_bounds(const slicer::MotionProgram& p, int layer) {
  slicer::Vec2 lo(1e9, 1e9), hi(-1e9, -1e9);
  for (const auto& s : deposit_segments(p)) {
    if (s.layer != layer) continue;
    for (const slicer::Vec3& q : {s.a, s.b}) lo = lo.cwiseMin(q.head<2>()), hi = hi.cwiseMax(q.head<2>());
  }
  return {lo, hi};
}

double min_gap_between_unjoined(const slicer::MotionProgram& p, int layer) {
  std::vector<DepositSeg> segs;
  for (const auto& s : deposit_segments(p)) {
    if (s.layer == layer) segs.push_back(s);
  }
  double gap = 1e9;
  for (std::size_t i = 0; i < segs.size(); ++i) {
    const slicer::Vec2 a = segs[i].a.head<2>(), b = segs[i].b.head<2>();
    for (std::size_t j = i + 1; j < segs.size(); ++j) {
      const slicer::Vec2 c = segs[j].a.head<2>(), d = segs[j].b.head<2>();
      const double joined = std::min({(a - c).norm(), (a - d).norm(), (b - c).norm(), (b - d).norm()});
      if (joined < 2e-3) continue;
      gap = std::min({gap, slicer::point_segment_distance(a, c, d), slicer::point_segment_distance(b, c, d),
                      slicer::point_segment_distance(c, a, b), slicer::point_segment_distance(d, a, b)});
    }
  }
  return gap;
}

void expect_sound_lattice(const EmittedPart& e, const std::string& what) {
  SCOPED_TRACE(what);
  const auto c = post::find_contacts(e.parsed.program, 0.01, 1e-3);
  EXPECT_TRUE(c.crossings.empty()) << c.crossings.size() << " crossings, first at "
                                   << (c.crossings.empty() ? slicer::Vec2(0, 0) : c.crossings[0].at_mm).transpose();
  const auto est = post::estimate(e.parsed.program);
  ASSERT_EQ(est.layers.size(), e.toolpath.layers.size());
  for (const auto& l : est.layers) {
    EXPECT_EQ(l.strands, e.toolpath.derived.at("strands_per_layer").get<int>()) << "layer " << l.layer;
    EXPECT_EQ(l.strands, 1) << "layer " << l.layer;
  }
  const auto [lo, hi] = deposit_bounds(e.parsed.program, 0);
  const auto& fp = e.toolpath.derived.at("footprint_mm");
  const double d = e.toolpath.parameters.at("nozzle").get<double>();
  EXPECT_NEAR(hi.x() - lo.x() + d, fp[0].get<double>(), 0.01);
  EXPECT_NEAR(hi.y() - lo.y() + d, fp[1].get<double>(), 0.01);
  EXPECT_NEAR(hi.x() + lo.x(), 0.0, 0.01) << "centred";
  EXPECT_NEAR(hi.y() + lo.y(), 0.0, 0.01) << "centred";
  EXPECT_GE(min_gap_between_unjoined(e.parsed.program, 0), d - 2e-3)
      << "filaments that are not joined keep a nozzle apart";
}

}  // namespace strand::testing
