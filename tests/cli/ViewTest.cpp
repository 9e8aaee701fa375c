// `shadowlab view` end to end, as a subprocess: without a display it exits 2 with one line before any window or
// frame; bad input is one line and exit 1, checked before the display; and under Xvfb a recorded session
// (tests/data/view/session.log, made by record_session.sh with `view --record`) drives the window: it switches
// technique and buffer, probes a pixel, changes a parameter and the light size and saves screenshots, which must
// show the pipeline's frame pixel for pixel, ring the probed pixel, and match the committed baselines
// (tests/data/view/baselines; SHADOWLAB_BLESS=1 rewrites them). The session is recorded again while it replays,
// and the recording must hold the same input events.
#include "io/ImageIO.h"
#include "metrics/RegressionComparison.h"
#include "support/CliRun.h"
#include "support/TempDir.h"
#include "support/TestSupport.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

namespace sl
{
namespace
{

namespace fs = std::filesystem;
using test::RunResult;
using test::TempDir;

fs::path viewData()
{
  return test::sourceDir() / "tests" / "data" / "view";
}

const char* const kBlessCommand = "SHADOWLAB_BLESS=1 build/tests/cli_tests --gtest_filter='ViewCommand.*'";

bool blessRequested()
{
  const char* value = std::getenv("SHADOWLAB_BLESS");
  return value != nullptr && std::string(value) == "1";
}

// The command line record_session.sh recorded session.log with, less --record and --screenshot-dir.
std::vector<std::string> viewArguments()
{
  return { "view", test::datasetPath("contact").string(), "--resolution", "128x128", "--technique", "pcf", "--set",
    "shadow_map_size=512" };
}

std::vector<std::string> with(std::vector<std::string> arguments, const std::vector<std::string>& more)
{
  arguments.insert(arguments.end(), more.begin(), more.end());
  return arguments;
}

// shadowlab under a fresh Xvfb (xvfb-run -a: the first free display from a number this process picks, so that
// parallel ctest processes rarely race for one), stdout and stderr captured.
RunResult runUnderXvfb(const std::vector<std::string>& arguments, const fs::path& workDir)
{
  RunResult result;
  const fs::path outFile = workDir.parent_path() / (".capture-" + workDir.filename().string() + ".stdout");
  const fs::path errFile = workDir.parent_path() / (".capture-" + workDir.filename().string() + ".stderr");
  std::string command = "cd " + test::shellQuote(workDir.string()) + " && exec xvfb-run -a -n " +
    std::to_string(100 + getpid() % 800) + " -s '-screen 0 1600x1200x24 -nolisten tcp' " +
    test::shellQuote(SL_SHADOWLAB_EXE);
  for (const std::string& argument : arguments)
  {
    command += " " + test::shellQuote(argument);
  }
  result.commandLine = command;
  const int status = std::system(("(" + command + ") >" + test::shellQuote(outFile.string()) + " 2>" +
    test::shellQuote(errFile.string()) + " </dev/null")
                                   .c_str());
  result.exitCode = (status != -1 && WIFEXITED(status)) ? WEXITSTATUS(status) : -1;
  result.out = test::readFile(outFile);
  result.err = test::readFile(errFile);
  fs::remove(outFile);
  fs::remove(errFile);
  return result;
}

// A nonzero exit `exitCode`, exactly one line on stderr mentioning `mentions`, nothing on stdout (no window, no
// session line), nothing written next to it.
void expectOneLineFailure(const RunResult& run, int exitCode, const std::vector<std::string>& mentions,
  const fs::path& workDir)
{
  EXPECT_EQ(run.exitCode, exitCode) << run.describe();
  EXPECT_EQ(run.errLines(), 1u) << run.describe();
  for (const std::string& mention : mentions)
  {
    EXPECT_NE(run.err.find(mention), std::string::npos) << "stderr should mention '" << mention << "'\n"
                                                        << run.describe();
  }
  EXPECT_EQ(run.out, "") << run.describe();
  EXPECT_EQ(test::joined(test::entriesOf(workDir)), "") << run.describe();
}

// Each pixel of `image` as a zoom x zoom block.
ImageU8 enlarged(const ImageU8& image, int zoom)
{
  ImageU8 result(image.width * zoom, image.height * zoom, image.components);
  for (int y = 0; y < result.height; ++y)
  {
    for (int x = 0; x < result.width; ++x)
    {
      for (int c = 0; c < image.components; ++c)
      {
        result.at(x, y, c) = image.at(x / zoom, y / zoom, c);
      }
    }
  }
  return result;
}

struct ScreenshotDifference
{
  double meanAbsDiff = 0.0; // over every channel of every pixel, 0..255 units
  RegressionComparison comparison;
};

ScreenshotDifference differenceOf(const ImageU8& actual, const ImageU8& expected, const RegressionTolerance& tolerance)
{
  ScreenshotDifference difference;
  difference.comparison = compareWithTolerance(actual, expected, tolerance);
  if (difference.comparison.sameSize)
  {
    double sum = 0.0;
    for (std::size_t i = 0; i < actual.data.size(); ++i)
    {
      sum += std::abs(static_cast<int>(actual.data[i]) - static_cast<int>(expected.data[i]));
    }
    difference.meanAbsDiff = sum / static_cast<double>(actual.data.size());
  }
  return difference;
}

// ---- no display, bad input --------------------------------------------------------------------------------

TEST(ViewCommand, WithoutADisplayExitsTwoWithOneLineBeforeAnyWindowOrFrame)
{
  TempDir temp;
  const std::vector<std::string> arguments = with(viewArguments(), { "--screenshot-dir", "shots" });
  expectOneLineFailure(test::runShadowlabIn(arguments, temp.path(), "unset DISPLAY"), 2,
    { "no display", "DISPLAY is not set" }, temp.path());
  // The display is checked before the pipeline starts: an EGL platform that cannot exist is never reached.
  expectOneLineFailure(test::runShadowlabIn(arguments, temp.path(), "unset DISPLAY; export SHADOWLAB_EGL=nowhere"), 2,
    { "no display" }, temp.path());
  // DISPLAY set, but no X server answers there.
  expectOneLineFailure(test::runShadowlabIn(arguments, temp.path(), "export DISPLAY=:4095"), 2,
    { "no display", "cannot open the X display ':4095'" }, temp.path());
}

TEST(ViewCommand, BadInputIsOneLineAndExitOneBeforeTheDisplayIsChecked)
{
  // Without a display, reaching the display check would exit 2: exit 1 shows the input was checked first.
  TempDir temp;
  TempDir elsewhere; // holds a file where --screenshot-dir wants a directory, outside the working directory
  const fs::path file = elsewhere.path() / "a-file";
  test::writeFile(file, "x");
  const auto expectFailure = [&](const std::vector<std::string>& arguments, const std::vector<std::string>& mentions) {
    SCOPED_TRACE(test::joined(arguments));
    expectOneLineFailure(test::runShadowlabIn(arguments, temp.path(), "unset DISPLAY"), 1, mentions, temp.path());
  };
  const std::string contact = test::datasetPath("contact").string();
  expectFailure({ "view", contact, "--technique", "nosuch" }, { "nosuch" });
  expectFailure({ "view", (temp.path() / "missing.json").string() }, { "missing.json" });
  expectFailure(with(viewArguments(), { "--set", "bogus=1" }), { "bogus" });
  expectFailure({ "view", contact, "--resolution", "0x8" }, { "--resolution" });
  expectFailure({ "view", contact, "--light", "3" }, { "--light 3" });
  expectFailure(with(viewArguments(), { "--play", "missing.log" }), { "--play", "missing.log" });
  expectFailure(with(viewArguments(), { "--record", "no/such/dir/session.log" }), { "--record" });
  expectFailure(with(viewArguments(), { "--screenshot-dir", file.string() }), { "--screenshot-dir" });
}

TEST(ViewCommand, RecordNeverReplacesAnInputNorAFileThatIsNotARecordingWithoutForce)
{
  // Checked after the scene is loaded and before the display: without one, exit 1 is a refusal and exit 2 means
  // the checks let the file through (and nothing was written yet).
  TempDir temp;
  fs::create_directories(temp.path() / "data");
  fs::copy(test::datasetPath("contact").parent_path(), temp.path() / "data", fs::copy_options::recursive);
  const std::string scene = (temp.path() / "data" / "scene.json").string();
  const std::string sceneBytes = test::readFile(scene);
  test::writeFile(temp.path() / "notes.txt", "my notes");
  test::writeFile(temp.path() / "old.log", "# StreamVersion 1.1\nExposeEvent 0 0 0 0 0 0\n");
  writePng(temp.path() / "b.png", ImageU8(8, 8, 3, 10));
  const auto view = [&](const std::vector<std::string>& more) {
    std::vector<std::string> arguments{ "view", scene, "--resolution", "16x16", "--technique", "hard" };
    arguments.insert(arguments.end(), more.begin(), more.end());
    return test::runShadowlabIn(arguments, temp.path(), "unset DISPLAY");
  };
  const auto expectExit = [](const RunResult& run, int exitCode, const std::string& mention) {
    EXPECT_EQ(run.exitCode, exitCode) << run.describe();
    EXPECT_EQ(run.errLines(), 1u) << run.describe();
    EXPECT_NE(run.err.find(mention), std::string::npos) << run.describe();
  };
  for (const bool force : { false, true })
  {
    const std::vector<std::string> forced = force ? std::vector<std::string>{ "--force" } : std::vector<std::string>{};
    SCOPED_TRACE(force ? "--force" : "no --force");
    expectExit(view(with({ "--record", scene }, forced)), 1, "an input");
    expectExit(view(with({ "--record", "data/../data/scene.json" }, forced)), 1, "an input");
    expectExit(view(with({ "--record", "old.log", "--play", "old.log" }, forced)), 1, "an input");
  }
  EXPECT_EQ(test::readFile(scene), sceneBytes);
  // A file parameter is an input too (ss08's budget image).
  const RunResult budget = test::runShadowlabIn({ "view", scene, "--resolution", "16x16", "--technique", "ss08",
                                                  "--set", "budget_map=image", "--set", "budget_image=b.png",
                                                  "--record", "b.png", "--force" },
    temp.path(), "unset DISPLAY");
  expectExit(budget, 1, "b.png");
  // Not a recording: refused without --force, let through with it; an earlier recording is let through.
  expectExit(view({ "--record", "notes.txt" }), 1, "--force");
  expectExit(view({ "--record", "notes.txt", "--force" }), 2, "no display");
  EXPECT_EQ(test::readFile(temp.path() / "notes.txt"), "my notes");
  expectExit(view({ "--record", "old.log" }), 2, "no display");
}

// ---- a recorded session under Xvfb ------------------------------------------------------------------------

TEST(ViewCommand, RecordedSessionDrivesTheWindowAndItsScreenshotsMatchTheBaselines)
{
  // The README's set-up installs Xvfb (scripts/bootstrap.sh): without it this test fails rather than skips, so CI
  // never passes a viewer it did not drive.
  ASSERT_EQ(std::system("command -v xvfb-run >/dev/null 2>&1"), 0)
    << "xvfb-run not found: apt-get install xvfb xauth (scripts/bootstrap.sh installs them)";
  TempDir temp;
  const RunResult run = runUnderXvfb(with(viewArguments(), { "--play", (viewData() / "session.log").string(),
                                                             "--record", "replayed.log", "--screenshot-dir", "shots" }),
    temp.path());
  ASSERT_EQ(run.exitCode, 0) << run.describe();
  EXPECT_EQ(run.err, "") << run.describe();

  // What the keys did, in order (one stdout line per action).
  const std::vector<std::string> actions = { "view: showing pcf, image",
    "view: screenshot shots/view-001-pcf-image.png = shadowlab render",
    "view: buffer visibility",
    "view: screenshot shots/view-002-pcf-visibility.png",
    "view: technique hard (Hard shadow mapping with depth biasing)",
    "view: probe (100, 37) hard: GPU visibility 0, twin 0 (agree",
    "view: parameter bias_constant_texels = 0.5",
    "view: parameter bias_constant_texels = 2 texel footprints (0 .. 64)",
    "view: light size 1\n",
    "view: buffer texel_ratio [pixels/texel]",
    "view: screenshot shots/view-003-hard-texel_ratio.png = shadowlab render " + test::datasetPath("contact").string() +
      " -t hard --set bias_constant_texels=2 --scene-set /lights/0/size=1 --resolution 128x128",
    "view: buffer visibility",
    "view: screenshot shots/view-004-hard-visibility.png",
    "h           print these keys",
    "view: keys shown in the window (h hides them) and printed on the terminal",
    "view: screenshot shots/view-005-hard-visibility.png",
    // hard's figure is three rows of panels (the compared texels' grid among them), two on show: f scrolls a row.
    "view: probe figure rows 2..3 of 3" };
  std::size_t at = 0;
  for (const std::string& action : actions)
  {
    const std::size_t found = run.out.find(action, at);
    ASSERT_NE(found, std::string::npos) << "missing, or out of order: '" << action << "'\n" << run.describe();
    at = found + action.size();
  }

  // Where the image lies in the window (the viewer says so), and the screenshots.
  std::smatch layout;
  ASSERT_TRUE(std::regex_search(run.out, layout,
    std::regex(R"(image pixel \(x, y\) at window pixel \((\d+) \+ (\d+)x, (\d+) \+ (\d+)y\))")))
    << run.describe();
  const int left = std::stoi(layout[1]);
  const int zoom = std::stoi(layout[2]);
  const int bottom = std::stoi(layout[3]);
  ASSERT_EQ(zoom, std::stoi(layout[4]));
  ASSERT_EQ(zoom, 2) << "a 128x128 frame is drawn 2 screen pixels per pixel (ViewerSession.cpp)";
  const std::vector<std::string> names = { "view-001-pcf-image.png", "view-002-pcf-visibility.png",
    "view-003-hard-texel_ratio.png", "view-004-hard-visibility.png", "view-005-hard-visibility.png" };
  ASSERT_EQ(test::joined(test::entriesOf(temp.path() / "shots")), test::joined(names)) << run.describe();
  std::vector<ImageU8> shots;
  for (const std::string& name : names)
  {
    shots.push_back(readPng(temp.path() / "shots" / name));
  }

  // The frame on show is the pipeline's, pixel for pixel: the shaded image and the visibility heat map that
  // `render` writes for the same settings, each pixel a zoom x zoom block at the place the viewer reported.
  const RunResult render = test::runShadowlabIn({ "render", test::datasetPath("contact").string(), "--resolution",
                                                  "128x128", "--technique", "pcf", "--set", "shadow_map_size=512",
                                                  "--out", "rendered", "--quiet" },
    temp.path());
  ASSERT_EQ(render.exitCode, 0) << render.describe();
  const ImageU8 image = enlarged(readPng(temp.path() / "rendered" / "image.png"), zoom);
  const ImageU8 heatMap =
    enlarged(readPng(temp.path() / "rendered" / "heatmap_visibility.png").crop(0, 0, 128, 128), zoom);
  const RegressionTolerance exact{ 0.0, 0.0 };
  for (const auto& [shot, expected, what] : { std::tuple{ &shots[0], &image, "image.png" },
         std::tuple{ &shots[1], &heatMap, "heatmap_visibility.png" } })
  {
    const ImageU8 shown = shot->crop(left, bottom, expected->width, expected->height);
    const RegressionComparison comparison = compareWithTolerance(shown, *expected, exact);
    EXPECT_TRUE(comparison.passes(exact)) << describeComparison(what, comparison, exact);
  }

  // The probed pixel (100, 37) is ringed in the marker colour two screen pixels outside its block, and the
  // probe figure fills the right panel, which showed only its hint before the click.
  const auto pixelAt = [](const ImageU8& shot, int x, int y) {
    return std::vector<int>{ shot.at(x, y, 0), shot.at(x, y, 1), shot.at(x, y, 2) };
  };
  const std::vector<int> magenta = { 255, 0, 255 };
  for (const ImageU8* shot : { &shots[2], &shots[3] })
  {
    EXPECT_EQ(pixelAt(*shot, left + 100 * zoom - 3, bottom + 37 * zoom - 3), magenta);
    EXPECT_EQ(pixelAt(*shot, left + 101 * zoom + 2, bottom + 38 * zoom + 2), magenta);
    EXPECT_NE(pixelAt(*shot, left + 100 * zoom, bottom + 37 * zoom), magenta);
  }
  // The right panel: grey only (its background and the hint's text) before the click, the figure's colours after.
  const auto colouredPixelsRightOfTheImage = [&](const ImageU8& shot) {
    int count = 0;
    for (int y = bottom; y < shot.height; ++y)
    {
      for (int x = shot.width / 2; x < shot.width; ++x) // within the right panel, past any colour key
      {
        const int r = shot.at(x, y, 0);
        const int g = shot.at(x, y, 1);
        const int b = shot.at(x, y, 2);
        count += std::max({ r, g, b }) - std::min({ r, g, b }) > 30 ? 1 : 0;
      }
    }
    return count;
  };
  EXPECT_EQ(colouredPixelsRightOfTheImage(shots[0]), 0) << "before the click: the panel's background and hint";
  EXPECT_GT(colouredPixelsRightOfTheImage(shots[3]), 2000) << "after the click: the probe figure";

  // The probe figure at full size (issue 31: it was shrunk to about 600 x 400): its white page covers most of the
  // right half of the window above the status.
  const auto isWhite = [&](const ImageU8& shot, int x, int y) {
    return shot.at(x, y, 0) == 255 && shot.at(x, y, 1) == 255 && shot.at(x, y, 2) == 255;
  };
  int whiteInRightPanel = 0;
  for (int y = bottom; y < shots[3].height; ++y)
  {
    for (int x = shots[3].width / 2; x < shots[3].width; ++x)
    {
      whiteInRightPanel += isWhite(shots[3], x, y) ? 1 : 0;
    }
  }
  EXPECT_GT(whiteInRightPanel, 300000) << "the probe figure is not at full size";
  // h: the keys over the probe panel on a dark backing (view-005), where the figure's white page was (view-004).
  const auto darkInTopRight = [&](const ImageU8& shot) {
    int count = 0;
    for (int y = shot.height - 200; y < shot.height - 8; ++y)
    {
      for (int x = shot.width - 1200; x < shot.width - 700; ++x)
      {
        count += std::max({ shot.at(x, y, 0), shot.at(x, y, 1), shot.at(x, y, 2) }) < 40 ? 1 : 0;
      }
    }
    return count;
  };
  EXPECT_GT(darkInTopRight(shots[4]), darkInTopRight(shots[3]) + 20000) << "h shows the keys in the window";

  // The same session recorded again while it replayed: the same input events (RenderEvent is VTK reporting a
  // render, not input: the screenshots' renders add some).
  const auto inputEvents = [](const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream stream(text);
    for (std::string line; std::getline(stream, line);)
    {
      if (line.rfind("RenderEvent", 0) != 0)
      {
        lines.push_back(line);
      }
    }
    return lines;
  };
  const std::vector<std::string> recorded = inputEvents(test::readFile(temp.path() / "replayed.log"));
  EXPECT_EQ(recorded, inputEvents(test::readFile(viewData() / "session.log")));
  EXPECT_GT(recorded.size(), 40u);

  // The baselines, within the tolerance stored beside them.
  const nlohmann::json toleranceData =
    nlohmann::json::parse(std::ifstream(viewData() / "baselines" / "tolerance.json"));
  const RegressionTolerance tolerance{ toleranceData.at("max_abs_diff").get<double>(),
    toleranceData.at("max_failing_fraction").get<double>() };
  const double maxMeanAbsDiff = toleranceData.at("max_mean_abs_diff").get<double>();
  const fs::path failures = test::testOutputDir() / "view";
  for (std::size_t i = 0; i < names.size(); ++i)
  {
    const fs::path baseline = viewData() / "baselines" / names[i];
    if (blessRequested())
    {
      fs::copy_file(temp.path() / "shots" / names[i], baseline, fs::copy_options::overwrite_existing);
      std::cout << "blessed " << baseline << "\n";
      continue;
    }
    ASSERT_TRUE(fs::is_regular_file(baseline)) << baseline << " missing: " << kBlessCommand << " writes it";
    const ImageU8 expected = readPng(baseline);
    const ScreenshotDifference difference = differenceOf(shots[i], expected, tolerance);
    const bool passes = difference.comparison.passes(tolerance) && difference.meanAbsDiff <= maxMeanAbsDiff;
    if (!passes)
    {
      fs::create_directories(failures);
      writePng(failures / names[i], shots[i]);
      if (difference.comparison.sameSize)
      {
        writePng(failures / ("diff-" + names[i]), amplifiedDifference(shots[i], expected));
      }
    }
    EXPECT_TRUE(passes) << describeComparison(names[i].c_str(), difference.comparison, tolerance)
                        << "; mean abs diff " << difference.meanAbsDiff << " (allowed " << maxMeanAbsDiff << "); "
                        << "the screenshot and its difference (x8) are in " << failures << "; if the change is "
                        << "intended: " << kBlessCommand;
  }
}

} // namespace
} // namespace sl
