// Issue 31 item 4, "honest heat maps" (vis/HeatMap.h, vis/BufferHeatMap.h, vis/Montage.h), on synthetic images:
// pixels a quantity does not apply to are light grey (never the diverging map's white, "at the threshold"), robust
// scales leave at most about 2 % of the pixels saturated, bit masks are drawn as bit counts, categorical titles give
// no numeric range, and montage labels never overlap at 128 x 128 panels and list only what differs.
#include "core/Error.h"
#include "output/OutputWriter.h"
#include "vis/BufferHeatMap.h"
#include "vis/Canvas.h"
#include "vis/HeatMap.h"
#include "vis/Montage.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <array>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

namespace sl
{
namespace
{

using HonestRgb8 = std::array<std::uint8_t, 3>;

HonestRgb8 honestPixelAt(const ImageU8& image, int x, int y)
{
  return { image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2) };
}

int honestColourDistance(const HonestRgb8& a, const HonestRgb8& b)
{
  int distance = 0;
  for (int c = 0; c < 3; ++c)
    distance = std::max(distance, std::abs(int(a[c]) - int(b[c])));
  return distance;
}

// A signed buffer as depth_margin looks: a 100 x 100 image whose left 20 columns are surfaces without a shadow
// test (the shader wrote 0 there), its top row background, the rest uniform in [-1, 1] plus 0.25 % outliers at
// +-1000 that a min/max scale would let flatten everything to white.
struct SignedSample
{
  ImageF values{ 100, 100, 1 };
  ImageU8 mask{ 100, 100, 1, 1 };
  int valued = 0;
};

SignedSample signedSample()
{
  SignedSample sample;
  std::mt19937 random(31);
  std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
  for (int y = 0; y < 100; ++y)
    for (int x = 0; x < 100; ++x)
    {
      float& value = sample.values.at(x, y);
      std::uint8_t& mark = sample.mask.at(x, y);
      if (y == 99)
        mark = 0;
      else if (x < 20)
        mark = kNotApplicablePixel;
      value = mark == 1 ? uniform(random) : 0.0f;
      if (mark == 1 && (x * 7 + y * 13) % 400 == 0)
        value = (x % 2 ? 1000.0f : -1000.0f);
      sample.valued += mark == 1;
    }
  return sample;
}

TEST(HonestHeatMap, NotApplicablePixelsAreGreyAndTheRobustScaleSaturatesAtMostTwoPercent)
{
  const SignedSample sample = signedSample();
  HeatMapOptions options;
  options.title = "depth_margin";
  options.colorMap = ColorMapKind::Diverging;
  options.robustRange = true;
  const HeatMapScale scale = heatMapScale({ { &sample.values, &sample.mask } }, options);
  EXPECT_EQ(scale.valuePixels, static_cast<std::size_t>(sample.valued));
  EXPECT_EQ(scale.notApplicablePixels, 99u * 20u);
  EXPECT_EQ(scale.noSurfacePixels, 100u);
  EXPECT_EQ(scale.colorRange.min, -scale.colorRange.max) << "diverging scales stay symmetric about 0";
  EXPECT_LT(scale.colorRange.max, 1.0) << "the outliers must not set the scale";
  EXPECT_GT(scale.colorRange.max, 0.9);
  EXPECT_LE(scale.clippedPercent(), 2.0) << scale.clippedPixels << " of " << scale.valuePixels;
  EXPECT_GT(scale.clippedPixels, 0u);

  const ImageU8 canvas = renderHeatMap(sample.values, &sample.mask, options);
  const HonestRgb8 grey = toRgb8(kNotApplicableColor);
  const HonestRgb8 dark = toRgb8(kInvalidPixelColor);
  const HonestRgb8 white = toRgb8(ColorMap(ColorMapKind::Diverging).map(0.5));
  const HonestRgb8 bottomEnd = toRgb8(ColorMap(ColorMapKind::Diverging).map(0.0));
  const HonestRgb8 topEnd = toRgb8(ColorMap(ColorMapKind::Diverging).map(1.0));
  int wrongGrey = 0, wrongDark = 0, saturated = 0, nearWhite = 0;
  for (int y = 0; y < 100; ++y)
    for (int x = 0; x < 100; ++x)
    {
      const HonestRgb8 drawn = honestPixelAt(canvas, x, y);
      const std::uint8_t mark = sample.mask.at(x, y);
      if (mark == kNotApplicablePixel)
      {
        wrongGrey += drawn != grey;
        continue;
      }
      if (mark == 0)
      {
        wrongDark += drawn != dark;
        continue;
      }
      saturated += drawn == bottomEnd || drawn == topEnd;
      nearWhite += honestColourDistance(drawn, white) <= 16;
    }
  EXPECT_EQ(wrongGrey, 0) << "untested pixels must be the not-applicable grey, never the white of 0";
  EXPECT_EQ(wrongDark, 0);
  EXPECT_NE(grey, white);
  EXPECT_LE(100.0 * saturated / sample.valued, 2.0) << saturated << " of " << sample.valued << " pixels saturate";
  // A min/max scale (+-1000) would draw nearly every pixel within a few steps of white.
  EXPECT_LT(nearWhite, sample.valued / 4) << nearWhite << " of " << sample.valued << " pixels are near white";

  // The key holds a swatch of each grey, beside the values.
  int keyGrey = 0, keyDark = 0;
  for (int y = 0; y < canvas.height; ++y)
    for (int x = 100; x < canvas.width; ++x)
    {
      keyGrey += honestPixelAt(canvas, x, y) == grey;
      keyDark += honestPixelAt(canvas, x, y) == dark;
    }
  EXPECT_GT(keyGrey, 4) << "no 'not tested / n.a.' swatch in the key";
  EXPECT_GT(keyDark, 4) << "no 'no surface' swatch in the key";

  const std::vector<std::string> title = heatMapTitleLines(options, scale);
  ASSERT_EQ(title.size(), 2u);
  EXPECT_EQ(title[0], "depth_margin");
  EXPECT_NE(title[1].find("values [-1e+03, 1e+03]"), std::string::npos) << title[1];
  EXPECT_NE(title[1].find("% of pixels beyond"), std::string::npos) << title[1];
}

TEST(HonestHeatMap, ContinuousScaleEndsAtTheRobustPercentiles)
{
  // 0 .. 9959 and 40 pixels at 1e6: the 99.5th percentile (rank floor(0.995 * 9999) = 9949) is 9949, the 0.5th
  // (rank 49) 49.
  ASSERT_EQ(kRobustTail, 0.005);
  ImageF values(100, 100, 1);
  for (int i = 0; i < 10000; ++i)
    values.data[static_cast<std::size_t>(i)] = i < 9960 ? static_cast<float>(i) : 1e6f;
  HeatMapOptions options;
  options.robustRange = true;
  const HeatMapScale scale = heatMapScale({ { &values, nullptr } }, options);
  EXPECT_EQ(scale.colorRange.min, 49.0);
  EXPECT_EQ(scale.colorRange.max, 9949.0);
  EXPECT_EQ(scale.clippedPixels, 99u); // 0 .. 48 below; 9950 .. 9959 and the 40 outliers above
  EXPECT_TRUE(scale.clippedBelow && scale.clippedAbove);
  EXPECT_LE(scale.clippedPercent(), 2.0);
  // Without robustRange: the full range, nothing clipped (error maps, probe figures).
  const HeatMapScale full = heatMapScale({ { &values, nullptr } }, HeatMapOptions{});
  EXPECT_EQ(full.colorRange.max, 1e6);
  EXPECT_EQ(full.clippedPixels, 0u);
  // All but the tails equal: the scale is the full range rather than none.
  ImageF mostlyZero(1000, 1, 1, 0.0f);
  mostlyZero.data[0] = 5.0f;
  const HeatMapScale tails = heatMapScale({ { &mostlyZero, nullptr } }, options);
  EXPECT_EQ(tails.colorRange.min, 0.0);
  EXPECT_EQ(tails.colorRange.max, 5.0);
}

TEST(HonestHeatMap, CategoricalTitleHasNoNumericRange)
{
  ImageF classes(6, 1, 1);
  for (int x = 0; x < 6; ++x)
    classes.at(x, 0) = static_cast<float>(1 + x % 3); // ids 1 .. 3
  HeatMapOptions options;
  options.title = "classification";
  options.colorMap = ColorMapKind::Categorical;
  options.categoryLabels = { "not tested", "lit", "penumbra", "umbra" };
  const HeatMapScale scale = heatMapScale({ { &classes, nullptr } }, options);
  const std::vector<std::string> title = heatMapTitleLines(options, scale);
  EXPECT_EQ(title, std::vector<std::string>{ "classification" });
  const ImageU8 canvas = renderHeatMap(classes, nullptr, options);
  // The key's swatches carry the classes' colours (the title band is text only).
  for (const long long id : { 1, 2, 3 })
  {
    const HonestRgb8 swatch = toRgb8(ColorMap::categoryColor(id));
    int found = 0;
    for (int y = 0; y < canvas.height; ++y)
      for (int x = 6; x < canvas.width; ++x)
        found += honestPixelAt(canvas, x, y) == swatch;
    EXPECT_GT(found, 4) << "class " << id;
  }
}

TEST(HonestHeatMap, BitMasksAreDrawnAsTheirSetBitCountAndSummedAreaTablesNotAtAll)
{
  NamedImage mask{ "light_sample_mask", ImageF(2, 1, 2), "bits", "", BufferKind::BitMask };
  mask.image.at(0, 0, 0) = 65535.0f; // 16 bits
  mask.image.at(0, 0, 1) = 5.0f;     // 2 bits
  mask.image.at(1, 0, 0) = 0.0f;
  mask.image.at(1, 0, 1) = 32768.0f; // 1 bit
  EXPECT_TRUE(drawsHeatMap(mask));
  const ImageF counts = heatMapValues(mask);
  ASSERT_EQ(counts.components, 1);
  EXPECT_EQ(counts.at(0, 0), 18.0f);
  EXPECT_EQ(counts.at(1, 0), 1.0f);
  const HeatMapOptions options = bufferHeatMapOptions(mask, nullptr);
  EXPECT_EQ(options.rangeMin, 0.0);
  EXPECT_EQ(options.rangeMax, 32.0);
  EXPECT_EQ(options.unit, "bits set, of 32");

  const NamedImage sat{ "sat_z", ImageF(4, 4, 1, 1.0f), "", "", BufferKind::SummedArea };
  EXPECT_FALSE(drawsHeatMap(sat));
  const NamedImage position{ "position", ImageF(4, 4, 3), "world units", "", BufferKind::Continuous };
  EXPECT_FALSE(drawsHeatMap(position));
}

TEST(HonestHeatMap, ShadowTestedBuffersAreNotApplicableWhereNoTestRan)
{
  // Pixel 0: background; 1: covered and tested; 2: covered, not tested (a face turned from the light).
  std::vector<NamedImage> frame = { { "coverage", ImageF(3, 1, 1), "", "" },
    { "shadow_tested", ImageF(3, 1, 1), "", "" } };
  frame[0].image.data = { 0.0f, 1.0f, 1.0f };
  frame[1].image.data = { 0.0f, 1.0f, 0.0f };
  NamedImage margin{ "depth_margin", ImageF(3, 1, 1, 0.0f), "world units", "", BufferKind::Signed };
  EXPECT_EQ(bufferValueMask(margin, frame).data, (std::vector<std::uint8_t>{ 0, 1, 1 })) << "declared on Covered";
  margin.domain = BufferDomain::ShadowTested;
  EXPECT_EQ(bufferValueMask(margin, frame).data, (std::vector<std::uint8_t>{ 0, 1, kNotApplicablePixel }));
  // A run without shadow_tested (written before it existed): coverage alone.
  frame.pop_back();
  EXPECT_EQ(bufferValueMask(margin, frame).data, (std::vector<std::uint8_t>{ 0, 1, 1 }));
}

// Touching counts: two lines whose boxes share an edge have glyphs (descenders, underscores) that meet.
TEST(HonestHeatMap, SymmetricLogScaleShowsValuesNearZeroBesideFarOnesWithoutSaturating)
{
  const ValueRange range{ -10.0, 10.0 };
  const double width = 0.001; // linear within +-0.001, 4 decades to 10
  EXPECT_EQ(colorMapPosition(0.0, range, width), 0.5);
  EXPECT_NEAR(colorMapPosition(10.0, range, width), 1.0, 1e-12);
  EXPECT_NEAR(colorMapPosition(-10.0, range, width), 0.0, 1e-12);
  // A value at the linear width sits log(2) / log(10001) of the way to the end: visibly off white, where a linear
  // scale would put it 1e-4 of the way.
  EXPECT_NEAR(colorMapPosition(width, range, width) - 0.5, 0.5 * std::log(2.0) / std::log(10001.0), 1e-12);
  EXPECT_GT(colorMapPosition(width, range, width) - 0.5, 0.03);
  for (const double t : { 0.0, 0.1, 0.37, 0.5, 0.8, 1.0 })
    EXPECT_NEAR(colorMapPosition(colorMapValueAt(t, range, width), range, width), t, 1e-12) << t;
  EXPECT_EQ(colorMapPosition(2.5, range, 0.0), 0.625) << "width 0: linear";

  // A montage of a signed buffer with values 1e-3 .. 10 (both signs) on the log scale: the smallest are not white,
  // and the title says which scale it is.
  MontagePanel panel;
  panel.values = ImageF(100, 1, 1);
  for (int x = 0; x < 100; ++x)
    panel.values.at(x, 0) = static_cast<float>((x % 2 ? 1.0 : -1.0) * std::pow(10.0, -3.0 + 4.0 * x / 99.0));
  MontageOptions options;
  options.title = "depth_margin";
  options.kind = BufferKind::Signed;
  options.signedLogLinearQuantile = 0.1;
  const MontageLayout layout = montageLayout({ panel }, options);
  EXPECT_GT(layout.signedLogLinearWidth, 1e-3);
  EXPECT_LT(layout.signedLogLinearWidth, 1e-2);
  const ImageU8 canvas = renderMontage({ panel }, options);
  const HonestRgb8 white = toRgb8(ColorMap(ColorMapKind::Diverging).map(0.5));
  EXPECT_GT(honestColourDistance(honestPixelAt(canvas, layout.panelLeft[0] + 1, layout.panelBottom), white), 8)
    << "a value of 1e-3 must not be drawn white on the log scale";
  bool titleSaysLog = false;
  for (const MontageTextBox& box : layout.titleBoxes)
    titleSaysLog = titleSaysLog || box.text.find("log scale, linear within") != std::string::npos;
  EXPECT_TRUE(titleSaysLog);
  options.signedLogLinearQuantile = 1.0;
  EXPECT_THROW(montageLayout({ panel }, options), InputError);
}

bool boxesOverlap(const MontageTextBox& a, const MontageTextBox& b)
{
  return a.left <= b.left + b.width && b.left <= a.left + a.width && a.bottom <= b.bottom + b.height &&
    b.bottom <= a.bottom + a.height;
}

void expectNoLabelCollisions(const std::vector<MontagePanel>& panels, const MontageOptions& options)
{
  const MontageLayout layout = montageLayout(panels, options);
  std::vector<MontageTextBox> boxes = layout.titleBoxes;
  for (std::size_t p = 0; p < panels.size(); ++p)
  {
    const int columnRight =
      (p + 1 < panels.size() ? layout.panelLeft[p + 1] : layout.keyLeft) - layout.paddingPx;
    for (const MontageTextBox& box : layout.labelBoxes[p])
    {
      EXPECT_GE(box.left, layout.panelLeft[p]) << box.text;
      EXPECT_LE(box.left + box.width, columnRight) << "label '" << box.text << "' runs out of its column " << p;
      EXPECT_LE(box.bottom + box.height, layout.panelBottom) << "label '" << box.text << "' reaches into the panel";
      EXPECT_GE(box.bottom, 0) << box.text;
      boxes.push_back(box);
    }
  }
  for (const MontageTextBox& box : layout.titleBoxes)
  {
    EXPECT_LE(box.left + box.width, layout.width) << box.text;
    EXPECT_GE(box.bottom, layout.panelBottom + layout.keyHeight) << "title line '" << box.text << "' over the panels";
    EXPECT_LE(box.bottom + box.height, layout.height) << box.text;
  }
  for (std::size_t i = 0; i < boxes.size(); ++i)
    for (std::size_t j = i + 1; j < boxes.size(); ++j)
      EXPECT_FALSE(boxesOverlap(boxes[i], boxes[j]))
        << "'" << boxes[i].text << "' at (" << boxes[i].left << ", " << boxes[i].bottom << ") overlaps '"
        << boxes[j].text
        << "' at (" << boxes[j].left << ", " << boxes[j].bottom << ")";
  // Every character of every label is drawn: the wrapped lines join back to the labels.
  for (std::size_t p = 0; p < panels.size(); ++p)
  {
    std::string drawn, given;
    for (const MontageTextBox& box : layout.labelBoxes[p])
      drawn += box.text;
    for (const std::string& label : panels[p].labels)
      for (const char c : label)
        given += c == ' ' ? "" : std::string(1, c);
    drawn.erase(std::remove(drawn.begin(), drawn.end(), ' '), drawn.end());
    EXPECT_EQ(drawn, given) << "panel " << p;
  }
}

TEST(MontageLabels, NeverOverlapAt128PixelPanelsNorAtTinyOnes)
{
  for (const int side : { 128, 32 })
  {
    std::vector<MontagePanel> panels;
    for (int p = 0; p < 5; ++p)
    {
      MontagePanel panel;
      panel.values = ImageF(side, side, 1, static_cast<float>(p));
      panel.labels = { format("bias-default-run-", p), format("bias_constant_texels=", 0.5 * p),
        "bias_slope_texels=16 depth_layer=midpoint", "an_unbreakable_parameter_name_longer_than_any_panel=1234567890",
        "GPU 11.5 ms", "RMSE 0.0346" };
      panels.push_back(std::move(panel));
    }
    MontageOptions options;
    options.title = "depth_margin";
    options.unit = "world units";
    options.kind = BufferKind::Signed;
    options.commonLines = { "technique hard", "scene grazing", "128x128", "cascades=1", "warp=none",
      "a_shared_parameter_with_a_long_name=some-long-value-that-must-wrap-too" };
    SCOPED_TRACE(format(side, "x", side, " panels"));
    expectNoLabelCollisions(panels, options);
    // At 128 x 128 the columns are the panels' own width: labels wrap instead of widening them.
    const MontageLayout layout = montageLayout(panels, options);
    if (side == 128)
      EXPECT_EQ(layout.panelLeft[1] - layout.panelLeft[0], 128 + layout.paddingPx);
  }
}

TEST(MontageLabels, ListOnlyWhatDiffersAndWhatIsSharedOnceInTheTitle)
{
  std::vector<nlohmann::json> stats;
  for (const double slope : { 0.0, 1.0, 16.0 })
    stats.push_back({ { "technique", "hard" }, { "scene", "datasets/grazing/scene.json" },
      { "resolution", { 128, 128 } },
      { "parameters",
        { { "bias_constant_texels", 0.5 }, { "bias_slope_texels", slope }, { "depth_layer", "first" } } } });
  const std::vector<std::vector<std::string>> labels = montageRunLabels({ "off", "on", "large" }, stats);
  ASSERT_EQ(labels.size(), 3u);
  EXPECT_EQ(labels[0], (std::vector<std::string>{ "off", "bias_slope_texels=0" }));
  EXPECT_EQ(labels[2], (std::vector<std::string>{ "large", "bias_slope_texels=16" }));
  const std::vector<std::string> common = montageCommonLabels(stats);
  EXPECT_EQ(common, (std::vector<std::string>{ "technique hard", "bias_constant_texels=0.5", "depth_layer=first",
                      "scene grazing", "128x128" }));

  // Two techniques: each panel names its technique, and a parameter one of them lacks is in neither list.
  stats[1]["technique"] = "pcf";
  stats[1]["parameters"]["pcf_taps"] = 4;
  const std::vector<std::vector<std::string>> mixed = montageRunLabels({ "off", "on", "large" }, stats);
  EXPECT_EQ(mixed[1].front(), "on: pcf");
  EXPECT_EQ(std::count(mixed[1].begin(), mixed[1].end(), "pcf_taps=4"), 0);
  const std::vector<std::string> mixedCommon = montageCommonLabels(stats);
  EXPECT_EQ(std::count(mixedCommon.begin(), mixedCommon.end(), "technique hard"), 0);
  EXPECT_EQ(std::count(mixedCommon.begin(), mixedCommon.end(), "pcf_taps=4"), 0);
}

TEST(MontageLabels, WrapTextBreaksAtSpacesThenBetweenCharacters)
{
  const int fontPx = 12;
  const int width = measureText("abcdefghij", fontPx).width;
  EXPECT_EQ(wrapText("abc def ghi", width, fontPx), (std::vector<std::string>{ "abc def", "ghi" }));
  EXPECT_EQ(wrapText("abcdefghijklmno", width, fontPx), (std::vector<std::string>{ "abcdefghij", "klmno" }));
  EXPECT_EQ(wrapText("", width, fontPx), std::vector<std::string>{ "" });
  // A parameter wider than the column breaks after a '_' or '=' that fits rather than inside a name.
  const int wider = measureText("bias_constant_tex", fontPx).width;
  EXPECT_EQ(wrapText("bias_constant_texels=0.5", wider, fontPx),
    (std::vector<std::string>{ "bias_constant_", "texels=0.5" }));
}

// stats.json's min/max/mean of a buffer declared on shadow-tested pixels: over those pixels only, not the 0 the
// shader writes where no test ran (a face turned from the light), nor the background.
TEST(HonestStats, BufferStatisticsCoverTheBufferDomainOnly)
{
  const int width = 4;
  const int height = 2;
  NamedImage coverage{ "coverage", ImageF(width, height, 1, 1.0f), "", "" };
  coverage.image.at(3, 1) = 0.0f; // background
  NamedImage tested{ "shadow_tested", ImageF(width, height, 1, 1.0f), "", "" };
  tested.image.at(0, 0) = 0.0f; // covered, turned from the light
  tested.image.at(1, 0) = 0.0f;
  tested.image.at(3, 1) = 0.0f;
  NamedImage margin{ "depth_margin", ImageF(width, height, 1, 0.0f), "linear depth", "" };
  margin.domain = BufferDomain::ShadowTested;
  const float testedValues[] = { 0.5f, 0.75f, 2.0f, -0.25f, 1.0f };
  const int testedPixels[][2] = { { 2, 0 }, { 3, 0 }, { 0, 1 }, { 1, 1 }, { 2, 1 } };
  double testedSum = 0.0;
  for (int i = 0; i < 5; ++i)
  {
    margin.image.at(testedPixels[i][0], testedPixels[i][1]) = testedValues[i];
    testedSum += testedValues[i];
  }
  margin.image.at(3, 1) = 99.0f; // background: never counted
  NamedImage depth{ "depth", ImageF(width, height, 1, 3.0f), "linear depth", "" };
  depth.image.at(0, 0) = 1.0f;
  depth.image.at(3, 1) = -50.0f; // background

  const nlohmann::json summaries = bufferSummaries({ coverage, tested, margin, depth });
  const nlohmann::json& marginStats = summaries.at("depth_margin");
  EXPECT_EQ(marginStats.at("domain"), "shadow_tested");
  EXPECT_EQ(marginStats.at("domain_pixels"), 5u);
  EXPECT_DOUBLE_EQ(marginStats.at("min").get<double>(), -0.25) << marginStats.dump();
  EXPECT_DOUBLE_EQ(marginStats.at("max").get<double>(), 2.0) << marginStats.dump();
  EXPECT_NEAR(marginStats.at("mean").get<double>(), testedSum / 5.0, 1e-12) << marginStats.dump();
  // A buffer declared on covered pixels: the two untested covered pixels count, the background does not.
  const nlohmann::json& depthStats = summaries.at("depth");
  EXPECT_EQ(depthStats.at("domain"), "covered");
  EXPECT_EQ(depthStats.at("domain_pixels"), 7u);
  EXPECT_DOUBLE_EQ(depthStats.at("min").get<double>(), 1.0) << depthStats.dump();
  EXPECT_NEAR(depthStats.at("mean").get<double>(), (1.0 + 6 * 3.0) / 7.0, 1e-12) << depthStats.dump();
  EXPECT_EQ(summaries.at("coverage").at("domain"), "all pixels");
  EXPECT_EQ(summaries.at("coverage").at("domain_pixels"), 8u);
  // Without shadow_tested (a run written before it existed) the shadow-tested buffer falls back to the covered
  // pixels, and says so.
  const nlohmann::json fallback = bufferSummaries({ coverage, margin });
  EXPECT_EQ(fallback.at("depth_margin").at("domain"), "covered");
  EXPECT_EQ(fallback.at("depth_margin").at("domain_pixels"), 7u);
  EXPECT_DOUBLE_EQ(fallback.at("depth_margin").at("min").get<double>(), -0.25);
}

} // namespace
} // namespace sl
