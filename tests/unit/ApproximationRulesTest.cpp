// The per-pixel approximation rules (techniques/ApproximationRules.h) on synthetic shadow maps whose answer is
// known in closed form: a unit square light 2 above a flat ground facing it, the map written texel by texel in the
// light's tangent coordinates, and receivers on the ground. Each rule is shown flagging where the approximation
// changes the value by more than the tolerance and leaving the pixel alone where it cannot.
#include "frame/FrameResult.h"
#include "lightspace/LightView.h"
#include "scene/Scene.h"
#include "techniques/ApproximationRules.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <functional>

namespace sl
{
namespace
{

constexpr double kGroundDepth = 2.0;

// A frame whose shadow map (resolution^2 texels over tangents [-halfWindow, halfWindow]^2) stores
// depthAt(tangent x, tangent y) per texel centre, with one receiver pixel per entry of `receiverTangents`: the ground
// point the light sees at those tangents (x only; y = 0).
struct SyntheticFrame
{
  Scene scene;
  FrameResult frame;

  SyntheticFrame(int resolution, double halfWindow, const std::function<double(double, double)>& depthAt,
    const std::vector<double>& receiverTangents)
  {
    Light light;
    light.type = LightType::Area;
    light.shape = LightShape::Square;
    light.center = { 0.0, kGroundDepth, 0.0 };
    light.normal = { 0.0, -1.0, 0.0 };
    light.up = { 0.0, 0.0, 1.0 };
    light.size = 1.0;
    scene.lights.push_back(light);

    LightView view;
    view.projection = LightProjection::Perspective;
    view.eyeWs = light.center;
    view.viewFromWorld = glm::lookAt(light.center, light.center + light.normal, light.up);
    view.nearDepth = 0.5; // the nearest caster; also sets casterRange's pyramid level (texels here)
    view.farDepth = 10.0;
    view.window = { -halfWindow, halfWindow, -halfWindow, halfWindow };
    view.clipFromView = glm::frustum(-halfWindow * view.nearDepth, halfWindow * view.nearDepth,
      -halfWindow * view.nearDepth, halfWindow * view.nearDepth, view.nearDepth, view.farDepth);
    view.clipFromWorld = view.clipFromView * view.viewFromWorld;
    view.resolution = resolution;

    ImageF map(resolution, resolution, 1, 0.0f);
    const double texel = 2.0 * halfWindow / resolution;
    for (int j = 0; j < resolution; ++j)
    {
      for (int i = 0; i < resolution; ++i)
      {
        map.at(i, j) = static_cast<float>(depthAt(-halfWindow + (i + 0.5) * texel, -halfWindow + (j + 0.5) * texel));
      }
    }

    const int width = static_cast<int>(receiverTangents.size());
    ImageF position(width, 1, 3, 0.0f);
    ImageF normal(width, 1, 3, 0.0f);
    const glm::dmat4 worldFromView = glm::inverse(view.viewFromWorld);
    for (int x = 0; x < width; ++x)
    {
      const glm::dvec3 pWs(worldFromView *
        glm::dvec4(receiverTangents[static_cast<std::size_t>(x)] * kGroundDepth, 0.0, -kGroundDepth, 1.0));
      for (int c = 0; c < 3; ++c)
      {
        position.at(x, 0, c) = static_cast<float>(pWs[c]);
      }
      normal.at(x, 0, 1) = 1.0f;
    }
    frame.technique = "synthetic";
    frame.lightView = view;
    frame.buffers = { { "position", position }, { "normal", normal }, { "coverage", ImageF(width, 1, 1, 1.0f) },
      { "receives_shadows", ImageF(width, 1, 1, 1.0f) } };
    frame.lightSpace = { { "shadow_map_depth", map } };
  }

  ApproximationContext context() const { return { &frame, &scene, 0 }; }
  int width() const { return frame.find("position")->image.width; }
};

std::vector<float> codesOf(const ImageF& codes)
{
  std::vector<float> values;
  for (int x = 0; x < codes.width; ++x)
  {
    values.push_back(codes.at(x, 0));
  }
  return values;
}

TEST(ApproximationRules, BlockerDepthRatioIsTheSpreadOfPenumbraEstimates)
{
  // Penumbra estimates (d - z) / z: 1.0 at z = 1 and 0.5/1.5 at z = 1.5 over a receiver at 2, ratio 3.
  EXPECT_NEAR(blockerDepthRatio(1.0, 1.5, 2.0), 3.0, 1e-12);
  EXPECT_NEAR(blockerDepthRatio(1.0, 1.0, 2.0), 1.0, 1e-12);
  // The same 0.03 spread weighs 6% at mid depth, 30% near the receiver.
  EXPECT_NEAR(blockerDepthRatio(1.0, 1.03, 2.0), 1.03 / 0.97, 1e-12);
  EXPECT_NEAR(blockerDepthRatio(1.9, 1.93, 2.0), 1.93 * 0.1 / (1.9 * 0.07), 1e-12);
}

TEST(ApproximationRules, MultipleBlockerDepthsFlagsOnlyAPenumbraSpreadBeyondTheTolerance)
{
  // Fine map (texels 1/32 tangent, 0.0625 world at the ground: no wide texel); casters at depth 1 left of the axis and
  // `right` to the right of it, ground beyond |x| 0.75. The receiver under the axis sees both within its blocker
  // search region (half-width 0.25 tangent at depth 1).
  const auto frameWith = [](double right) {
    return SyntheticFrame(64, 1.0, [right](double u, double) {
      return std::abs(u) > 0.75 ? kGroundDepth : (u < 0.0 ? 1.0 : right);
    }, { 0.0 });
  };
  const SyntheticFrame near(frameWith(1.03)); // ratio 1.062
  const SyntheticFrame far(frameWith(1.2));   // ratio 1.5
  for (const auto& [frame, tolerance, flagged] : { std::tuple{ &near, 0.1, false }, std::tuple{ &near, 0.05, true },
         std::tuple{ &far, 0.1, true } })
  {
    const ShadowMapFootprint footprint(frame->context());
    const ShadowMapFootprint::CasterRange range = footprint.casterRange(0, 0);
    ASSERT_TRUE(range.found);
    ImageF codes(1, 1, 1, 0.0f);
    markMultipleBlockerDepths(footprint, codes, 1.0f, tolerance);
    EXPECT_EQ(codes.at(0, 0), flagged ? 1.0f : 0.0f)
      << "casters " << range.minDepth << ".." << range.maxDepth << ", tolerance " << tolerance;
  }
}

TEST(ApproximationRules, CoarseShadowMapFlagsAnEdgeTexelWiderThanTheTolerance)
{
  // Texels 1/32 tangent; a caster at depth 1 over u >= 0. From the ground (d = 2) one caster texel back-projects onto
  // (1/32) * 1 * 2 / (2 - 1) = 0.0625 of the unit light: an edge misplaced by one texel moves 6.25% of the light.
  const SyntheticFrame frame(64, 1.0, [](double u, double) { return u >= 0.0 ? 1.0 : kGroundDepth; }, { -0.01, -0.9 });
  const ShadowMapFootprint footprint(frame.context());
  const ShadowMapFootprint::CasterRange range = footprint.casterRange(0, 0);
  ASSERT_TRUE(range.found && range.receiverSeen);
  EXPECT_NEAR(range.texelOnLight, 0.0625, 1e-9);
  ImageF codes(frame.width(), 1, 1, 0.0f);
  markCoarseShadowMap(footprint, codes, 2.0f, 0.05);
  EXPECT_EQ(codesOf(codes), (std::vector<float>{ 2.0f, 0.0f })) << "the receiver far from the edge sees no caster";
  codes = ImageF(frame.width(), 1, 1, 0.0f);
  markCoarseShadowMap(footprint, codes, 2.0f, 0.1);
  EXPECT_EQ(codesOf(codes), (std::vector<float>{ 0.0f, 0.0f }));
}

TEST(ApproximationRules, CoarseShadowMapFlagsAWideTexelOnlyWhereTheCastersItHidesMatter)
{
  // Texels 1/8 tangent, 0.25 world at the ground: the receiver's margin (about one texel) exceeds 5% of d = 2, and a
  // caster 0.24 above the ground (depth 1.76, inside the margin) is invisible to the technique. It fills the texel
  // column u in [0, 1/8); the receiver at u = -0.03 sees it on the light at 0.03 * 14.67 = 0.44 .. 0.5 (scale
  // z d / (d - z) = 14.67): it hides 6% of the light, so only a tolerance under 6% needs the flag.
  const SyntheticFrame narrow(16, 1.0, [](double u, double) { return u >= 0.0 && u < 0.125 ? 1.76 : kGroundDepth; },
    { -0.03 });
  const ShadowMapFootprint footprint(narrow.context());
  EXPECT_NEAR(footprint.hiddenByMargin(0, 0, 1.0), 0.5 - 0.03 * 1.76 * 2.0 / 0.24, 1e-6); // a float map
  EXPECT_FALSE(footprint.casterRange(0, 0).found) << "the caster lies within the receiver's margin";
  for (const auto& [tolerance, flagged] : { std::pair{ 0.1, false }, std::pair{ 0.05, true } })
  {
    ImageF codes(1, 1, 1, 0.0f);
    markCoarseShadowMap(footprint, codes, 2.0f, tolerance);
    EXPECT_EQ(codes.at(0, 0), flagged ? 2.0f : 0.0f) << "tolerance " << tolerance;
  }
  // The same caster over the receiver's own column hides 0.5 + 0.44 of the light: flagged.
  const SyntheticFrame over(16, 1.0, [](double u, double) { return u >= -0.125 && u < 0.0 ? 1.76 : kGroundDepth; },
    { -0.03 });
  const ShadowMapFootprint overFootprint(over.context());
  EXPECT_NEAR(overFootprint.hiddenByMargin(0, 0, 1.0), 0.5 + 0.03 * 1.76 * 2.0 / 0.24, 1e-6);
  ImageF codes(1, 1, 1, 0.0f);
  markCoarseShadowMap(overFootprint, codes, 2.0f, 0.1);
  EXPECT_EQ(codes.at(0, 0), 2.0f);
  // A flat ground and nothing else: the margin hides nothing, no flag however wide the texel.
  const SyntheticFrame empty(16, 1.0, [](double, double) { return kGroundDepth; }, { -0.03 });
  const ShadowMapFootprint emptyFootprint(empty.context());
  EXPECT_EQ(emptyFootprint.hiddenByMargin(0, 0, 1.0), 0.0);
  codes = ImageF(1, 1, 1, 0.0f);
  markCoarseShadowMap(emptyFootprint, codes, 2.0f, 0.01);
  EXPECT_EQ(codes.at(0, 0), 0.0f);
}

} // namespace
} // namespace sl
