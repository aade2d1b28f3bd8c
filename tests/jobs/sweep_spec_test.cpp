// Sweep files: ranges, product and zip expansion, names, constraints, shards, bad input.
#include "jobs/sweep_spec.h"

#include <gtest/gtest.h>

#include "slicer/input_error.h"

namespace strand::jobs {
namespace {

nlohmann::json sweep(nlohmann::json vary, nlohmann::json extra = nlohmann::json::object()) {
  nlohmann::json j = {{"job", {{"generator", "scaffold"}, {"params", {{"size", "20x20"}, {"height", 3}}}}},
                      {"vary", std::move(vary)}};
  j.update(extra);
  return j;
}

std::string error_of(const nlohmann::json& j) {
  try {
    expand_points(sweep_spec_from_json(j));
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(SweepSpec, RangeHitsItsEndDespiteBinaryRounding) {
  const auto v = range_values({{"from", 0.8}, {"to", 1.6}, {"step", 0.4}}, "r");
  ASSERT_EQ(v.size(), 3u);
  EXPECT_EQ(v[2].get<double>(), 1.6);  // exactly, not 1.6000000000000001
  const auto d = range_values({{"from", 0.3}, {"to", 0.1}, {"step", -0.1}}, "r");
  ASSERT_EQ(d.size(), 3u);
  EXPECT_EQ(d[1].get<double>(), 0.2);
  const auto i = range_values({{"from", 2}, {"to", 10}, {"step", 4}}, "r");
  ASSERT_EQ(i.size(), 3u);
  EXPECT_TRUE(i[2].is_number_integer());
}

TEST(SweepSpec, ProductVariesTheLastKeyFastestAndNamesFromValues) {
  const auto points = expand_points(sweep_spec_from_json(
      sweep({{"nozzle", {0.6, 0.84}}, {"gap", {{"from", 0.8}, {"to", 1.6}, {"step", 0.4}}}})));
  ASSERT_EQ(points.size(), 6u);
  EXPECT_EQ(points[0].name, "scaffold_gap-0.8_nozzle-0.6");
  EXPECT_EQ(points[1].name, "scaffold_gap-0.8_nozzle-0.84");
  EXPECT_EQ(points[5].name, "scaffold_gap-1.6_nozzle-0.84");
  EXPECT_EQ(points[5].params.at("size"), "20x20");
  EXPECT_EQ(points[5].params.at("gap").get<double>(), 1.6);
}

TEST(SweepSpec, ZipPairsValuesAndNeedsEqualLengths) {
  const auto points = expand_points(
      sweep_spec_from_json(sweep({{"nozzle", {0.6, 0.84}}, {"gap", {1.0, 1.6}}}, {{"mode", "zip"}})));
  ASSERT_EQ(points.size(), 2u);
  EXPECT_EQ(points[1].varied, (nlohmann::json{{"gap", 1.6}, {"nozzle", 0.84}}));
  EXPECT_NE(error_of(sweep({{"nozzle", {0.6, 0.84}}, {"gap", {1.0}}}, {{"mode", "zip"}})).find("sweep.vary.nozzle"),
            std::string::npos);
}

TEST(SweepSpec, WhereDropsPointsWithTheReason) {
  const auto points = expand_points(sweep_spec_from_json(
      sweep({{"nozzle", {0.6, 1.2}}, {"gap", {0.8, 1.6}}}, {{"where", {"gap >= nozzle"}}})));
  int dropped = 0;
  for (const auto& p : points) {
    const bool should_drop = p.varied.at("gap").get<double>() < p.varied.at("nozzle").get<double>();
    EXPECT_EQ(!p.dropped.empty(), should_drop) << p.name;
    if (should_drop) {
      EXPECT_NE(p.dropped.find("gap >= nozzle"), std::string::npos);
    }
    dropped += should_drop;
  }
  EXPECT_EQ(dropped, 1);
}

struct BadSweep {
  const char* name;
  nlohmann::json sweep;
  const char* must_mention;
};

class SweepSpecBadInput : public ::testing::TestWithParam<BadSweep> {};

TEST_P(SweepSpecBadInput, ThrowsNamingTheKeyPath) {
  const std::string e = error_of(GetParam().sweep);
  EXPECT_NE(e.find(GetParam().must_mention), std::string::npos) << e;
}

INSTANTIATE_TEST_SUITE_P(
    Cases, SweepSpecBadInput,
    ::testing::Values(
        BadSweep{"unknown_parameter", sweep({{"nozle", {0.4}}}), "sweep.vary.nozle: unknown parameter"},
        BadSweep{"empty_list", sweep({{"nozzle", nlohmann::json::array()}}), "sweep.vary.nozzle: empty list"},
        BadSweep{"step_zero", sweep({{"gap", {{"from", 1}, {"to", 2}, {"step", 0}}}}), "sweep.vary.gap.step = 0"},
        BadSweep{"wrong_sign", sweep({{"gap", {{"from", 2.0}, {"to", 1.0}, {"step", 0.5}}}}), "sweep.vary.gap.step = 0.5: must have the sign"},
        BadSweep{"no_vary", sweep(nlohmann::json::object()), "sweep.vary"},
        BadSweep{"unknown_key", sweep({{"nozzle", {0.4}}}, {{"vari", 1}}), "sweep.vari: unknown key"},
        BadSweep{"bad_mode", sweep({{"nozzle", {0.4}}}, {{"mode", "cartesian"}}), "sweep.mode = cartesian"},
        BadSweep{"where_unknown_name", sweep({{"nozzle", {0.4}}}, {{"where", {"gapp >= nozzle"}}}), "sweep.where[0]"},
        BadSweep{"where_drops_all", sweep({{"nozzle", {0.4}}}, {{"where", {"nozzle > 1"}}}), "sweep.where: drops every one"},
        BadSweep{"duplicate_value", sweep({{"nozzle", {0.4, 0.4}}}), "sweep.vary: two points"},
        BadSweep{"unknown_base_parameter",
                 nlohmann::json{{"job", {{"generator", "scaffold"}, {"params", {{"nozle", 1}}}}}, {"vary", {{"gap", {1}}}}},
                 "sweep.job.params.nozle: unknown parameter"},
        BadSweep{"bad_generator", nlohmann::json{{"job", {{"generator", "nope"}}}, {"vary", {{"a", {1}}}}}, "sweep.job.generator = nope"}),
    [](const auto& info) { return std::string(info.param.name); });

TEST(SweepShard, ParsesAndRejectsOutsideOneToN) {
  EXPECT_EQ(parse_shard("2/3").index, 2);
  for (const char* bad : {"0/3", "4/3", "1/0", "a/b", "3", "1/3x", "-1/3"}) {
    EXPECT_THROW(parse_shard(bad), InputError) << bad;
  }
}

TEST(SweepShard, ShardsPartitionThePoints) {
  for (int p = 0; p < 20; ++p) {
    int owners = 0;
    for (int i = 1; i <= 3; ++i) owners += in_shard(p, Shard{i, 3});
    EXPECT_EQ(owners, 1) << p;
  }
}

}  // namespace
}  // namespace strand::jobs
