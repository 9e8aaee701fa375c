#include "techniques/gbp07/Gbp07Technique.h"

#include "techniques/ShadowMapParameters.h"
#include "techniques/SoftShadowSupport.h"
#include "techniques/backprojection/ContourBackprojection.h"
#include "techniques/gbp07/vtkSLGbp07Pass.h"

#include <algorithm>
#include <cmath>

namespace sl
{

TechniqueDescriptor gbp07Technique()
{
  TechniqueDescriptor descriptor;
  descriptor.name = "gbp07";
  descriptor.title = "Contour-based soft shadow mapping (back-projection, radial integration)";
  descriptor.paper = "Guennebaud et al. 2007; Yang et al. 2009 §4, Eq. 1; Schwarz & Stamminger 2007 (MSSM kernels)";
  descriptor.parameters = shadowMapParameters();
  for (ParameterSpec& spec : descriptor.parameters)
  {
    if (spec.name == "shadow_map_size")
    {
      spec.defaultValue = 1024; // Yang et al. 2009's comparisons; brute-force kernels grow with the resolution
    }
  }
  descriptor.parameters.push_back(receiverPlaneBiasParameter());
  descriptor.parameters.insert(descriptor.parameters.end(), {
    { "hsm", 1, 0, 1, "", "min-max structure for kernels and lit/umbra: nbuffers (the MSSM's exact ranges, Schwarz & Stamminger 2007) or mipmap (a conservative HSM, Guennebaud et al. 2006)", { "mipmap", "nbuffers" }, true },
    { "kernel_refinements", 2, 0, 4, "iterations", "times the kernel is shrunk to the minimum occluder depth inside it (Eq. 1 with z_occ_min)", {}, true },
  });
  descriptor.lightStructures = { LightStructure::ShadowMap, LightStructure::HierarchicalShadowMap };
  descriptor.buffers = {
    { "kernel_texels", "texels", "width of the kernel searched for contour edges (Eq. 1, Yang 2009 Fig. 5 left)" },
    { "contour_edges", "edges", "contour edges extracted and back-projected" },
    { "visited_cells", "cells", "dual cells (2 x 2 sample blocks) examined" },
    { "classification", "", "how the pixel was decided; 4 = a penumbra kernel of more than 60000 cells, which GLs capping loop iterations per invocation (llvmpipe: 65535) cut short", BufferKind::Categorical, { "not tested", "lit", "umbra", "penumbra", "penumbra over the loop budget" } },
  };
  descriptor.supportedLights = { LightType::Area };
  descriptor.supportedAreaShapes = { LightShape::Square };
  descriptor.coversLightArea = true;
  // Brute-force kernels grow with the map resolution squared: the test sweeps use 128^2 (near-light: 130 s a
  // case at 256^2 on llvmpipe).
  descriptor.sweepTestSettings = { "shadow_map_size=128" };
  descriptor.createPass = [] { return vtkSmartPointer<vtkSLTechniquePass>(vtkSmartPointer<vtkSLGbp07Pass>::New()); };
  return descriptor;
}

Gbp07Sample gbp07Reference(const ShadowMapInputs& inputs, const HierarchicalShadowMap& hsm,
  const ParameterValues& values, int x, int y)
{
  Gbp07Sample result;
  const ShadowLookup lookup = prepareShadowLookup(inputs, biasSettings(values), x, y);
  result.sample = lookup.sample;
  if (!lookup.sample.evaluated)
  {
    return result;
  }
  const SoftShadowGeometry geometry =
    softShadowGeometry(inputs, lookup, values.choice("receiver_plane_bias") == "on", x, y);
  const double d = geometry.d;
  const double bias = lookup.sample.bias;
  const int size = geometry.mapSize;
  const glm::dvec2 uv = lookup.sm.uvTexels;
  const auto finish = [&](double visibility, BackprojectionClass classification) {
    result.sample.visibility = visibility;
    result.classification = classification;
    return result;
  };
  // The samples whose dual cells can hold edges: the kernel's texels plus one ring, inside the map.
  const auto ringed = [&](const TexelRectangle& kernel) {
    TexelRectangle rectangle;
    rectangle.lo = glm::max(kernel.lo - 1, glm::ivec2(0));
    rectangle.hi = glm::min(kernel.hi + 1, glm::ivec2(size - 1));
    return rectangle;
  };
  // Eq. 1 with the map's near plane, then with the minimum depth found inside the kernel.
  glm::dvec2 half = geometry.kernelHalfTexels(geometry.nearDepth);
  TexelRectangle kernel = kernelRectangle(uv, half, size, &result.kernelEdgeMargin);
  glm::dvec2 depthRange = hsm.range(ringed(kernel).lo, ringed(kernel).hi);
  for (int refinement = 0; refinement < values.getInt("kernel_refinements"); ++refinement)
  {
    const double occluderMin = std::clamp(depthRange.x, geometry.nearDepth, d);
    half = geometry.kernelHalfTexels(occluderMin);
    kernel = kernelRectangle(uv, half, size, &result.kernelEdgeMargin);
    depthRange = hsm.range(ringed(kernel).lo, ringed(kernel).hi);
  }
  result.kernelTexels = 2.0 * std::max(half.x, half.y);
  const TexelRectangle samples = ringed(kernel);
  const glm::dvec2 comparison = geometry.comparisonDepthRange(samples.lo, samples.hi, bias);
  result.decisionMargin = std::min(std::abs(depthRange.x - comparison.y), std::abs(depthRange.y - comparison.x)) / d;
  if (depthRange.x >= comparison.y)
  {
    return finish(1.0, BackprojectionClass::Lit);
  }
  // Umbra only when the ring lies inside the map: beyond it the contour method sees non-occluders.
  const bool ringInsideMap = samples.lo == kernel.lo - 1 && samples.hi == kernel.hi + 1;
  if (ringInsideMap && depthRange.y < comparison.x)
  {
    return finish(0.0, BackprojectionClass::Umbra);
  }

  // Sample status (occluder?) and depth; samples outside the map never occlude, which closes contours there.
  const auto sampleAt = [&](int i, int j, bool& occluding) {
    occluding = false;
    if (i < 0 || j < 0 || i >= size || j >= size)
    {
      return 0.0;
    }
    const double z = inputs.shadowMapLinear.at(i, j);
    const double compared = geometry.tapComparisonDepth(glm::dvec2(i + 0.5, j + 0.5), bias);
    result.sample.noteDepthComparison(compared, z);
    occluding = z < compared;
    return z;
  };
  const auto cellCorners = [&](int i, int j, std::array<bool, 4>& occluding, std::array<double, 4>& depths) {
    const std::array<glm::ivec2, 4> offsets = { glm::ivec2(0, 0), glm::ivec2(1, 0), glm::ivec2(1, 1), glm::ivec2(0, 1) };
    for (std::size_t k = 0; k < 4; ++k)
    {
      bool occludes = false;
      depths[k] = sampleAt(i + offsets[k].x, j + offsets[k].y, occludes);
      occluding[k] = occludes;
    }
  };

  // Radial integration around the light centre: f(O) from the cell holding the receiver's own map position.
  const double halfSize = 0.5 * geometry.lightSize;
  const glm::dvec2 receiverTangent = geometry.windowMin + uv * geometry.texelTangent;
  const glm::dvec2 receiverXy = receiverTangent * d;
  const glm::ivec2 centreCell(static_cast<int>(std::floor(uv.x - 0.5)), static_cast<int>(std::floor(uv.y - 0.5)));
  std::array<bool, 4> occluding;
  std::array<double, 4> depths;
  cellCorners(centreCell.x, centreCell.y, occluding, depths);
  double occludedArea = insideReconstructedOccluder(occluding, glm::dvec2(centreCell) + 0.5, uv) ? 4.0 * halfSize * halfSize : 0.0;
  // Every dual cell with a corner in the kernel (its corners span the ring).
  for (int j = kernel.lo.y - 1; j <= kernel.hi.y; ++j)
  {
    for (int i = kernel.lo.x - 1; i <= kernel.hi.x; ++i)
    {
      ++result.visitedCells;
      cellCorners(i, j, occluding, depths);
      std::array<ContourEdge, 2> edges;
      const int count = marchingSquaresEdges(occluding, depths, glm::dvec2(i, j) + 0.5, edges);
      for (int e = 0; e < count; ++e)
      {
        const ContourEdge& edge = edges[static_cast<std::size_t>(e)];
        const glm::dvec2 a = backProject(geometry.windowMin + edge.a * geometry.texelTangent, edge.depthA, receiverXy, d);
        const glm::dvec2 b = backProject(geometry.windowMin + edge.b * geometry.texelTangent, edge.depthB, receiverXy, d);
        occludedArea += radialEdgeArea(a, b, halfSize);
        ++result.contourEdges;
      }
    }
  }
  const bool overBudget = (kernel.hi.x - kernel.lo.x + 2) * (kernel.hi.y - kernel.lo.y + 2) > gbp07LoopBudgetCells;
  return finish(std::clamp(1.0 - occludedArea / (4.0 * halfSize * halfSize), 0.0, 1.0),
    overBudget ? BackprojectionClass::OverLoopBudget : BackprojectionClass::Penumbra);
}

} // namespace sl
