// `shadowlab montage` and `shadowlab lessons` end to end (issue 15, items 3 and 4), run as subprocesses:
//  - a montage of two real runs is the documented size, draws every valid pixel of both panels with the ONE scale
//    whose ends are the global min and max of the runs' stats.json (symmetric about 0 for a signed buffer), and
//    bad inputs are one-line errors that leave no file;
//  - each lesson, regenerated at 64x64 (one ctest case per lesson), writes a page whose every measured number
//    equals the value at the JSON pointer it names in the run's stats.json, whose figures are readable PNGs and
//    whose commands are real shadowlab commands (techniques, settings, scene overrides and datasets that exist).
#include "core/Error.h"
#include "io/ImageIO.h"
#include "lessons/LessonRegistry.h"
#include "lessons/RunMontage.h"
#include "scene/Scene.h"
#include "support/CliRun.h"
#include "support/TempDir.h"
#include "support/TestSupport.h"
#include "techniques/Registry.h"
#include "vis/Canvas.h"
#include "vis/Montage.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace sl
{
namespace
{

namespace fs = std::filesystem;
using Json = nlohmann::json;
using test::RunResult;
using test::TempDir;

using test::readJson;

// ---- montage --------------------------------------------------------------------------------------------------

// Three runs rendered once for the montage tests: two techniques with different map sizes (so texel_ratio's
// maxima differ about fourfold) and hard without bias (depth_margin, a signed buffer, in two runs).
class MontageCommand : public ::testing::Test
{
protected:
  static void SetUpTestSuite()
  {
    runs_ = new TempDir;
    const std::string grazing = test::datasetPath("grazing").string();
    for (const auto& [name, arguments] : std::vector<std::pair<std::string, std::vector<std::string>>>{
           { "hard", { "-t", "hard", "--set", "shadow_map_size=2048" } },
           { "pcf", { "-t", "pcf", "--set", "shadow_map_size=512" } },
           { "hard-bias-off", { "-t", "hard", "--set", "bias_constant_texels=0", "--set", "bias_slope_texels=0" } },
         })
    {
      std::vector<std::string> command = { "render", grazing, "-r", "64x64", "--out", name, "-q" };
      command.insert(command.end(), arguments.begin(), arguments.end());
      const RunResult run = test::runShadowlabIn(command, runs_->path());
      ASSERT_EQ(run.exitCode, 0) << run.describe();
    }
  }
  static void TearDownTestSuite()
  {
    delete runs_;
    runs_ = nullptr;
  }
  static fs::path run(const std::string& name) { return runs_->path() / name; }

  // The one-line failure contract: nonzero exit, one line naming every `mentions`, and nothing written into
  // `temp` (no PNG, no temporary sibling).
  static void expectCleanFailure(const TempDir& temp, const std::vector<std::string>& arguments,
    const std::vector<std::string>& mentions, const std::string& prelude = "")
  {
    const auto before = test::entriesOf(temp.path());
    const RunResult result = test::runShadowlabIn(arguments, temp.path(), prelude);
    EXPECT_NE(result.exitCode, 0) << result.describe();
    EXPECT_EQ(result.errLines(), 1u) << result.describe();
    for (const std::string& mention : mentions)
    {
      EXPECT_NE(result.err.find(mention), std::string::npos) << "stderr should mention '" << mention << "'\n"
                                                             << result.describe();
    }
    EXPECT_EQ(result.err.find(".shadowlab-partial"), std::string::npos) << result.describe();
    EXPECT_EQ(test::entriesOf(temp.path()), before)
      << "a failed montage left files: " << test::joined(test::entriesOf(temp.path())) << "\n" << result.describe();
  }

  static TempDir* runs_;
};
TempDir* MontageCommand::runs_ = nullptr;

// The scale montage reported on stderr: "... scale [min, max], WxH px -> FILE".
ValueRange reportedScale(const std::string& err)
{
  static const std::regex pattern(R"(scale \[([^,\]]+), ([^\]]+)\])");
  std::smatch match;
  EXPECT_TRUE(std::regex_search(err, match, pattern)) << err;
  return match.empty() ? ValueRange{} : ValueRange{ std::stod(match[1]), std::stod(match[2]) };
}

bool near(double a, double b, double relative = 1e-6)
{
  return std::abs(a - b) <= relative * std::max({ 1.0, std::abs(a), std::abs(b) });
}

int colourDistance(const ImageU8& image, int x, int y, const std::array<std::uint8_t, 3>& rgb)
{
  int distance = 0;
  for (int c = 0; c < 3; ++c)
  {
    distance = std::max(distance, std::abs(int(image.at(x, y, c)) - int(rgb[c])));
  }
  return distance;
}

// The panels montage builds from run directories (values, coverage, labels), to lay the PNG out the same way.
std::vector<MontagePanel> panelsOf(const std::vector<fs::path>& dirs, const std::string& buffer)
{
  std::vector<MontagePanel> panels;
  std::vector<std::string> names;
  std::vector<Json> stats;
  for (const fs::path& dir : dirs)
  {
    const std::vector<NamedImage> buffers = readVti(dir / "buffers.vti");
    stats.push_back(readJson(dir / "stats.json"));
    const NamedImage& values = *findNamed(buffers, buffer);
    panels.push_back({ values.image, runValueMask(buffers, values, runBufferSpec(stats.back(), buffer)), {} });
    names.push_back(dir.filename().string());
  }
  const auto labels = montageRunLabels(names, stats);
  for (std::size_t p = 0; p < panels.size(); ++p)
  {
    panels[p].labels = labels[p];
  }
  return panels;
}

// What montage lists once in its title band for these runs.
std::vector<std::string> commonOf(const std::vector<fs::path>& dirs)
{
  std::vector<Json> stats;
  for (const fs::path& dir : dirs)
  {
    stats.push_back(readJson(dir / "stats.json"));
  }
  return montageCommonLabels(stats);
}

// The value of rank floor(q (n - 1)) among the panels' pixels with a value (|value| with `magnitudes`): the
// percentiles the robust scale ends at (vis/HeatMap.h heatMapScale).
double panelQuantile(const std::vector<MontagePanel>& panels, double q, bool magnitudes)
{
  std::vector<double> values;
  for (const MontagePanel& panel : panels)
  {
    for (std::size_t i = 0; i < panel.values.pixelCount(); ++i)
    {
      if (panel.validMask.data[i] == 1)
      {
        values.push_back(magnitudes ? std::abs(double(panel.values.data[i])) : double(panel.values.data[i]));
      }
    }
  }
  std::sort(values.begin(), values.end());
  return values.at(static_cast<std::size_t>(q * static_cast<double>(values.size() - 1)));
}

TEST_F(MontageCommand, TwoTechniquesShareOneRobustScaleOverBothRuns)
{
  TempDir temp;
  const RunResult result = test::runShadowlabIn(
    { "montage", run("hard").string(), run("pcf").string(), "--buffer", "texel_ratio", "--out", "m.png" }, temp.path());
  ASSERT_EQ(result.exitCode, 0) << result.describe();
  EXPECT_EQ(result.errLines(), 1u) << result.describe();
  EXPECT_EQ(test::entriesOf(temp.path()), std::vector<std::string>{ "m.png" }) << "a temporary file was left";

  // The scale's ends are the 0.5th and 99.5th percentiles of texel_ratio over both runs' shadow-tested pixels
  // (texel_ratio is declared on them: the faces turned from the light hold no ratio).
  const Json hard = readJson(run("hard") / "stats.json")["buffers"]["texel_ratio"];
  const Json pcf = readJson(run("pcf") / "stats.json")["buffers"]["texel_ratio"];
  ASSERT_GT(pcf["max"].get<double>(), 2.0 * hard["max"].get<double>()) << "the runs should differ in their maxima";
  const std::vector<MontagePanel> panels = panelsOf({ run("hard"), run("pcf") }, "texel_ratio");
  const double globalMin = panelQuantile(panels, kRobustTail, false);
  const double globalMax = panelQuantile(panels, 1.0 - kRobustTail, false);
  const ValueRange scale = reportedScale(result.err);
  EXPECT_TRUE(near(scale.min, globalMin)) << scale.min << " vs " << globalMin;
  EXPECT_TRUE(near(scale.max, globalMax)) << scale.max << " vs " << globalMax;

  // The documented layout: panels 1:1, the size montageLayout gives for these panels.
  const ImageU8 png = readPng(temp.path() / "m.png");
  MontageOptions options;
  options.title = "texel_ratio";
  options.unit = "pixels/texel";
  options.commonLines = commonOf({ run("hard"), run("pcf") });
  const MontageLayout layout = montageLayout(panels, options);
  ASSERT_EQ(png.width, layout.width);
  ASSERT_EQ(png.height, layout.height);
  EXPECT_GE(png.width, 2 * 64 + layout.paddingPx * 3);
  EXPECT_NEAR(layout.colorRange.min, globalMin, 1e-5);
  EXPECT_NEAR(layout.colorRange.max, globalMax, 1e-5);

  // Every pixel with a value of both panels has viridis((v - min) / (max - min)) on the shared scale (clamped),
  // the untested ones the not-applicable grey; at most 2 % of the pixels with a value saturate.
  const ColorMap viridis(ColorMapKind::Viridis);
  const auto top = toRgb8(viridis.map(1.0));
  int saturated = 0, valued = 0, notApplicable = 0;
  for (std::size_t p = 0; p < panels.size(); ++p)
  {
    int wrong = 0;
    for (int y = 0; y < 64; ++y)
      for (int x = 0; x < 64; ++x)
      {
        const int px = layout.panelLeft[p] + x;
        const int py = layout.panelBottom + y;
        const std::uint8_t mark = panels[p].validMask.at(x, y);
        const auto expected = mark == 1
          ? toRgb8(viridis.map((panels[p].values.at(x, y) - globalMin) / (globalMax - globalMin)))
          : toRgb8(mark == kNotApplicablePixel ? kNotApplicableColor : kInvalidPixelColor);
        wrong += colourDistance(png, px, py, expected) > 1;
        valued += mark == 1;
        notApplicable += mark == kNotApplicablePixel;
        saturated += mark == 1 &&
          (colourDistance(png, px, py, top) == 0 || colourDistance(png, px, py, toRgb8(viridis.map(0.0))) == 0);
      }
    EXPECT_EQ(wrong, 0) << "panel " << p << ": pixels off the shared scale";
  }
  std::cout << "texel_ratio montage: " << saturated << " of " << valued << " pixels saturate, " << notApplicable
            << " not tested\n";
  EXPECT_LE(100.0 * saturated / valued, 2.0);
  // The colour bar beside the panels runs from the bottom colour to the top colour.
  bool barHasBottom = false, barHasTop = false;
  for (int y = 0; y < png.height; ++y)
    for (int x = layout.keyLeft; x < png.width; ++x)
    {
      barHasBottom = barHasBottom || colourDistance(png, x, y, toRgb8(viridis.map(0.0))) <= 1;
      barHasTop = barHasTop || colourDistance(png, x, y, top) <= 1;
    }
  EXPECT_TRUE(barHasBottom && barHasTop);
}

TEST_F(MontageCommand, ASignedBufferIsCentredOnZeroAndDiverging)
{
  TempDir temp;
  const RunResult result = test::runShadowlabIn({ "montage", run("hard").string(), run("hard-bias-off").string(),
                                                  "--buffer", "depth_margin", "--out", "signed.png" },
    temp.path());
  ASSERT_EQ(result.exitCode, 0) << result.describe();
  EXPECT_NE(result.err.find("signed scale"), std::string::npos) << result.err;
  // m = the 99.5th percentile of |depth_margin| over both runs' shadow-tested pixels.
  const std::vector<MontagePanel> panels = panelsOf({ run("hard"), run("hard-bias-off") }, "depth_margin");
  const double magnitude = panelQuantile(panels, 1.0 - kRobustTail, true);
  const ValueRange scale = reportedScale(result.err);
  EXPECT_TRUE(near(scale.min, -magnitude)) << scale.min << " vs " << -magnitude;
  EXPECT_TRUE(near(scale.max, magnitude)) << scale.max << " vs " << magnitude;
  // Pixels of value 0 would be white; a pixel's colour is the diverging map's at (v + m) / 2m.
  const ImageU8 png = readPng(temp.path() / "signed.png");
  MontageOptions options;
  options.title = "depth_margin";
  options.unit = "world units";
  options.kind = BufferKind::Signed;
  options.commonLines = commonOf({ run("hard"), run("hard-bias-off") });
  const MontageLayout layout = montageLayout(panels, options);
  ASSERT_EQ(png.width, layout.width);
  const ColorMap diverging(ColorMapKind::Diverging);
  int wrong = 0;
  for (std::size_t p = 0; p < panels.size(); ++p)
    for (int y = 0; y < 64; ++y)
      for (int x = 0; x < 64; ++x)
        if (panels[p].validMask.at(x, y) == kNotApplicablePixel)
        {
          const auto grey = toRgb8(kNotApplicableColor);
          wrong += colourDistance(png, layout.panelLeft[p] + x, layout.panelBottom + y, grey) > 0;
        }
        else if (panels[p].validMask.at(x, y))
        {
          const double t = (panels[p].values.at(x, y) + magnitude) / (2.0 * magnitude);
          wrong += colourDistance(png, layout.panelLeft[p] + x, layout.panelBottom + y, toRgb8(diverging.map(t))) > 1;
        }
  EXPECT_EQ(wrong, 0);
  EXPECT_EQ(toRgb8(diverging.map(0.5)), (std::array<std::uint8_t, 3>{ 255, 255, 255 }));
}

TEST_F(MontageCommand, RunsOfDifferentResolutionsAreDrawnAtTheirOwnSize)
{
  TempDir temp;
  const RunResult small = test::runShadowlabIn({ "render", test::datasetPath("grazing").string(), "-t", "hard",
                                                 "-r", "48x32", "--out", "small", "-q" },
    temp.path());
  ASSERT_EQ(small.exitCode, 0) << small.describe();
  const RunResult result = test::runShadowlabIn(
    { "montage", run("hard").string(), "small", "--buffer", "visibility", "--out", "mixed.png" }, temp.path());
  ASSERT_EQ(result.exitCode, 0) << result.describe();
  const ImageU8 png = readPng(temp.path() / "mixed.png");
  const auto panels = panelsOf({ run("hard"), temp.path() / "small" }, "visibility");
  EXPECT_NE(std::find(panels[1].labels.begin(), panels[1].labels.end(), "48x32"), panels[1].labels.end())
    << "the label gives the resolution when the runs' differ";
  MontageOptions options{ "visibility", "", BufferKind::Continuous, {}, {} };
  options.commonLines = commonOf({ run("hard"), temp.path() / "small" });
  const MontageLayout layout = montageLayout(panels, options);
  EXPECT_EQ(png.width, layout.width);
  EXPECT_EQ(png.height, layout.height);
}

TEST_F(MontageCommand, BadInputsAreOneLineErrorsAndWriteNothing)
{
  TempDir temp;
  const std::string hard = run("hard").string();
  const std::string pcf = run("pcf").string();
  fs::create_directories(temp.path() / "no-buffers");
  fs::copy_file(run("hard") / "stats.json", temp.path() / "no-buffers" / "stats.json");
  fs::create_directories(temp.path() / "a-directory");
  temp.write("notes.png", "my notes, not a PNG");

  expectCleanFailure(temp, { "montage", hard, "no-buffers", "--buffer", "visibility", "--out", "m.png" },
    { "no-buffers", "buffers.vti" });
  expectCleanFailure(temp, { "montage", hard, "missing-run", "--buffer", "visibility", "--out", "m.png" },
    { "missing-run", "no such directory" });
  // A buffer one run lacks: the run is named and its buffers listed.
  expectCleanFailure(temp, { "montage", hard, pcf, "--buffer", "depth_margin", "--out", "m.png" },
    { pcf, "depth_margin", "it has:", "kernel_texels" });
  expectCleanFailure(temp, { "montage", hard, "--buffer", "position", "--out", "m.png" }, { "position", "3 components" });
  expectCleanFailure(temp, { "montage", hard, pcf, "--buffer", "texel_ratio", "--out", "a-directory" },
    { "a-directory", "is a directory" });
  expectCleanFailure(temp, { "montage", hard, "--buffer", "visibility", "--out", "nowhere/m.png" },
    { "nowhere", "does not exist" });
  expectCleanFailure(temp, { "montage", hard, "--buffer", "visibility", "--out", "m.jpg" }, { "m.jpg", ".png" });
  expectCleanFailure(temp, { "montage", hard, "--buffer", "visibility", "--out", "notes.png" },
    { "notes.png", "montage did not write it", "--force" });
  EXPECT_EQ(test::readFile(temp.path() / "notes.png"), "my notes, not a PNG");
  // A write that fails part way (a file size limit, like a full disk): no partial PNG.
  expectCleanFailure(temp, { "montage", hard, pcf, "--buffer", "texel_ratio", "--out", "m.png" },
    { "m.png", "cannot write" }, "ulimit -f 2; trap '' XFSZ");
  // --reference of another resolution cannot be compared.
  const RunResult small = test::runShadowlabIn({ "render", test::datasetPath("grazing").string(), "-t", "hard",
                                                 "-r", "32x32", "--out", "small", "-q" },
    temp.path());
  ASSERT_EQ(small.exitCode, 0) << small.describe();
  expectCleanFailure(temp, { "montage", hard, "--buffer", "visibility", "--reference", "small", "--out", "m.png" },
    { "32x32" });
}

TEST_F(MontageCommand, AnExistingMontageIsReplacedAndAReferenceIsAccepted)
{
  TempDir temp;
  for (int pass = 0; pass < 2; ++pass)
  {
    const RunResult result = test::runShadowlabIn({ "montage", run("pcf").string(), run("hard-bias-off").string(),
                                                    "--buffer", "visibility", "--reference", run("hard").string(),
                                                    "--out", "again.png" },
      temp.path());
    ASSERT_EQ(result.exitCode, 0) << result.describe();
  }
  EXPECT_EQ(test::entriesOf(temp.path()), std::vector<std::string>{ "again.png" });
  EXPECT_GT(readPng(temp.path() / "again.png").width, 2 * 64);
}

// "No option of any command can delete or overwrite a file it did not create": a PNG of the user's (here a
// render's image.png, a valid PNG montage did not write) is kept byte for byte without --force; with it, it is
// replaced, and the new file carries the signature that lets the next montage replace it without --force.
TEST_F(MontageCommand, APngMontageDidNotWriteIsReplacedOnlyWithForce)
{
  TempDir temp;
  fs::copy_file(run("hard") / "image.png", temp.path() / "photo.png");
  const std::string photo = test::readFile(temp.path() / "photo.png");
  EXPECT_EQ(readPngText(temp.path() / "photo.png", "Software"), "");
  expectCleanFailure(temp, { "montage", run("hard").string(), "--buffer", "visibility", "--out", "photo.png" },
    { "photo.png", "montage did not write it", "--force" });
  EXPECT_EQ(test::readFile(temp.path() / "photo.png"), photo);

  const std::vector<std::string> montage = { "montage", run("hard").string(), "--buffer", "visibility", "-q",
    "--out", "photo.png" };
  std::vector<std::string> forced = montage;
  forced.push_back("--force");
  const RunResult withForce = test::runShadowlabIn(forced, temp.path());
  ASSERT_EQ(withForce.exitCode, 0) << withForce.describe();
  EXPECT_NE(test::readFile(temp.path() / "photo.png"), photo);
  const std::string signature = readPngText(temp.path() / "photo.png", "Software");
  std::cout << "montage's tEXt Software: \"" << signature << "\"\n";
  EXPECT_EQ(signature, "ShadowLab montage");
  EXPECT_GT(readPng(temp.path() / "photo.png").width, 64);
  const RunResult again = test::runShadowlabIn(montage, temp.path());
  EXPECT_EQ(again.exitCode, 0) << again.describe();
  EXPECT_EQ(test::entriesOf(temp.path()), std::vector<std::string>{ "photo.png" });
}

TEST(Montage, ClipQuantileEndsTheScaleAtThatQuantile)
{
  MontagePanel panel;
  panel.values = ImageF(10, 10, 1);
  for (int i = 0; i < 100; ++i)
  {
    panel.values.data[static_cast<std::size_t>(i)] = static_cast<float>(i - 20); // -20 .. 79
  }
  MontageOptions options;
  options.title = "ramp";
  options.clipQuantile = 0.5;
  const MontageLayout continuous = montageLayout({ panel }, options);
  EXPECT_EQ(continuous.colorRange.min, -20.0);
  EXPECT_NEAR(continuous.colorRange.max, 29.0, 1.0); // the median of -20 .. 79
  options.kind = BufferKind::Signed;
  const MontageLayout signedLayout = montageLayout({ panel }, options);
  EXPECT_EQ(signedLayout.colorRange.min, -signedLayout.colorRange.max);
  EXPECT_NEAR(signedLayout.colorRange.max, 29.0, 1.0); // the median of |-20 .. 79|: 0, 1, 1, ..., 20, 20, 21, ..., 79
  options.clipQuantile.reset(); // the robust scale: +-(99.5th percentile of |value|), rank 98 of 0, 1, 1, ..., 79
  EXPECT_EQ(montageLayout({ panel }, options).colorRange.max, 78.0);
  options.clipQuantile = 0.0;
  EXPECT_THROW(montageLayout({ panel }, options), InputError);
}

// ---- lessons --------------------------------------------------------------------------------------------------

std::vector<std::string> lessonNames()
{
  std::vector<std::string> names;
  for (const Lesson& lesson : lessonRegistry())
  {
    names.push_back(lesson.name);
  }
  return names;
}

// The shell words of a command line (single quotes as LessonBuilder writes them).
std::vector<std::string> shellWords(const std::string& line)
{
  std::vector<std::string> words;
  std::string word;
  bool inWord = false, quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i)
  {
    const char c = line[i];
    if (quoted)
    {
      if (c == '\'')
        quoted = false;
      else
        word += c;
    }
    else if (c == '\'')
    {
      quoted = inWord = true;
    }
    else if (c == '\\' && i + 1 < line.size())
    {
      word += line[++i];
      inWord = true;
    }
    else if (c == ' ')
    {
      if (inWord)
        words.push_back(word);
      word.clear();
      inWord = false;
    }
    else
    {
      word += c;
      inWord = true;
    }
  }
  if (inWord)
    words.push_back(word);
  return words;
}

std::vector<std::string> splitOn(const std::string& text, const std::string& separator)
{
  std::vector<std::string> parts;
  std::size_t start = 0;
  for (std::size_t at = text.find(separator); at != std::string::npos; at = text.find(separator, start))
  {
    parts.push_back(text.substr(start, at - start));
    start = at + separator.size();
  }
  parts.push_back(text.substr(start));
  return parts;
}

// The values of every option `name` in `words`.
std::vector<std::string> optionValues(const std::vector<std::string>& words, const std::set<std::string>& names)
{
  std::vector<std::string> values;
  for (std::size_t i = 0; i + 1 < words.size(); ++i)
  {
    if (names.count(words[i]))
    {
      values.push_back(words[i + 1]);
    }
  }
  return values;
}

// A command the page suggests is one shadowlab would accept: its scene exists (from the repository root), its
// techniques, settings, sweeps and scene overrides are valid, and a montage or compare reads runs that an earlier
// command of the same line wrote.
void checkCommandLine(const std::string& line, const std::string& where)
{
  std::set<std::string> written;
  for (const std::string& command : splitOn(line, " && "))
  {
    const std::vector<std::string> words = shellWords(command);
    ASSERT_GE(words.size(), 2u) << where << ": " << command;
    ASSERT_EQ(words[0], "shadowlab") << where << ": " << command;
    const std::string& subcommand = words[1];
    const std::vector<std::string> outs = optionValues(words, { "--out", "-o" });
    ASSERT_EQ(outs.size(), 1u) << where << ": every suggested command names its output: " << command;
    if (subcommand == "render" || subcommand == "reference" || subcommand == "bench" || subcommand == "probe")
    {
      const fs::path scene = test::sourceDir() / words[2];
      ASSERT_TRUE(fs::is_regular_file(scene)) << where << ": no scene " << words[2] << " in " << command;
      const std::vector<std::string> overrides = optionValues(words, { "--scene-set" });
      EXPECT_NO_THROW(loadScene(scene, overrides)) << where << ": " << command;
      std::vector<std::string> techniques;
      for (const std::string& list : optionValues(words, { "-t", "--technique", "--techniques" }))
      {
        const std::vector<std::string> names = splitOn(list, ",");
        techniques.insert(techniques.end(), names.begin(), names.end());
      }
      if (subcommand != "reference")
      {
        ASSERT_FALSE(techniques.empty()) << where << ": " << command;
      }
      std::vector<std::string> settings = optionValues(words, { "--set", "-s" });
      for (const std::string& sweep : optionValues(words, { "--sweep" }))
      {
        // key=v1,v2 or keys taking their values together, k1+k2=a1+a2,b1+b2.
        const std::vector<std::string> keys = splitOn(sweep.substr(0, sweep.find('=')), "+");
        for (const std::string& tuple : splitOn(sweep.substr(sweep.find('=') + 1), ","))
        {
          const std::vector<std::string> values = keys.size() == 1 ? std::vector<std::string>{ tuple } : splitOn(tuple, "+");
          ASSERT_EQ(values.size(), keys.size()) << where << ": " << sweep << " in " << command;
          for (std::size_t k = 0; k < keys.size(); ++k)
          {
            settings.push_back(keys[k] + "=" + values[k]);
          }
        }
      }
      for (const std::string& setting : settings)
      {
        const std::string key = setting.substr(0, setting.find('='));
        int techniquesWithKey = 0;
        for (const std::string& technique : techniques)
        {
          const TechniqueDescriptor& descriptor = findTechnique(technique);
          if (descriptor.findParameter(key))
          {
            ++techniquesWithKey;
            ParameterValues values = descriptor.defaultParameters();
            EXPECT_NO_THROW(values.set(setting)) << where << ": " << setting << " in " << command;
          }
        }
        EXPECT_GT(techniquesWithKey, 0) << where << ": no technique has " << key << " in " << command;
      }
    }
    else if (subcommand == "montage" || subcommand == "compare")
    {
      for (std::size_t i = 2; i < words.size() && words[i].rfind("-", 0) != 0; ++i)
      {
        const std::string run = fs::path(words[i]).filename() == "buffers.vti" ? fs::path(words[i]).parent_path().string()
                                                                              : words[i];
        EXPECT_TRUE(written.count(run)) << where << ": " << words[i] << " is not written earlier in: " << line;
      }
    }
    else
    {
      ADD_FAILURE() << where << ": unexpected subcommand " << subcommand << " in " << command;
    }
    written.insert(outs.front());
  }
}

class LessonPage : public ::testing::TestWithParam<std::string>
{
};

TEST_P(LessonPage, EveryNumberIsTheRunsStatsValueAtTheNamedPointer)
{
  const Lesson& lesson = findLesson(GetParam());
  TempDir temp;
  const RunResult result = test::runShadowlabIn(
    { "lessons", "--out", "lessons", "--resolution", "64x64", "--only", lesson.name }, temp.path());
  ASSERT_EQ(result.exitCode, 0) << result.describe();
  const fs::path dir = temp.path() / "lessons" / lesson.name;
  const std::string page = test::readFile(dir / "README.md");
  ASSERT_FALSE(page.empty()) << dir;
  EXPECT_EQ(page.rfind("# " + lesson.title + "\n", 0), 0u) << page.substr(0, 200);
  for (const char* section : { "## Question", "## Scene", "## Figures", "## Measured", "## Commands to try next" })
  {
    EXPECT_NE(page.find(std::string("\n") + section + "\n"), std::string::npos) << section << " missing";
  }
  EXPECT_EQ(page.find(temp.path().string()), std::string::npos) << "the page names the temporary directory";
  EXPECT_EQ(page.find(test::sourceDir().string()), std::string::npos) << "the page names the source directory";

  // Every row of a table whose last column is `from`: the value equals the stats.json value it names.
  static const std::regex row(R"(^\| (.+) \| `([^`]+)` \| ([^|]+) \| `runs/([^/`]+)/stats\.json: (/[^`]*)` \|$)");
  std::istringstream lines(page);
  std::string line;
  int rows = 0;
  bool inMeasured = false;
  while (std::getline(lines, line))
  {
    if (line.rfind("## ", 0) == 0)
    {
      inMeasured = line == "## Measured";
    }
    std::smatch match;
    if (!std::regex_match(line, match, row))
    {
      EXPECT_FALSE(inMeasured && line.rfind("| ", 0) == 0 && line.find("stats.json") != std::string::npos)
        << "a Measured row the test cannot read: " << line;
      continue;
    }
    EXPECT_TRUE(inMeasured) << "a measured row outside Measured: " << line;
    ++rows;
    const std::string run = match[2];
    EXPECT_EQ(std::string(match[4]), run) << line;
    const fs::path statsFile = dir / "runs" / std::string(match[4]) / "stats.json";
    ASSERT_TRUE(fs::is_regular_file(statsFile)) << line;
    const Json stats = readJson(statsFile);
    const Json::json_pointer pointer(match[5].str());
    ASSERT_TRUE(stats.contains(pointer)) << line;
    ASSERT_TRUE(stats[pointer].is_number()) << line;
    const double expected = stats[pointer].get<double>();
    const std::string valueText = match[3];
    std::size_t parsed = 0;
    const double shown = std::stod(valueText, &parsed);
    EXPECT_EQ(parsed, valueText.size()) << "not one number: '" << valueText << "' in " << line;
    if (stats[pointer].is_number_integer() || stats[pointer].is_number_unsigned())
    {
      EXPECT_EQ(shown, expected) << line;
    }
    else
    {
      EXPECT_LE(std::abs(shown - expected), 5e-4 * std::abs(expected) + 1e-300) << line << ": stats.json has " << expected;
    }
  }
  EXPECT_GE(rows, 3) << "too few measured numbers on the page";

  // Figures: each a readable PNG beside the page; no buffers.vti is kept.
  static const std::regex figure(R"(!\[[^\]]*\]\(([^)]+)\))");
  int figures = 0;
  for (auto it = std::sregex_iterator(page.begin(), page.end(), figure); it != std::sregex_iterator(); ++it)
  {
    ++figures;
    const ImageU8 png = readPng(dir / (*it)[1].str());
    EXPECT_GE(png.width, 64) << (*it)[1];
  }
  EXPECT_GE(figures, 1);
  for (const auto& entry : fs::recursive_directory_iterator(dir))
  {
    EXPECT_NE(entry.path().extension(), ".vti") << entry.path() << ": the pages keep no buffers";
  }

  // Commands: every line of the page's sh blocks.
  std::istringstream blocks(page);
  bool inBlock = false;
  int commands = 0;
  while (std::getline(blocks, line))
  {
    const std::string trimmed = line.substr(std::min(line.find_first_not_of(' '), line.size()));
    if (trimmed.rfind("```", 0) == 0)
    {
      inBlock = trimmed == "```sh";
      continue;
    }
    if (inBlock && !trimmed.empty())
    {
      ++commands;
      checkCommandLine(trimmed, lesson.name);
    }
  }
  EXPECT_GE(commands, 2);

  // The index lists the lesson, and lesson.json records the command.
  EXPECT_NE(test::readFile(temp.path() / "lessons" / "README.md").find("(" + lesson.name + "/README.md)"),
    std::string::npos);
  const Json summary = readJson(dir / "lesson.json");
  EXPECT_EQ(summary["command"], "shadowlab lessons --out lessons --resolution 64x64 --only " + lesson.name);
}

INSTANTIATE_TEST_SUITE_P(Lessons, LessonPage, ::testing::ValuesIn(lessonNames()),
  [](const ::testing::TestParamInfo<std::string>& info) {
    std::string name = info.param;
    std::replace(name.begin(), name.end(), '-', '_');
    return name;
  });

TEST(LessonsCommand, OnlyKeepsTheOtherLessonsAndAnUnknownNameIsAnError)
{
  TempDir temp;
  for (const char* name : { "acne-and-bias", "perspective-aliasing" })
  {
    const RunResult result =
      test::runShadowlabIn({ "lessons", "--out", "lessons", "--resolution", "32x32", "--only", name }, temp.path());
    ASSERT_EQ(result.exitCode, 0) << result.describe();
  }
  const std::string index = test::readFile(temp.path() / "lessons" / "README.md");
  EXPECT_NE(index.find("(acne-and-bias/README.md)"), std::string::npos) << index;
  EXPECT_NE(index.find("(perspective-aliasing/README.md)"), std::string::npos) << index;
  EXPECT_TRUE(fs::is_regular_file(temp.path() / "lessons" / "acne-and-bias" / "runs" / "bias-off" / "stats.json"));

  const RunResult unknown =
    test::runShadowlabIn({ "lessons", "--out", "other", "--resolution", "32x32", "--only", "no-such-lesson" }, temp.path());
  EXPECT_EQ(unknown.exitCode, 1) << unknown.describe();
  EXPECT_EQ(unknown.errLines(), 1u) << unknown.describe();
  EXPECT_NE(unknown.err.find("no-such-lesson"), std::string::npos) << unknown.describe();
  EXPECT_NE(unknown.err.find("acne-and-bias"), std::string::npos) << "the lessons are listed: " << unknown.describe();
  EXPECT_FALSE(fs::exists(temp.path() / "other"));

  // A directory shadowlab did not write is not replaced.
  fs::create_directories(temp.path() / "mine");
  temp.write("mine/keep.txt", "mine");
  const RunResult refused =
    test::runShadowlabIn({ "lessons", "--out", "mine", "--resolution", "32x32", "--only", "acne-and-bias" }, temp.path());
  EXPECT_EQ(refused.exitCode, 1) << refused.describe();
  EXPECT_EQ(refused.errLines(), 1u) << refused.describe();
  EXPECT_EQ(test::readFile(temp.path() / "mine" / "keep.txt"), "mine");
}

} // namespace
} // namespace sl
