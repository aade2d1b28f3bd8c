// The contact sheet: a card per point with its thumbnail, values and links; sortable.
#include "jobs/sweep_index.h"

#include <gtest/gtest.h>

namespace strand::jobs {
namespace {

const nlohmann::json kManifest = {
    {"sweep", {{"generator", "scaffold"}, {"machine", "m"}, {"vary", {"nozzle"}}}},
    {"points",
     {{{"index", 0}, {"name", "s_nozzle-0.6"}, {"status", "ok"}, {"parameters", {{"nozzle", 0.6}}},
       {"output", "s_nozzle-0.6.gcode"}, {"preview", "previews/s_nozzle-0.6.png"},
       {"preview_html", "previews/s_nozzle-0.6.html"}, {"porosity", 0.634}, {"ink_volume_ml", 0.8},
       {"time_s", 12.0}, {"layers", 4}, {"check", {{"ok", true}}}},
      {{"index", 1}, {"name", "s_nozzle-<b>"}, {"status", "failed"}, {"parameters", {{"nozzle", 9}}},
       {"error", "too big"}}}}};

TEST(SweepIndex, OneCardPerPointWithLinks) {
  const std::string h = sweep_index_html(kManifest);
  EXPECT_NE(h.find("<img src=\"previews/s_nozzle-0.6.png\""), std::string::npos);
  EXPECT_NE(h.find("href=\"s_nozzle-0.6.gcode\""), std::string::npos);
  EXPECT_NE(h.find("href=\"previews/s_nozzle-0.6.html\""), std::string::npos);
  EXPECT_NE(h.find("63.4 %"), std::string::npos);
  EXPECT_NE(h.find("failed: too big"), std::string::npos);
  EXPECT_NE(h.find("s_nozzle-&lt;b&gt;"), std::string::npos) << "names are escaped";
  EXPECT_EQ(h.find("<b>\""), std::string::npos);
  EXPECT_NE(h.find("1 ok, 1 failed, 0 dropped"), std::string::npos);
}

TEST(SweepIndex, CardsCarrySortKeysForEveryVariedParameterAndFigure) {
  const std::string h = sweep_index_html(kManifest);
  EXPECT_NE(h.find("data-pnozzle=\"0.6\""), std::string::npos);
  EXPECT_NE(h.find("data-pporosity=\"0.634\""), std::string::npos);
  EXPECT_NE(h.find("<option value=\"pnozzle\">nozzle</option>"), std::string::npos);
  EXPECT_EQ(h.find("http"), std::string::npos) << "no network";
}

}  // namespace
}  // namespace strand::jobs
