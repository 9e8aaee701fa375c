// Z-partitioning (survey §4.3.1, lightspace/Cascades.h) on the CPU: the split depths against their closed forms, the
// selection twin's depth bands and containment, texel snapping, the owner planes of a fit, and which techniques list
// the parameters.
#include "core/Error.h"
#include "lightspace/CameraView.h"
#include "lightspace/Cascades.h"
#include "lightspace/PartitionViews.h"
#include "structures/shadowmap/ShadowMapStructure.h"
#include "techniques/Registry.h"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <iostream>

namespace sl
{
namespace
{

TEST(Cascades, SplitDepthsMatchTheClosedForms)
{
  // z_n = 1, z_f = 100, m = 4: uniform 1, 25.75, 50.5, 75.25, 100; log 1, 100^(1/4) = 3.1623, 10, 31.623, 100; practical
  // the λ-weighted mean of the two (PSSM), λ = 0 and 1 its limits.
  const double zNear = 1.0, zFar = 100.0;
  const std::vector<double> uniform = splitDepths(SplitScheme::Uniform, 0.5, zNear, zFar, 4);
  const std::vector<double> log = splitDepths(SplitScheme::Log, 0.5, zNear, zFar, 4);
  const double expectedUniform[] = { 1.0, 25.75, 50.5, 75.25, 100.0 };
  const double expectedLog[] = { 1.0, std::sqrt(10.0), 10.0, 10.0 * std::sqrt(10.0), 100.0 };
  ASSERT_EQ(uniform.size(), 5u);
  for (int i = 0; i <= 4; ++i)
  {
    EXPECT_NEAR(uniform[i], expectedUniform[i], 1e-12) << i;
    EXPECT_NEAR(log[i], expectedLog[i], 1e-12) << i;
  }
  for (const double lambda : { 0.0, 0.5, 1.0 })
  {
    const std::vector<double> practical = splitDepths(SplitScheme::Practical, lambda, zNear, zFar, 4);
    for (int i = 0; i <= 4; ++i)
    {
      EXPECT_NEAR(practical[i], lambda * expectedLog[i] + (1.0 - lambda) * expectedUniform[i], 1e-12)
        << "lambda " << lambda << " split " << i;
    }
  }
  // The log split's slices all have the same far/near ratio (z_f / z_n)^(1/m): the optimal warp's discretisation.
  const std::vector<double> eight = splitDepths(SplitScheme::Log, 0.0, 0.5, 400.0, 8);
  for (int i = 0; i < 8; ++i)
  {
    EXPECT_NEAR(eight[i + 1] / eight[i], std::pow(800.0, 1.0 / 8.0), 1e-12) << i;
  }
  // One cascade: the whole range.
  const std::vector<double> one = splitDepths(SplitScheme::Log, 0.5, 2.0, 3.0, 1);
  EXPECT_EQ(one, (std::vector<double>{ 2.0, 3.0 }));
}

CameraView lookingDownMinusZ()
{
  CameraView camera;
  camera.viewFromWorld = glm::lookAt(glm::dvec3(0.0, 1.0, 0.0), glm::dvec3(0.0, 1.0, -1.0), glm::dvec3(0.0, 1.0, 0.0));
  camera.nearDepth = 0.5;
  camera.farDepth = 200.0;
  return camera;
}

TEST(Cascades, DepthSelectionBlendsTheLastBandOfASliceIntoTheNext)
{
  const CameraView camera = lookingDownMinusZ();
  PartitionSet cascades;
  cascades.cascadeSettings.count = 3;
  cascades.cascadeSettings.selection = CascadeSelection::Depth;
  cascades.cascadeSettings.blend = 0.25;
  cascades.splits = { 1.0, 5.0, 21.0, 101.0 };
  cascades.views.resize(3);
  const auto at = [&](double depth) { return selectCascade(cascades, camera, glm::dvec3(0.3, 0.0, -depth)); };
  EXPECT_NEAR(eyeDepthOf(camera, glm::dvec3(0.3, 0.0, -7.0)), 7.0, 1e-12);
  // Slice 0 is [1, 5): its band [4, 5) blends into 1, weight (5 - d) / 1.
  EXPECT_EQ(at(2.0).primary, 0);
  EXPECT_EQ(at(2.0).primaryWeight, 1.0);
  EXPECT_EQ(at(4.5).primary, 0);
  EXPECT_EQ(at(4.5).secondary, 1);
  EXPECT_NEAR(at(4.5).primaryWeight, 0.5, 1e-12);
  // Slice 1 is [5, 21): band [17, 21).
  EXPECT_EQ(at(5.0).primary, 1);
  EXPECT_EQ(at(5.0).primaryWeight, 1.0);
  EXPECT_NEAR(at(20.0).primaryWeight, 0.25, 1e-12);
  EXPECT_EQ(at(20.0).secondary, 2);
  // The last slice has nothing to blend into; depths beyond the ends stay in the end slices.
  EXPECT_EQ(at(100.0).primary, 2);
  EXPECT_EQ(at(100.0).primaryWeight, 1.0);
  EXPECT_EQ(at(500.0).primary, 2);
  EXPECT_EQ(at(0.1).primary, 0);
  // Blend 0: a hard switch.
  cascades.cascadeSettings.blend = 0.0;
  EXPECT_EQ(at(4.99).primaryWeight, 1.0);
  EXPECT_EQ(at(4.99).primary, 0);

  // The owner planes: slice 1 extended toward the eye by slice 0's band (its pixels read map 1 too), up to C_2.
  cascades.cascadeSettings.blend = 0.25;
  const std::vector<glm::dvec4> planes = cascadeOwnerPlanes(camera, cascades.splits, 1, cascades.cascadeSettings);
  ASSERT_EQ(planes.size(), 2u);
  const auto inside = [&](double depth) {
    for (const glm::dvec4& plane : planes)
    {
      if (glm::dot(plane, glm::dvec4(0.0, 5.0, -depth, 1.0)) < 0.0)
      {
        return false;
      }
    }
    return true;
  };
  EXPECT_FALSE(inside(3.9));
  EXPECT_TRUE(inside(4.1));
  EXPECT_TRUE(inside(20.9));
  EXPECT_FALSE(inside(21.1));
  EXPECT_EQ(cascadeOwnerPlanes(camera, cascades.splits, 0, cascades.cascadeSettings).size(), 1u); // no near side
  EXPECT_EQ(cascadeOwnerPlanes(camera, cascades.splits, 2, cascades.cascadeSettings).size(), 1u); // no far side
}

// An orthographic light at height 5 looking down -y with window `window` (world x/z) and depth range [0, farDepth].
LightView overheadView(const glm::dvec4& window, int resolution, double farDepth)
{
  LightView view;
  view.projection = LightProjection::Orthographic;
  view.viewFromWorld = glm::lookAt(glm::dvec3(0.0, 5.0, 0.0), glm::dvec3(0.0, 4.0, 0.0), glm::dvec3(0.0, 0.0, -1.0));
  view.window = window;
  view.nearDepth = 0.0;
  view.farDepth = farDepth;
  view.resolution = resolution;
  view.clipFromView = glm::ortho(window.x, window.y, window.z, window.w, view.nearDepth, view.farDepth);
  view.clipFromWorld = view.clipFromView * view.viewFromWorld;
  return view;
}

TEST(Cascades, ContainmentPicksTheFinestMapThatHoldsThePointWithItsMargin)
{
  // Light ∥ view (survey §4.3.1): cascade 0's map also covers points of slice 1; containment reads it there.
  const CameraView camera = lookingDownMinusZ();
  PartitionSet cascades;
  cascades.cascadeSettings.count = 2;
  cascades.cascadeSettings.selection = CascadeSelection::Containment;
  cascades.splits = { 1.0, 4.0, 50.0 };
  cascades.marginTexels = 2.0;
  // Light view x = world x, y = world -z (looking down with up = -z). Map 0 covers |x|, |z| < 8 with 64 texels
  // (0.25 per texel, margin 0.5); map 1 covers |x|, |z| < 64.
  cascades.views = { overheadView({ -8.0, 8.0, -8.0, 8.0 }, 64, 10.0), overheadView({ -64.0, 64.0, -64.0, 64.0 }, 64, 20.0) };
  EXPECT_EQ(selectCascade(cascades, camera, glm::dvec3(0.0, 0.0, -6.0)).primary, 0);  // eye depth 6: slice 1
  EXPECT_EQ(selectCascade(cascades, camera, glm::dvec3(0.0, 0.0, -7.6)).primary, 1);  // within the margin of map 0
  EXPECT_EQ(selectCascade(cascades, camera, glm::dvec3(0.0, 0.0, -7.4)).primary, 0);
  EXPECT_EQ(selectCascade(cascades, camera, glm::dvec3(0.0, -6.0, -6.0)).primary, 1); // below map 0's depth range
  // The own slice's map holds its receivers by construction (its focus owns them): slice 0 reads map 0 even where
  // the test would fail.
  EXPECT_EQ(selectCascade(cascades, camera, glm::dvec3(0.0, 0.0, -3.0)).primary, 0);
  EXPECT_EQ(selectCascade(cascades, camera, glm::dvec3(7.9, -6.0, -3.0)).primary, 0);
  double edge = 0.0;
  ASSERT_TRUE(mapHolds(cascades.views[0], 2.0, glm::dvec3(3.75, 0.0, 0.0), edge));
  EXPECT_NEAR(edge, 0.5, 1e-12); // the inner window's half-width is 7.5
  // A band of 0.25 of the half-width blends toward map 1: at 3/4 of the way to the edge, weight 1/4 / 1/4 = 1 ...
  cascades.cascadeSettings.blend = 0.25;
  EXPECT_EQ(selectCascade(cascades, camera, glm::dvec3(0.0, 0.0, -5.625)).primaryWeight, 1.0);
  // ... and at 7/8 of the way, 1/8 / 1/4 = 0.5.
  const ViewSelection blended = selectCascade(cascades, camera, glm::dvec3(0.0, 0.0, -6.5625));
  EXPECT_EQ(blended.primary, 0);
  EXPECT_EQ(blended.secondary, 1);
  EXPECT_NEAR(blended.primaryWeight, 0.5, 1e-12);
}

TEST(Cascades, SnappedWindowsKeepTheirTexelGridWhenTheReceiversMoveALittle)
{
  // The snapped window's texel size is a power of 2^(1/4) and its edges whole texels from the light's origin, so the
  // receivers moving by less than a texel (a camera step) keeps the size and shifts the window by whole texels only.
  const int resolution = 256;
  const double margin = 2.0;
  const glm::dvec4 receivers(-3.1, 17.4, 2.2, 9.9);
  const glm::dvec4 window = snappedWindow(receivers, resolution, margin);
  for (int axis = 0; axis < 2; ++axis)
  {
    const double lo = window[2 * axis], hi = window[2 * axis + 1];
    const double texel = (hi - lo) / resolution;
    EXPECT_NEAR(std::log2(texel) * 4.0, std::round(std::log2(texel) * 4.0), 1e-9) << axis;
    EXPECT_NEAR(lo / texel, std::round(lo / texel), 1e-9) << axis;
    // The receivers with margin texels to spare, and no more than 2^(1/4) x the fitted texel.
    EXPECT_LE(lo + margin * texel, receivers[2 * axis]) << axis;
    EXPECT_GE(hi - margin * texel, receivers[2 * axis + 1]) << axis;
    EXPECT_LT(texel, std::pow(2.0, 0.25) * (receivers[2 * axis + 1] - receivers[2 * axis]) / (resolution - 6.0)) << axis;
    for (const double step : { 0.1, 0.37, 0.93 })
    {
      const glm::dvec4 moved = snappedWindow(receivers + glm::dvec4(step, step, -step, -step) * texel, resolution, margin);
      EXPECT_NEAR((moved[2 * axis + 1] - moved[2 * axis]) / resolution, texel, 1e-12 * texel) << step;
      const double shift = (moved[2 * axis] - lo) / texel;
      EXPECT_NEAR(shift, std::round(shift), 1e-9) << step;
    }
  }
}

TEST(Cascades, OnlyHardAndPcfListTheCascadeParameters)
{
  // The cascade loop picks one map per pixel and blends the technique's buffers; the techniques that read a
  // filtered or hierarchical structure built from one map (moments, SAT, HSM, back-projections) must not list them.
  int listing = 0;
  for (const TechniqueDescriptor& technique : techniqueRegistry())
  {
    const bool lists = technique.findParameter("cascades") != nullptr;
    for (const char* name : { "split_scheme", "split_lambda", "cascade_selection", "cascade_blend", "cascade_snap" })
    {
      EXPECT_EQ(lists, technique.findParameter(name) != nullptr) << technique.name << " " << name;
    }
    EXPECT_EQ(lists, technique.name == "hard" || technique.name == "pcf") << technique.name;
    listing += lists ? 1 : 0;
    if (technique.needs(shadowMapStructure()))
    {
      EXPECT_EQ(shadowMapSettings(technique, technique.defaultParameters()).cascades.count, 1) << technique.name;
    }
  }
  EXPECT_EQ(listing, 2);
  ParameterValues values = findTechnique("hard").defaultParameters();
  values.set("cascades=4");
  values.set("split_scheme=uniform");
  values.set("cascade_selection=containment");
  values.set("cascade_blend=0.2");
  values.set("cascade_snap=off");
  const CascadeSettings settings = shadowMapSettings(findTechnique("hard"), values).cascades;
  EXPECT_EQ(settings.count, 4);
  EXPECT_EQ(settings.scheme, SplitScheme::Uniform);
  EXPECT_EQ(settings.selection, CascadeSelection::Containment);
  EXPECT_EQ(settings.blend, 0.2);
  EXPECT_FALSE(settings.snap);
  // Other lights: one line naming the parameter.
  try
  {
    requireCascadableLight(settings, LightType::Spot);
    FAIL() << "a spot light's cascades were accepted";
  }
  catch (const InputError& error)
  {
    EXPECT_NE(std::string(error.what()).find("--set cascades=4"), std::string::npos) << error.what();
  }
  EXPECT_NO_THROW(requireCascadableLight(CascadeSettings{}, LightType::Point));
}

} // namespace
} // namespace sl
