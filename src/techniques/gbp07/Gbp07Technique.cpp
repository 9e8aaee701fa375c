#include "techniques/gbp07/Gbp07Technique.h"

#include "techniques/ApproximationRules.h"

#include "structures/hsm/HsmStructure.h"
#include "structures/shadowmap/ShadowMapStructure.h"

#include "techniques/ProbeSupport.h"
#include "techniques/ShadowMapParameters.h"
#include "techniques/SoftShadowSupport.h"
#include "techniques/ContourBackprojection.h"
#include "techniques/ContourReceiver.h"
#include "techniques/gbp07/vtkSLGbp07Pass.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace sl
{

TechniqueDescriptor gbp07Technique()
{
  TechniqueDescriptor descriptor = describeShadowMapTechnique("gbp07",
    "Contour-based soft shadow mapping (back-projection, radial integration)",
    "Guennebaud et al. 2007; Yang et al. 2009 §4, Eq. 1; Schwarz & Stamminger 2007 (MSSM kernels)", 1024);
  descriptor.parameters.push_back(receiverPlaneBiasParameter());
  descriptor.addParameters({
    { "hsm", 1, 0, 2, "", "min-max structure for kernels and lit/umbra: nbuffers (the MSSM's exact ranges, Schwarz & Stamminger 2007), mipmap (a conservative HSM, Guennebaud et al. 2006) or ysm (the HSM plus an MSSM of its ~256^2 level, Schwarz & Stamminger 2008 §6)", { "mipmap", "nbuffers", "ysm" }, true },
    hsmLevelsParameter("hsm_levels", "N-buffers"),
    { "kernel_refinements", 2, 0, 4, "iterations", "times the kernel is shrunk to the minimum occluder depth inside it (Eq. 1 with z_occ_min)", {}, true },
    subLightsParameter(),
  });
  descriptor.lightStructures = { &shadowMapStructure(), &hierarchicalShadowMapStructure() };
  // Its only queries of the hierarchy are the kernel ranges of Eq. 1 (ContourKernel.glsl).
  descriptor.lightSpaceRequest = [](const ParameterValues&) {
    LightSpaceRequest request;
    request.minMaxQueriesWithinNearPlaneKernel = true;
    return request;
  };
  descriptor.buffers = {
    { "kernel_texels", "texels", "width of the kernel searched for contour edges (Eq. 1, Yang 2009 Fig. 5 left)" },
    { "contour_edges", "edges", "contour edges extracted and back-projected (summed over sub-lights)", BufferKind::Continuous, {}, SubLightCombine::Sum },
    { "visited_cells", "cells", "dual cells (2 x 2 sample blocks) examined (summed over sub-lights)", BufferKind::Continuous, {}, SubLightCombine::Sum },
    backprojectionClassificationBuffer("how the pixel was decided (first sub-light); " +
        std::to_string(static_cast<int>(BackprojectionClass::OverLoopBudget)) + " = a penumbra kernel whose cell loop "
        "the GL's cap on loop iterations per invocation (llvmpipe: 65535) cut short, detected: its last cell was never reached",
      SubLightCombine::First),
  };
  descriptor.shaderConstants = contourKernelShaderConstants();
  descriptor.supportedLights = { LightType::Area };
  descriptor.supportedAreaShapes = { LightShape::Square };
  descriptor.coversLightArea = true;
  // Brute-force kernels grow with the map resolution squared: the test sweeps use 128^2 (near-light: 130 s a
  // case at 256^2 on llvmpipe).
  descriptor.sweepTestSettings = { "shadow_map_size=128" };
  descriptor.createPass = newTechniquePass<vtkSLGbp07Pass>;
  descriptor.probe = [](const ProbeContext& context, glm::ivec2 pixel, ProbeRecorder& recorder) {
    requireSingleSubLight(*context.frame);
    const ShadowMapInputs inputs = shadowMapInputsOf(*context.frame, *context.scene, context.lightIndex);
    const HierarchicalShadowMap hsm = buildHierarchicalShadowMap(inputs.shadowMapLinear, context.frame->parameters,
      inputs.lightView, *inputs.light, true);
    const Gbp07Sample sample = gbp07Reference(inputs, hsm, Gbp07Settings::from(context.frame->parameters), pixel.x, pixel.y, &recorder);
    // Gbp07Test.MatchesTheCpuImplementation: 1e-3 (float back-projection and clipping over up to a few hundred
    // edges), on pixels without a decision near its boundary.
    ProbeOutcome outcome = probeOutcome(sample.sample, 1e-3, "gbp07Reference (gbp07/Gbp07Technique.h), double precision");
    noteBackprojectionAmbiguity(outcome.ambiguity, sample, *context.frame, pixel);
    return outcome;
  };
  // Back-projection of one shadow-map layer (GBP06, GBP07, Yang et al. 2009): exact for blockers on one plane parallel
  // to the light; where the casters that hide part of the light lie at different depths their back-projections
  // overlap or leave gaps (occluder fusion) and casters hidden from the light's centre are missed.
  descriptor.accuracy = oneLayerSoftShadowContract(BlockerDepthModel::OccluderFusion, 0.05);
  return descriptor;
}

Gbp07Settings Gbp07Settings::from(const ParameterValues& values)
{
  Gbp07Settings settings;
  settings.receiver = ContourReceiverSettings::from(values);
  return settings;
}

Gbp07Sample gbp07Reference(const ShadowMapInputs& inputs, const HierarchicalShadowMap& hsm,
  const Gbp07Settings& settings, int x, int y, ProbeRecorder* recorder)
{
  ContourReceiver receiver = prepareContourReceiver(inputs, settings.receiver, hsm, x, y, recorder);
  Gbp07Sample result;
  const auto finish = [&](BackprojectionClass classification) {
    recordReceiver(receiver, classification, result);
    if (recorder && receiver.lookup.sample.evaluated)
    {
      recorder->beginGroup("visibility");
      recorder->quantity("contour_edges", result.contourEdges, "edges", "GBP07: marching squares on the dual grid");
      recorder->quantity("visited_cells", result.visitedCells, "cells", "GBP07: every dual cell with a corner in the kernel");
      recordClassification(*recorder, classification);
      recorder->quantity("visibility", receiver.lookup.sample.visibility, "",
        classification == BackprojectionClass::Lit || classification == BackprojectionClass::Umbra
          ? decisionSourceOf(classification)
          : "GBP07: V = clamp(1 - (f(O) A + sum of s_e |L beyond e|) / A, 0, 1)");
    }
    return result;
  };
  if (receiver.classification != BackprojectionClass::Penumbra)
  {
    return finish(receiver.classification);
  }
  const std::array<glm::ivec2, 4> offsets = { glm::ivec2(0, 0), glm::ivec2(1, 0), glm::ivec2(1, 1), glm::ivec2(0, 1) };
  // Radial integration around the light centre: f(O), then every dual cell with a corner in the kernel.
  const double lightArea = 4.0 * receiver.lightHalfSize * receiver.lightHalfSize;
  if (recorder)
  {
    recorder->beginGroup("light centre (radial integration)");
  }
  double occludedArea = receiver.centreOccluded(inputs, recorder) ? lightArea : 0.0;
  const glm::ivec2 first = receiver.firstCell();
  const glm::ivec2 last = receiver.lastCell();
  if (recorder)
  {
    recorder->beginGroup("contour extraction and back-projection");
    recorder->quantity("first_cell", glm::dvec2(first), "cells", "GBP07: dual cell (i, j) joins samples (i, j) .. (i + 1, j + 1)");
    recorder->quantity("last_cell", glm::dvec2(last), "cells", "GBP07: the kernel's dual cells");
    receiver.recordSamples(inputs, receiver.samples, *recorder, "contour sample");
  }
  for (int j = first.y; j <= last.y; ++j)
  {
    for (int i = first.x; i <= last.x; ++i)
    {
      ++result.visitedCells;
      std::array<bool, 4> occluding{};
      std::array<double, 4> depths{};
      for (std::size_t k = 0; k < 4; ++k)
      {
        occluding[k] = receiver.occludes(inputs, glm::ivec2(i, j) + offsets[k], depths[k]);
      }
      std::array<ContourEdge, 2> edges;
      const int count = marchingSquaresEdges(occluding, depths, glm::dvec2(i, j) + 0.5, edges);
      for (int e = 0; e < count; ++e)
      {
        const ContourEdge& edge = edges[static_cast<std::size_t>(e)];
        occludedArea += receiver.edgeArea(edge.a, edge.depthA, edge.b, edge.depthB, recorder);
        ++result.contourEdges;
      }
    }
  }
  const glm::ivec2 cells = last - first + 1;
  const bool overBudget = cells.x * cells.y > gbp07LoopBudgetCells;
  receiver.lookup.sample.visibility = std::clamp(1.0 - occludedArea / lightArea, 0.0, 1.0);
  if (recorder)
  {
    recorder->beginGroup("radial integration");
    recorder->quantity("light_area", lightArea, "world units^2", "GBP07: A, the square light");
    recorder->quantity("occluded_area", occludedArea, "world units^2",
      "GBP07 radial integration: f(O) A + sum over edges of s_e |L beyond e| (the light polygon and edges' signed areas)");
    recorder->quantity("loop_cells", static_cast<double>(cells.x) * cells.y, "cells",
      "ShadowLab: the twin's estimate of the cut (gbp07LoopBudgetCells; the shader detects it)");
  }
  return finish(overBudget ? BackprojectionClass::OverLoopBudget : BackprojectionClass::Penumbra);
}

} // namespace sl
