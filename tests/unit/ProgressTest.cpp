// core/Progress.h on a simulated clock: a run expected to outlast the threshold prints the estimate after the first
// unit, a line per interval with the time left, and a final line; a short run and a run without a stream print
// nothing, and ask the pass to wait for the GPU only before and after the first unit (none without a stream).
#include "core/Progress.h"

#include <gtest/gtest.h>

#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace sl
{
namespace
{

std::vector<std::string> lines(const std::string& text)
{
  std::vector<std::string> result;
  std::istringstream stream(text);
  for (std::string line; std::getline(stream, line);)
  {
    result.push_back(line);
  }
  return result;
}

// Runs `total` units of `secondsPerUnit` each; returns what was printed, counting the waits asked for.
std::string simulate(std::size_t total, double secondsPerUnit, double announceAfter, int& syncs)
{
  double clock = 100.0;
  ProgressSettings settings;
  settings.announceAfterSeconds = announceAfter;
  settings.intervalSeconds = 5.0;
  settings.clock = [&clock] { return clock; };
  std::ostringstream out;
  Progress progress("reference-sm", "2000000 triangles x 64 maps", "map", total, &out, settings);
  syncs = progress.needsSync(0) ? 1 : 0;
  progress.begin();
  for (std::size_t done = 1; done <= total; ++done)
  {
    clock += secondsPerUnit;
    syncs += progress.needsSync(done) ? 1 : 0;
    progress.step(done);
  }
  progress.finish();
  return out.str();
}

TEST(Progress, ALongRunPrintsTheEstimateProgressAndAFinalLine)
{
  int syncs = 0;
  const std::string text = simulate(64, 2.0, 20.0, syncs); // 128 s expected
  std::cout << text << "waits for the GPU: " << syncs << "\n";
  const std::vector<std::string> printed = lines(text);
  ASSERT_GE(printed.size(), 3u);
  EXPECT_EQ(printed.front(), "shadowlab: reference-sm: 2000000 triangles x 64 maps, expect about 128 s on this "
                             "machine (measured: 1 map in 2.0 s)");
  EXPECT_EQ(printed[1], "shadowlab: reference-sm: 4/64 maps, 8.0 s elapsed, about 120 s left");
  EXPECT_EQ(printed.back(), "shadowlab: reference-sm: 64 maps in 128 s");
  // A line at least 5 s after the last (every third map at 2 s a map): maps 4, 7, ..., 61, besides the estimate
  // and the final line.
  EXPECT_EQ(printed.size(), 1u + 20u + 1u);
  // A wait before the first map and after it; then, the run being long, one per map.
  EXPECT_EQ(syncs, 2 + 63);
}

TEST(Progress, AShortRunPrintsNothingAndWaitsOnlyAroundTheFirstUnit)
{
  int syncs = 0;
  const std::string text = simulate(64, 0.25, 20.0, syncs); // 16 s expected, under the 20 s threshold
  std::cout << "printed: \"" << text << "\", waits for the GPU: " << syncs << "\n";
  EXPECT_EQ(text, "");
  EXPECT_EQ(syncs, 2); // before the first map and after it, none after

}

// The settings the CLI's --progress uses (cli/CommandProgress.cpp): no threshold, no interval, the total always.
ProgressSettings everyUnitSettings(double& clock)
{
  ProgressSettings settings;
  settings.announceAfterSeconds = 0.0;
  settings.intervalSeconds = 0.0;
  settings.alwaysReportTotal = true;
  settings.clock = [&clock] { return clock; };
  return settings;
}

TEST(Progress, AskedForEveryUnitItPrintsALinePerUnitWithElapsedAndLeft)
{
  double clock = 10.0;
  std::ostringstream out;
  Progress progress("bench", "3 configuration(s)", "configuration", 3, &out, everyUnitSettings(clock));
  for (std::size_t done = 1; done <= 3; ++done)
  {
    clock += 2.0;
    progress.step(done);
  }
  progress.finish();
  EXPECT_EQ(out.str(),
    "shadowlab: bench: 3 configuration(s), expect about 6.0 s on this machine (measured: 1 configuration in 2.0 s)\n"
    "shadowlab: bench: 2/3 configurations, 4.0 s elapsed, about 2.0 s left\n"
    "shadowlab: bench: 3 configurations in 6.0 s\n");
}

TEST(Progress, ARunDoneAtItsFirstReportPrintsOnlyItsTotalWhenAskedTo)
{
  double clock = 10.0;
  std::ostringstream asked;
  Progress reported("reference", "16x16 pixels x 4 samples", "row", 16, &asked, everyUnitSettings(clock));
  clock += 0.5;
  reported.step(16);
  reported.finish();
  EXPECT_EQ(asked.str(), "shadowlab: reference: 16 rows in 0.5 s\n");
  // Without alwaysReportTotal (a terminal's settings), such a run prints nothing.
  std::ostringstream terminal;
  ProgressSettings settings = everyUnitSettings(clock);
  settings.alwaysReportTotal = false;
  Progress quiet("reference", "16x16 pixels x 4 samples", "row", 16, &terminal, settings);
  clock += 0.5;
  quiet.step(16);
  quiet.finish();
  EXPECT_EQ(terminal.str(), "");
}

TEST(Progress, WithoutAStreamNothingIsPrintedAndNoWaitIsAsked)
{
  setProgressStream(nullptr);
  Progress progress("dcs", "1000000 triangles", "wedge chunk", 16);
  EXPECT_FALSE(progress.needsSync(0));
  for (std::size_t done = 1; done <= 16; ++done)
  {
    EXPECT_FALSE(progress.needsSync(done));
    progress.step(done);
  }
  progress.finish();
  EXPECT_FALSE(progress.announced());
}

} // namespace
} // namespace sl
