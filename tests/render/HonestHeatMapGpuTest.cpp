// Issue 31 item 4 end to end on llvmpipe: hard's depth_margin on `grazing` (a box lit from the side), drawn as
// `render` draws it. The box's faces turned from the light reach no shadow test (the shader writes 0 there): its heat
// map must draw them light grey, not the white of "margin 0, at the acne threshold", and the robust scale must leave at
// most 2 % of the tested pixels saturated. The CPU's shadow_tested is checked against the shader's own decision
// (hard writes kernel_texels = 1 exactly where it ran the test).
#include "support/TestSupport.h"
#include "vis/BufferHeatMap.h"
#include "vis/Canvas.h"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <iostream>

namespace sl
{
namespace
{

TEST(HonestHeatMapGpu, DepthMarginIsGreyWhereNoShadowTestRanAndSaturatesAtMostTwoPercent)
{
  const Scene scene = test::loadDataset("grazing");
  const FrameResult frame = test::renderDataset(scene, "hard", 128, 128);
  const NamedImage* margin = frame.find("depth_margin");
  ASSERT_NE(margin, nullptr);
  ASSERT_EQ(margin->domain, BufferDomain::ShadowTested);
  const ImageF& coverage = test::bufferOf(frame, "coverage");
  const ImageF& tested = test::bufferOf(frame, "shadow_tested");
  const ImageF& kernel = test::bufferOf(frame, "kernel_texels");

  int covered = 0, untested = 0, disagree = 0;
  for (int y = 0; y < 128; ++y)
    for (int x = 0; x < 128; ++x)
    {
      if (coverage.at(x, y) <= 0.5f)
        continue;
      ++covered;
      const bool cpuTested = tested.at(x, y) > 0.5f;
      untested += !cpuTested;
      disagree += cpuTested != (kernel.at(x, y) == 1.0f);
      if (!cpuTested)
        EXPECT_EQ(margin->image.at(x, y), 0.0f) << "the shader writes 0 where it ran no test, at " << x << ", " << y;
    }
  std::cout << "grazing 128x128 hard: " << covered << " covered pixels, " << untested << " without a shadow test, "
            << disagree << " where shadow_tested and the shader disagree\n";
  EXPECT_GT(untested, 200) << "the box's two visible faces are turned from the light";
  EXPECT_LE(disagree, covered / 200) << "shadow_tested must match the shader's test up to grazing float rounding";

  const ImageU8 mask = bufferValueMask(*margin, frame.buffers);
  const HeatMapOptions options = bufferHeatMapOptions(*margin, &mask);
  const ImageU8 canvas = renderHeatMap(heatMapValues(*margin), &mask, options);
  const ColorMap diverging(ColorMapKind::Diverging);
  const auto rgbAt = [&](int x, int y) {
    return std::array<std::uint8_t, 3>{ canvas.at(x, y, 0), canvas.at(x, y, 1), canvas.at(x, y, 2) };
  };
  int notGrey = 0, valued = 0, saturated = 0;
  for (int y = 0; y < 128; ++y)
    for (int x = 0; x < 128; ++x)
    {
      if (mask.at(x, y) == kNotApplicablePixel)
        notGrey += rgbAt(x, y) != toRgb8(kNotApplicableColor);
      else if (mask.at(x, y) != 0)
      {
        ++valued;
        saturated += rgbAt(x, y) == toRgb8(diverging.map(0.0)) || rgbAt(x, y) == toRgb8(diverging.map(1.0));
      }
    }
  std::cout << "depth_margin heat map: " << saturated << " of " << valued << " tested pixels in an end colour\n";
  EXPECT_EQ(notGrey, 0) << "faces turned from the light must be the not-applicable grey";
  EXPECT_LE(100.0 * saturated / valued, 2.0) << saturated << " of " << valued;
}

} // namespace
} // namespace sl
