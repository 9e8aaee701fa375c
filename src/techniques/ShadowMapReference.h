// What a CPU reference of a shadow-map technique needs: the read-back inputs the GPU used (G-buffer,
// shadow map, light view) and a way to report, per pixel, how close a decision was to flipping, so tests
// can separate real disagreements from float-vs-double rounding at a decision boundary.
#pragma once

#include "core/Image.h"
#include "frame/ProbeRecord.h"
#include "lightspace/CameraView.h"
#include "lightspace/LightView.h"
#include "lightspace/ShadowMapMath.h"
#include "scene/Scene.h"
#include "structures/shadowmap/ShadowMapStructure.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

namespace sl
{

struct ShadowMapInputs
{
  const Light* light = nullptr;
  CameraView camera;
  LightView lightView;
  ImageF position;       // 3 components, from buffers (pWs)
  ImageF normal;         // 3 components (nWs)
  ImageF coverage;       // 1 component
  ImageF receives;       // 1 component: 1 if the surface receives shadows (G-buffer normal.w)
  ImageF shadowMapLinear; // linear depth per texel
  ImageF shadowMapWindow; // hardware depth per texel (window coordinates)
  // depth_layer = polygon_id (survey §5): the map's nearest triangle id per texel and each pixel's own (float, exact
  // below 2^24); empty otherwise.
  ImageF shadowMapPolygonId;
  ImageF receiverPolygonId;
};

// The result of a reference evaluation at one pixel.
struct ReferenceSample
{
  double visibility = 0.0;
  // Smallest distance of any comparison in this pixel to its decision boundary: depth distance relative
  // to the depth, and tap distance to a texel edge in texels. Tiny values mean float rounding on the GPU
  // may legitimately flip the decision.
  double depthMargin = 1e300;
  double texelEdgeMargin = 1e300;
  double reachMargin = 1e300; // |cos| of the light-reach tests (facing, area-light plane)
  double bias = 0.0;
  double texelRatio = 0.0;
  bool evaluated = false; // false when the pixel never reaches a shadow test (uncovered, facing away, ...)

  // Records a depth comparison of `compared` against the stored depth `stored`.
  void noteDepthComparison(double compared, double stored)
  {
    depthMargin = std::min(depthMargin, std::abs(compared - stored) / std::max(1e-30, std::abs(stored)));
  }
};

// Shared per-pixel preamble of hard and pcf: returns nullopt-equivalent `evaluated = false` with the
// final visibility for pixels decided without the shadow map; otherwise fills bias and the shadow-map
// sample and returns evaluated = true.
struct ShadowLookup
{
  ReferenceSample sample;
  ShadowMapSample sm;
  double comparisonDepth = 0.0;
};
// `recorder` (optional, `shadowlab probe`): the receiver's point, normal, shadow-map position, depth, bias and
// texel ratio, group "receiver".
ShadowLookup prepareShadowLookup(const ShadowMapInputs& inputs, const BiasSettings& bias, int x, int y,
  ProbeRecorder* recorder = nullptr);

// The texel that holds a shadow-map position (in texels) and its four edges: the distance to each, in
// texels, and the neighbour across it. A GPU tap within float rounding of an edge may read that neighbour.
struct TexelEdge
{
  double distance = 0.0;
  glm::ivec2 neighbour{ 0 };
};
struct TexelWithEdges
{
  glm::ivec2 texel{ 0 };
  std::array<TexelEdge, 4> edges;
};
TexelWithEdges texelWithEdges(const glm::dvec2& uvTexels);

// One nearest-texel comparison with margins (texel index clamped to the map like texelFetch).
// `recorder` (optional): the texel as a ProbeTexel of role `role` with weight `weight`.
double nearestTexelTest(const ShadowMapInputs& inputs, const glm::dvec2& uvTexels, double comparisonDepth,
  ReferenceSample& sample, ProbeRecorder* recorder = nullptr, const char* role = "tap", double weight = 1.0);

// Polygon-id test (Hourcade & Nicolas 1985, survey §5): 1 iff the texel holding `uvTexels` (clamped like texelFetch)
// stores the id of the triangle pixel (x, y) sees. `recorder` (optional): the texel, its id as the "depth".
double polygonIdTest(const ShadowMapInputs& inputs, const glm::dvec2& uvTexels, int x, int y,
  ProbeRecorder* recorder = nullptr);

// The depth a texel compares receivers with, from its nearest caster depth `first` (z1) and the second-nearest
// `second` (z2, depth peeling; 2 x far where none), survey §5. CPU twin of shadowmap/DepthLayerCombine.glsl.
//   First     z1
//   Midpoint  (z1 + z2) / 2 (Woo 1992)
//   Dual      min((z1 + z2) / 2, z1 + dualMaxOffsetTexels x texelWorldSizeAtFirst) (Weiskopf & Ertl 2003, as the
//             survey §5 summarises them: a parameter limiting the effective caster thickness)
double layerComparisonDepth(
  ShadowMapDepthLayer layer, double first, double second, double texelWorldSizeAtFirst, double dualMaxOffsetTexels);
// The same over whole maps (read back): `texelWorldSize` is LightView::texelWorldSize of the map's view.
ImageF layerComparisonMap(ShadowMapDepthLayer layer, const ImageF& first, const ImageF& second, const LightView& view,
  double dualMaxOffsetTexels);

} // namespace sl
