// `shadowlab probe` end to end (issue 15): the files it writes and what they hold, --pick, and the bad-input
// contract (one line, nonzero exit, no output directory).
#include "lightspace/CameraView.h"
#include "probe/Probe.h"
#include "support/CliRun.h"
#include "support/TempDir.h"
#include "support/TestSupport.h"
#include "techniques/Registry.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <vtkMultiBlockDataSet.h>
#include <vtkNew.h>
#include <vtkXMLMultiBlockDataReader.h>

#include <cmath>
#include <filesystem>
#include <string>

namespace sl
{
namespace
{

namespace fs = std::filesystem;
using Json = nlohmann::json;

constexpr int kSide = 64;

// `dataset` at 64 x 64 with `technique`, rendered in this process exactly as the CLI renders it.
const FrameResult& frameOf(const std::string& dataset, const std::string& technique)
{
  static std::map<std::string, FrameResult> frames;
  const std::string key = dataset + "/" + technique;
  auto found = frames.find(key);
  if (found == frames.end())
  {
    found = frames.emplace(key, test::renderDataset(test::loadDataset(dataset), technique, kSide, kSide)).first;
  }
  return found->second;
}

const FrameResult& stackedFrame(const std::string& technique)
{
  return frameOf("stacked-occluders", technique);
}

// The first pixel in scan order whose visibility satisfies `wanted` and that is covered (or not, for background).
glm::ivec2 firstPixel(const FrameResult& frame, bool covered, const std::function<bool(float)>& wanted)
{
  const ImageF& coverage = frame.find("coverage")->image;
  const ImageF& visibility = frame.find("visibility")->image;
  for (int y = 0; y < kSide; ++y)
  {
    for (int x = 0; x < kSide; ++x)
    {
      if ((coverage.at(x, y) > 0.5f) == covered && wanted(visibility.at(x, y)))
      {
        return { x, y };
      }
    }
  }
  ADD_FAILURE() << "no such pixel";
  return { 0, 0 };
}

std::vector<std::string> probeArguments(const std::string& technique, const std::vector<std::string>& where, const fs::path& out,
  const std::string& dataset = "stacked-occluders")
{
  std::vector<std::string> arguments = { "probe", test::datasetPath(dataset).string(), "-t", technique,
    "--resolution", std::to_string(kSide) + "x" + std::to_string(kSide), "--out", out.string() };
  arguments.insert(arguments.end(), where.begin(), where.end());
  return arguments;
}

std::string pixelText(glm::ivec2 pixel)
{
  return std::to_string(pixel.x) + "," + std::to_string(pixel.y);
}

TEST(CliProbe, WritesJsonDataSetAndFigureWithTheGpuAndTwinValues)
{
  const FrameResult& frame = stackedFrame("hard");
  const glm::ivec2 umbra = firstPixel(frame, true, [](float v) { return v == 0.0f; });
  test::TempDir temp;
  const fs::path out = temp.path() / "probe";
  const test::RunResult run = test::runShadowlabIn(probeArguments("hard", { "--pixel", pixelText(umbra) }, out), temp.path());
  ASSERT_EQ(run.exitCode, 0) << run.describe();
  EXPECT_EQ(run.errLines(), 1u) << run.describe();
  EXPECT_NE(run.err.find("pixel " + pixelText(umbra)), std::string::npos) << run.describe();
  for (const char* name : { "probe.json", "probe.vtm", "probe.png", "probe" })
  {
    EXPECT_TRUE(fs::exists(out / name)) << name;
  }
  const Json json = Json::parse(test::readFile(out / "probe.json"));
  EXPECT_EQ(json.at("technique"), "hard");
  EXPECT_EQ(json.at("pixel"), Json::array({ umbra.x, umbra.y }));
  EXPECT_EQ(json.at("gpu_visibility").get<double>(), 0.0);
  EXPECT_EQ(json.at("twin_visibility").get<double>(), 0.0);
  EXPECT_TRUE(json.at("agrees").get<bool>());
  // Every quantity says where it comes from; the receiver's depth and the single nearest texel are there.
  bool depth = false;
  for (const Json& quantity : json.at("quantities"))
  {
    EXPECT_FALSE(quantity.at("source").get<std::string>().empty()) << quantity.dump();
    depth = depth || quantity.at("name") == "receiver_depth";
  }
  EXPECT_TRUE(depth);
  ASSERT_EQ(json.at("texels").size(), 1u);
  EXPECT_TRUE(json.at("texels")[0].at("occluding").get<bool>()) << "an umbra pixel's one texel occludes";
  // probe.vtm opens with VTK's reader (as in ParaView): the three documented blocks.
  vtkNew<vtkXMLMultiBlockDataReader> reader;
  reader->SetFileName((out / "probe.vtm").string().c_str());
  reader->Update();
  auto* blocks = vtkMultiBlockDataSet::SafeDownCast(reader->GetOutput());
  ASSERT_NE(blocks, nullptr);
  ASSERT_EQ(blocks->GetNumberOfBlocks(), 3u);
}

TEST(CliProbe, PickFindsThePixelThatShowsAWorldPoint)
{
  const FrameResult& frame = stackedFrame("hard");
  const glm::ivec2 lit = firstPixel(frame, true, [](float v) { return v == 1.0f; });
  const ImageF& position = frame.find("position")->image;
  const std::string point = format(position.at(lit.x, lit.y, 0), ",", position.at(lit.x, lit.y, 1), ",",
    position.at(lit.x, lit.y, 2));
  // `--pick X,Y,Z` (issue 31) and the older `--pick world X,Y,Z` pick the same pixel, without a note.
  for (const std::vector<std::string>& pick :
    { std::vector<std::string>{ "--pick", point }, std::vector<std::string>{ "--pick", "world", point } })
  {
    test::TempDir temp;
    const fs::path out = temp.path() / "probe";
    const test::RunResult run = test::runShadowlabIn(probeArguments("hard", pick, out), temp.path());
    ASSERT_EQ(run.exitCode, 0) << run.describe();
    EXPECT_EQ(run.err.find("note"), std::string::npos) << run.describe();
    const Json json = Json::parse(test::readFile(out / "probe.json"));
    EXPECT_EQ(json.at("pixel"), Json::array({ lit.x, lit.y })) << pick.size();
    EXPECT_EQ(json.at("gpu_visibility").get<double>(), 1.0);
  }
}

// One line on stderr mentioning each of `mentions`, a nonzero exit, and nothing written.
void expectCleanProbeFailure(const std::string& technique, const std::vector<std::string>& where,
  const std::vector<std::string>& mentions, const std::string& dataset = "stacked-occluders")
{
  test::TempDir temp;
  const fs::path out = temp.path() / "probe";
  const test::RunResult run = test::runShadowlabIn(probeArguments(technique, where, out, dataset), temp.path());
  EXPECT_NE(run.exitCode, 0) << run.describe();
  EXPECT_EQ(run.errLines(), 1u) << run.describe();
  for (const std::string& mention : mentions)
  {
    EXPECT_NE(run.err.find(mention), std::string::npos) << "stderr should mention " << mention << "\n" << run.describe();
  }
  EXPECT_EQ(test::entriesOf(temp.path()), std::vector<std::string>{}) << "a failed probe left files";
}

TEST(CliProbeErrors, PixelOutsideTheImage)
{
  expectCleanProbeFailure("hard", { "--pixel", "64,3" }, { "--pixel 64,3", "outside", "64x64" });
  expectCleanProbeFailure("hard", { "--pixel", "-1,3" }, { "--pixel -1,3", "outside" });
}

TEST(CliProbeErrors, BackgroundPixel)
{
  // The bunny's ground ends inside the view (stacked-occluders' ground fills it).
  const glm::ivec2 background = firstPixel(frameOf("bunny", "hard"), false, [](float) { return true; });
  expectCleanProbeFailure(
    "hard", { "--pixel", pixelText(background) }, { "--pixel " + pixelText(background), "background" }, "bunny");
}

TEST(CliProbeErrors, MalformedOrMissingPixel)
{
  expectCleanProbeFailure("hard", { "--pixel", "3;4" }, { "--pixel 3;4", "X,Y" });
  expectCleanProbeFailure("hard", {}, { "--pixel", "--pick" });
  expectCleanProbeFailure("hard", { "--pixel", "3,4", "--pick", "world", "0,0,0" }, { "exactly one" });
  expectCleanProbeFailure("hard", { "--pick", "screen", "0,0,0" }, { "--pick screen", "world" });
  expectCleanProbeFailure("hard", { "--pick", "world", "0,nan,0" }, { "--pick world 0,nan,0" });
  expectCleanProbeFailure("hard", { "--pick", "1,2" }, { "--pick 1,2", "X,Y,Z" });
  expectCleanProbeFailure("hard", { "--pick", "1,2,3,4" }, { "--pick 1,2,3,4", "X,Y,Z" });
  expectCleanProbeFailure("hard", { "--pick", "1,x,3" }, { "--pick 1,x,3", "X,Y,Z" });
}

TEST(CliProbeErrors, PickOfAPointNoPixelShows)
{
  // Half way from the camera's near plane to the surface a pixel shows: it projects into that pixel, but no surface
  // is there.
  const FrameResult& frame = stackedFrame("hard");
  const glm::ivec2 pixel = firstPixel(frame, true, [](float) { return true; }) + glm::ivec2(kSide / 2, kSide / 2);
  const ImageF& position = frame.find("position")->image;
  const glm::dvec3 surface(position.at(pixel.x, pixel.y, 0), position.at(pixel.x, pixel.y, 1), position.at(pixel.x, pixel.y, 2));
  const glm::dvec3 midway = 0.5 * (surface + unprojectPixel(frame.camera, pixel.x + 0.5, pixel.y + 0.5, -1.0));
  const std::string point = format(midway.x, ",", midway.y, ",", midway.z);
  expectCleanProbeFailure("hard", { "--pick", "world", point }, { "--pick world " + point, "not a visible surface point" });
  // Named as typed: without the word `world`.
  expectCleanProbeFailure("hard", { "--pick", point }, { "--pick " + point, "not a visible surface point" });
}

TEST(CliProbeErrors, UnknownTechnique)
{
  expectCleanProbeFailure("nope", { "--pixel", "3,4" }, { "--technique nope", "unknown" });
}

TEST(Probe, ATechniqueWithoutAProbeRecorderIsRefusedByName)
{
  const FrameResult& frame = stackedFrame("hard");
  TechniqueDescriptor withoutProbe = *frame.descriptor;
  withoutProbe.probe = nullptr;
  FrameResult copy = frame;
  copy.descriptor = &withoutProbe;
  const Scene scene = test::loadDataset("stacked-occluders");
  try
  {
    probePixel(copy, scene, 0, firstPixel(frame, true, [](float) { return true; }));
    FAIL() << "expected InputError";
  }
  catch (const InputError& error)
  {
    EXPECT_NE(std::string(error.what()).find("no probe recorder"), std::string::npos) << error.what();
  }
}

} // namespace
} // namespace sl
