// shadowlab reference --light-samples PATTERN --reference-samples N --seed S, end to end through the executable: the shared
// light-sample set of technique `dcs`, and the per-sample arrays sample_crossings and light_sample_mask in
// buffers.vti. The scene is planar-occluder: one square occluder over a ground plane, both horizontal under a
// light above them, so no sample is below a tangent plane, a sample is hidden exactly when its segment crosses the
// occluder, and no segment crosses more than that one quad (one of its two triangles).
#include "io/ImageIO.h"
#include "support/CliRun.h"
#include "support/TempDir.h"
#include "support/TestSupport.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkXMLImageDataReader.h>

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

namespace sl
{
namespace
{

using test::RunResult;

// Every point-data array of a .vti as VTK (and ParaView) read it, any number of components: the per-sample arrays
// have N of them, beyond what readVti accepts.
std::vector<NamedImage> readArraysWithVtk(const std::filesystem::path& file)
{
  vtkNew<vtkXMLImageDataReader> reader;
  reader->SetFileName(file.string().c_str());
  reader->Update();
  vtkImageData* data = reader->GetOutput();
  int dimensions[3] = { 0, 0, 0 };
  data->GetDimensions(dimensions);
  std::vector<NamedImage> images;
  for (int a = 0; a < data->GetPointData()->GetNumberOfArrays(); ++a)
  {
    vtkDataArray* array = data->GetPointData()->GetArray(a);
    if (!array || !array->GetName())
    {
      continue;
    }
    NamedImage named;
    named.name = array->GetName();
    named.image = ImageF(dimensions[0], dimensions[1], array->GetNumberOfComponents());
    for (vtkIdType t = 0; t < array->GetNumberOfTuples(); ++t)
    {
      for (int c = 0; c < named.image.components; ++c)
      {
        named.image.data[static_cast<std::size_t>(t) * named.image.components + c] =
          static_cast<float>(array->GetComponent(t, c));
      }
    }
    images.push_back(std::move(named));
  }
  return images;
}

using test::arrayNamed;

using test::readJson;

int popcount(std::uint32_t bits)
{
  int count = 0;
  for (; bits; bits &= bits - 1)
  {
    ++count;
  }
  return count;
}

// The arrays of one run: component counts, crossings in {0, 1}, mask bits = crossed samples, visibility = the
// fraction of samples not hidden on every covered receiving pixel, and some samples crossed, some not.
void expectConsistentArrays(const std::filesystem::path& out, int sampleCount, const std::string& label)
{
  const std::vector<NamedImage> buffers = readArraysWithVtk(out / "buffers.vti");
  const ImageF& crossings = arrayNamed(buffers, "sample_crossings").image;
  const ImageF& mask = arrayNamed(buffers, "light_sample_mask").image;
  const ImageF& visibility = arrayNamed(buffers, "visibility").image;
  const ImageF& coverage = arrayNamed(buffers, "coverage").image;
  const ImageF& receives = arrayNamed(buffers, "receives_shadows").image;
  ASSERT_EQ(crossings.components, sampleCount) << label;
  ASSERT_EQ(mask.components, sampleCount / 16) << label;
  ASSERT_EQ(crossings.width, 32) << label;
  ASSERT_EQ(mask.height, 32) << label;
  int crossedSamples = 0;
  int clearSamples = 0;
  for (int y = 0; y < 32; ++y)
  {
    for (int x = 0; x < 32; ++x)
    {
      const std::string where = label + ", pixel " + std::to_string(x) + "," + std::to_string(y);
      int hidden = 0;
      for (int i = 0; i < sampleCount; ++i)
      {
        const float count = crossings.at(x, y, i);
        ASSERT_TRUE(count == 0.0f || count == 1.0f) << where << " sample " << i << ": " << count;
        const auto bits = static_cast<std::uint32_t>(mask.at(x, y, i / 16));
        ASSERT_EQ(static_cast<float>(bits), mask.at(x, y, i / 16)) << where;
        EXPECT_EQ((bits >> (i % 16)) & 1u, count > 0.0f ? 1u : 0u) << where << " sample " << i;
        hidden += count > 0.0f;
        if (coverage.at(x, y) > 0.5f)
        {
          (count > 0.0f ? crossedSamples : clearSamples) += 1;
        }
      }
      int popcounted = 0;
      for (int c = 0; c < sampleCount / 16; ++c)
      {
        popcounted += popcount(static_cast<std::uint32_t>(mask.at(x, y, c)));
      }
      EXPECT_EQ(popcounted, hidden) << where;
      if (coverage.at(x, y) > 0.5f && receives.at(x, y) > 0.5f)
      {
        EXPECT_FLOAT_EQ(visibility.at(x, y), static_cast<float>(sampleCount - hidden) / sampleCount) << where;
      }
      else if (coverage.at(x, y) <= 0.5f)
      {
        EXPECT_EQ(hidden, 0) << where << ": uncovered pixels have no samples";
      }
    }
  }
  EXPECT_GT(crossedSamples, sampleCount * 20) << label << ": the occluder's shadow";
  EXPECT_GT(clearSamples, sampleCount * 20) << label << ": the lit ground";
}

TEST(ReferenceLightSamplesCommand, WritesSampleCrossingsAndMaskWithTheSetsCount)
{
  const std::string scene = test::datasetPath("planar-occluder").string();
  const std::filesystem::path out = test::freshOutputDir("reference-light-samples");
  const RunResult run = test::runShadowlabInTempDir({ "reference", scene, "--light-samples", "poisson", "--reference-samples", "64", "--seed",
    "3", "-r", "32x32", "--out", out.string() });
  ASSERT_EQ(run.exitCode, 0) << run.describe();
  // The log says the pattern, N and the seed.
  EXPECT_NE(run.err.find("64 poisson samples (light-sample set, seed 3)"), std::string::npos) << run.err;
  expectConsistentArrays(out, 64, "poisson x 64");
  const nlohmann::json stats = readJson(out / "stats.json");
  EXPECT_EQ(stats.at("samples").get<int>(), 64);
  EXPECT_EQ(stats.at("sampling").get<std::string>(), "poisson");
  EXPECT_EQ(stats.at("light_samples").at("pattern").get<std::string>(), "poisson");
  EXPECT_EQ(stats.at("light_samples").at("count").get<int>(), 64);
  EXPECT_EQ(stats.at("light_samples").at("seed").get<int>(), 3);
  EXPECT_EQ(stats.at("buffers").at("sample_crossings").at("components").get<int>(), 64);
  EXPECT_EQ(stats.at("buffers").at("light_sample_mask").at("components").get<int>(), 4);

  // Interleaved, N = 256 (16 mask components), and N = 16 by default.
  const std::filesystem::path interleaved = test::freshOutputDir("reference-light-samples-256");
  const RunResult run256 = test::runShadowlabInTempDir({ "reference", scene, "--light-samples", "zero_two_4x4", "-n", "256", "-r",
    "32x32", "-q", "--out", interleaved.string() });
  ASSERT_EQ(run256.exitCode, 0) << run256.describe();
  expectConsistentArrays(interleaved, 256, "zero_two_4x4 x 256");
  const std::filesystem::path byDefault = test::freshOutputDir("reference-light-samples-16");
  const RunResult run16 = test::runShadowlabInTempDir({ "reference", scene, "--light-samples", "grid", "-r", "32x32", "-q", "--out",
    byDefault.string() });
  ASSERT_EQ(run16.exitCode, 0) << run16.describe();
  expectConsistentArrays(byDefault, 16, "grid, default N");

  // Without --light-samples, neither array.
  const std::filesystem::path plain = test::freshOutputDir("reference-plain-samples");
  ASSERT_EQ(test::runShadowlabInTempDir({ "reference", scene, "-n", "16", "-r", "32x32", "-q", "--out", plain.string() }).exitCode, 0);
  const std::vector<NamedImage> plainBuffers = readArraysWithVtk(plain / "buffers.vti");
  EXPECT_EQ(findNamed(plainBuffers, "sample_crossings"), nullptr);
  EXPECT_EQ(findNamed(plainBuffers, "light_sample_mask"), nullptr);
}

// The reference with per-sample arrays is still a reference: compare reads it (and the technique's output) as
// any other, whatever the arrays' component counts.
TEST(ReferenceLightSamplesCommand, CompareReadsTheReference)
{
  const std::string scene = test::datasetPath("planar-occluder").string();
  const std::filesystem::path hard = test::freshOutputDir("reference-light-samples-hard");
  const std::filesystem::path reference = test::freshOutputDir("reference-light-samples-compared");
  const std::filesystem::path out = test::freshOutputDir("reference-light-samples-compare");
  ASSERT_EQ(test::runShadowlabInTempDir({ "render", scene, "-t", "hard", "-r", "32x32", "-q", "--out", hard.string() }).exitCode, 0);
  const RunResult referenceRun = test::runShadowlabInTempDir({ "reference", scene, "--light-samples", "stratified", "-n", "64", "-r",
    "32x32", "-q", "--out", reference.string() });
  ASSERT_EQ(referenceRun.exitCode, 0) << referenceRun.describe();
  const RunResult run = test::runShadowlabInTempDir({ "compare", (hard / "buffers.vti").string(),
    (reference / "buffers.vti").string(), "-q", "--out", out.string() });
  EXPECT_EQ(run.exitCode, 0) << run.describe();
  EXPECT_TRUE(std::filesystem::exists(out / "metrics.json"));
}

TEST(ReferenceLightSamplesCommand, BadSetsAreOneLineErrorsWithNoOutput)
{
  const std::string planar = test::datasetPath("planar-occluder").string();
  const std::filesystem::path out = test::freshOutputDir("reference-light-samples-bad");
  struct Case
  {
    std::vector<std::string> arguments;
    std::vector<std::string> named; // what the message must name
  };
  const std::vector<Case> cases = {
    { { planar, "--light-samples", "spiral", "--reference-samples", "16" }, { "--light-samples", "spiral" } },
    { { planar, "--light-samples", "grid", "--reference-samples", "10" }, { "--reference-samples", "10" } },
    { { planar, "--light-samples", "poisson", "--reference-samples", "1024" }, { "--reference-samples", "1024" } },
    { { planar, "--light-samples", "grid", "--sampling", "halton" }, { "--light-samples", "--sampling" } },
    { { planar, "--sampling", "stratified", "--light-samples", "grid" }, { "--light-samples", "--sampling" } },
    { { planar, "--light-samples", "grid", "--seed", "4294967296" }, { "--seed", "4294967296" } },
    { { test::datasetPath("sphere-point").string(), "--light-samples", "grid" }, { "--light-samples", "area light" } },
  };
  for (const Case& c : cases)
  {
    std::vector<std::string> arguments = { "reference" };
    arguments.insert(arguments.end(), c.arguments.begin(), c.arguments.end());
    arguments.insert(arguments.end(), { "-r", "32x32", "--out", out.string() });
    const RunResult run = test::runShadowlabInTempDir(arguments);
    EXPECT_NE(run.exitCode, 0) << run.describe();
    EXPECT_EQ(run.errLines(), 1u) << run.describe();
    for (const std::string& name : c.named)
    {
      EXPECT_NE(run.err.find(name), std::string::npos) << "should name " << name << "\n" << run.describe();
    }
    EXPECT_FALSE(std::filesystem::exists(out)) << run.describe();
  }
}

} // namespace
} // namespace sl
