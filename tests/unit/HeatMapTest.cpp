// Heat maps (vis/HeatMap.h): colour maps against their published values, pixel colours against the colour map
// of the normalised value, range handling, layout (key margin, title text) and the PNG file.
#include "vis/HeatMap.h"

#include "vis/Canvas.h"
#include "vis/ColorKey.h"
#include "vis/ColorMap.h"

#include <gtest/gtest.h>

#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <optional>
#include <set>
#include <sstream>
#include <string>

namespace sl
{
namespace
{

using Rgb8 = std::array<std::uint8_t, 3>;

Rgb8 pixelAt(const ImageU8& image, int x, int y)
{
  return { image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2) };
}

std::string toString(const Rgb8& rgb)
{
  return format("(", int(rgb[0]), ",", int(rgb[1]), ",", int(rgb[2]), ")");
}

std::string toString(const RgbColor& rgb)
{
  return format("(", rgb[0], ",", rgb[1], ",", rgb[2], ")");
}

bool isDark(const Rgb8& rgb)
{
  return rgb[0] < 100 && rgb[1] < 100 && rgb[2] < 100;
}

// CIELAB lightness L* of an sRGB colour (D65), to compare the two halves of the diverging map.
double lightness(const RgbColor& srgb)
{
  auto linear = [](double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); };
  const double luminance = 0.2126 * linear(srgb[0]) + 0.7152 * linear(srgb[1]) + 0.0722 * linear(srgb[2]);
  const double f = luminance > 0.008856 ? std::cbrt(luminance) : 7.787 * luminance + 16.0 / 116.0;
  return 116.0 * f - 16.0;
}

void expectColorNear(
  const RgbColor& actual, const RgbColor& expected, double tolerance, const std::string& what)
{
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(actual[c], expected[c], tolerance)
      << what << " channel " << c << ": got " << toString(actual) << " expected " << toString(expected);
}

// values(x, y) = x / (width - 1): 0 at the left edge, 1 at the right; the bottom row (y = 0) runs the other way
// (1 at the left), so that a flipped image is detectable.
ImageF makeRamp(int width, int height)
{
  ImageF ramp(width, height, 1);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
    {
      const float t = static_cast<float>(x) / static_cast<float>(width - 1);
      ramp.at(x, y) = y == 0 ? 1.0f - t : t;
    }
  return ramp;
}

// The colour renderHeatMap must give a valid pixel of value v for the colour range [rangeMin, rangeMax].
Rgb8 expectedColor(ColorMapKind kind, double value, double rangeMin, double rangeMax)
{
  return toRgb8(ColorMap(kind).map((value - rangeMin) / (rangeMax - rangeMin)));
}

// Colours present in the columns [left, right) of rows [bottom, top).
std::set<Rgb8> colorsIn(const ImageU8& image, int left, int right, int bottom, int top)
{
  std::set<Rgb8> colors;
  for (int y = bottom; y < top; ++y)
    for (int x = left; x < right; ++x)
      colors.insert(pixelAt(image, x, y));
  return colors;
}

TEST(ColorMap, ViridisMatchesPublishedValues)
{
  // matplotlib's _viridis_data: entry 0, entries 63/64 (t = 0.25), 127/128 (t = 0.5), entry 255.
  const ColorMap viridis(ColorMapKind::Viridis);
  expectColorNear(viridis.map(0.0), { 0.267004, 0.004874, 0.329415 }, 1e-2, "t=0");
  expectColorNear(viridis.map(0.25), { 0.230707, 0.320234, 0.545270 }, 1e-2, "t=0.25");
  expectColorNear(viridis.map(0.5), { 0.128149, 0.565107, 0.550893 }, 1e-2, "t=0.5");
  expectColorNear(viridis.map(1.0), { 0.993248, 0.906157, 0.143936 }, 1e-2, "t=1");
  // Out-of-range t is clamped; NaN reads as 0.
  EXPECT_EQ(viridis.map(-3.0), viridis.map(0.0));
  EXPECT_EQ(viridis.map(7.0), viridis.map(1.0));
  EXPECT_EQ(viridis.map(std::numeric_limits<double>::quiet_NaN()), viridis.map(0.0));
}

TEST(ColorMap, DivergingIsWhiteAtHalfAndSymmetric)
{
  const ColorMap diverging(ColorMapKind::Diverging);
  expectColorNear(diverging.map(0.5), kWhite, 1e-2, "t=0.5");
  double previousLightness = lightness(diverging.map(0.5));
  for (double offset = 0.05; offset <= 0.5 + 1e-9; offset += 0.05)
  {
    const RgbColor low = diverging.map(0.5 - offset);
    const RgbColor high = diverging.map(0.5 + offset);
    EXPECT_GT(low[2], low[0]) << "below 0.5 is blue, offset " << offset << " colour " << toString(low);
    EXPECT_GT(high[0], high[2]) << "above 0.5 is red, offset " << offset << " colour " << toString(high);
    // Equal distances from the centre are equally strong: same lightness on both sides, darker further out.
    EXPECT_NEAR(lightness(low), lightness(high), 5.0) << "offset " << offset;
    EXPECT_LT(lightness(low), previousLightness) << "offset " << offset;
    previousLightness = lightness(low);
  }
}

TEST(ColorMap, CategoricalColorsAreDistinctAndRepeat)
{
  std::set<Rgb8> palette;
  for (long long id = 0; id < 10; ++id)
    palette.insert(toRgb8(ColorMap::categoryColor(id)));
  EXPECT_EQ(palette.size(), 10u);
  EXPECT_EQ(ColorMap::categoryColor(10), ColorMap::categoryColor(0));
  EXPECT_EQ(ColorMap::categoryColor(-1), ColorMap::categoryColor(9));
  EXPECT_EQ(palette.count(toRgb8(kInvalidPixelColor)), 0u) << "invalid grey must not be a class colour";
}

TEST(HeatMap, FormatsThreeSignificantDigits)
{
  EXPECT_EQ(formatThreeSignificant(0.03125), "0.0312");
  EXPECT_EQ(formatThreeSignificant(1500.0), "1.5e+03");
  EXPECT_EQ(formatThreeSignificant(2.0), "2");
  EXPECT_EQ(formatThreeSignificant(-0.123456), "-0.123");
}

// Issue 31: VSM's key read 3.48, 3.47, 3.47, 3.47, 3.46. The heat maps' keys (and the probe figure's, which
// draws the same ColorKey) label their five ticks with the digits that tell them apart, each the tick's value.
TEST(ColorKey, TickLabelsAreDistinctAndReadTheirValues)
{
  const ColorMap viridis(ColorMapKind::Viridis);
  const struct
  {
    double lo, hi;
  } ranges[] = { { 3.4668, 3.4752 }, { 0.0, 1.0 }, { 1000.0, 1000.004 }, { -2e-6, 3e-6 }, { 12.0, 4096.0 } };
  for (const auto& range : ranges)
  {
    const ColorKey key = ColorKey::continuous(viridis, range.lo, range.hi, 12);
    const std::vector<std::string> labels = key.tickLabels();
    ASSERT_EQ(labels.size(), 5u);
    EXPECT_EQ(std::set<std::string>(labels.begin(), labels.end()).size(), 5u)
      << "[" << range.lo << ", " << range.hi << "]: " << labels[0] << " " << labels[1] << " " << labels[2] << " "
      << labels[3] << " " << labels[4];
    const double quarter = 0.25 * (range.hi - range.lo);
    for (int i = 0; i < 5; ++i)
    {
      // The label parses back to its tick's value within half the step between ticks: distinct and right.
      EXPECT_NEAR(std::stod(labels[std::size_t(i)]), range.lo + i * quarter, 0.5 * quarter)
        << "[" << range.lo << ", " << range.hi << "] tick " << i << " reads " << labels[std::size_t(i)];
      // Never more digits than it takes: 15 would print 3.46680000000000.
      EXPECT_LE(labels[std::size_t(i)].size(), 10u) << labels[std::size_t(i)];
    }
  }
  EXPECT_EQ(ColorKey::continuous(viridis, 0.0, 1.0, 12).tickLabels(),
    (std::vector<std::string>{ "0", "0.25", "0.5", "0.75", "1" }));
  // Open ends keep their "<=" / ">=" in front of the distinct label.
  const std::vector<std::string> open = ColorKey::continuous(viridis, 3.4668, 3.4752, 12, true, true).tickLabels();
  EXPECT_EQ(open.front().rfind("<=3.46", 0), 0u) << open.front();
  EXPECT_EQ(open.back().rfind(">=3.47", 0), 0u) << open.back();
  EXPECT_TRUE(ColorKey::categorical(0, 3, { "a", "b", "c" }, 12).tickLabels().empty());
}

TEST(HeatMap, RampPixelsAreColorMapOfNormalisedValue)
{
  const int width = 64, height = 48;
  const ImageF ramp = makeRamp(width, height);
  const ImageU8 canvas = renderHeatMap(ramp, nullptr, HeatMapOptions{});
  ASSERT_EQ(canvas.components, 3);

  // The values sit at the canvas' bottom-left, 1:1; the colour range is the data range [0, 1].
  for (const int y : { 1, height / 2, height - 1 })
    for (const int x : { 0, 1, width / 3, width / 2, width - 1 })
    {
      const Rgb8 expected = expectedColor(ColorMapKind::Viridis, ramp.at(x, y), 0.0, 1.0);
      EXPECT_EQ(pixelAt(canvas, x, y), expected)
        << "pixel " << x << "," << y << " value " << ramp.at(x, y) << " got " << toString(pixelAt(canvas, x, y))
        << " expected " << toString(expected);
    }
  // Row 0 of the canvas is row 0 of the values (reversed ramp), not the top row: no flip in memory.
  EXPECT_EQ(pixelAt(canvas, 0, 0), toRgb8(ColorMap(ColorMapKind::Viridis).map(1.0)));
  EXPECT_EQ(pixelAt(canvas, width - 1, 0), toRgb8(ColorMap(ColorMapKind::Viridis).map(0.0)));
  EXPECT_EQ(pixelAt(canvas, 0, height - 1), toRgb8(ColorMap(ColorMapKind::Viridis).map(0.0)));
}

TEST(HeatMap, InvalidPixelsAreGreyAndDoNotAffectTheRange)
{
  const int width = 32, height = 32;
  ImageF values = makeRamp(width, height); // valid values span [0, 1]
  ImageU8 mask(width, height, 1, 1);
  for (int y = 10; y < 20; ++y)
  {
    mask.at(5, y) = 0;
    values.at(5, y) = 1000.0f; // masked out: must not stretch the range
  }
  values.at(7, 3) = std::numeric_limits<float>::quiet_NaN();
  values.at(8, 3) = std::numeric_limits<float>::infinity();
  values.at(9, 3) = -std::numeric_limits<float>::infinity();

  const std::optional<ValueRange> range = validValueRange(values, &mask);
  ASSERT_TRUE(range.has_value());
  EXPECT_EQ(range->min, 0.0);
  EXPECT_EQ(range->max, 1.0);

  const ImageU8 canvas = renderHeatMap(values, &mask, HeatMapOptions{});
  const Rgb8 grey = toRgb8(kInvalidPixelColor);
  EXPECT_EQ(pixelAt(canvas, 5, 15), grey) << "masked pixel";
  EXPECT_EQ(pixelAt(canvas, 7, 3), grey) << "NaN";
  EXPECT_EQ(pixelAt(canvas, 8, 3), grey) << "+inf";
  EXPECT_EQ(pixelAt(canvas, 9, 3), grey) << "-inf";
  EXPECT_EQ(pixelAt(canvas, width - 1, 15), expectedColor(ColorMapKind::Viridis, 1.0, 0.0, 1.0));
  EXPECT_EQ(pixelAt(canvas, 10, 15), expectedColor(ColorMapKind::Viridis, values.at(10, 15), 0.0, 1.0));

  // No valid pixel at all: all grey, and the title says so.
  const ImageU8 noneValid(width, height, 1, 0);
  const ImageU8 greyCanvas = renderHeatMap(values, &noneValid, HeatMapOptions{});
  EXPECT_EQ(colorsIn(greyCanvas, 0, width, 0, height), std::set<Rgb8>{ grey });
  EXPECT_EQ(heatMapTitle(HeatMapOptions{ "blockers", "", ColorMapKind::Viridis, {}, {}, {} }, std::nullopt),
    "blockers  no valid pixels");
}

TEST(HeatMap, ExplicitRangeIsHonoured)
{
  ImageF values(16, 16, 1, 2.5f);
  values.at(3, 3) = 20.0f; // above rangeMax: clamped to the top colour
  values.at(4, 3) = -5.0f; // below rangeMin: clamped to the bottom colour
  HeatMapOptions options;
  options.rangeMin = 0.0;
  options.rangeMax = 10.0;
  const ValueRange colorRange = colorMapRange(validValueRange(values, nullptr), options);
  EXPECT_EQ(colorRange.min, 0.0);
  EXPECT_EQ(colorRange.max, 10.0);

  const ImageU8 canvas = renderHeatMap(values, nullptr, options);
  const ColorMap viridis(ColorMapKind::Viridis);
  EXPECT_EQ(pixelAt(canvas, 0, 0), toRgb8(viridis.map(0.25)));
  EXPECT_EQ(pixelAt(canvas, 3, 3), toRgb8(viridis.map(1.0)));
  EXPECT_EQ(pixelAt(canvas, 4, 3), toRgb8(viridis.map(0.0)));

  // The title reports the data, so clipping by the explicit range stays visible.
  options.title = "kernel_texels";
  options.unit = "texels";
  EXPECT_EQ(heatMapTitle(options, validValueRange(values, nullptr)), "kernel_texels [texels]  range [-5, 20]");

  options.rangeMin = 11.0;
  EXPECT_THROW(colorMapRange(validValueRange(values, nullptr), options), InputError);
}

TEST(HeatMap, DivergingRangeIsSymmetricAboutZero)
{
  ImageF values = makeRamp(32, 32);
  for (float& value : values.data)
    value = 4.0f * value - 1.0f; // [-1, 3]
  values.at(0, 5) = 0.0f;
  HeatMapOptions options;
  options.colorMap = ColorMapKind::Diverging;
  const ValueRange colorRange = colorMapRange(validValueRange(values, nullptr), options);
  EXPECT_EQ(colorRange.min, -3.0);
  EXPECT_EQ(colorRange.max, 3.0);

  const ImageU8 canvas = renderHeatMap(values, nullptr, options);
  EXPECT_EQ(pixelAt(canvas, 0, 5), toRgb8(kWhite)) << "value 0 must be white";
  EXPECT_EQ(pixelAt(canvas, 31, 5), expectedColor(ColorMapKind::Diverging, 3.0, -3.0, 3.0));

  options.rangeMax = 0.5; // a single explicit bound is mirrored
  const ValueRange mirrored = colorMapRange(validValueRange(values, nullptr), options);
  EXPECT_EQ(mirrored.min, -0.5);
  EXPECT_EQ(mirrored.max, 0.5);
}

TEST(HeatMap, ConstantImageGetsTheMiddleColourAndAFiniteScale)
{
  for (const float constant : { 7.0f, 0.0f, -1e-6f })
  {
    const ImageF values(20, 20, 1, constant);
    const ValueRange colorRange = colorMapRange(validValueRange(values, nullptr), HeatMapOptions{});
    EXPECT_LT(colorRange.min, colorRange.max) << "constant " << constant;
    EXPECT_TRUE(std::isfinite(colorRange.min) && std::isfinite(colorRange.max)) << "constant " << constant;
    EXPECT_DOUBLE_EQ(0.5 * (colorRange.min + colorRange.max), constant) << "constant " << constant;

    const ImageU8 canvas = renderHeatMap(values, nullptr, HeatMapOptions{});
    EXPECT_EQ(pixelAt(canvas, 10, 10), toRgb8(ColorMap(ColorMapKind::Viridis).map(0.5)))
      << "constant " << constant;
    // The bar still spans the whole colour map.
    const std::set<Rgb8> keyColors = colorsIn(canvas, values.width, canvas.width, 0, canvas.height);
    EXPECT_EQ(keyColors.count(toRgb8(ColorMap(ColorMapKind::Viridis).map(0.0))), 1u) << "constant " << constant;
    EXPECT_EQ(keyColors.count(toRgb8(ColorMap(ColorMapKind::Viridis).map(1.0))), 1u) << "constant " << constant;
  }
  EXPECT_EQ(
    heatMapTitle(HeatMapOptions{ "depth", "m", ColorMapKind::Viridis, {}, {}, {} }, ValueRange{ 7.0, 7.0 }),
    "depth [m]  range [7, 7]");
}

TEST(HeatMap, MarginsHoldTheColourBarAndTitleText)
{
  for (const int size : { 16, 64, 300 })
  {
    const ImageF values = makeRamp(size, size);
    HeatMapOptions options;
    options.title = "kernel_texels";
    options.unit = "texels";
    const ImageU8 canvas = renderHeatMap(values, nullptr, options);
    EXPECT_GT(canvas.width, values.width) << "size " << size;
    EXPECT_GT(canvas.height, values.height) << "size " << size;

    // Above the values, in their columns, there is only the title: dark text pixels on white, not a filled box.
    int darkPixels = 0, titleBandPixels = 0;
    for (int y = values.height; y < canvas.height; ++y)
      for (int x = 0; x < values.width; ++x, ++titleBandPixels)
        darkPixels += isDark(pixelAt(canvas, x, y)) ? 1 : 0;
    EXPECT_GT(darkPixels, 10) << "size " << size << ": no title text rendered";
    EXPECT_LT(darkPixels, titleBandPixels / 2) << "size " << size;
    // The whole title fits on the canvas: its lines wrap to it, so every word of them fits.
    const std::vector<std::string> titleLines = heatMapTitleLines(options, heatMapScale({ { &values, nullptr } }, options));
    ASSERT_EQ(titleLines.size(), 2u) << "size " << size;
    for (const std::string& line : titleLines)
    {
      std::istringstream words(line);
      for (std::string word; words >> word;)
        EXPECT_GE(canvas.width, measureText(word, heatMapFontPx(size)).width) << "size " << size << ": " << word;
    }

    // The right margin holds the bar (both ends of the colour map) and dark label/outline pixels.
    const std::set<Rgb8> keyColors = colorsIn(canvas, values.width, canvas.width, 0, canvas.height);
    EXPECT_EQ(keyColors.count(toRgb8(ColorMap(ColorMapKind::Viridis).map(0.0))), 1u) << "size " << size;
    EXPECT_EQ(keyColors.count(toRgb8(ColorMap(ColorMapKind::Viridis).map(1.0))), 1u) << "size " << size;
    EXPECT_EQ(keyColors.count(toRgb8(kBlack)), 1u) << "size " << size;
  }
}

TEST(HeatMap, LargeImagesScaleTheFont)
{
  EXPECT_EQ(heatMapFontPx(16), 12);
  EXPECT_EQ(heatMapFontPx(4096), 96);
  const ImageF values = makeRamp(4096, 4096);
  const ImageU8 canvas =
    renderHeatMap(values, nullptr, HeatMapOptions{ "big", "", ColorMapKind::Viridis, {}, {}, {} });
  EXPECT_GT(canvas.width, 4096);
  EXPECT_GT(canvas.height, 4096 + heatMapFontPx(4096));
  EXPECT_EQ(pixelAt(canvas, 4095, 4095), expectedColor(ColorMapKind::Viridis, 1.0, 0.0, 1.0));
}

TEST(HeatMap, CategoricalColoursClassesAndDrawsALegend)
{
  ImageF classes(24, 24, 1, 0.0f);
  for (int x = 8; x < 16; ++x)
    classes.at(x, 0) = 1.2f; // rounds to class 1
  for (int x = 16; x < 24; ++x)
    classes.at(x, 0) = 2.0f;
  HeatMapOptions options;
  options.title = "shadow_class";
  options.colorMap = ColorMapKind::Categorical;
  options.categoryLabels = { "lit", "penumbra", "umbra" };
  const ImageU8 canvas = renderHeatMap(classes, nullptr, options);
  EXPECT_EQ(pixelAt(canvas, 0, 0), toRgb8(ColorMap::categoryColor(0)));
  EXPECT_EQ(pixelAt(canvas, 10, 0), toRgb8(ColorMap::categoryColor(1)));
  EXPECT_EQ(pixelAt(canvas, 20, 0), toRgb8(ColorMap::categoryColor(2)));

  // The legend has a swatch per label and no continuous bar.
  const std::set<Rgb8> keyColors = colorsIn(canvas, classes.width, canvas.width, 0, canvas.height);
  for (long long id = 0; id < 3; ++id)
    EXPECT_EQ(keyColors.count(toRgb8(ColorMap::categoryColor(id))), 1u) << "swatch " << id;
  EXPECT_EQ(keyColors.count(toRgb8(ColorMap::categoryColor(3))), 0u);
  EXPECT_EQ(keyColors.count(toRgb8(ColorMap(ColorMapKind::Viridis).map(0.5))), 0u);
}

class HeatMapPng : public ::testing::Test
{
protected:
  void SetUp() override
  {
    directory_ =
      std::filesystem::temp_directory_path() /
      format("shadowlab_heatmap_test_", ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(directory_);
    std::filesystem::create_directories(directory_);
  }
  void TearDown() override { std::filesystem::remove_all(directory_); }

  std::filesystem::path directory_;
};

TEST_F(HeatMapPng, WritesAReadableRgbPngWithTheTopRowFirst)
{
  const ImageF ramp = makeRamp(40, 30);
  const HeatMapOptions options{ "kernel_texels", "texels", ColorMapKind::Viridis, {}, {}, {} };
  const std::filesystem::path pngPath = directory_ / "ramp.png";
  writeHeatMapPng(ramp, nullptr, options, pngPath);
  const ImageU8 canvas = renderHeatMap(ramp, nullptr, options);

  // vtkPNGReader returns row 0 = bottom of the PNG (the Image convention): the file must equal the canvas.
  vtkNew<vtkPNGReader> reader;
  ASSERT_TRUE(reader->CanReadFile(pngPath.string().c_str()));
  reader->SetFileName(pngPath.string().c_str());
  reader->Update();
  vtkImageData* png = reader->GetOutput();
  const int* dimensions = png->GetDimensions();
  ASSERT_EQ(dimensions[0], canvas.width);
  ASSERT_EQ(dimensions[1], canvas.height);
  ASSERT_EQ(png->GetNumberOfScalarComponents(), 3);
  ASSERT_EQ(png->GetScalarType(), VTK_UNSIGNED_CHAR);
  const auto* pngPixels = static_cast<const std::uint8_t*>(png->GetScalarPointer());
  EXPECT_TRUE(std::equal(canvas.data.begin(), canvas.data.end(), pngPixels))
    << "PNG differs from renderHeatMap";

  // So the PNG's bottom row holds the values' distinct row 0 (1 at the left), and its top row the title band.
  const Rgb8 bottomLeft{ pngPixels[0], pngPixels[1], pngPixels[2] };
  EXPECT_EQ(bottomLeft, expectedColor(ColorMapKind::Viridis, 1.0, 0.0, 1.0)) << toString(bottomLeft);
  const std::size_t topRowStart = 3 * static_cast<std::size_t>(canvas.width) * (canvas.height - 1);
  EXPECT_EQ(
    (Rgb8{ pngPixels[topRowStart], pngPixels[topRowStart + 1], pngPixels[topRowStart + 2] }), toRgb8(kWhite));
}

TEST_F(HeatMapPng, UnwritablePathThrowsInputErrorNamingIt)
{
  const std::filesystem::path pngPath = directory_ / "no_such_directory" / "ramp.png";
  try
  {
    writeHeatMapPng(makeRamp(16, 16), nullptr, HeatMapOptions{}, pngPath);
    FAIL() << "no exception for " << pngPath;
  }
  catch (const InputError& error)
  {
    EXPECT_NE(std::string(error.what()).find(pngPath.string()), std::string::npos) << error.what();
  }
  EXPECT_FALSE(std::filesystem::exists(pngPath));
}

} // namespace
} // namespace sl
