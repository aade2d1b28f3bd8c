// Manifests: CSV columns and quoting, shard merge order and its refusals.
#include "jobs/sweep_manifest.h"

#include <gtest/gtest.h>

#include "slicer/input_error.h"

namespace strand::jobs {
namespace {

SweepSpec spec() {
  return sweep_spec_from_json({{"job", {{"generator", "scaffold"}, {"params", {{"size", "20x20"}, {"height", 3}}}}},
                               {"vary", {{"nozzle", {0.6, 0.84, 1.0}}}}});
}

nlohmann::json row(int index, const std::string& status) {
  nlohmann::json r = {{"index", index}, {"name", "p" + std::to_string(index)}, {"status", status},
                      {"parameters", {{"nozzle", 0.6 + index}}}};
  if (status == "ok") {
    r.update({{"output", "p.gcode"}, {"content_hash", "00"}, {"porosity", 0.5}, {"ink_volume_ml", 1.0},
              {"time_s", 2.0}, {"layers", 3}, {"strands_per_layer", {1, 1, 1}},
              {"derived", {{"footprint_mm", {20, 20}}}}, {"check", {{"ok", true}, {"crossings", 0}}}});
  } else {
    r["error"] = "scaffold.size = 1,2: \"quoted\"";
  }
  return r;
}

TEST(SweepManifest, CsvHasOneLinePerPointAndQuotesCommas) {
  const auto m = make_manifest(spec(), {}, {row(0, "ok"), row(1, "failed")}, Shard{});
  const std::string csv = manifest_csv(m);
  EXPECT_EQ(csv.substr(0, csv.find('\n')),
            "index,name,status,nozzle,porosity,ink_volume_ml,time_s,layers,strands_per_layer,derived.footprint_mm,"
            "check_ok,crossings,output,content_hash,error");
  EXPECT_NE(csv.find("\n0,p0,ok,0.6,0.5,1,2,3,1 1 1,20 20,true,0,p.gcode,00,\n"), std::string::npos) << csv;
  EXPECT_NE(csv.find(",\"scaffold.size = 1,2: \"\"quoted\"\"\"\n"), std::string::npos) << csv;
}

TEST(SweepManifest, MergeOrdersRowsByIndexAndDropsTheShardKey) {
  const SweepSpec s = spec();
  const auto a = make_manifest(s, {}, {row(0, "ok"), row(2, "ok")}, Shard{1, 2});
  const auto b = make_manifest(s, {}, {row(1, "failed")}, Shard{2, 2});
  const auto merged = merge_manifests({b, a}, {"b", "a"});
  EXPECT_EQ(merged, make_manifest(s, {}, {row(0, "ok"), row(1, "failed"), row(2, "ok")}, Shard{}));
}

TEST(SweepManifest, MergeRefusesMixedSweepsDuplicatesAndGaps) {
  const SweepSpec s = spec();
  const auto a = make_manifest(s, {}, {row(0, "ok")}, Shard{1, 2});
  const auto other = make_manifest(s, {{"other", 1}}, {row(1, "ok")}, Shard{2, 2});
  EXPECT_THROW(merge_manifests({a, other}, {"a", "other"}), InputError);
  EXPECT_THROW(merge_manifests({a, a}, {"a", "a2"}), InputError);
  EXPECT_THROW(merge_manifests({a}, {"a"}), InputError);
  EXPECT_THROW(merge_manifests({make_manifest(s, {}, {}, Shard{})}, {"whole"}), InputError);
}

}  // namespace
}  // namespace strand::jobs
