#include "techniques/izb/IzbTechnique.h"

#include "lightspace/LightView.h"
#include "techniques/ApproximationRules.h"
#include "techniques/ProbeSupport.h"
#include "techniques/izb/IzbTwin.h"
#include "techniques/izb/vtkSLIzbPass.h"

#include <cmath>
#include <string>

namespace sl
{

namespace
{

const Category<IzbStatus> izbStatusCategories[] = {
  { IzbStatus::NoTest, "NO_TEST", "no shadow test (uncovered, not receiving, or unreachable)" },
  { IzbStatus::Tested, "TESTED", "tested against every triangle over its light texel" },
  { IzbStatus::CutShort, "CUT_SHORT", "not tested: its texel's list or the node budget was full (not exact)", true },
};

} // namespace

IzbSettings IzbSettings::from(const ParameterValues& values)
{
  IzbSettings settings;
  settings.gridSize = values.getInt("grid_size");
  settings.nodeBudget = values.getInt("node_budget");
  settings.listBudget = values.getInt("list_budget");
  settings.normalOffset = values.get("normal_offset");
  return settings;
}

TechniqueDescriptor izbTechnique()
{
  TechniqueDescriptor descriptor = describeTechnique("izb", "Irregular z-buffer (exact hard shadows)",
    "Johnson, Mark & Burns 2004; Aila & Laine 2004; Johnson et al. 2005; Sintorn et al. 2008; survey (Scherzer et "
    "al. 2011) §4.5");
  descriptor.parameters = {
    { "grid_size", 256, 16, 2048, "texels",
      "texels per side of the light-space grid the samples are listed in (one face for a directional light, six cube "
      "faces around a point or spot light or an area light's centre); sets the cost, never the result",
      {}, true },
    { "node_budget", 4194304, 64, 16777216, "nodes",
      "list nodes available (one per listed sample); samples beyond it are flagged cut short", {}, true },
    { "list_budget", 16384, 1, 60000, "samples",
      "samples one texel's list may hold (the walk per triangle and texel stays under llvmpipe's 65535 loop "
      "iterations); samples beyond it are flagged cut short",
      {}, true },
    { "normal_offset", 1e-4, 0.0, 1e-2, "of the scene radius",
      "the tested point leaves its surface along its normal by this, as the ray tracer's origin does "
      "(test::RayCaster::pointVisibility)" },
  };
  descriptor.lightStructures = {}; // its own light-space grid, no shadow map
  // An area light is tested from its centre, as hard and pcf sample it (ReferenceModel::LightCentre), with its
  // one-sided reach (lightCanReach).
  descriptor.supportedLights = { LightType::Area, LightType::Point, LightType::Spot, LightType::Directional };
  descriptor.buffers = {
    { "izb_list_length", "samples", "visible samples listed in (projecting to) the pixel's light-space texel",
      BufferKind::Continuous, {}, SubLightCombine::Sum },
    { "izb_triangle_tests", "triangles",
      "caster triangles tested against the pixel's sample (those whose conservative cover holds its texel)",
      BufferKind::Continuous, {}, SubLightCombine::Sum },
    { "izb_ambiguous", "",
      "1 where the decision lies within float rounding of a triangle edge or plane (or the sample's texel "
      "placement does): either visibility is right there" },
    categoricalBuffer("izb_status", "whether the pixel's sample was tested, or cut short by a budget",
      izbStatusCategories, SubLightCombine::First),
  };
  descriptor.shaderConstants = {
    { "IZB_FLAG_TESTED", static_cast<int>(IzbFlagTested), "pixel state bit (IzbTechnique.h IzbFlag)" },
    { "IZB_FLAG_SHADOW", static_cast<int>(IzbFlagShadow), "pixel state bit" },
    { "IZB_FLAG_DEFINITE", static_cast<int>(IzbFlagDefinite), "pixel state bit" },
    { "IZB_FLAG_UNCERTAIN", static_cast<int>(IzbFlagUncertain), "pixel state bit" },
    { "IZB_FLAG_CUT_SHORT", static_cast<int>(IzbFlagCutShort), "pixel state bit" },
    { "IZB_FLAG_AMBIGUOUS_PLACEMENT", static_cast<int>(IzbFlagAmbiguousPlacement), "pixel state bit" },
    { "IZB_COVERAGE_MARGIN_INVERSE", izbCoverageMarginInverse, "1 / the cover's margin in texels (IzbTwin.h)" },
    { "IZB_EDGE_TOP_BIT_SHIFT", izbEdgeTopBitShift, "the flag bit of a lone-edge event's words (IzbTwin.h izbEdgeEvent)" },
  };
  descriptor.createPass = newTechniquePass<vtkSLIzbPass>;
  descriptor.probe = [](const ProbeContext& context, glm::ivec2 pixel, ProbeRecorder& recorder) {
    return probeIzb(*context.frame, *context.scene, context.lightIndex, pixel, recorder);
  };
  // Exact hard shadows of the light's centre; alpha textures are not sampled, so a perforated caster shadows as if
  // solid. Pixels within float rounding of a decision are published (izb_ambiguous), and so are those a budget cut
  // short (izb_status).
  descriptor.accuracy.reference = ReferenceModel::LightCentre;
  descriptor.accuracy.tolerance = 1e-3;
  descriptor.accuracy.approximations = {
    { "perforated caster as solid", "the segment to the light crosses a caster with an alpha texture" },
    { "float rounding", "izb_ambiguous: a triangle edge or plane (or the texel placement) within float rounding" },
    { "cut short", "izb_status cut short: the sample was not listed (list_budget or node_budget full)" },
  };
  descriptor.accuracy.markApproximations = [](const ApproximationContext& context, ImageF& codes) {
    markCentreRayThroughPerforatedCaster(context, codes, 1.0f);
    const ImageF& ambiguous = context.frame->find("izb_ambiguous")->image;
    const ImageF& status = context.frame->find("izb_status")->image;
    for (std::size_t index = 0; index < codes.data.size(); ++index)
    {
      if (ambiguous.data[index] > 0.5f)
      {
        codes.data[index] = 2.0f;
      }
      if (std::lround(status.data[index]) == static_cast<long>(IzbStatus::CutShort))
      {
        codes.data[index] = 3.0f;
      }
    }
  };
  return descriptor;
}

ProbeOutcome probeIzb(const FrameResult& frame, const Scene& scene, int lightIndex, glm::ivec2 pixel,
  ProbeRecorder& recorder)
{
  const Light& light = scene.lights.at(static_cast<std::size_t>(lightIndex));
  const IzbSettings settings = IzbSettings::from(frame.parameters);
  ProbeOutcome outcome;
  outcome.twin = "izbSampleTest (izb/IzbTwin.h) in double against every caster triangle whose conservative cover "
                 "holds the sample's texel";
  outcome.tolerance = 0.0;
  if (bufferValue(frame, "coverage", pixel) <= 0.5)
  {
    return outcome;
  }
  const glm::dvec3 pWs = bufferVector(frame, "position", pixel);
  const glm::dvec3 nWs = bufferVector(frame, "normal", pixel);
  recorder.beginGroup("receiver");
  recorder.quantity("position", pWs, "world units", "G-buffer (pWs)");
  recorder.quantity("normal", nWs, "", "G-buffer (nWs)");
  if (litWithoutShadowTest(frame, pixel, recorder, outcome))
  {
    return outcome;
  }
  noteAmbiguity(outcome.ambiguity, "light-reach margin", izbReachMargin(light, pWs, nWs), izbReachAmbiguity);
  if (!lightCanReach(light, pWs, nWs))
  {
    recorder.category("light_reach", "faces away / outside the light's reach: unlit, no shadow test",
      "ShadowLab (lightCanReach, LightView.h)");
    return outcome;
  }
  const glm::dvec3 q = izbSamplePoint(pWs, nWs, static_cast<float>(settings.offsetWorld(scene)));
  recorder.quantity("sample_point", q, "world units",
    "ShadowLab: pWs + normal_offset radius nWs (the ray tracer's origin)");
  const IzbGrid grid = IzbGrid::fit(light, scene.bounds(), settings.gridSize);
  const IzbGrid::Place place = grid.place(q);
  recorder.beginGroup("light-space grid");
  recorder.quantity("face", place.face, "", "Johnson et al. 2005: the sample's light-space texel (cube face)");
  recorder.quantity("texel", place.texels, "texels", "Johnson et al. 2005: position in the face");
  if (grid.placementErrorTexels(q) > 0.5 / izbCoverageMarginInverse)
  {
    outcome.ambiguity += (outcome.ambiguity.empty() ? "" : ", ") + std::string("texel placement within rounding");
  }

  recorder.beginGroup("triangles over the texel");
  const std::vector<glm::dvec3> triangles = izbCasterTriangles(scene);
  const std::vector<std::uint32_t> vertexIds = izbCasterVertexIds(scene);
  const IzbLight izbLight = IzbLight::from(light);
  std::uint32_t edgeEvents = 0, xorFirst = 0, xorSecond = 0;
  const std::uint32_t texel = static_cast<std::uint32_t>(place.texel);
  std::vector<std::uint32_t> texels;
  int tests = 0;
  bool shadowed = false, definite = false, uncertain = false;
  for (std::size_t t = 0; t + 2 < triangles.size(); t += 3)
  {
    texels.clear();
    grid.triangleTexels(triangles[t], triangles[t + 1], triangles[t + 2],
      [texel](std::uint32_t candidate) { return candidate == texel; }, texels);
    if (texels.empty())
    {
      continue;
    }
    ++tests;
    const IzbSampleTest test = izbSampleTest(
      triangles[t], triangles[t + 1], triangles[t + 2], q, izbLight, static_cast<float>(settings.offsetWorld(scene)));
    if (test.shadows || test.uncertain)
    {
      recorder.quantity("triangle_" + std::to_string(t / 3) + (test.uncertain ? " (within rounding)" : " (covers)"),
        triangles[t], "world units (first vertex)", "Aila & Laine 2004: covers the sample, between it and the light");
    }
    shadowed = shadowed || test.shadows;
    definite = definite || test.definite;
    uncertain = uncertain || test.uncertain;
    if (test.loneEdge >= 0)
    {
      const IzbEdgeEvent event = izbEdgeEvent(vertexIds[t + static_cast<std::size_t>(test.loneEdge)],
        vertexIds[t + static_cast<std::size_t>((test.loneEdge + 1) % 3)], test.orientation);
      ++edgeEvents;
      xorFirst ^= event.first;
      xorSecond ^= event.second;
    }
  }
  const bool paired = izbEdgePairCovers(edgeEvents, xorFirst, xorSecond);
  if (paired)
  {
    recorder.quantity("shared_edge_pair", 1.0, "",
      "ShadowLab (README.md, Shared edges): two triangles sharing the edge the sample lies within rounding of");
  }
  shadowed = shadowed || paired;
  recorder.quantity("izb_triangle_tests", tests, "triangles", "the triangles whose conservative cover holds the texel");
  recorder.quantity("gpu_izb_triangle_tests", bufferValue(frame, "izb_triangle_tests", pixel), "triangles",
    "the pass's count at the pixel (equal unless the float placement picked a neighbouring texel)");
  recorder.quantity("gpu_izb_list_length", bufferValue(frame, "izb_list_length", pixel), "samples",
    "Johnson et al. 2005: the samples listed in the pixel's texel");
  if (uncertain && !definite && !paired)
  {
    outcome.ambiguity += (outcome.ambiguity.empty() ? "" : ", ") +
      std::string("a triangle edge or plane within float rounding of the sample");
  }
  recorder.beginGroup("result");
  const auto status = static_cast<IzbStatus>(std::lround(bufferValue(frame, "izb_status", pixel)));
  if (status == IzbStatus::CutShort)
  {
    outcome.ambiguity = "the GPU cut this pixel short (izb_status): its sample was not listed";
  }
  outcome.evaluated = true;
  outcome.visibility = shadowed ? 0.0 : 1.0;
  recorder.quantity(
    "visibility", outcome.visibility, "", "Johnson et al. 2005: lit unless a triangle covers the sample");
  return outcome;
}

} // namespace sl
