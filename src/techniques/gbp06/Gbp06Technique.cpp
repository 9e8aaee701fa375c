#include "techniques/gbp06/Gbp06Technique.h"

#include "techniques/ApproximationRules.h"

#include "structures/hsm/HsmStructure.h"
#include "structures/shadowmap/ShadowMapStructure.h"

#include "techniques/ProbeSupport.h"
#include "techniques/ShadowMapParameters.h"
#include "techniques/SoftShadowSupport.h"
#include "techniques/ContourBackprojection.h"
#include "techniques/ContourReceiver.h"
#include "techniques/gbp06/vtkSLGbp06Pass.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace sl
{

Gbp06Settings Gbp06Settings::from(const ParameterValues& values)
{
  Gbp06Settings settings;
  settings.receiver = ContourReceiverSettings::from(values);
  settings.gapFilling = gapFillingOf(values);
  settings.traversal =
    choiceOf<Gbp06Traversal>(values, "traversal", { { "kernel", Gbp06Traversal::Kernel }, { "hsm", Gbp06Traversal::Hsm } });
  return settings;
}

TechniqueDescriptor gbp06Technique()
{
  TechniqueDescriptor descriptor = describeShadowMapTechnique("gbp06",
    "Soft shadow mapping by back-projection of micropatches, with gap filling and a DU07 traversal",
    "Guennebaud et al. 2006; Dmitriev & Uralsky 2007 (HSM traversal); Yang et al. 2009 §2.3, Eq. 1; "
    "Schwarz & Stamminger 2008 (gap-filling rule)", 1024);
  descriptor.parameters.push_back(receiverPlaneBiasParameter());
  descriptor.addParameters({
    { "hsm", 1, 0, 2, "", "min-max structure for kernels, lit/umbra and the hsm traversal: nbuffers (exact ranges, Schwarz & Stamminger 2007), mipmap (the HSM of Guennebaud et al. 2006) or ysm (the HSM plus an MSSM of its ~256^2 level for the ranges, Schwarz & Stamminger 2008 §6)", { "mipmap", "nbuffers", "ysm" }, true },
    hsmLevelsParameter("hsm_levels", "N-buffers"),
    { "kernel_refinements", 2, 0, 4, "iterations", "times the kernel is shrunk to the minimum occluder depth inside it (Eq. 1 with z_occ_min)", {}, true },
    { "gap_filling", 1, 0, 2, "", "extend each occluding micropatch's back-projection to the shared edges of its occluding neighbours, closing the gaps between micropatches of different depths: left_bottom, to its left and bottom neighbours in texture space, GBP06's rule as Schwarz & Stamminger 2008 describe it (SS08 §3); right_top, to its right and top ones (the mirror convention); off", { "off", "left_bottom", "right_top" }, true },
    { "traversal", 0, 0, 1, "", "micropatches from every texel of the kernel, or from a depth-first walk of the min-max quadtree pruning nodes that cannot occlude (Dmitriev & Uralsky 2007); same visibility", { "kernel", "hsm" }, true },
  });
  descriptor.lightStructures = { &shadowMapStructure(), &hierarchicalShadowMapStructure() };
  // traversal=kernel queries the hierarchy for Eq. 1's kernel ranges only; the DU07 walk starts from the node that
  // holds the whole region, up to the top of the quadtree.
  descriptor.lightSpaceRequest = [](const ParameterValues& values) {
    LightSpaceRequest request;
    request.minMaxQueriesWithinNearPlaneKernel = Gbp06Settings::from(values).traversal == Gbp06Traversal::Kernel;
    return request;
  };
  descriptor.buffers = {
    { "kernel_texels", "texels", "width of the kernel searched for occluding micropatches (Eq. 1, Yang 2009 Fig. 5 left)" },
    { "occluding_texels", "texels", "occluding micropatches back-projected and accumulated" },
    { "visited_nodes", "nodes", "texels examined (traversal=kernel) or min-max quadtree nodes examined, leaves included (traversal=hsm)" },
    backprojectionClassificationBuffer("how the pixel was decided; " +
        std::to_string(static_cast<int>(BackprojectionClass::OverLoopBudget)) + " = a penumbra pixel whose traversal "
        "the GL's cap on loop iterations per invocation (llvmpipe: 65535) cut short, detected: its texel loop never "
        "reached its last texel, or the hsm walk never took its exit",
      SubLightCombine::Mean),
  };
  descriptor.shaderConstants = contourKernelShaderConstants();
  descriptor.supportedLights = { LightType::Area };
  descriptor.supportedAreaShapes = { LightShape::Square };
  descriptor.coversLightArea = true;
  // As gbp07: the registry-wide sweeps use 128^2 maps to bound the brute-force kernels on llvmpipe.
  descriptor.sweepTestSettings = { "shadow_map_size=128" };
  descriptor.createPass = newTechniquePass<vtkSLGbp06Pass>;
  descriptor.probe = [](const ProbeContext& context, glm::ivec2 pixel, ProbeRecorder& recorder) {
    const ShadowMapInputs inputs = shadowMapInputsOf(*context.frame, *context.scene, context.lightIndex);
    const HierarchicalShadowMap hsm = buildHierarchicalShadowMap(inputs.shadowMapLinear, context.frame->parameters,
      inputs.lightView, *inputs.light, Gbp06Settings::from(context.frame->parameters).traversal == Gbp06Traversal::Kernel);
    const Gbp06Sample sample = gbp06Reference(inputs, hsm, Gbp06Settings::from(context.frame->parameters), pixel.x, pixel.y, &recorder);
    // Gbp06Test.MatchesTheCpuImplementation: 1e-3 (float back-projection and clipping, ~1e-7 of the light per
    // micropatch), on pixels without a decision near its boundary; visited_nodes where no pruning test is.
    ProbeOutcome outcome = probeOutcome(sample.sample, 1e-3, "gbp06Reference (gbp06/Gbp06Technique.h), double precision");
    noteBackprojectionAmbiguity(outcome.ambiguity, sample, *context.frame, pixel);
    noteAmbiguity(outcome.ambiguity, "hsm pruning test from its boundary (relative; visited_nodes may differ)",
      sample.pruningMargin, 1e-5);
    return outcome;
  };
  // Back-projection of one shadow-map layer (GBP06, GBP07, Yang et al. 2009): exact for blockers on one plane parallel
  // to the light; where the casters that hide part of the light lie at different depths their back-projections
  // overlap or leave gaps (occluder fusion) and casters hidden from the light's centre are missed.
  descriptor.accuracy = oneLayerSoftShadowContract(BlockerDepthModel::OccluderFusion, 0.05);
  return descriptor;
}

namespace
{

// The mip-map quadtree's node (level, index): texels [index 2^level, (index + 1) 2^level), clipped to the map
// (HierarchicalShadowMap::node, any layout but the dual grid).
glm::dvec2 quadtreeNode(const HierarchicalShadowMap& hsm, int level, glm::ivec2 index)
{
  return hsm.node(level, index);
}

struct MicropatchAccumulator
{
  const ShadowMapInputs& inputs;
  ContourReceiver& receiver;
  GapFilling gapFilling = GapFilling::LeftBottom;
  ProbeRecorder* recorder = nullptr;
  double occludedArea = 0.0;
  int occludingTexels = 0;
  // For a probe: micropatches that gap filling extended, and the light area the extensions added.
  int gapFilled = 0;
  double gapFillingArea = 0.0;

  // The texel as a probe's ProbeTexel (stored depth, the tap's comparison depth).
  void recordTexel(glm::ivec2 texel, const char* role) const
  {
    const int size = receiver.geometry.mapSize;
    if (texel.x < 0 || texel.y < 0 || texel.x >= size || texel.y >= size)
    {
      return; // outside the map: nothing read, never occludes
    }
    const double stored = inputs.shadowMapLinear.at(texel.x, texel.y);
    const double compared = receiver.geometry.tapComparisonDepth(glm::dvec2(texel) + 0.5, receiver.bias);
    recorder->texel({ texel, role, stored, compared, stored < compared, 1.0 });
  }

  // A neighbour gap filling reads, recorded for a probe.
  bool neighbourOccludes(glm::ivec2 neighbour, double& depth)
  {
    const bool occluding = receiver.occludes(inputs, neighbour, depth);
    if (recorder)
    {
      recordTexel(neighbour, "gap-filling neighbour");
    }
    return occluding;
  }

  // The back-projection of the occluding micropatch `texel` at `depth` (GLSL: micropatchArea), gap-filled,
  // clipped to the light; its area is accumulated.
  void add(glm::ivec2 texel, double depth)
  {
    const SoftShadowGeometry& geometry = receiver.geometry;
    const double d = geometry.d;
    const glm::dvec2 tangentLo = geometry.windowMin + glm::dvec2(texel) * geometry.texelTangent;
    const glm::dvec2 tangentHi = geometry.windowMin + glm::dvec2(texel + 1) * geometry.texelTangent;
    // backProject is increasing in the tangent for a fixed depth in front of the receiver: corners map to corners.
    glm::dvec2 lo = backProject(tangentLo, depth, receiver.receiverXy, d);
    glm::dvec2 hi = backProject(tangentHi, depth, receiver.receiverXy, d);
    if (recorder)
    {
      recordTexel(texel, "micropatch");
    }
    const glm::dvec2 unfilledLo = lo;
    const glm::dvec2 unfilledHi = hi;
    // Gap filling: out to an occluding neighbour's shared edge at the neighbour's depth, when further out.
    double neighbourDepth = 0.0;
    if (gapFilling == GapFilling::LeftBottom)
    {
      // SS08 §3 (GBP06): "extending a micropatch to its left and bottom neighbors in texture space". The
      // left neighbour's right edge and the bottom neighbour's top edge pass through the corner tangentLo.
      if (neighbourOccludes(texel - glm::ivec2(1, 0), neighbourDepth))
      {
        lo.x = std::min(lo.x, backProject(tangentLo, neighbourDepth, receiver.receiverXy, d).x);
      }
      if (neighbourOccludes(texel - glm::ivec2(0, 1), neighbourDepth))
      {
        lo.y = std::min(lo.y, backProject(tangentLo, neighbourDepth, receiver.receiverXy, d).y);
      }
    }
    else if (gapFilling == GapFilling::RightTop)
    {
      // The mirror convention: the right neighbour's left edge and the top neighbour's bottom edge (tangentHi).
      if (neighbourOccludes(texel + glm::ivec2(1, 0), neighbourDepth))
      {
        hi.x = std::max(hi.x, backProject(tangentHi, neighbourDepth, receiver.receiverXy, d).x);
      }
      if (neighbourOccludes(texel + glm::ivec2(0, 1), neighbourDepth))
      {
        hi.y = std::max(hi.y, backProject(tangentHi, neighbourDepth, receiver.receiverXy, d).y);
      }
    }
    const double h = receiver.lightHalfSize;
    const glm::dvec2 extent = glm::max(glm::min(hi, glm::dvec2(h)) - glm::max(lo, glm::dvec2(-h)), glm::dvec2(0.0));
    occludedArea += extent.x * extent.y;
    ++occludingTexels;
    if (recorder)
    {
      const bool filled = lo != unfilledLo || hi != unfilledHi;
      const glm::dvec2 unfilled =
        glm::max(glm::min(unfilledHi, glm::dvec2(h)) - glm::max(unfilledLo, glm::dvec2(-h)), glm::dvec2(0.0));
      gapFilled += filled ? 1 : 0;
      gapFillingArea += extent.x * extent.y - unfilled.x * unfilled.y;
      if (extent.x > 0.0 && extent.y > 0.0)
      {
        // The part over the light (counter-clockwise): what the micropatch adds to the occluded area.
        const glm::dvec2 a = glm::max(lo, glm::dvec2(-h));
        const glm::dvec2 b = glm::min(hi, glm::dvec2(h));
        recorder->lightPolygon({ filled ? "micropatch (gap-filled)" : "micropatch",
          { { a.x, a.y }, { b.x, a.y }, { b.x, b.y }, { a.x, b.y } }, extent.x * extent.y });
      }
    }
  }

  // Returns whether the texel occludes (a micropatch, accumulated).
  bool examine(glm::ivec2 texel)
  {
    double depth = 0.0;
    if (receiver.occludes(inputs, texel, depth))
    {
      add(texel, depth);
      return true;
    }
    if (recorder)
    {
      recordTexel(texel, "examined");
    }
    return false;
  }
};

} // namespace

Gbp06Sample gbp06Reference(const ShadowMapInputs& inputs, const HierarchicalShadowMap& hsm,
  const Gbp06Settings& settings, int x, int y, ProbeRecorder* recorder)
{
  const bool kernelTraversal = settings.traversal == Gbp06Traversal::Kernel;
  ContourReceiver receiver = prepareContourReceiver(inputs, settings.receiver, hsm, x, y, recorder);
  Gbp06Sample result;
  const auto finish = [&](BackprojectionClass classification) {
    recordReceiver(receiver, classification, result);
    if (recorder && receiver.lookup.sample.evaluated)
    {
      recorder->beginGroup("visibility");
      recorder->quantity("occluding_texels", result.occludingTexels, "texels", "GBP06: micropatches accumulated");
      recorder->quantity("visited_nodes", result.visitedNodes, "nodes", kernelTraversal
        ? "GBP06: texels examined (every texel of the kernel plus one ring)"
        : "DU07 (Dmitriev & Uralsky 2007): quadtree nodes examined, leaves included");
      recordClassification(*recorder, classification);
      recorder->quantity("visibility", receiver.lookup.sample.visibility, "",
        classification == BackprojectionClass::Lit || classification == BackprojectionClass::Umbra
          ? decisionSourceOf(classification)
          : "GBP06: V = clamp(1 - sum of the micropatches' clipped back-projected areas / A, 0, 1)");
    }
    return result;
  };
  if (receiver.classification != BackprojectionClass::Penumbra)
  {
    return finish(receiver.classification);
  }
  MicropatchAccumulator accumulator{ inputs, receiver, settings.gapFilling, recorder };
  // The kernel's texels plus one ring, clamped to the map (see the header).
  const glm::ivec2 lo = receiver.samples.lo;
  const glm::ivec2 hi = receiver.samples.hi;
  const double d = receiver.geometry.d;
  if (recorder)
  {
    recorder->beginGroup(kernelTraversal ? "micropatches (every texel of the kernel + ring)"
                                                                 : "micropatches (DU07 quadtree walk)");
    recorder->category("gap_filling", gapFillingName(settings.gapFilling),
      "Schwarz & Stamminger 2008 (SS08 §3): GBP06 extends a micropatch to its left and bottom neighbours "
      "(right_top: the mirror convention)");
  }
  if (kernelTraversal)
  {
    for (int j = lo.y; j <= hi.y; ++j)
    {
      for (int i = lo.x; i <= hi.x; ++i)
      {
        ++result.visitedNodes;
        accumulator.examine({ i, j });
      }
    }
    result.loopIterations = result.visitedNodes;
  }
  else
  {
    // Whether node (level, index) may hold an occluding texel of [lo, hi]: its minimum depth is in front of the
    // largest comparison depth over its texels inside the rectangle.
    const std::string structure = probeStructureName(hsm.layout == HsmLayout::NBuffers ? "n-buffers" : "mip-map");
    const auto mayOcclude = [&](int level, glm::ivec2 index) {
      ++result.visitedNodes;
      const glm::ivec2 first = glm::max(index << level, lo);
      const glm::ivec2 last = glm::min(((index + 1) << level) - 1, hi);
      const glm::dvec2 comparison = receiver.geometry.comparisonDepthRange(first, last, receiver.bias);
      const glm::dvec2 node = quadtreeNode(hsm, level, index);
      const double nodeMin = node.x;
      result.pruningMargin = std::min(result.pruningMargin, std::abs(nodeMin - comparison.y) / d);
      const bool may = nodeMin < comparison.y;
      if (recorder)
      {
        const glm::ivec2 lastTexel(receiver.geometry.mapSize - 1);
        recorder->node({ structure, level, glm::min(index << level, lastTexel),
          glm::min(((index + 1) << level) - 1, lastTexel), node.x, node.y,
          !may ? "pruned: min depth >= the largest comparison depth over its texels (DU07)"
               : level == 0 ? "leaf: texel examined" : "descend" });
      }
      return may;
    };
    // DU07, depth first from the lowest node covering the rectangle, entered as the one child of its parent
    // that meets it; a node's index is its path (bit k of x and y: the child taken below level k + 1).
    int rootLevel = 0;
    while ((lo.x >> rootLevel) != (hi.x >> rootLevel) || (lo.y >> rootLevel) != (hi.y >> rootLevel))
    {
      ++rootLevel;
    }
    const int topLevel = rootLevel + 1;
    if (recorder)
    {
      recorder->quantity("root_level", rootLevel, "level",
        "DU07: the lowest quadtree node covering the searched texels, entered as the child of its parent");
    }
    int level = topLevel; // the level of `node`, whose children are examined
    glm::ivec2 node = lo >> topLevel;
    int child = 0;
    while (true)
    {
      ++result.loopIterations;
      if (child == 4)
      {
        if (level == topLevel)
        {
          break;
        }
        child = (node.x & 1) + 2 * (node.y & 1) + 1;
        node >>= 1;
        ++level;
        continue;
      }
      const glm::ivec2 index = 2 * node + glm::ivec2(child & 1, child >> 1);
      const glm::ivec2 first = index << (level - 1);
      const glm::ivec2 last = ((index + 1) << (level - 1)) - 1;
      if (first.x > hi.x || first.y > hi.y || last.x < lo.x || last.y < lo.y || !mayOcclude(level - 1, index))
      {
        ++child;
      }
      else if (level == 1)
      {
        accumulator.examine(index);
        ++child;
      }
      else
      {
        node = index;
        --level;
        child = 0;
      }
    }
  }
  result.occludingTexels = accumulator.occludingTexels;
  const double lightArea = 4.0 * receiver.lightHalfSize * receiver.lightHalfSize;
  receiver.lookup.sample.visibility = std::clamp(1.0 - accumulator.occludedArea / lightArea, 0.0, 1.0);
  if (recorder)
  {
    recorder->quantity("loop_iterations", result.loopIterations, "iterations",
      "ShadowLab: the twin's estimate of the GL's loop cap (gbp06LoopBudget; the shader detects the cut)");
    recorder->beginGroup("gap filling");
    recorder->quantity("gap_filled_micropatches", accumulator.gapFilled, "count",
      "Schwarz & Stamminger 2008 (SS08 §3): micropatches extended to an occluding neighbour's shared edge");
    recorder->quantity("gap_filling_area", accumulator.gapFillingArea, "world units^2",
      "ShadowLab: light area the extensions added (clipped), included in occluded_area");
    recorder->beginGroup("back-projection onto the light");
    recorder->quantity("light_area", lightArea, "world units^2", "GBP06: A, the square light");
    recorder->quantity("occluded_area", accumulator.occludedArea, "world units^2",
      "GBP06: the sum of the micropatches' clipped back-projected areas (overlaps counted twice; the light polygons)");
  }
  // The twin can only estimate the cut by the count (gbp06LoopBudget; the shader detects it).
  return finish(result.loopIterations > gbp06LoopBudget ? BackprojectionClass::OverLoopBudget : BackprojectionClass::Penumbra);
}

} // namespace sl
