// ss08 (quality-scalable soft shadow mapping, Schwarz & Stamminger 2008, SS08) against the paper's claims as
// numbers (tests 7-10 below, and the budget map of Fig. 1 d):
//  - the smoothed LOQ map is continuous on each surface although the raw one is not (SS08 §4.2);
//  - blending between floor(l) and ceil(l) weakens the seams where ceil(l) changes (Fig. 1 a vs b), and without
//    blending microrects show weaker seams than micropatches (Fig. 13);
//  - quality scales with the budget: the error against the Embree reference does not grow as the budget grows,
//    the micro-occluders examined do, and the share of back-projecting pixels does not (Table 2, Fig. 10);
//  - a budget map lowers the cost where it lowers the budget (Fig. 1 d);
//  - at coarse forced levels microrects with occlusion bitmasks beat micropatches (Fig. 12), and the bitmasks help
//    microrects where they overlap.
// Each prints its figures in [ measured ] lines. Frames 128^2, shadow maps 512^2 (llvmpipe; Fig. 12: 256^2).
#include "metrics/ErrorMetrics.h"
#include "reference/ReferenceRenderer.h"
#include "support/TestSupport.h"
#include "techniques/ss08/Ss08Technique.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <iostream>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <tuple>
#include <vector>

namespace sl
{
namespace
{


constexpr int kQualityFrameSize = 128;
const char* const kMapSetting = "shadow_map_size=512";

using test::bufferOf;

double statistic(const FrameResult& frame, const std::string& name)
{
  const auto found = frame.techniqueStatistics.find(name);
  if (found == frame.techniqueStatistics.end())
  {
    throw std::runtime_error("ss08 frame has no technique statistic '" + name + "'");
  }
  return found->second;
}

// A gtest name: every character that is not a letter or digit turned into '_'.
std::string gtestName(std::string name)
{
  for (char& c : name)
  {
    c = std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  }
  return name;
}

std::string datasetTestName(const ::testing::TestParamInfo<std::string>& info)
{
  return gtestName(info.param);
}

// The Embree reference at a frame's G-buffer points (the ground truth of Table 2's and Fig. 12's comparisons, which
// the paper makes against many shadow maps), with the RMS of its standard error: the noise every RMSE against it
// carries.
constexpr int kReferenceSamples = 2048;

struct Reference
{
  ImageF visibility;
  ImageF standardError;
  ImageF coverage;               // the frame's: ErrorMetrics compares the covered pixels
  double rmsErrorCovered = 0.0;  // RMS of the standard error (Bernoulli bound) over the covered pixels
  double rmsErrorPenumbra = 0.0; // ... over the reference's penumbra (0 < V < 1)

  bool covered(std::size_t i) const { return coverage.data[i * coverage.components] > 0.5f; }
  // The error of a frame of the same camera (any ss08 settings) over the pixels ErrorMetrics compares.
  ErrorMetrics errorOf(const FrameResult& frame) const
  {
    return computeErrorMetrics(bufferOf(frame, "visibility"), visibility, coverage, coverage);
  }
};

Reference referenceOf(const FrameResult& frame, const Scene& scene)
{
  const ReferenceInputs inputs = test::referenceInputs(frame, scene);
  ReferenceSettings settings;
  settings.samples = kReferenceSamples;
  const ReferenceResult rays = renderReference(inputs, settings);
  Reference reference;
  reference.visibility = rays.visibility;
  reference.standardError = rays.standardError;
  reference.coverage = inputs.coverage;
  double sums[2] = { 0.0, 0.0 };
  int counts[2] = { 0, 0 };
  for (std::size_t i = 0; i < reference.visibility.data.size(); ++i)
  {
    if (!reference.covered(i))
    {
      continue;
    }
    const double variance = static_cast<double>(rays.standardError.data[i]) * rays.standardError.data[i];
    const bool penumbra = reference.visibility.data[i] > 0.0f && reference.visibility.data[i] < 1.0f;
    for (int set = 0; set < (penumbra ? 2 : 1); ++set)
    {
      sums[set] += variance;
      ++counts[set];
    }
  }
  reference.rmsErrorCovered = counts[0] > 0 ? std::sqrt(sums[0] / counts[0]) : 0.0;
  reference.rmsErrorPenumbra = counts[1] > 0 ? std::sqrt(sums[1] / counts[1]) : 0.0;
  return reference;
}

std::string describe(const Reference& reference)
{
  std::ostringstream text;
  text << kReferenceSamples << " samples, RMS standard error (Bernoulli bound) " << reference.rmsErrorCovered
       << " over the covered pixels, " << reference.rmsErrorPenumbra << " over its penumbra";
  return text.str();
}

// Pixels that back-project micro-occluders: the search's penumbra, or (growth=on) the penumbra of the grown query
// only (Ss08Technique.h, Ss08Class).
std::vector<bool> backProjectingPixels(const FrameResult& frame)
{
  const ImageF& classes = bufferOf(frame, "classification");
  const bool growth = frame.parameters.choice("growth") == "on";
  std::vector<bool> mask(classes.pixelCount());
  for (std::size_t i = 0; i < mask.size(); ++i)
  {
    const int code = static_cast<int>(classes.data[i]);
    mask[i] = code == static_cast<int>(Ss08Class::Penumbra) || (growth && code == static_cast<int>(Ss08Class::GrowthPenumbra));
  }
  return mask;
}

// The smoothing's own same-surface test (Ss08LoqSmoothing.glsl): |delta camera depth| <= smoothing_depth_threshold x
// the smaller depth; the camera depth is the `depth` buffer (the G-buffer's, which the smoothing reads).
bool sameSurface(double depthA, double depthB, double threshold)
{
  return std::abs(depthA - depthB) <= threshold * std::min(depthA, depthB);
}

struct PixelPair
{
  std::size_t a = 0;
  std::size_t b = 0;
};

// The eligible pairs of test 7: 4-neighbour pairs of back-projecting pixels on the same surface.
std::vector<PixelPair> eligiblePairs(const FrameResult& frame)
{
  const ImageF& depth = bufferOf(frame, "depth");
  const std::vector<bool> backProjects = backProjectingPixels(frame);
  const double threshold = frame.parameters.get("smoothing_depth_threshold");
  std::vector<PixelPair> pairs;
  for (int y = 0; y < depth.height; ++y)
  {
    for (int x = 0; x < depth.width; ++x)
    {
      const std::size_t a = static_cast<std::size_t>(y) * depth.width + x;
      if (!backProjects[a])
      {
        continue;
      }
      for (const glm::ivec2 step : { glm::ivec2(1, 0), glm::ivec2(0, 1) })
      {
        if (x + step.x >= depth.width || y + step.y >= depth.height)
        {
          continue;
        }
        const std::size_t b = static_cast<std::size_t>(y + step.y) * depth.width + (x + step.x);
        if (backProjects[b] && sameSurface(depth.data[a], depth.data[b], threshold))
        {
          pairs.push_back({ a, b });
        }
      }
    }
  }
  return pairs;
}

// Whether the smoothing's 11 x 11 box around pixel i is whole: every pixel in it back-projects and no run inside it
// crosses a depth discontinuity. Where it is not, the separable runs of neighbouring pixels are cut at different
// places, and their averages may differ by more than a whole box's would.
bool wholeSmoothingBox(const FrameResult& frame, const std::vector<bool>& backProjects, std::size_t i)
{
  const ImageF& depth = bufferOf(frame, "depth");
  const double threshold = frame.parameters.get("smoothing_depth_threshold");
  const int x = static_cast<int>(i % depth.width);
  const int y = static_cast<int>(i / depth.width);
  const int r = ss08SmoothingRadius;
  if (x < r || y < r || x + r >= depth.width || y + r >= depth.height)
  {
    return false;
  }
  for (int ny = y - r; ny <= y + r; ++ny)
  {
    for (int nx = x - r; nx <= x + r; ++nx)
    {
      if (!backProjects[static_cast<std::size_t>(ny) * depth.width + nx] ||
        (nx < x + r && !sameSurface(depth.at(nx, ny), depth.at(nx + 1, ny), threshold)) ||
        (ny < y + r && !sameSurface(depth.at(nx, ny), depth.at(nx, ny + 1), threshold)))
      {
        return false;
      }
    }
  }
  return true;
}

// |delta l| over the eligible pairs: after smoothing (`loq`) and before (`loq_raw`).
struct Continuity
{
  std::size_t pairs = 0;
  std::size_t within = 0;        // |delta loq| <= 0.3
  std::size_t outsideWhole = 0;  // |delta loq| > 0.3 with both smoothing boxes whole
  double maxSmoothed = 0.0;
  double maxRaw = 0.0;
  std::size_t rawAboveHalf = 0; // |delta loq_raw| > 0.5
  double fractionWithin() const { return pairs > 0 ? static_cast<double>(within) / pairs : 0.0; }
};

Continuity continuityOf(const FrameResult& frame)
{
  const ImageF& smoothed = bufferOf(frame, "loq");
  const ImageF& raw = bufferOf(frame, "loq_raw");
  const std::vector<bool> backProjects = backProjectingPixels(frame);
  Continuity result;
  for (const PixelPair& pair : eligiblePairs(frame))
  {
    const double smoothedStep = std::abs(smoothed.data[pair.a] - smoothed.data[pair.b]);
    const double rawStep = std::abs(raw.data[pair.a] - raw.data[pair.b]);
    ++result.pairs;
    if (smoothedStep <= 0.3)
    {
      ++result.within;
    }
    else if (wholeSmoothingBox(frame, backProjects, pair.a) && wholeSmoothingBox(frame, backProjects, pair.b))
    {
      ++result.outsideWhole;
    }
    result.rawAboveHalf += rawStep > 0.5 ? 1 : 0;
    result.maxSmoothed = std::max(result.maxSmoothed, smoothedStep);
    result.maxRaw = std::max(result.maxRaw, rawStep);
  }
  return result;
}

// The seam ratio of test 8: R = mean |delta V| over the eligible pairs whose ceil(loq) differs (seam
// pairs) / mean |delta V| over the other eligible pairs. Sums, so that frames can be pooled.
struct SeamRatio
{
  std::size_t seamPairs = 0;
  std::size_t otherPairs = 0;
  double seamSum = 0.0;
  double otherSum = 0.0;
  double seamMean() const { return seamPairs > 0 ? seamSum / seamPairs : 0.0; }
  double otherMean() const { return otherPairs > 0 ? otherSum / otherPairs : 0.0; }
  double ratio() const { return otherMean() > 0.0 ? seamMean() / otherMean() : 0.0; }
  SeamRatio& operator+=(const SeamRatio& other)
  {
    seamPairs += other.seamPairs;
    otherPairs += other.otherPairs;
    seamSum += other.seamSum;
    otherSum += other.otherSum;
    return *this;
  }
};

SeamRatio seamRatioOf(const FrameResult& frame)
{
  const ImageF& levels = bufferOf(frame, "loq");
  const ImageF& visibility = bufferOf(frame, "visibility");
  SeamRatio result;
  for (const PixelPair& pair : eligiblePairs(frame))
  {
    const double step = std::abs(visibility.data[pair.a] - visibility.data[pair.b]);
    if (std::ceil(levels.data[pair.a]) != std::ceil(levels.data[pair.b]))
    {
      ++result.seamPairs;
      result.seamSum += step;
    }
    else
    {
      ++result.otherPairs;
      result.otherSum += step;
    }
  }
  return result;
}

std::string describe(const SeamRatio& seams)
{
  std::ostringstream text;
  text << "R " << seams.ratio() << " (" << seams.seamPairs << " seam pairs, mean |dV| " << seams.seamMean() << "; "
       << seams.otherPairs << " other pairs, mean |dV| " << seams.otherMean() << ")";
  return text.str();
}

// The seam tests pool budgets 3..9: one budget puts a few tens of seam pairs on a dataset (stacked-occluders: 0 to
// 80), and where they fall moves with the budget, so a single budget's R is noisy.
const std::vector<int> kSeamBudgets = { 3, 4, 5, 7, 9 };

// Test 7 (SS08 §4.2: the LOQ map is smoothed "to avoid abrupt changes" of quality). At a 512^2
// map the raw map steps by whole levels between neighbours where the refined search area's span jumps (the minimum
// depth inside it switches occluder); budget 5 is gated. Budget 3 is reported: there the bunny's raw map steps by up
// to 4 levels, more than an 11-wide box spreads below 0.3 per pixel (4 / 11 > 0.36), so the 99 % cannot hold by
// construction. On stacked-occluders at budget 3 the grown queries (level ceil(l) = 6, 64-texel supports) all reach
// the upper occluder, so the raw map is flat on every surface and the case proves nothing (reported only).
TEST(Ss08Quality, LoqMapIsContinuousOnEachSurfaceAfterSmoothing)
{
  constexpr int gatedBudget = 5;
  for (const std::string dataset : { "bunny", "stacked-occluders" })
  {
    const Scene scene = test::loadDataset(dataset);
    for (const int budget : { 3, gatedBudget })
    {
      for (const std::string floor : { "none", "raw" })
      {
        const std::vector<std::string> settings = { kMapSetting, "budget=" + std::to_string(budget), "loq_floor=" + floor };
        const FrameResult frame = test::renderSs08(scene, kQualityFrameSize, kQualityFrameSize, settings);
        const Continuity continuity = continuityOf(frame);
        const std::string label = test::caseLabel(dataset, settings);
        const bool gated = budget == gatedBudget && floor == "none"; // the default floor; raw restores the raw steps
        std::cout << "[ measured ] ss08 LOQ continuity, " << label << (gated ? " (gated)" : " (reported)") << ": "
                  << continuity.pairs << " eligible pairs, " << 100.0 * continuity.fractionWithin()
                  << " % with |dl| <= 0.3 after smoothing (max " << continuity.maxSmoothed << "; of the "
                  << continuity.pairs - continuity.within << " above, " << continuity.outsideWhole
                  << " with both 11 x 11 boxes whole); raw map: max |dl| " << continuity.maxRaw << ", "
                  << continuity.rawAboveHalf << " pairs above 0.5\n";
        EXPECT_GT(continuity.pairs, 500u) << label;
        if (gated)
        {
          EXPECT_GT(continuity.maxRaw, 0.5) << label << ": the raw LOQ map must step somewhere, otherwise this proves nothing";
          EXPECT_GE(continuity.fractionWithin(), 0.99) << label;
        }
      }
    }
  }
}

// Test 8, blending (Fig. 1 a vs b; SS08 §4.2): at the pairs where ceil(l) changes, visibility
// steps more than elsewhere unless the two levels are blended. One case per square-light dataset; a dataset with
// fewer than 20 seam pairs over the budgets is skipped (said in its [ measured ] line).
class Ss08Seams : public ::testing::TestWithParam<std::string>
{
};

TEST_P(Ss08Seams, BlendingWeakensTheSeamsWhereTheLevelChanges)
{
  const std::string dataset = GetParam();
  const Scene scene = test::loadDataset(dataset);
  SeamRatio pooled[2]; // blend_band = 0, 1
  for (const int budget : kSeamBudgets)
  {
    SeamRatio ratios[2];
    for (int blend = 0; blend < 2; ++blend)
    {
      const FrameResult frame = test::renderSs08(scene, kQualityFrameSize, kQualityFrameSize,
        { kMapSetting, "budget=" + std::to_string(budget), "blend_band=" + std::to_string(blend) });
      ratios[blend] = seamRatioOf(frame);
      pooled[blend] += ratios[blend];
    }
    std::cout << "[ measured ] ss08 seams on " << dataset << " (" << kMapSetting << ", budget=" << budget
              << "): blend_band=1 " << describe(ratios[1]) << "; blend_band=0 " << describe(ratios[0]) << "\n";
    // Blending does not touch the LOQ map, so both frames have the same pairs.
    EXPECT_EQ(ratios[1].seamPairs, ratios[0].seamPairs) << dataset << " budget " << budget;
    EXPECT_EQ(ratios[1].otherPairs, ratios[0].otherPairs) << dataset << " budget " << budget;
  }
  std::cout << "[ measured ] ss08 seams on " << dataset << ", budgets 3, 4, 5, 7, 9 pooled: blend_band=1 "
            << describe(pooled[1]) << "; blend_band=0 " << describe(pooled[0]) << "\n";
  if (pooled[0].seamPairs < 20)
  {
    std::cout << "[ measured ] ss08 seams on " << dataset << ": skipped, " << pooled[0].seamPairs
              << " seam pairs (< 20): the level does not change between neighbours on one surface\n";
    return;
  }
  EXPECT_LT(pooled[1].ratio(), pooled[0].ratio()) << dataset;
}

INSTANTIATE_TEST_SUITE_P(SquareLightDatasets, Ss08Seams,
  ::testing::Values("bunny", "contact", "fence", "grazing", "near-light", "planar-occluder", "stacked-occluders"),
  datasetTestName);

// Test 8, Fig. 13: without blending, micropatches (min-aggregated texels) step more at the level seams
// than microrects (bounding rectangles of texels merged by depth, SS08 §5.2), with area accumulation (the bitmasks
// the paper pairs microrects with come later). The paper says "often"; per budget the order flips on some budgets
// (printed), so the gate is on the pooled ratio. Micro_occluder changes the grown queries, hence the LOQ map and
// the seams: each kind is measured on its own seams.
TEST(Ss08Quality, MicrorectsShowWeakerSeamsThanMicropatchesWithoutBlending)
{
  for (const std::string dataset : { "bunny", "stacked-occluders" })
  {
    const Scene scene = test::loadDataset(dataset);
    const char* const kinds[2] = { "micropatch", "microrect" };
    SeamRatio pooled[2];
    for (const int budget : kSeamBudgets)
    {
      SeamRatio ratios[2];
      for (int k = 0; k < 2; ++k)
      {
        const FrameResult frame = test::renderSs08(scene, kQualityFrameSize, kQualityFrameSize,
          { kMapSetting, "budget=" + std::to_string(budget), "blend_band=0", std::string("micro_occluder=") + kinds[k] });
        ratios[k] = seamRatioOf(frame);
        pooled[k] += ratios[k];
      }
      std::cout << "[ measured ] ss08 seams without blending on " << dataset << " (" << kMapSetting << ", budget="
                << budget << "): micropatch " << describe(ratios[0]) << "; microrect " << describe(ratios[1]) << "\n";
    }
    std::cout << "[ measured ] ss08 seams without blending on " << dataset << ", budgets 3, 4, 5, 7, 9 pooled: micropatch "
              << describe(pooled[0]) << "; microrect " << describe(pooled[1]) << "\n";
    ASSERT_GE(pooled[0].seamPairs, 20u) << dataset;
    ASSERT_GE(pooled[1].seamPairs, 20u) << dataset;
    EXPECT_LT(pooled[1].ratio(), pooled[0].ratio()) << dataset;
  }
}

// Test 9 (Table 2, Fig. 10): over budgets 3, 5, 9, 12, 16 and unlimited, the RMSE against the Embree
// reference at the same pixels does not grow (to 0.002), the share of back-projecting pixels does not grow (small
// budgets mean coarse levels, whose grown depth-range queries (Fig. 7) reach more occluders), and the micro-occluders
// examined per back-projecting pixel grow strictly over the finite budgets. The unlimited budget neither smooths nor
// blends (level 0 alone), while every finite one blends floor(l) and ceil(l) (up to (2b)^2 + b^2 slots, §8):
// where a budget hardly binds (the bunny at 512^2: mean l 0.03 at b = 16) the blend's second level costs more than
// the budget saves. So the unlimited budget is compared with the finite ones' floor(l) slots alone (the cost of one
// level, micro_occluders / blend_overhead_vs_floor_level), and the blend overhead is printed.
class Ss08Scaling : public ::testing::TestWithParam<std::string>
{
};

TEST_P(Ss08Scaling, QualityAndCostScaleWithTheBudget)
{
  const std::string dataset = GetParam();
  const Scene scene = test::loadDataset(dataset);
  const std::vector<int> budgets = { 3, 5, 9, 12, 16, 0 }; // 0 = unlimited, last
  struct Row
  {
    int budget = 0;
    ErrorMetrics error;
    double backProjectingPercent = 0.0;
    double microOccludersMean = 0.0;
    double microOccludersStdev = 0.0;
    double floorLevelMean = 0.0; // floor(l)'s slots alone
    double blendOverhead = 0.0;
    double meanLoq = 0.0;
    double cutShort = 0.0;
  };
  std::vector<Row> rows;
  std::optional<Reference> reference; // the camera, hence the G-buffer points, are the same at every budget
  for (const int budget : budgets)
  {
    const FrameResult frame = test::renderSs08(scene, kQualityFrameSize, kQualityFrameSize,
      { kMapSetting, "budget=" + std::to_string(budget) });
    if (!reference)
    {
      reference = referenceOf(frame, scene);
    }
    Row row;
    row.budget = budget;
    row.error = reference->errorOf(frame);
    row.backProjectingPercent = statistic(frame, "backprojecting_pixels_percent");
    row.microOccludersMean = statistic(frame, "micro_occluders_mean");
    row.microOccludersStdev = statistic(frame, "micro_occluders_stdev");
    row.blendOverhead = statistic(frame, "blend_overhead_vs_floor_level");
    row.floorLevelMean = row.blendOverhead > 0.0 ? row.microOccludersMean / row.blendOverhead : 0.0;
    row.meanLoq = statistic(frame, "mean_loq");
    row.cutShort = statistic(frame, "cut_short_pixels");
    rows.push_back(row);
  }
  std::cout << "[ measured ] ss08 quality by budget on " << dataset << " (" << kQualityFrameSize << "^2, " << kMapSetting
            << "; Embree " << describe(*reference) << ")\n"
            << "[ measured ]   budget | RMSE | penumbra RMSE | % back-projecting | micro-occluders mean | stdev | floor(l) alone | blend overhead | mean l | cut short\n";
  for (const Row& row : rows)
  {
    std::cout << "[ measured ]   " << (row.budget == 0 ? std::string("inf") : std::to_string(row.budget)) << " | "
              << row.error.covered.rmse << " | " << row.error.penumbra.rmse << " | " << row.backProjectingPercent << " | "
              << row.microOccludersMean << " | " << row.microOccludersStdev << " | " << row.floorLevelMean << " | "
              << row.blendOverhead << " | " << row.meanLoq << " | " << row.cutShort << "\n";
  }
  // The reference is the same image for every budget, so its noise shifts the RMSEs alike; it must still be small
  // next to the spread being measured.
  const double spread = rows.front().error.covered.rmse - rows.back().error.covered.rmse;
  EXPECT_LT(reference->rmsErrorCovered, 0.25 * spread) << dataset << ": the reference's noise must be well below the differences";
  for (std::size_t i = 0; i < rows.size(); ++i)
  {
    const std::string label = dataset + " budget " + std::to_string(rows[i].budget);
    EXPECT_EQ(rows[i].cutShort, 0.0) << label << ": pixels cut short by the loop cap are not exact";
    EXPECT_GT(rows[i].error.penumbra.pixels, 200u) << label;
    if (i == 0)
    {
      continue;
    }
    const Row& smaller = rows[i - 1];
    const std::string versus = label + " vs budget " + std::to_string(smaller.budget);
    EXPECT_LE(rows[i].error.covered.rmse, smaller.error.covered.rmse + 0.002) << versus << ": the error must not grow with the budget";
    EXPECT_LE(rows[i].backProjectingPercent, smaller.backProjectingPercent) << versus << ": back-projecting pixels must not grow with the budget";
    if (rows[i].budget != 0)
    {
      EXPECT_GT(rows[i].microOccludersMean, smaller.microOccludersMean) << versus << ": the micro-occluders examined must grow with the budget";
    }
    else
    {
      EXPECT_EQ(rows[i].blendOverhead, 1.0) << label << ": the unlimited budget examines one level";
      EXPECT_GE(rows[i].microOccludersMean, smaller.floorLevelMean) << versus << " (floor(l) alone): level 0 examines the most";
      EXPECT_GT(rows[i].microOccludersMean, rows.front().microOccludersMean) << label << " vs budget 3";
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Datasets, Ss08Scaling, ::testing::Values("bunny", "stacked-occluders"), datasetTestName);

// The budget map of Fig. 1 d: budget_map=ramp_x, 12 at the centre column falling to 5 at the left and right ones.
// The budget buffer holds exactly those values wherever the search ran, and the micro-occluders examined per
// back-projecting pixel are fewer in the outer fifths of the columns than in the central fifth, and fewer there than
// at a uniform 12 (the border's cost falls because its budget does, not only because of what lies there).
TEST(Ss08Quality, BudgetMapLowersTheCostAtTheBorders)
{
  const Scene scene = test::loadDataset("bunny");
  const FrameResult ramp = test::renderSs08(scene, kQualityFrameSize, kQualityFrameSize,
    { kMapSetting, "budget_map=ramp_x", "budget=12", "budget_border=5" });
  const FrameResult uniform = test::renderSs08(scene, kQualityFrameSize, kQualityFrameSize, { kMapSetting, "budget=12" });
  const ImageF& budget = bufferOf(ramp, "budget");
  const ImageF& classes = bufferOf(ramp, "classification");
  const int width = budget.width;
  const int height = budget.height;
  int checkedBorder = 0;
  int checkedCentre = 0;
  // The centre column(s): (width - 1) / 2 and width / 2, one and the same for an odd width.
  for (const int x : { 0, width - 1, (width - 1) / 2, width / 2 })
  {
    const bool border = x == 0 || x == width - 1;
    for (int y = 0; y < height; ++y)
    {
      if (classes.at(x, y) == static_cast<float>(Ss08Class::NotTested)) // not searched: budget 0
      {
        continue;
      }
      EXPECT_EQ(budget.at(x, y), border ? 5.0f : 12.0f) << "pixel " << x << "," << y;
      ++(border ? checkedBorder : checkedCentre);
    }
  }
  EXPECT_GT(checkedBorder, height);
  EXPECT_GT(checkedCentre, height);

  // Mean micro_occluders over the back-projecting pixels of the columns [from, to).
  const auto meanCost = [&](const FrameResult& frame, int from, int to, int& pixels) {
    const std::vector<bool> backProjects = backProjectingPixels(frame);
    const ImageF& counts = bufferOf(frame, "micro_occluders");
    double sum = 0.0;
    pixels = 0;
    for (int y = 0; y < height; ++y)
    {
      for (int x = from; x < to; ++x)
      {
        if (backProjects[static_cast<std::size_t>(y) * width + x])
        {
          sum += counts.at(x, y);
          ++pixels;
        }
      }
    }
    return sum;
  };
  const int fifth = width / 5;
  const int centreFrom = (width - fifth) / 2;
  const auto outerAndCentre = [&](const FrameResult& frame, int& outerPixels, int& centrePixels, double& outer, double& centre) {
    int left = 0;
    int right = 0;
    outer = meanCost(frame, 0, fifth, left) + meanCost(frame, width - fifth, width, right);
    outerPixels = left + right;
    outer /= std::max(outerPixels, 1);
    centre = meanCost(frame, centreFrom, centreFrom + fifth, centrePixels) / std::max(centrePixels, 1);
  };
  int rampOuterPixels = 0;
  int rampCentrePixels = 0;
  int uniformOuterPixels = 0;
  int uniformCentrePixels = 0;
  double rampOuter = 0.0;
  double rampCentre = 0.0;
  double uniformOuter = 0.0;
  double uniformCentre = 0.0;
  outerAndCentre(ramp, rampOuterPixels, rampCentrePixels, rampOuter, rampCentre);
  outerAndCentre(uniform, uniformOuterPixels, uniformCentrePixels, uniformOuter, uniformCentre);
  std::cout << "[ measured ] ss08 budget map ramp_x 12 -> 5 on bunny (" << kQualityFrameSize << "^2, " << kMapSetting
            << "): budget buffer 5 at the border columns, 12 at the centre (" << checkedBorder << " / " << checkedCentre
            << " pixels); mean micro-occluders outer fifths " << rampOuter << " (" << rampOuterPixels
            << " back-projecting pixels), central fifth " << rampCentre << " (" << rampCentrePixels << "); uniform 12: outer "
            << uniformOuter << ", central " << uniformCentre << "; frame means ramp " << statistic(ramp, "micro_occluders_mean")
            << ", uniform " << statistic(uniform, "micro_occluders_mean") << "\n";
  ASSERT_GT(rampOuterPixels, 100);
  ASSERT_GT(rampCentrePixels, 100);
  EXPECT_LT(rampOuter, rampCentre);
  EXPECT_LT(rampOuter, uniformOuter) << "the lower border budget must lower the border's cost";
}

// The standard error that the reference's own noise puts on MSE(a) - MSE(b) over the covered pixels: its error e_i
// enters the difference as -2 (a_i - b_i) e_i / N (e_i^2 cancels), so sigma = 2 sqrt(sum (a_i - b_i)^2 s_i^2) / N with
// s_i its standard error (Bernoulli bound).
double mseDifferenceNoise(const Reference& reference, const ImageF& a, const ImageF& b)
{
  double sum = 0.0;
  std::size_t pixels = 0;
  for (std::size_t i = 0; i < a.data.size(); ++i)
  {
    if (reference.covered(i))
    {
      const double difference = static_cast<double>(a.data[i]) - b.data[i];
      const double standardError = reference.standardError.data[i];
      sum += difference * difference * standardError * standardError;
      ++pixels;
    }
  }
  return pixels > 0 ? 2.0 * std::sqrt(sum) / static_cast<double>(pixels) : 0.0;
}

// Test 10, Fig. 12 (SS08 §8): at a coarse level, microrects approximate the occluders better than
// micropatches (min-aggregated texels, which grow each occluder to whole level-j texels), with the occlusion bitmasks
// the paper pairs them with: microrects overlap by design (§5.2), so area accumulation counts the overlaps twice.
// One case per dataset and forced level (force_level: l = level everywhere, alpha = 0, one level), each printing the
// four RMSEs against the Embree reference over the covered pixels (ErrorMetrics' `covered`, as Ss08Scaling):
// micropatch + area, micropatch + bitmask (Fig. 12 b), microrect + area (c), microrect + bitmask (d).
//
// Map 256^2: levels 2 and 3 are then 64 and 32 micro-occluders across the map, coarse next to these occluders, as in
// Fig. 12; a case takes 2-4 s on llvmpipe (5-7 s as a ctest case at -j2). On finer maps the same levels are finer and
// the claim stops holding in places: at 1024^2 on bunny level 2 and stacked-occluders levels 2 and 3 (256^2 images,
// docs/bench/ss08/table.md §5), and with 128^2 images also on stacked-occluders level 2 at 512^2 (0.0284 against
// 0.0274). Where it fails the error is a leak: on the ground of stacked-occluders under the upper square's edge, where
// the lower square hides behind it in the map, both kinds let through light that the hidden part blocks, microrects
// more (256^2 image, pixel 132,146, level 2, 512^2 map: reference 0.148, micropatch 0.293, microrect 0.543, GPU =
// twin); micropatches, grown to whole level-j texels, cover more of the gap ("rather conservative concerning
// occlusion", §5.2).
const char* const kFig12MapSetting = "shadow_map_size=256";
// The bitmasks help microrects where they overlap (§5.2): there area accumulation over-occludes, and the bitmask's
// 256 samples cost less than that. Where they hardly overlap, area accumulation is the exact integral and the bitmask
// only adds its sampling error (near-light level 2: microrect + area 0.0028 RMSE, + bitmask 0.0088). The measure of
// overlap is the mean area_overcount over the back-projecting pixels. Micropatches of one level do not overlap in the
// map (their back-projections may, from different depths), and theirs stays within |mean| <= 0.0086 on these six
// cases: the bitmask pairing is gated where the microrects' exceeds 0.01.
constexpr double kMicrorectOverlapGate = 0.01;

class Ss08Fig12 : public ::testing::TestWithParam<std::tuple<std::string, int>>
{
};

TEST_P(Ss08Fig12, MicrorectsBeatMicropatchesAtCoarseLevelsWithBitmasks)
{
  const std::string dataset = std::get<0>(GetParam());
  const int level = std::get<1>(GetParam());
  const Scene scene = test::loadDataset(dataset);
  const char* const kinds[2] = { "micropatch", "microrect" };
  const char* const accumulations[2] = { "area", "bitmask" };
  std::optional<Reference> reference; // force_level changes no camera: one reference for the four frames
  ErrorMetrics error[2][2];           // [micro-occluder][accumulation]
  ImageF visibility[2][2];
  double overcount[2] = { 0.0, 0.0 }; // mean area_overcount over the back-projecting pixels, bitmask frames
  for (int k = 0; k < 2; ++k)
  {
    for (int a = 0; a < 2; ++a)
    {
      const std::vector<std::string> settings = { kFig12MapSetting, "force_level=" + std::to_string(level),
        std::string("micro_occluder=") + kinds[k], std::string("accumulation=") + accumulations[a] };
      const FrameResult frame = test::renderSs08(scene, kQualityFrameSize, kQualityFrameSize, settings);
      if (!reference)
      {
        reference = referenceOf(frame, scene);
      }
      error[k][a] = reference->errorOf(frame);
      visibility[k][a] = bufferOf(frame, "visibility");
      const std::string label = test::caseLabel(dataset, settings);
      EXPECT_EQ(statistic(frame, "cut_short_pixels"), 0.0) << label << ": pixels cut short by the loop cap are not exact";
      EXPECT_GT(error[k][a].penumbra.pixels, 200u) << label;
      if (a == 1)
      {
        const std::vector<bool> backProjects = backProjectingPixels(frame);
        const ImageF& overcounts = bufferOf(frame, "area_overcount");
        std::size_t pixels = 0;
        for (std::size_t i = 0; i < backProjects.size(); ++i)
        {
          if (backProjects[i])
          {
            overcount[k] += overcounts.data[i];
            ++pixels;
          }
        }
        overcount[k] /= static_cast<double>(std::max<std::size_t>(pixels, 1));
      }
    }
  }
  const auto mse = [&](int k, int a) { return error[k][a].covered.rmse * error[k][a].covered.rmse; };
  const double rectVsPatchNoise = mseDifferenceNoise(*reference, visibility[0][1], visibility[1][1]);
  const double bitmaskVsAreaNoise = mseDifferenceNoise(*reference, visibility[1][0], visibility[1][1]);
  std::cout << "[ measured ] ss08 Fig. 12 on " << dataset << ", force_level=" << level << " (" << kQualityFrameSize << "^2, "
            << kFig12MapSetting << "; Embree " << describe(*reference) << "): RMSE micropatch+area "
            << error[0][0].covered.rmse << ", micropatch+bitmask " << error[0][1].covered.rmse << ", microrect+area "
            << error[1][0].covered.rmse << ", microrect+bitmask " << error[1][1].covered.rmse << " over "
            << error[0][0].covered.pixels << " covered pixels; penumbra RMSE " << error[0][0].penumbra.rmse << ", "
            << error[0][1].penumbra.rmse << ", " << error[1][0].penumbra.rmse << ", " << error[1][1].penumbra.rmse
            << "; MSE gaps (reference noise sigma): micropatch - microrect with bitmasks " << mse(0, 1) - mse(1, 1) << " ("
            << rectVsPatchNoise << "), microrect area - bitmask " << mse(1, 0) - mse(1, 1) << " (" << bitmaskVsAreaNoise
            << "); mean area_overcount over back-projecting pixels: micropatch " << overcount[0] << ", microrect "
            << overcount[1] << "\n";
  const std::string label = dataset + " force_level=" + std::to_string(level) + " " + kFig12MapSetting;
  EXPECT_LT(error[1][1].covered.rmse, error[0][1].covered.rmse) << label << ": microrect+bitmask must beat micropatch+bitmask";
  EXPECT_GT(mse(0, 1) - mse(1, 1), 3.0 * rectVsPatchNoise) << label << ": the gap must stand out of the reference's noise";
  if (dataset != "near-light") // one occluder (a square) near the light; bunny and stacked-occluders must not lose the gate
  {
    EXPECT_GT(overcount[1], kMicrorectOverlapGate) << label << ": microrects must overlap here";
  }
  if (overcount[1] > kMicrorectOverlapGate)
  {
    EXPECT_LE(error[1][1].covered.rmse, error[1][0].covered.rmse) << label << ": bitmasks must help overlapping microrects";
    EXPECT_GT(mse(1, 0) - mse(1, 1), 3.0 * bitmaskVsAreaNoise) << label << ": the gap must stand out of the reference's noise";
  }
  else
  {
    std::cout << "[ measured ] ss08 Fig. 12 on " << label << ": microrect+bitmask <= microrect+area not gated, mean "
              << "area_overcount " << overcount[1] << " <= " << kMicrorectOverlapGate << " (microrects hardly overlap)\n";
  }
}

std::string fig12CaseName(const ::testing::TestParamInfo<std::tuple<std::string, int>>& info)
{
  return gtestName(std::get<0>(info.param) + "_level" + std::to_string(std::get<1>(info.param)));
}

INSTANTIATE_TEST_SUITE_P(CoarseLevels, Ss08Fig12,
  ::testing::Combine(::testing::Values("bunny", "stacked-occluders", "near-light"), ::testing::Values(2, 3)), fig12CaseName);

} // namespace
} // namespace sl
