// Progress output: a redrawn bar on a terminal, plain lines otherwise; ETA clock text.
#include "cli/progress.h"

#include <gtest/gtest.h>

#include <sstream>

namespace strand::cli {
namespace {

TEST(Progress, PlainLinesWithoutATerminal) {
  std::ostringstream out;
  ProgressBar bar(out, false);
  bar.update(1, 3, 0, "a", "ok");
  bar.update(2, 3, 1, "b", "failed: boom");
  bar.finish();
  EXPECT_EQ(out.str(), "sweep: 1/3 a ok\nsweep: 2/3 b failed: boom\n");
}

TEST(Progress, TerminalBarRedrawsInPlaceAndKeepsFailures) {
  std::ostringstream out;
  ProgressBar bar(out, true);
  bar.update(1, 2, 0, "a", "ok");
  bar.update(2, 2, 1, "b", "failed: boom");
  bar.finish();
  const std::string s = out.str();
  EXPECT_NE(s.find("\r[###############...............] 1/2"), std::string::npos) << s;
  EXPECT_NE(s.find("] 2/2, 1 failed"), std::string::npos) << s;
  EXPECT_NE(s.find("b failed: boom\n"), std::string::npos) << s;
  EXPECT_NE(s.find("ETA"), std::string::npos);
  EXPECT_EQ(s.back(), '\n');
}

TEST(Progress, ClockText) {
  EXPECT_EQ(clock_text(0), "0:00");
  EXPECT_EQ(clock_text(65.4), "1:05");
  EXPECT_EQ(clock_text(3600 * 12 + 3), "12:00:03");
}

}  // namespace
}  // namespace strand::cli
