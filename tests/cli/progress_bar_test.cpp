// Progress output: a redrawn bar on a terminal, plain lines otherwise; ETA clock text.
#include "cli/progress_bar.h"

#include <gtest/gtest.h>

#include <sstream>
#include <stdexcept>

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

// A clock the test moves by hand.
struct FakeClock {
  double now = 100.0;
  PhaseProgress::Clock clock() {
    return [this] { return now; };
  }
};

TEST(PhaseProgress, PlainLinesOnlyOnceTheRunPassesTheThreshold) {
  std::ostringstream out;
  FakeClock t;
  {
    PhaseProgress p(out, false, "slice", 4, 1.0, t.clock());
    p.phase("reading the mesh");
    t.now += 0.5;
    p.phase("slicing");
    EXPECT_EQ(out.str(), "") << "a short run stays silent";
    t.now += 0.7;
    p.phase("filling layers", 10);
    for (std::size_t k = 1; k <= 10; ++k) p.step(k);
    t.now += 2.0;
    p.phase("planning");
  }
  EXPECT_EQ(out.str(),
            "slice: 3/4 filling layers (1.2 s)\n"
            "slice: 4/4 planning (3.2 s)\n"
            "slice: done in 3.2 s\n");
}

TEST(PhaseProgress, ALongPhaseIsNamedByItsFirstStepPastTheThreshold) {
  std::ostringstream out;
  FakeClock t;
  PhaseProgress p(out, false, "check", 2, 1.0, t.clock());
  p.phase("checking", 100);
  p.step(1);
  t.now += 1.5;
  p.step(50);
  p.step(51);
  p.finish();
  EXPECT_EQ(out.str(), "check: 1/2 checking (1.5 s)\ncheck: done in 1.5 s\n");
}

TEST(PhaseProgress, QuickRunPrintsNothingAtAll) {
  std::ostringstream out;
  FakeClock t;
  PhaseProgress p(out, false, "plot", 3, 1.0, t.clock());
  p.phase("laying out");
  p.phase("planning");
  p.finish();
  EXPECT_EQ(out.str(), "");
}

TEST(PhaseProgress, TerminalBarShowsPhaseStepsAndTimeLeftThenErasesItself) {
  std::ostringstream out;
  FakeClock t;
  PhaseProgress p(out, true, "slice", 2, 1.0, t.clock());
  p.phase("filling layers", 4);
  t.now += 1.0;
  p.step(2);  // half of phase 1 of 2: a quarter done after 1 s, 3 s left
  const std::string s = out.str();
  EXPECT_NE(s.find("\r\033[Kslice [....................] 1/2 filling layers 0/4  0:00 elapsed"),
            std::string::npos)
      << s;
  EXPECT_NE(s.find("\r\033[Kslice [#####...............] 1/2 filling layers 2/4  0:01 elapsed, 0:03 left"),
            std::string::npos)
      << s;
  EXPECT_EQ(s.find('\n'), std::string::npos) << "redrawn in place";
  p.clear();
  EXPECT_TRUE(out.str().ends_with("\r\033[K"));
  t.now += 0.01;
  p.step(3);  // within 0.1 s of the last drawing: not redrawn
  EXPECT_TRUE(out.str().ends_with("\r\033[K"));
  t.now += 1.0;
  p.phase("planning");
  p.finish();
  EXPECT_TRUE(out.str().ends_with("\r\033[K")) << "no bar is left behind";
  EXPECT_EQ(out.str().find('\n'), std::string::npos);
}

TEST(PhaseProgress, TerminalLineIsCutToTheWidth) {
  std::ostringstream out;
  FakeClock t;
  PhaseProgress p(out, true, "preview", 1, 1.0, t.clock(), 30);
  p.phase("drawing a very long phase name that would wrap");
  const std::string s = out.str();
  EXPECT_EQ(s.size(), std::string("\r\033[K").size() + 29) << s;
}

TEST(PhaseProgress, AnErrorLeavesNoDoneLine) {
  std::ostringstream out;
  FakeClock t;
  try {
    PhaseProgress p(out, false, "slice", 2, 1.0, t.clock());
    t.now += 2.0;
    p.phase("slicing");
    throw std::runtime_error("bad mesh");
  } catch (const std::runtime_error&) {
  }
  EXPECT_EQ(out.str(), "slice: 1/2 slicing (2.0 s)\n");
}

}  // namespace
}  // namespace strand::cli
