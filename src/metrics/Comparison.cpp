#include "metrics/Comparison.h"

#include "core/Error.h"
#include "io/ImageIO.h"
#include "output/OutputWriter.h"
#include "frame/FrameResult.h"
#include "vis/HeatMap.h"

#include <cmath>
#include <utility>
#include <vector>

namespace sl
{

const ImageF& requireArray(const std::vector<NamedImage>& arrays, const std::string& name,
  const std::filesystem::path& file)
{
  if (const NamedImage* named = findNamed(arrays, name))
  {
    return named->image;
  }
  std::string available;
  for (const NamedImage& named : arrays)
  {
    available += (available.empty() ? "" : ", ") + named.name;
  }
  throw InputError(format(file.string(), ": no array '", name, "' (arrays: ", available.empty() ? "none" : available,
    ")"));
}

Comparison compareVtiFiles(const std::filesystem::path& testFile, const std::filesystem::path& referenceFile,
  const std::string& array)
{
  const std::vector<NamedImage> testArrays = readVti(testFile);
  const std::vector<NamedImage> referenceArrays = readVti(referenceFile);
  const ImageF& test = requireArray(testArrays, array, testFile);
  const ImageF& reference = requireArray(referenceArrays, array, referenceFile);
  // A missing coverage array is passed as an empty image: compareImages then uses the other file's.
  const ImageF noCoverage;
  const NamedImage* testCoverage = findNamed(testArrays, "coverage");
  const NamedImage* referenceCoverage = findNamed(referenceArrays, "coverage");
  return compareImages(test, reference, testCoverage ? testCoverage->image : noCoverage,
    referenceCoverage ? referenceCoverage->image : noCoverage,
    ComparisonInputNames{ testFile.string(), referenceFile.string(), array });
}

nlohmann::json comparisonJson(const Comparison& comparison, const std::filesystem::path& testFile,
  const std::filesystem::path& referenceFile)
{
  nlohmann::json document = metricsJson(comparison.metrics);
  document["test"] = testFile.string();
  document["reference"] = referenceFile.string();
  document["resolution"] = { comparison.error.width, comparison.error.height };
  return document;
}

void writeComparison(const Comparison& comparison, const std::filesystem::path& testFile,
  const std::filesystem::path& referenceFile, const OutputTarget& output)
{
  const ImageF& error = comparison.error;
  const ImageF& mask = comparison.mask;
  SL_CHECK(error.components == 1 && mask.components == 1);
  SL_CHECK(error.width == mask.width && error.height == mask.height);
  SL_CHECK(comparison.test.width == error.width && comparison.test.height == error.height);
  SL_CHECK(comparison.reference.width == error.width && comparison.reference.height == error.height);
  const std::string& array = comparison.metrics.array;

  ImageF absError(error.width, error.height, 1);
  ImageU8 validMask(error.width, error.height, 1);
  for (std::size_t i = 0; i < error.pixelCount(); ++i)
  {
    absError.data[i] = std::abs(error.data[i]);
    validMask.data[i] = mask.data[i] > 0.5f ? 1 : 0;
  }
  std::vector<NamedImage> images;
  images.push_back({ "error", error, "", "test - reference where compared, 0 elsewhere" });
  images.push_back({ "abs_error", std::move(absError), "", "|test - reference| where compared, 0 elsewhere" });
  images.push_back({ "reference", comparison.reference, "", "the reference's '" + array + "'" });
  images.push_back({ "test", comparison.test, "", "the test's '" + array + "'" });
  images.push_back({ "compared", mask, "", "1 where covered in both images (coverage > 0.5), else 0" });

  HeatMapOptions heatMap;
  heatMap.title = "error (test - reference)";
  heatMap.colorMap = ColorMapKind::Diverging; // range symmetric about 0 (no explicit bounds)
  const nlohmann::json document = comparisonJson(comparison, testFile, referenceFile);

  writeDirectoryAtomically(output, [&](const std::filesystem::path& dir) {
    writeVti(dir / "error.vti", images);
    writeHeatMapPng(error, &validMask, heatMap, dir / "error.png");
    writeJson(document, dir / "metrics.json");
  });
}

} // namespace sl
