// The shadowlab executable end to end, run as a subprocess (SL_SHADOWLAB_EXE): the files `render` writes and
// what they contain, a clean stderr on success (no false GL/VTK errors), one-line errors naming the offending
// input with no partial output, atomic replacement of --out, and `list` / `list --json` / `--help`.
// Every test works in a fresh temporary directory; resolutions and shadow maps are small to keep the suite fast
// on llvmpipe.
#include "io/ImageIO.h"
#include "pipeline/ShadowRenderer.h"
#include "support/CliRun.h"
#include "support/TempDir.h"
#include "support/TestSupport.h"
#include "techniques/Registry.h"

#include "techniques/yfgl09/Yfgl09Technique.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <vector>

namespace sl
{
namespace
{

namespace fs = std::filesystem;
using Json = nlohmann::json;

// ---- helpers --------------------------------------------------------------------------------------------

using test::TempDir;

using test::entriesOf;
using test::joined;
using test::readFile;
using test::RunResult;
using test::writeFile;

RunResult runShadowlab(const std::vector<std::string>& arguments, const fs::path& workDir)
{
  return test::runShadowlabIn(arguments, workDir);
}

fs::path datasetScene(const std::string& name)
{
  return test::datasetPath(name);
}

const NamedImage* findArray(const std::vector<NamedImage>& arrays, const std::string& name)
{
  for (const NamedImage& array : arrays)
  {
    if (array.name == name)
    {
      return &array;
    }
  }
  return nullptr;
}

// The failure contract: nonzero exit, exactly one line on stderr containing every `mentions`, and no output
// directory (nor a leftover temporary sibling of it) created.
void expectCleanFailure(const std::vector<std::string>& arguments, const std::vector<std::string>& mentions)
{
  TempDir temp;
  const fs::path outDir = temp.path() / "out";
  std::vector<std::string> full = arguments;
  full.push_back("--out");
  full.push_back(outDir.string());
  const RunResult run = runShadowlab(full, temp.path());
  EXPECT_NE(run.exitCode, 0) << run.describe();
  EXPECT_EQ(run.errLines(), 1u) << "expected exactly one line on stderr\n" << run.describe();
  EXPECT_FALSE(run.err.empty() || run.err.back() != '\n') << run.describe();
  for (const std::string& mention : mentions)
  {
    EXPECT_NE(run.err.find(mention), std::string::npos) << "stderr should mention '" << mention << "'\n"
                                                        << run.describe();
  }
  EXPECT_FALSE(fs::exists(outDir)) << "a failed run created " << outDir << "\n" << run.describe();
  EXPECT_EQ(entriesOf(temp.path()), std::vector<std::string>{})
    << "a failed run left files next to --out: " << joined(entriesOf(temp.path())) << "\n" << run.describe();
}

// ---- render: outputs --------------------------------------------------------------------------------------

TEST(CliRender, HardWritesEveryDocumentedOutput)
{
  TempDir temp;
  const fs::path outDir = temp.path() / "ok";
  const RunResult run = runShadowlab({ "render", datasetScene("planar-occluder").string(), "--technique", "hard",
                                       "--resolution", "96x64", "--out", outDir.string() },
    temp.path());
  ASSERT_EQ(run.exitCode, 0) << run.describe();
  for (const char* file : { "buffers.vti", "light_space.vti", "image.png", "visibility.exr", "stats.json",
         "heatmap_visibility.png", "heatmap_texel_ratio.png", "open_in_paraview.py" })
  {
    EXPECT_TRUE(fs::is_regular_file(outDir / file)) << file << " missing; " << outDir << " has "
                                                    << joined(entriesOf(outDir));
  }
  // Only the directory itself next to it: the temporary ".ok.partial-*" sibling has been moved into place.
  EXPECT_EQ(entriesOf(temp.path()), std::vector<std::string>{ "ok" }) << joined(entriesOf(temp.path()));

  const ImageU8 image = readPng(outDir / "image.png");
  EXPECT_EQ(image.width, 96);
  EXPECT_EQ(image.height, 64);
  EXPECT_EQ(image.components, 3);

  const ImageF visibility = readExr(outDir / "visibility.exr");
  ASSERT_EQ(visibility.width, 96);
  ASSERT_EQ(visibility.height, 64);
  float minVisibility = 1.0f;
  float maxVisibility = 0.0f;
  for (std::size_t i = 0; i < visibility.data.size(); ++i)
  {
    const float v = visibility.data[i];
    ASSERT_TRUE(std::isfinite(v) && v >= 0.0f && v <= 1.0f)
      << "visibility " << v << " at " << i % 96 << "," << i / 96;
    minVisibility = std::min(minVisibility, v);
    maxVisibility = std::max(maxVisibility, v);
  }
  // The quad above the ground casts a shadow in view: both shadowed and lit pixels.
  EXPECT_EQ(minVisibility, 0.0f);
  EXPECT_EQ(maxVisibility, 1.0f);

  const std::vector<NamedImage> arrays = readVti(outDir / "buffers.vti");
  const std::vector<std::pair<std::string, int>> expectedArrays = { { "visibility", 1 }, { "position", 3 },
    { "normal", 3 }, { "depth", 1 }, { "coverage", 1 }, { "kernel_texels", 1 }, { "texel_ratio", 1 } };
  for (const auto& [name, components] : expectedArrays)
  {
    const NamedImage* array = findArray(arrays, name);
    ASSERT_NE(array, nullptr) << "buffers.vti has no array '" << name << "'";
    EXPECT_EQ(array->image.width, 96) << name;
    EXPECT_EQ(array->image.height, 64) << name;
    EXPECT_EQ(array->image.components, components) << name;
    const auto nonFinite = std::find_if(array->image.data.begin(), array->image.data.end(),
      [](float value) { return !std::isfinite(value); });
    EXPECT_EQ(nonFinite, array->image.data.end())
      << name << ": non-finite value at index " << (nonFinite - array->image.data.begin());
  }
  // The .vti's visibility is the .exr's, pixel for pixel (same row order).
  const NamedImage* vtiVisibility = findArray(arrays, "visibility");
  ASSERT_NE(vtiVisibility, nullptr);
  EXPECT_EQ(vtiVisibility->image.data, visibility.data) << "buffers.vti visibility differs from visibility.exr";
  // Hard shadows filter nothing: one texel on every covered pixel (the plane faces the light), 0 on background.
  const NamedImage* kernel = findArray(arrays, "kernel_texels");
  const NamedImage* coverage = findArray(arrays, "coverage");
  ASSERT_NE(kernel, nullptr);
  ASSERT_NE(coverage, nullptr);
  std::size_t covered = 0;
  for (std::size_t i = 0; i < kernel->image.data.size(); ++i)
  {
    const bool isCovered = coverage->image.data[i] > 0.5f;
    covered += isCovered ? 1 : 0;
    ASSERT_EQ(kernel->image.data[i], isCovered ? 1.0f : 0.0f)
      << "kernel_texels at " << i % 96 << "," << i / 96 << " coverage " << coverage->image.data[i];
  }
  EXPECT_GT(covered, 96u * 64u / 2) << "the ground plane should fill most of the view";

  const std::vector<NamedImage> lightSpace = readVti(outDir / "light_space.vti");
  EXPECT_NE(findArray(lightSpace, "shadow_map_depth"), nullptr) << "light_space.vti lacks shadow_map_depth";

  for (const char* heatMap : { "heatmap_visibility.png", "heatmap_texel_ratio.png" })
  {
    const ImageU8 png = readPng(outDir / heatMap);
    EXPECT_GE(png.width, 96) << heatMap;
    EXPECT_GE(png.height, 64) << heatMap;
  }

  Json stats;
  ASSERT_NO_THROW(stats = Json::parse(readFile(outDir / "stats.json"))) << readFile(outDir / "stats.json");
  EXPECT_EQ(stats.value("technique", ""), "hard");
  EXPECT_EQ(stats.at("resolution"), Json::array({ 96, 64 }));
  EXPECT_FALSE(stats.value("gl_renderer", "").empty()) << stats.dump(2);
  const TechniqueDescriptor& hard = findTechnique("hard");
  ASSERT_TRUE(stats.at("parameters").is_object());
  EXPECT_EQ(stats.at("parameters").size(), hard.parameters.size()) << stats.at("parameters").dump();
  for (const ParameterSpec& spec : hard.parameters)
  {
    ASSERT_TRUE(stats.at("parameters").contains(spec.name)) << spec.name << " missing from stats.json parameters";
    const Json& value = stats.at("parameters").at(spec.name);
    if (isAutomaticValue(spec, spec.defaultValue))
    {
      EXPECT_EQ(value, spec.automatic) << spec.name;
    }
    else if (spec.choices.empty())
    {
      ASSERT_TRUE(value.is_number()) << spec.name << ": " << value.dump();
      EXPECT_DOUBLE_EQ(value.get<double>(), spec.defaultValue) << spec.name;
    }
    else
    {
      EXPECT_EQ(value, spec.choices.at(static_cast<std::size_t>(spec.defaultValue))) << spec.name;
    }
  }
  const std::vector<std::string> expectedStages = { "gbuffer", "focus", "shadow_map", "technique", "shading" };
  std::vector<std::string> stageNames;
  for (const Json& stage : stats.at("stages"))
  {
    const std::string name = stage.value("stage", "");
    stageNames.push_back(name);
    EXPECT_TRUE(stage.at("gpu_ms").is_number()) << stage.dump();
    EXPECT_GE(stage.value("gpu_ms", -1.0), 0.0) << stage.dump();
    EXPECT_GT(stage.value("wall_ms", 0.0), 0.0) << stage.dump();
  }
  EXPECT_EQ(stageNames, expectedStages) << stats.at("stages").dump(2);
}

// The false-error requirement: a successful run prints no GLEW/VTK error or warning (and here one line, the
// summary); also covers the pcf outputs.
TEST(CliRender, SuccessfulRunHasCleanStderr)
{
  TempDir temp;
  const fs::path outDir = temp.path() / "pcf";
  const RunResult run =
    runShadowlab({ "render", datasetScene("planar-occluder").string(), "--technique", "pcf", "--resolution", "64x64",
                   "--set", "shadow_map_size=512", "--set", "kernel_texels=5", "--out", outDir.string() },
      temp.path());
  ASSERT_EQ(run.exitCode, 0) << run.describe();
  for (const char* marker : { "GLEW could not be initialized", "ERR|", "WARN|", "rror", "arning" })
  {
    EXPECT_EQ(run.err.find(marker), std::string::npos) << "stderr contains '" << marker << "'\n" << run.describe();
  }
  EXPECT_NE(run.err.find("rendered"), std::string::npos) << run.describe();
  EXPECT_NE(run.err.find("pcf"), std::string::npos) << run.describe();

  const Json stats = Json::parse(readFile(outDir / "stats.json"));
  // The summary line, and the note on the pixels where pcf is approximate by design (its filtered edges) when any.
  const double approximate = stats.at("technique_statistics").value("approximate_pixels", -1.0);
  EXPECT_GE(approximate, 0.0) << stats.at("technique_statistics").dump();
  EXPECT_EQ(run.errLines(), approximate > 0.0 ? 2u : 1u) << run.describe();
  if (approximate > 0.0)
  {
    EXPECT_NE(run.err.find("shadowlab: note: pcf: " + std::to_string(static_cast<int>(approximate)) + " pixel(s)"),
      std::string::npos) << run.describe();
  }
  EXPECT_EQ(stats.value("technique", ""), "pcf");
  EXPECT_EQ(stats.at("parameters").value("shadow_map_size", 0.0), 512.0) << stats.at("parameters").dump();
  EXPECT_EQ(stats.at("parameters").value("kernel_texels", 0.0), 5.0) << stats.at("parameters").dump();
  EXPECT_EQ(stats.at("parameters").value("pattern", ""), "grid") << stats.at("parameters").dump();
  const std::vector<NamedImage> arrays = readVti(outDir / "buffers.vti");
  const NamedImage* kernel = findArray(arrays, "kernel_texels");
  ASSERT_NE(kernel, nullptr);
  EXPECT_EQ(*std::max_element(kernel->image.data.begin(), kernel->image.data.end()), 5.0f)
    << "--set kernel_texels=5 did not reach the shader";
  EXPECT_NE(findArray(arrays, "taps"), nullptr) << "pcf publishes 'taps'";

  // --quiet: nothing on stderr but the one note on pixels where hard is approximate by design (its shadow edge's
  // texels), which --quiet keeps like the cut-short warning (issue 27).
  const RunResult quiet =
    runShadowlab({ "render", datasetScene("planar-occluder").string(), "--technique", "hard", "--resolution", "32x32",
                   "--set", "shadow_map_size=256", "--quiet", "--out", (temp.path() / "quiet").string() },
      temp.path());
  EXPECT_EQ(quiet.exitCode, 0) << quiet.describe();
  const double quietApproximate = Json::parse(readFile(temp.path() / "quiet" / "stats.json"))
                                    .at("technique_statistics")
                                    .value("approximate_pixels", -1.0);
  if (quietApproximate > 0.0)
  {
    EXPECT_EQ(quiet.errLines(), 1u) << quiet.describe();
    EXPECT_EQ(quiet.err.rfind("shadowlab: note: hard: " + std::to_string(static_cast<int>(quietApproximate)), 0), 0u)
      << quiet.describe();
  }
  else
  {
    EXPECT_EQ(quiet.err, "") << quiet.describe();
  }
}

TEST(CliRender, PixelsCutShortAreWarnedAboutAndCounted)
{
  // yfgl09's brute force (hierarchy off) over ~400-texel kernels at a 1024^2 map outruns llvmpipe's
  // loop cap (issue 13): one warning line naming the count and the flag, the count in stats.json; also with
  // --quiet, since the image is not what the user asked for.
  TempDir temp;
  const auto render = [&](const std::string& outName, const std::vector<std::string>& settings) {
    std::vector<std::string> arguments = { "render", datasetScene("stacked-occluders").string(), "--technique", "yfgl09",
      "--resolution", "16x12", "--quiet", "--out", (temp.path() / outName).string(), "--set", "shadow_map_size=1024" };
    const std::vector<std::string> scene = test::sceneSetArguments(test::wideKernelOverrides());
    arguments.insert(arguments.end(), scene.begin(), scene.end());
    for (const std::string& setting : settings)
    {
      arguments.insert(arguments.end(), { "--set", setting });
    }
    return runShadowlab(arguments, temp.path());
  };
  const RunResult run = render("cut", { "hierarchy=off" });
  ASSERT_EQ(run.exitCode, 0) << run.describe();
  const Json stats = Json::parse(readFile(temp.path() / "cut" / "stats.json"));
  const double cutShort = stats.at("technique_statistics").at("cut_short_pixels").get<double>();
  const std::vector<NamedImage> arrays = readVti(temp.path() / "cut" / "buffers.vti");
  const NamedImage* classes = findArray(arrays, "packet_class");
  ASSERT_NE(classes, nullptr);
  EXPECT_EQ(cutShort, static_cast<double>(std::count(classes->image.data.begin(), classes->image.data.end(),
                        static_cast<float>(PacketClass::CutShort))));
  // Categorical buffers carry their pixels per category (covered pixels; every pixel of this view is covered).
  const Json& categories = stats.at("buffers").at("packet_class").at("category_pixels");
  EXPECT_EQ(categories.at("cut short by the loop cap").get<double>(), cutShort) << categories.dump();
  double categorised = 0.0;
  for (const auto& [label, pixels] : categories.items())
  {
    categorised += pixels.get<double>();
  }
  EXPECT_EQ(categorised, 16.0 * 12.0) << categories.dump();
  if (stats.value("gl_renderer", "").find("llvmpipe") == std::string::npos)
  {
    GTEST_SKIP() << "no loop cap on " << stats.value("gl_renderer", "");
  }
  EXPECT_GT(cutShort, 0.0);
  // One warning line; a second line, the note on approximate pixels (occluder fusion), is no warning.
  EXPECT_EQ(run.errLines() - (run.err.find("shadowlab: note: ") != std::string::npos ? 1u : 0u), 1u) << run.describe();
  EXPECT_NE(run.err.find("warning: yfgl09: " + std::to_string(static_cast<int>(cutShort)) + " pixel(s)"), std::string::npos) << run.describe();
  EXPECT_NE(run.err.find("cut short"), std::string::npos) << run.describe();

  // The same scene with the hierarchy (the default): nothing cut short, a clean stderr.
  const RunResult exact = render("exact", {});
  ASSERT_EQ(exact.exitCode, 0) << exact.describe();
  // Nothing cut short: no warning, at most the note on the pixels where yfgl09 is approximate by design.
  EXPECT_EQ(exact.err.find("warning"), std::string::npos) << exact.describe();
  EXPECT_TRUE(exact.err.empty() || (exact.err.rfind("shadowlab: note: yfgl09: ", 0) == 0 && exact.errLines() == 1u))
    << exact.describe();
  const Json exactStats = Json::parse(readFile(temp.path() / "exact" / "stats.json"));
  EXPECT_EQ(exactStats.at("technique_statistics").at("cut_short_pixels").get<double>(), 0.0);
}

TEST(CliRender, EsmPixelsWhoseBiasSaturatesTheExponentialAreFlagged)
{
  // esm at shadow_map_size=16 (issue 27): the bias, in texel footprints, is so large in the light's depth range that
  // exp(c bias_n) (bias_gain) weighs each lit texel at the receiver's depth by 12 to 10^6, so one lit texel of the
  // 5 x 5 box lights the pixel and every pixel of stacked-occluders read 1 (the reference's mean is 0.818). Each
  // such pixel is flagged (bias_gain >= 2), counted in stats.json, and warned about in one line; without the bias the
  // same map is close to the truth, and at a 2048 map nothing is flagged.
  TempDir temp;
  const auto render = [&](const std::string& outName, const std::vector<std::string>& settings) {
    std::vector<std::string> arguments = { "render", datasetScene("stacked-occluders").string(), "--technique", "esm",
      "--resolution", "32x32", "--quiet", "--out", (temp.path() / outName).string() };
    for (const std::string& setting : settings)
    {
      arguments.insert(arguments.end(), { "--set", setting });
    }
    return runShadowlab(arguments, temp.path());
  };
  // stderr less the one note on approximate pixels render prints even with --quiet (TechniqueDescriptor::accuracy).
  const auto withoutNote = [](const std::string& err) {
    std::string kept;
    std::size_t start = 0;
    while (start < err.size())
    {
      const std::size_t end = std::min(err.find('\n', start), err.size());
      const std::string line = err.substr(start, end - start);
      if (line.rfind("shadowlab: note: ", 0) != 0)
      {
        kept += line + "\n";
      }
      start = end + 1;
    }
    return kept;
  };
  const auto statsOf = [&](const std::string& outName) { return Json::parse(readFile(temp.path() / outName / "stats.json")); };

  const RunResult coarse = render("coarse", { "shadow_map_size=16" });
  ASSERT_EQ(coarse.exitCode, 0) << coarse.describe();
  const Json stats = statsOf("coarse");
  const double flagged = stats.at("technique_statistics").at("bias_gain_flagged_pixels").get<double>();
  const std::vector<NamedImage> arrays = readVti(temp.path() / "coarse" / "buffers.vti");
  const NamedImage* gain = findArray(arrays, "bias_gain");
  ASSERT_NE(gain, nullptr);
  const auto counted = std::count_if(gain->image.data.begin(), gain->image.data.end(), [](float g) { return g >= 2.0f; });
  const double coarseMean = stats.at("buffers").at("visibility").at("mean").get<double>();
  const double smallestGain = stats.at("buffers").at("bias_gain").at("min").get<double>();
  std::cout << "[ measured ] esm at shadow_map_size=16: " << flagged << " of 1024 pixels flagged, bias_gain >= "
            << smallestGain << ", mean visibility " << coarseMean << "\n";
  EXPECT_EQ(flagged, static_cast<double>(counted));
  EXPECT_EQ(flagged, 32.0 * 32.0) << "every pixel of this view is covered and its bias saturates";
  EXPECT_GT(smallestGain, 2.0);
  EXPECT_GT(coarseMean, 0.99) << "the failure the flag explains";
  const std::string coarseWarnings = withoutNote(coarse.err);
  EXPECT_EQ(std::count(coarseWarnings.begin(), coarseWarnings.end(), '\n'), 1) << coarse.describe();
  EXPECT_NE(coarse.err.find("warning: esm: 1024 pixel(s)"), std::string::npos) << coarse.describe();
  EXPECT_NE(coarse.err.find("bias_gain >= 2"), std::string::npos) << coarse.describe();
  EXPECT_NE(coarse.err.find("shadow_map_size"), std::string::npos) << "the warning says what to change: " << coarse.describe();

  // The cause: the same map without the bias is no longer lit everywhere, and nothing is flagged.
  const RunResult unbiased = render("unbiased", { "shadow_map_size=16", "bias_constant_texels=0", "bias_slope_texels=0" });
  ASSERT_EQ(unbiased.exitCode, 0) << unbiased.describe();
  EXPECT_EQ(withoutNote(unbiased.err), "") << unbiased.describe();
  const Json unbiasedStats = statsOf("unbiased");
  const double unbiasedMean = unbiasedStats.at("buffers").at("visibility").at("mean").get<double>();
  std::cout << "[ measured ] esm at shadow_map_size=16 without bias: mean visibility " << unbiasedMean << "\n";
  EXPECT_LT(unbiasedMean, 0.9);
  EXPECT_EQ(unbiasedStats.at("technique_statistics").at("bias_gain_flagged_pixels").get<double>(), 0.0);

  // A fine map: a clean stderr and nothing flagged.
  const RunResult fine = render("fine", { "shadow_map_size=2048" });
  ASSERT_EQ(fine.exitCode, 0) << fine.describe();
  EXPECT_EQ(withoutNote(fine.err), "") << fine.describe();
  EXPECT_EQ(statsOf("fine").at("technique_statistics").at("bias_gain_flagged_pixels").get<double>(), 0.0);
}

// ---- render: errors ---------------------------------------------------------------------------------------

TEST(CliRenderErrors, AFilterWiderThanTheShadowMapAllowsIsRefused)
{
  // The focus leaves ceil(w / 2) + 1 texels on each side for a filter of w texels (pcf's kernel, the moment
  // techniques' prefilter box): one that leaves nothing for the receivers is an input error, not an internal check.
  expectCleanFailure({ "render", datasetScene("planar-occluder").string(), "--technique", "pcf", "--set",
                       "shadow_map_size=16", "--set", "kernel_texels=64" },
    { "kernel_texels", "shadow_map_size" });
  expectCleanFailure({ "render", datasetScene("planar-occluder").string(), "--technique", "vsm", "--set",
                       "shadow_map_size=16", "--set", "prefilter_texels=13" },
    { "prefilter_texels", "shadow_map_size" });
}

TEST(CliRenderErrors, UnknownTechniqueListsTheAvailableOnes)
{
  std::vector<std::string> mentions = { "nope" };
  for (const TechniqueDescriptor& technique : techniqueRegistry())
  {
    mentions.push_back(technique.name);
  }
  expectCleanFailure({ "render", datasetScene("planar-occluder").string(), "--technique", "nope" }, mentions);
}

TEST(CliRenderErrors, UnknownParameter)
{
  expectCleanFailure({ "render", datasetScene("planar-occluder").string(), "--technique", "pcf", "--set", "nope=1" },
    { "nope", "pcf" });
}

TEST(CliRenderErrors, AWarpNeedsADirectionalLight)
{
  // planar-occluder's light is an area light: the warp (survey §4.2) is refused in one line, before any GL.
  expectCleanFailure({ "render", datasetScene("planar-occluder").string(), "--technique", "hard", "--set", "warp=lispsm" },
    { "warp=lispsm", "directional" });
}

TEST(CliRender, WarpStatsUnderADirectionalLight)
{
  // stacked-occluders under a directional light (γ = 51°): stats.json's light_view.warp carries LiSPSM's n, which is
  // n_opt / sin γ = (z_n + sqrt(z_n z_f)) / sin γ of the reported eye depths.
  TempDir temp;
  const fs::path outDir = temp.path() / "out";
  const RunResult run = runShadowlab({ "render", datasetScene("stacked-occluders").string(), "-t", "pcf", "-r", "64x48",
                                       "-s", "warp=lispsm", "-s", "shadow_map_size=256", "--scene-set",
                                       R"(/lights/0={"type": "directional", "direction": [0.3, -1, 0.2]})", "--out",
                                       outDir.string() },
    temp.path());
  ASSERT_EQ(run.exitCode, 0) << run.describe();
  const Json warp = Json::parse(readFile(outDir / "stats.json")).at("light_view").at("warp");
  EXPECT_EQ(warp.at("kind"), "lispsm");
  const double zNear = warp.at("z_near").get<double>();
  const double zFar = warp.at("z_far").get<double>();
  const double gamma = warp.at("gamma_deg").get<double>() * 3.14159265358979323846 / 180.0;
  EXPECT_GT(zFar, zNear);
  EXPECT_NEAR(warp.at("gamma_deg").get<double>(), 51.17, 0.05);
  EXPECT_NEAR(warp.at("n").get<double>(), (zNear + std::sqrt(zNear * zFar)) / std::sin(gamma), 1e-9);
  EXPECT_EQ(warp.at("n"), warp.at("n_opt"));
  EXPECT_EQ(warp.at("near"), warp.at("n"));
  EXPECT_GT(warp.at("far").get<double>(), warp.at("near").get<double>());
}

TEST(CliRenderErrors, CascadesNeedADirectionalLight)
{
  // planar-occluder's light is an area light: cascades (survey §4.3.1) are refused in one line, before any GL.
  expectCleanFailure({ "render", datasetScene("planar-occluder").string(), "--technique", "pcf", "--set", "cascades=3" },
    { "cascades=3", "directional" });
}

TEST(CliRender, CascadeSplitsAndMapsInStats)
{
  // deep-view with 3 log cascades: stats.json's light_view.cascades holds the split depths C_i = z_n (z_f/z_n)^(i/3),
  // each slice's far the next one's near, and light_space lists every cascade's two maps.
  TempDir temp;
  const fs::path outDir = temp.path() / "out";
  const RunResult run = runShadowlab({ "render", datasetScene("deep-view").string(), "-t", "hard", "-r", "64x48", "-s",
                                       "shadow_map_size=128", "-s", "cascades=3", "-s", "split_scheme=log", "--out",
                                       outDir.string() },
    temp.path());
  ASSERT_EQ(run.exitCode, 0) << run.describe();
  const Json stats = Json::parse(readFile(outDir / "stats.json"));
  const Json& cascades = stats.at("light_view").at("cascades");
  ASSERT_EQ(cascades.size(), 3u);
  const double zNear = cascades.at(0).at("near").get<double>();
  const double zFar = cascades.at(2).at("far").get<double>();
  EXPECT_GT(zFar / zNear, 20.0);
  for (std::size_t k = 0; k < 3; ++k)
  {
    EXPECT_NEAR(cascades.at(k).at("near").get<double>(), zNear * std::pow(zFar / zNear, k / 3.0), 1e-9 * zFar) << k;
    EXPECT_NEAR(cascades.at(k).at("far").get<double>(), zNear * std::pow(zFar / zNear, (k + 1) / 3.0), 1e-9 * zFar) << k;
    EXPECT_EQ(cascades.at(k).at("resolution"), 128) << k;
    EXPECT_GT(cascades.at(k).at("texel_world_size").get<double>(), 0.0) << k;
    EXPECT_TRUE(stats.at("light_space").contains("shadow_map_depth_c" + std::to_string(k))) << k;
    EXPECT_TRUE(stats.at("light_space").contains("shadow_map_window_depth_c" + std::to_string(k))) << k;
  }
  EXPECT_EQ(stats.at("light_view").at("split_scheme"), "log");
  EXPECT_FALSE(stats.at("light_space").contains("shadow_map_depth"));
  EXPECT_TRUE(stats.at("buffers").contains("cascade"));
}

TEST(CliRender, FvsmTilesAndGridsInStats)
{
  // deep-view with fitted virtual shadow maps (survey §4.3.3): stats.json's light_view.fvsm lists tiles whose
  // rectangles are the root rectangle's quadtree cells (side / 2^level, on the 2^max_level grid) and do not overlap,
  // their effective resolution (tile - 2 margin) 2^level; unmet_pixels counts fvsm_unmet; light_space holds the grids
  // and every tile's maps.
  TempDir temp;
  const fs::path outDir = temp.path() / "out";
  const RunResult run = runShadowlab({ "render", datasetScene("deep-view").string(), "-t", "hard", "-r", "64x48", "-s",
                                       "fvsm=on", "-s", "fvsm_tile_size=34", "-s", "fvsm_max_level=4", "-s",
                                       "fvsm_max_tiles=10", "--out", outDir.string() },
    temp.path());
  ASSERT_EQ(run.exitCode, 0) << run.describe();
  const Json stats = Json::parse(readFile(outDir / "stats.json"));
  const Json& fvsm = stats.at("light_view").at("fvsm");
  const Json& tiles = fvsm.at("tiles");
  ASSERT_GE(tiles.size(), 2u);
  ASSERT_LE(tiles.size(), 10u);
  EXPECT_EQ(fvsm.at("tile_count"), tiles.size());
  EXPECT_EQ(fvsm.at("grid_size"), 16);
  const std::vector<double> root = fvsm.at("root_rect").get<std::vector<double>>();
  std::vector<std::vector<double>> rects;
  for (const Json& tile : tiles)
  {
    const int level = tile.at("level").get<int>();
    const std::vector<double> rect = tile.at("rect").get<std::vector<double>>();
    const std::vector<int> cell = tile.at("cell").get<std::vector<int>>();
    const double width = (root[1] - root[0]) / (1 << level);
    const double height = (root[3] - root[2]) / (1 << level);
    EXPECT_NEAR(rect[0], root[0] + cell[0] * width, 1e-9 * (root[1] - root[0]));
    EXPECT_NEAR(rect[1] - rect[0], width, 1e-9 * (root[1] - root[0]));
    EXPECT_NEAR(rect[2], root[2] + cell[1] * height, 1e-9 * (root[3] - root[2]));
    EXPECT_NEAR(rect[3] - rect[2], height, 1e-9 * (root[3] - root[2]));
    EXPECT_EQ(tile.at("effective_resolution").get<double>(), 32.0 * (1 << level));
    EXPECT_EQ(tile.at("met").get<bool>(),
      tile.at("required_resolution").get<double>() <= tile.at("effective_resolution").get<double>() * (1.0 + 1e-9));
    for (const std::vector<double>& other : rects)
    {
      EXPECT_FALSE(rect[0] < other[1] && other[0] < rect[1] && rect[2] < other[3] && other[2] < rect[3]);
    }
    rects.push_back(rect);
  }
  EXPECT_TRUE(fvsm.at("budget_reached").get<bool>() || fvsm.at("level_reached").get<bool>() ||
    fvsm.at("unmet_pixels").get<int>() == 0);
  EXPECT_GT(fvsm.at("prepass_samples").get<int>(), 500);
  for (std::size_t k = 0; k < tiles.size(); ++k)
  {
    EXPECT_TRUE(stats.at("light_space").contains("shadow_map_depth_t" + std::to_string(k))) << k;
  }
  EXPECT_TRUE(stats.at("light_space").contains("fvsm_required_resolution_grid"));
  EXPECT_TRUE(stats.at("light_space").contains("fvsm_level_grid"));
  for (const char* buffer : { "fvsm_tile", "fvsm_level", "fvsm_required_resolution", "fvsm_unmet" })
  {
    EXPECT_TRUE(stats.at("buffers").contains(buffer)) << buffer;
  }
  // Cascades and fvsm in one line: refused, naming both.
  expectCleanFailure({ "render", datasetScene("deep-view").string(), "-t", "hard", "-s", "fvsm=on", "-s", "cascades=2" },
    { "cascades=2", "fvsm" });
}

TEST(CliRenderErrors, OutOfRangeParameters)
{
  expectCleanFailure(
    { "render", datasetScene("planar-occluder").string(), "--technique", "pcf", "--set", "kernel_texels=0" },
    { "kernel_texels", "0", "1", "64" });
  expectCleanFailure(
    { "render", datasetScene("planar-occluder").string(), "--technique", "hard", "--set", "shadow_map_size=999999" },
    { "shadow_map_size", "999999", "8192" });
}

TEST(CliRenderErrors, BadEnumerationChoice)
{
  expectCleanFailure(
    { "render", datasetScene("planar-occluder").string(), "--technique", "pcf", "--set", "pattern=spiral" },
    { "pattern", "spiral", "grid", "poisson" });
}

TEST(CliRenderErrors, UnsupportedLightNamesItsTypeAndTheSupportedOnes) // probe T15, T38
{
  expectCleanFailure({ "render", datasetScene("sphere-point").string(), "--technique", "gbp06", "-r", "32x32" },
    { "sphere-point", "lights[0]", "gbp06", "point light", "square area" });
}

TEST(CliRenderErrors, MalformedResolution)
{
  expectCleanFailure({ "render", datasetScene("planar-occluder").string(), "--resolution", "12by5" },
    { "--resolution", "12by5" });
}

TEST(CliRenderErrors, MissingSceneFile)
{
  TempDir temp;
  const fs::path missing = temp.path() / "no-such-scene.json";
  expectCleanFailure({ "render", missing.string() }, { missing.string() });
}

TEST(CliRenderErrors, MalformedJsonScene)
{
  TempDir temp;
  const fs::path scene = temp.path() / "broken.json";
  writeFile(scene, "{\n  \"camera\": {\n    \"projection\": \"perspective\",\n");
  expectCleanFailure({ "render", scene.string(), "--resolution", "32x32" }, { scene.string() });
}

TEST(CliRenderErrors, SceneWhoseMeshIsMissing)
{
  TempDir temp;
  Json scene = Json::parse(readFile(datasetScene("bunny")));
  bool replaced = false;
  for (Json& object : scene.at("objects"))
  {
    if (object.contains("mesh"))
    {
      object["mesh"] = "missing-bunny.ply";
      replaced = true;
    }
  }
  ASSERT_TRUE(replaced) << "datasets/bunny/scene.json has no mesh object any more";
  const fs::path scenePath = temp.path() / "scene.json";
  writeFile(scenePath, scene.dump(2));
  expectCleanFailure({ "render", scenePath.string(), "--resolution", "32x32" }, { "missing-bunny.ply" });
}

// ---- render: atomic output directory ------------------------------------------------------------------------

TEST(CliRenderOutput, SuccessReplacesTheWholeDirectoryFailureLeavesItUntouched)
{
  TempDir temp;
  const fs::path outDir = temp.path() / "results";
  fs::create_directories(outDir / "sub");
  // An earlier output of shadowlab (it carries the marker), to which files were added since.
  writeFile(outDir / ".shadowlab-output", R"({"tool": "shadowlab", "command": "render"})");
  writeFile(outDir / "old.txt", "from an earlier run");
  writeFile(outDir / "sub" / "nested.txt", "nested");

  // A failure, early (bad parameter) and late (after the scene loaded and the GL context was made: a light
  // index the scene does not have), keeps the directory exactly as it was.
  for (const std::vector<std::string>& badArguments :
    { std::vector<std::string>{ "--set", "nope=1" }, std::vector<std::string>{ "--light", "7" } })
  {
    std::vector<std::string> arguments = { "render", datasetScene("planar-occluder").string(), "--technique", "hard",
      "--resolution", "32x32", "--set", "shadow_map_size=256", "--out", outDir.string() };
    arguments.insert(arguments.end(), badArguments.begin(), badArguments.end());
    const RunResult failed = runShadowlab(arguments, temp.path());
    EXPECT_NE(failed.exitCode, 0) << failed.describe();
    EXPECT_EQ(failed.errLines(), 1u) << failed.describe();
    EXPECT_EQ(entriesOf(outDir), (std::vector<std::string>{ ".shadowlab-output", "old.txt", "sub" }))
      << failed.describe();
    EXPECT_EQ(readFile(outDir / "old.txt"), "from an earlier run");
    EXPECT_EQ(entriesOf(temp.path()), std::vector<std::string>{ "results" })
      << "leftover next to --out: " << joined(entriesOf(temp.path()));
  }

  const RunResult ok =
    runShadowlab({ "render", datasetScene("planar-occluder").string(), "--technique", "hard", "--resolution", "32x32",
                   "--set", "shadow_map_size=256", "--out", outDir.string() },
      temp.path());
  ASSERT_EQ(ok.exitCode, 0) << ok.describe();
  EXPECT_FALSE(fs::exists(outDir / "old.txt")) << "old file survived a successful run";
  EXPECT_FALSE(fs::exists(outDir / "sub")) << "old subdirectory survived a successful run";
  EXPECT_TRUE(fs::is_regular_file(outDir / "image.png"));
  EXPECT_TRUE(fs::is_regular_file(outDir / "stats.json"));
  EXPECT_EQ(entriesOf(temp.path()), std::vector<std::string>{ "results" })
    << "leftover next to --out: " << joined(entriesOf(temp.path()));
}

TEST(CliRenderOutput, OutPathThatIsAFileIsAnError)
{
  TempDir temp;
  const fs::path file = temp.path() / "taken";
  writeFile(file, "not a directory");
  const RunResult run = runShadowlab({ "render", datasetScene("planar-occluder").string(), "--resolution", "32x32",
                                       "--set", "shadow_map_size=256", "--out", file.string() },
    temp.path());
  EXPECT_NE(run.exitCode, 0) << run.describe();
  EXPECT_EQ(run.errLines(), 1u) << run.describe();
  EXPECT_NE(run.err.find("taken"), std::string::npos) << run.describe();
  EXPECT_EQ(readFile(file), "not a directory");
  EXPECT_EQ(entriesOf(temp.path()), std::vector<std::string>{ "taken" }) << joined(entriesOf(temp.path()));
}

// ---- list and help ------------------------------------------------------------------------------------------

std::string formatNumber(double value)
{
  std::ostringstream text;
  text << value;
  return text.str();
}

TEST(CliList, TextListsEveryParameterWithDefaultAndRange)
{
  TempDir temp;
  const RunResult run = runShadowlab({ "list" }, temp.path());
  ASSERT_EQ(run.exitCode, 0) << run.describe();
  EXPECT_EQ(run.err, "") << run.describe();
  std::vector<std::string> lines;
  std::istringstream stream(run.out);
  for (std::string line; std::getline(stream, line);)
  {
    lines.push_back(line);
  }
  ASSERT_FALSE(techniqueRegistry().empty());
  for (const TechniqueDescriptor& technique : techniqueRegistry())
  {
    // The technique's block: from "<name> - ..." to the next line that starts in column 0.
    const auto header = std::find_if(lines.begin(), lines.end(),
      [&](const std::string& line) { return line.rfind(technique.name + " - ", 0) == 0; });
    ASSERT_NE(header, lines.end()) << "no '" << technique.name << " - ...' line\n" << run.out;
    const auto end = std::find_if(header + 1, lines.end(),
      [](const std::string& line) { return !line.empty() && line[0] != ' '; });
    for (const ParameterSpec& spec : technique.parameters)
    {
      std::string expectedDefault;
      std::string expectedRange;
      if (spec.file)
      {
        expectedDefault = "(none)";
        expectedRange = "file path";
      }
      else if (spec.choices.empty())
      {
        expectedDefault = isAutomaticValue(spec, spec.defaultValue) ? spec.automatic : formatNumber(spec.defaultValue);
        expectedRange = formatNumber(spec.minValue) + " .. " + formatNumber(spec.maxValue) +
          (spec.automatic.empty() ? "" : " or " + spec.automatic);
      }
      else
      {
        expectedDefault = spec.choices.at(static_cast<std::size_t>(spec.defaultValue));
        for (const std::string& choice : spec.choices)
        {
          expectedRange += (expectedRange.empty() ? "" : "|") + choice;
        }
      }
      // Parameter lines are indented by 4 spaces, their doc lines by 6.
      const auto line = std::find_if(header + 1, end,
        [&](const std::string& text) { return text.rfind("    " + spec.name + " ", 0) == 0; });
      ASSERT_NE(line, end) << technique.name << ": no line for parameter " << spec.name << "\n" << run.out;
      EXPECT_NE(line->find("default " + expectedDefault + " "), std::string::npos)
        << technique.name << "." << spec.name << " expected default " << expectedDefault << " in: " << *line;
      EXPECT_NE(line->find("range " + expectedRange), std::string::npos)
        << technique.name << "." << spec.name << " expected range " << expectedRange << " in: " << *line;
    }
  }
  // Spot checks against the values written in the descriptors (not derived from the registry).
  EXPECT_NE(run.out.find("kernel_texels          default 3        range 1 .. 64"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("pattern                default grid     range grid|poisson"), std::string::npos) << run.out;
}

TEST(CliList, TheShadowMapSizeSaysWhereItsBoundDependsOnTheGl)
{
  // With hsm=nbuffers or the dual-grid MSSM (a 3D texture), gbp06, gbp07, yfgl09, ss08 and vssm refuse maps
  // beyond the GL's GL_MAX_3D_TEXTURE_SIZE (2048 on llvmpipe) when they render; list has no context, so it names
  // the limit.
  TempDir temp;
  const RunResult run = runShadowlab({ "list" }, temp.path());
  ASSERT_EQ(run.exitCode, 0) << run.describe();
  const auto block = [&](const std::string& name) {
    const std::size_t start = run.out.find(name + " - ");
    const std::size_t end = run.out.find("\n\n", start);
    return start == std::string::npos ? std::string() : run.out.substr(start, end - start);
  };
  for (const char* name : { "gbp06", "gbp07", "yfgl09", "ss08", "vssm" })
  {
    EXPECT_NE(block(name).find("GL limit: "), std::string::npos) << name << "\n" << block(name);
    EXPECT_NE(block(name).find("GL_MAX_3D_TEXTURE_SIZE"), std::string::npos) << name;
  }
  for (const char* name : { "hard", "pcf", "pcss" })
  {
    EXPECT_EQ(block(name).find("GL limit: "), std::string::npos) << name << "\n" << block(name);
  }
  const RunResult json = runShadowlab({ "list", "--json" }, temp.path());
  ASSERT_EQ(json.exitCode, 0) << json.describe();
  EXPECT_NE(json.out.find("\"gl_limit\""), std::string::npos);
}

TEST(CliList, JsonListsTechniquesWithParameterTables)
{
  TempDir temp;
  const RunResult run = runShadowlab({ "list", "--json" }, temp.path());
  ASSERT_EQ(run.exitCode, 0) << run.describe();
  EXPECT_EQ(run.err, "") << run.describe();
  Json list;
  ASSERT_NO_THROW(list = Json::parse(run.out)) << run.out;
  ASSERT_TRUE(list.is_array()) << run.out;
  std::set<std::string> names;
  for (const Json& technique : list)
  {
    const std::string name = technique.value("name", "");
    names.insert(name);
    const TechniqueDescriptor& descriptor = findTechnique(name);
    ASSERT_TRUE(technique.at("parameters").is_array()) << technique.dump(2);
    ASSERT_EQ(technique.at("parameters").size(), descriptor.parameters.size()) << name;
    for (std::size_t p = 0; p < descriptor.parameters.size(); ++p)
    {
      const ParameterSpec& spec = descriptor.parameters[p];
      const Json& parameter = technique.at("parameters").at(p);
      for (const char* key : { "name", "default", "min", "max" })
      {
        ASSERT_TRUE(parameter.contains(key)) << name << " parameter " << p << " lacks '" << key << "': "
                                             << parameter.dump();
      }
      EXPECT_EQ(parameter.at("name"), spec.name);
      EXPECT_EQ(parameter.at("min").get<double>(), spec.minValue) << spec.name;
      EXPECT_EQ(parameter.at("max").get<double>(), spec.maxValue) << spec.name;
      const Json& defaultValue = parameter.at("default");
      if (isAutomaticValue(spec, spec.defaultValue))
      {
        EXPECT_EQ(defaultValue, spec.automatic) << name << "." << spec.name;
      }
      else if (spec.choices.empty())
      {
        // The default of a numeric parameter: a JSON number would be natural; a numeric string is accepted,
        // its value must be the descriptor's.
        const double value = defaultValue.is_number() ? defaultValue.get<double>()
                                                      : std::stod(defaultValue.get<std::string>());
        EXPECT_EQ(value, spec.defaultValue) << name << "." << spec.name << ": " << defaultValue.dump();
        EXPECT_TRUE(value >= spec.minValue && value <= spec.maxValue) << name << "." << spec.name;
      }
      else
      {
        EXPECT_EQ(defaultValue, spec.choices.at(static_cast<std::size_t>(spec.defaultValue))) << spec.name;
        EXPECT_EQ(parameter.at("choices"), Json(spec.choices)) << spec.name;
      }
    }
  }
  EXPECT_EQ(names.count("hard"), 1u) << run.out.substr(0, 2000);
  EXPECT_EQ(names.count("pcf"), 1u) << run.out.substr(0, 2000);
  EXPECT_EQ(names.size(), techniqueRegistry().size());
}

TEST(CliHelp, HelpExitsZeroAndNamesTheCommands)
{
  TempDir temp;
  const RunResult help = runShadowlab({ "--help" }, temp.path());
  EXPECT_EQ(help.exitCode, 0) << help.describe();
  EXPECT_NE(help.out.find("render"), std::string::npos) << help.describe();
  EXPECT_NE(help.out.find("list"), std::string::npos) << help.describe();

  const RunResult renderHelp = runShadowlab({ "render", "--help" }, temp.path());
  EXPECT_EQ(renderHelp.exitCode, 0) << renderHelp.describe();
  for (const char* option : { "--technique", "--set", "--resolution", "--out" })
  {
    EXPECT_NE(renderHelp.out.find(option), std::string::npos) << option << "\n" << renderHelp.describe();
  }

  // No subcommand is a usage error, not a silent success.
  const RunResult none = runShadowlab({}, temp.path());
  EXPECT_NE(none.exitCode, 0) << none.describe();
  EXPECT_EQ(entriesOf(temp.path()), std::vector<std::string>{});
}

} // namespace
} // namespace sl
