// The perspective warp (survey §4.2) against the survey's Fig. 12 closed forms: the fitted light view's matrix, not
// a copy of the formulas, is measured (its t coordinate and its dt/dz along the view axis), for uniform, PSM and
// LiSPSM, view ⟂ light, z in [1, 100]. Then the hard cases: γ -> 0, the bias footprint, non-directional lights.
#include "core/Error.h"
#include "lightspace/CameraView.h"
#include "lightspace/LightView.h"
#include "lightspace/PerspectiveWarp.h"
#include "lightspace/ShadowMapMath.h"
#include "probe/ProbeGeometry.h"
#include "scene/Scene.h"
#include "structures/shadowmap/ShadowMapStructure.h"
#include "techniques/Registry.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace sl
{
namespace
{

constexpr double kZNear = 1.0;
constexpr double kZFar = 100.0;
constexpr int kMapSize = 1024;

// Fig. 12's configuration: an overhead directional light, the eye at height 2 looking along -z (view ⟂ light), and
// receivers on the ground along the view axis at eye depths z in [1, 100], with two lateral points for a window.
struct Fig12Setup
{
  Scene scene;
  Light light;
  CameraView camera;
  ImageF position;
  ImageF normal;
};

Fig12Setup fig12Setup(const glm::dvec3& viewDirection = { 0.0, 0.0, -1.0 })
{
  Fig12Setup setup;
  setup.light.type = LightType::Directional;
  setup.light.direction = { 0.0, -1.0, 0.0 };
  SceneObject ground;
  ground.mesh.positions = { { -50.0f, 0.0f, 10.0f }, { 50.0f, 0.0f, 10.0f }, { 0.0f, 0.0f, -150.0f } };
  ground.mesh.normals.assign(3, glm::vec3(0.0f, 1.0f, 0.0f));
  ground.mesh.indices = { 0, 1, 2 };
  ground.castShadows = false;
  setup.scene.objects.push_back(ground);
  const glm::dvec3 eye(0.0, 2.0, 0.0);
  const glm::dvec3 up = std::abs(viewDirection.y) > 0.9 ? glm::dvec3(0.0, 0.0, -1.0) : glm::dvec3(0.0, 1.0, 0.0);
  setup.camera.viewFromWorld = glm::lookAt(eye, eye + viewDirection, up);
  setup.camera.nearDepth = 0.5;
  setup.camera.farDepth = 200.0;
  constexpr int count = 200;
  setup.position = ImageF(count + 2, 1, 4, 0.0f);
  setup.normal = ImageF(count + 2, 1, 4, 0.0f);
  for (int i = 0; i < count + 2; ++i)
  {
    const double z = i < count ? kZNear + (kZFar - kZNear) * i / (count - 1) : 50.0;
    const double x = i < count ? 0.0 : (i == count ? -3.0 : 3.0);
    setup.position.at(i, 0, 0) = static_cast<float>(x);
    setup.position.at(i, 0, 2) = static_cast<float>(-z);
    setup.position.at(i, 0, 3) = 1.0f;
    setup.normal.at(i, 0, 1) = 1.0f;
    setup.normal.at(i, 0, 3) = 1.0f;
  }
  return setup;
}

LightView fitFig12(const Fig12Setup& setup, WarpKind kind, double n = 0.0)
{
  FocusSettings focus;
  focus.resolution = kMapSize;
  focus.marginTexels = 0.0;
  focus.warp = { kind, n };
  focus.camera = &setup.camera;
  return fitLightView(setup.light, setup.scene, setup.position, setup.normal, focus);
}

// The map's t in [0, 1] at eye depth z on the view axis, and Eq. 1's dp/ds = (1/z) dz/ds from the matrix's gradient.
struct AxisSample
{
  double t;
  double aliasing;
};

AxisSample sampleAxis(const LightView& view, double z)
{
  const glm::dvec3 pWs(0.0, 0.0, -z);
  const glm::dmat4& m = view.clipFromWorld;
  const glm::dvec4 clip = m * glm::dvec4(pWs, 1.0);
  const double ndcY = clip.y / clip.w;
  // d(ndc.y)/d(world z) = (M_y,z - ndc.y M_w,z) / w; eye depth z grows along world -z.
  const double dNdcDz = -(m[2][1] - ndcY * m[2][3]) / clip.w;
  return { 0.5 * ndcY + 0.5, 1.0 / (z * std::abs(0.5 * dNdcDz)) };
}

TEST(PerspectiveWarp, Fig12ClosedFormsOverTheViewDepth)
{
  const Fig12Setup setup = fig12Setup();
  const double nOpt = lispsmOptimalN(kZNear, kZFar);
  EXPECT_NEAR(nOpt, 11.0, 1e-12);
  struct Case
  {
    WarpKind kind;
    double n;
  };
  for (const Case c : { Case{ WarpKind::Psm, kZNear }, Case{ WarpKind::Lispsm, nOpt },
         Case{ WarpKind::Lispsm, std::numeric_limits<double>::infinity() } })
  {
    // The last case: LiSPSM with warp_n at 1e300, the uniform map's limit of the same matrix.
    const LightView view = fitFig12(setup, c.kind, std::isinf(c.n) ? 1e300 : 0.0);
    ASSERT_TRUE(view.warp.active());
    EXPECT_NEAR(view.warp.gammaDeg, 90.0, 1e-9);
    EXPECT_NEAR(view.warp.zNear, kZNear, 1e-6);
    EXPECT_NEAR(view.warp.zFar, kZFar, 1e-5);
    if (!std::isinf(c.n))
    {
      EXPECT_NEAR(view.warp.n, c.n, 1e-5) << warpName(c.kind);
    }
    double maxTError = 0.0;
    double maxAliasingError = 0.0;
    for (int i = 0; i <= 99; ++i)
    {
      // Float receivers: the fit saw z_n and z_f as floats; the map's ends are exactly there.
      const double z = static_cast<float>(kZNear + (kZFar - kZNear) * i / 99.0);
      const AxisSample measured = sampleAxis(view, z);
      maxTError = std::max(maxTError, std::abs(measured.t - closedFormWarpT(z, kZNear, kZFar, c.n)));
      maxAliasingError = std::max(maxAliasingError,
        std::abs(measured.aliasing / closedFormWarpAliasing(z, kZNear, kZFar, c.n) - 1.0));
    }
    EXPECT_LT(maxTError, 1e-9) << warpName(c.kind) << " n " << c.n;
    EXPECT_LT(maxAliasingError, 1e-9) << warpName(c.kind) << " n " << c.n;
  }
}

TEST(PerspectiveWarp, Fig12FiguresAndTheOptimalNEqualisesTheEnds)
{
  const double infinity = std::numeric_limits<double>::infinity();
  const double nOpt = lispsmOptimalN(kZNear, kZFar);
  // Uniform 99 -> 0.99, PSM 0.99 -> 99, LiSPSM 9.9 at both ends with its minimum 3.27 at z = 10.
  EXPECT_NEAR(closedFormWarpAliasing(1.0, kZNear, kZFar, infinity), 99.0, 1e-12);
  EXPECT_NEAR(closedFormWarpAliasing(100.0, kZNear, kZFar, infinity), 0.99, 1e-12);
  EXPECT_NEAR(closedFormWarpAliasing(1.0, kZNear, kZFar, kZNear), 0.99, 1e-12);
  EXPECT_NEAR(closedFormWarpAliasing(100.0, kZNear, kZFar, kZNear), 99.0, 1e-12);
  EXPECT_NEAR(closedFormWarpAliasing(10.0, kZNear, kZFar, nOpt), 400.0 * 99.0 / (110.0 * 110.0), 1e-12);
  for (const glm::dvec2 range : { glm::dvec2(1.0, 100.0), glm::dvec2(0.1, 1000.0), glm::dvec2(3.0, 7.0) })
  {
    const double n = lispsmOptimalN(range.x, range.y);
    const double nearAliasing = closedFormWarpAliasing(range.x, range.x, range.y, n);
    const double farAliasing = closedFormWarpAliasing(range.y, range.x, range.y, n);
    EXPECT_LT(std::abs(nearAliasing / farAliasing - 1.0), 1e-12) << range.x << " " << range.y;
    // ... and no other n does: 1 % off n_opt unbalances the ends.
    EXPECT_GT(std::abs(closedFormWarpAliasing(range.x, range.x, range.y, 1.01 * n) /
                closedFormWarpAliasing(range.y, range.x, range.y, 1.01 * n) - 1.0), 1e-4);
  }
  // The measured map's ends, from its matrix.
  const LightView view = fitFig12(fig12Setup(), WarpKind::Lispsm);
  EXPECT_LT(std::abs(sampleAxis(view, kZNear).aliasing / sampleAxis(view, kZFar).aliasing - 1.0), 1e-9);
  EXPECT_NEAR(sampleAxis(view, kZNear).aliasing, 9.9, 1e-8);
}

TEST(PerspectiveWarp, UnwarpedMapIsTheUniformClosedForm)
{
  // warp = none: the plain focused map; dp/ds along the view axis is (z_f - z_n) / z, whichever map axis holds z.
  const LightView view = fitFig12(fig12Setup(), WarpKind::None);
  EXPECT_FALSE(view.warp.active());
  for (const double z : { 1.0, 10.0, 100.0 })
  {
    const glm::dvec3 step = glm::dvec3(view.clipFromWorld * glm::dvec4(0.0, 0.0, -1.0, 0.0));
    const double ndcPerUnit = std::max(std::abs(step.x), std::abs(step.y));
    EXPECT_NEAR(1.0 / (z * 0.5 * ndcPerUnit), closedFormWarpAliasing(z, kZNear, kZFar, std::numeric_limits<double>::infinity()), 1e-9);
  }
}

TEST(PerspectiveWarp, ViewParallelToTheLightDegradesToTheUniformMap)
{
  // Looking straight down (away from the light), straight up (into it) and nearly so: finite matrices; exactly
  // parallel, the same map as warp = none.
  for (const glm::dvec3 direction : { glm::dvec3(0.0, -1.0, 0.0), glm::dvec3(0.0, 1.0, 0.0),
         glm::normalize(glm::dvec3(0.0, -1.0, 1e-12)), glm::normalize(glm::dvec3(1e-7, -1.0, 0.0)) })
  {
    const Fig12Setup setup = fig12Setup(direction);
    for (const WarpKind kind : { WarpKind::Psm, WarpKind::Lispsm, WarpKind::Tsm })
    {
      const LightView warped = fitFig12(setup, kind);
      const LightView uniform = fitFig12(setup, WarpKind::None);
      for (int c = 0; c < 4; ++c)
      {
        for (int r = 0; r < 4; ++r)
        {
          ASSERT_TRUE(std::isfinite(warped.clipFromWorld[c][r])) << warpName(kind) << " " << c << "," << r;
        }
      }
      const bool parallel = std::abs(direction.x) < 1e-9 && std::abs(direction.z) < 1e-9;
      const double sinGamma = std::sin(glm::radians(warped.warp.gammaDeg));
      EXPECT_TRUE(!parallel || std::isinf(warped.warp.n)) << warpName(kind);
      EXPECT_LT(sinGamma, 1e-6);
      for (int i = 0; i < setup.position.width; ++i)
      {
        const glm::dvec3 pWs(setup.position.at(i, 0, 0), setup.position.at(i, 0, 1), setup.position.at(i, 0, 2));
        const ShadowMapSample a = projectToShadowMap(warped, pWs);
        const ShadowMapSample b = projectToShadowMap(uniform, pWs);
        ASSERT_TRUE(std::isfinite(a.uvTexels.x) && std::isfinite(a.uvTexels.y));
        for (const double coordinate : { a.uvTexels.x, a.uvTexels.y })
        {
          EXPECT_TRUE(coordinate >= -1e-6 && coordinate <= kMapSize + 1e-6) << warpName(kind) << " " << coordinate;
        }
        EXPECT_EQ(a.depthLin, b.depthLin);
        if (parallel)
        {
          EXPECT_NEAR(glm::length(a.uvTexels - b.uvTexels), 0.0, 1e-6) << warpName(kind) << " receiver " << i;
          EXPECT_NEAR(receiverTexelWorldSize(warped, pWs, a.depthLin), uniform.texelWorldSize(b.depthLin), 1e-12);
        }
      }
    }
  }
}

TEST(PerspectiveWarp, BiasFollowsTheWarpedTexelFootprint)
{
  // The texel's side along the view axis at depth z is dz/ds / N = z (dp/ds) / N (Eq. 1); across it, the window's
  // width times W(z) / N. The bias's footprint is the larger; unwarped it is texelWorldSize.
  const Fig12Setup setup = fig12Setup();
  const LightView view = fitFig12(setup, WarpKind::Lispsm);
  const double n = view.warp.n;
  BiasSettings bias;
  bias.constantTexels = 0.5;
  bias.slopeTexels = 1.0;
  const glm::dvec4 lateralRow(view.clipFromWorld[0][0], view.clipFromWorld[1][0], view.clipFromWorld[2][0],
    view.clipFromWorld[3][0]);
  for (const double z : { 1.0, 10.0, 100.0 })
  {
    const glm::dvec3 pWs(0.0, 0.0, -z);
    const double alongAxis = z * closedFormWarpAliasing(z, kZNear, kZFar, n) / kMapSize;
    const double w = 1.0 + (z - kZNear) / n;
    // On the view axis ndc.x = 0: one texel across is 2 / N of ndc, d(ndc.x)/dx = M_x,x / w.
    const double across = 2.0 / kMapSize / (std::abs(lateralRow.x) / w);
    const double expected = std::max(alongAxis, across);
    const double depthLin = projectToShadowMap(view, pWs).depthLin;
    EXPECT_NEAR(receiverTexelWorldSize(view, pWs, depthLin) / expected, 1.0, 1e-9) << "z " << z;
    EXPECT_NEAR(depthBiasAt(view, bias, 2.0, pWs, depthLin), expected * 2.5, 1e-9 * expected) << "z " << z;
  }
  // Near and far texels differ by z_f / z_n in size along the axis (equal dp/ds): the bias grows with them.
  const double nearSize = receiverTexelWorldSize(view, { 0.0, 0.0, -kZNear }, 0.0);
  const double farSize = receiverTexelWorldSize(view, { 0.0, 0.0, -kZFar }, 0.0);
  EXPECT_GT(farSize / nearSize, 50.0);
}

TEST(PerspectiveWarp, ProbeGeometryInvertsTheWarpedMap)
{
  // The probe draws texels in the world (worldFromTexel): under a warp it inverts the warped matrix.
  const Fig12Setup setup = fig12Setup(glm::normalize(glm::dvec3(0.3, -0.4, -1.0)));
  for (const WarpKind kind : { WarpKind::None, WarpKind::Psm, WarpKind::Lispsm, WarpKind::Tsm })
  {
    const LightView view = fitFig12(setup, kind);
    for (const glm::dvec2 uv : { glm::dvec2(0.5, 0.5), glm::dvec2(512.25, 17.0), glm::dvec2(1000.0, 1020.5) })
    {
      for (const double depth : { view.nearDepth, 0.5 * (view.nearDepth + view.farDepth), view.farDepth })
      {
        const ShadowMapSample back = projectToShadowMap(view, worldFromTexel(view, uv, depth));
        EXPECT_NEAR(glm::length(back.uvTexels - uv), 0.0, 1e-7) << warpName(kind);
        EXPECT_NEAR(back.depthLin, depth, 1e-9 * depth) << warpName(kind);
      }
    }
  }
}

TEST(PerspectiveWarp, NonDirectionalLightIsAnInputError)
{
  Fig12Setup setup = fig12Setup();
  setup.light.type = LightType::Spot;
  setup.light.center = { 0.0, 50.0, -50.0 };
  setup.light.normal = { 0.0, -1.0, 0.0 };
  setup.light.coneAngleDeg = 80.0;
  try
  {
    fitFig12(setup, WarpKind::Lispsm);
    FAIL() << "expected an InputError";
  }
  catch (const InputError& error)
  {
    EXPECT_EQ(std::string(error.what()).rfind("--set warp=lispsm: a perspective warp needs a directional light", 0), 0u)
      << error.what();
  }
}

TEST(PerspectiveWarp, TsmPutsTheBodysMiddleOnThe80PercentLine)
{
  // MT04's rule, as PerspectiveWarp.h reads it: t(L / 2) = 0.8 with n = L / 3.
  const double length = kZFar - kZNear;
  const double n = warpParameter(WarpKind::Tsm, kZNear, kZFar, length, 1.0);
  EXPECT_NEAR(closedFormWarpT(kZNear + 0.5 * length, kZNear, kZFar, n), 0.8, 1e-12);
  const LightView view = fitFig12(fig12Setup(), WarpKind::Tsm);
  EXPECT_NEAR(sampleAxis(view, kZNear + 0.5 * length).t, 0.8, 1e-6);
}

TEST(PerspectiveWarp, OnlyTechniquesWhoseLookupsHoldUnderAWarpListIt)
{
  // hard and pcf read the map through the warped matrix and the footprint bias; the others (filtered moments, the
  // back-projections, the soft-shadow searches) assume the unwarped window: they must not list it, and their
  // shadow-map settings never carry a warp.
  int listing = 0;
  for (const TechniqueDescriptor& technique : techniqueRegistry())
  {
    const bool lists = technique.findParameter("warp") != nullptr;
    EXPECT_EQ(lists, technique.findParameter("warp_n") != nullptr) << technique.name;
    EXPECT_EQ(lists, technique.name == "hard" || technique.name == "pcf") << technique.name;
    listing += lists ? 1 : 0;
    if (technique.needs(shadowMapStructure()))
    {
      EXPECT_EQ(shadowMapSettings(technique, technique.defaultParameters()).warp.kind, WarpKind::None) << technique.name;
    }
  }
  EXPECT_EQ(listing, 2);
  ParameterValues values = findTechnique("pcf").defaultParameters();
  values.set("warp=lispsm");
  values.set("warp_n=7.5");
  const ShadowMapSettings settings = shadowMapSettings(findTechnique("pcf"), values);
  EXPECT_EQ(settings.warp.kind, WarpKind::Lispsm);
  EXPECT_EQ(settings.warp.n, 7.5);
}

} // namespace
} // namespace sl
