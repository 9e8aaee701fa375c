// Per-pixel rules that decide where a technique's declared approximation applies (TechniqueDescriptor::accuracy,
// issue 27), computed from a rendered frame's published buffers and light-space exports. Each technique's
// descriptor picks the rules that describe its own approximations; the rules live here because several
// techniques share them (every shadow-map soft-shadow method reads one depth layer of blockers).
#pragma once

#include "core/Image.h"
#include "frame/TechniqueDescriptor.h"
#include "techniques/ShadowMapReference.h"

#include <cmath>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace sl
{

// The shadow map of a frame, with a min-max pyramid over its linear depths, asked about the caster texels that can
// hide some part of the light from a pixel.
class ShadowMapFootprint
{
public:
  // Throws when the frame has no shadow map; `view` names a partitioned frame's map (survey §4.3, PartitionViews.h),
  // -1 otherwise.
  explicit ShadowMapFootprint(const ApproximationContext& context, int view = -1);
  const ShadowMapInputs& inputs() const { return inputs_; }

  // The pixel's receiver point projected into the map, or nullopt where no shadow test happens (uncovered, not
  // receiving, the light cannot reach it, outside the map's depth range).
  struct Receiver
  {
    ShadowMapSample sample;
    double margin = 0.0; // a stored depth below sample.depthLin - margin is a caster, not the receiver itself
  };
  std::optional<Receiver> receiver(int x, int y) const;

  // The depth range of the caster texels that can hide part of the light from the pixel's point: a texel of depth
  // z at lateral offset t (light-space tangent) from the point's own is counted when |t| <= (w/2)(d - z)/(d z)
  // on both axes (PCSS's blocker-search region, Fernando 2005, for the circumscribed square of side w; exact
  // for a square light) and z < d - margin. Large regions are read through the pyramid's level whose texels are
  // at most 1/32 of the region, each node taken as a whole (its min, and its max when the node holds casters only),
  // so the spread found is never more than the texels' own.
  struct CasterRange
  {
    bool found = false;
    double minDepth = 0.0;
    double maxDepth = 0.0;
    bool receiverSeen = false; // the region also holds texels that are not casters (the light is partly seen)
    // The largest caster texel of the region back-projected from the point onto the light's plane, as a fraction of
    // the light's size: texelWorldSize(z) d / (d - z) / w. A caster edge is placed to within one texel, so the
    // visible fraction is known to about this much along it.
    double texelOnLight = 0.0;
  };
  CasterRange casterRange(int x, int y) const;

  // Whether the depth test against the receiver differs among the texels within `radius` texels of its nearest one,
  // with `bias` subtracted from the receiver's depth (stored < d - bias: occluded): the value then depends on which
  // texel the GPU reads or how its filter weights them, not on the geometry. `nearBias` also counts a texel whose
  // stored depth lies in [d - 2 bias, d) on the lit side: a caster so close to the receiver that the bias hides it.
  bool depthTestMixed(int x, int y, double radius, double bias, bool nearBias) const;

  // An upper bound on the fraction of the light hidden from the pixel's point by casters that the receiver's margin
  // hides from the technique: texels whose stored depth z lies in [d - margin, d) and above the receiver's own plane
  // (the tangent plane through the point, at its shallowest over the texel, less 1e-3 d), each back-projected from
  // the point onto the light's plane (scale z d / (d - z)) and clipped to the light. Stops counting once the sum
  // exceeds `limit`. 0 for a light without area.
  double hiddenByMargin(int x, int y, double limit) const;

private:
  ShadowMapInputs inputs_;
  double lightSize_ = 0.0;
  // Level k: min (max) over 2^k x 2^k texels; level 0 is inputs_.shadowMapLinear, levels 1.. are stored.
  const ImageF& minLevel(int level) const
  {
    return level == 0 ? inputs_.shadowMapLinear : coarseMinLevels_[static_cast<std::size_t>(level - 1)];
  }
  const ImageF& maxLevel(int level) const
  {
    return level == 0 ? inputs_.shadowMapLinear : coarseMaxLevels_[static_cast<std::size_t>(level - 1)];
  }
  int levelCount() const { return 1 + static_cast<int>(coarseMinLevels_.size()); }
  void buildPyramid() const; // levels 1.., once, on the first question that reads them
  mutable std::once_flag pyramidBuilt_;
  mutable std::vector<ImageF> coarseMinLevels_;
  mutable std::vector<ImageF> coarseMaxLevels_;
};

// How much an average blocker depth can misjudge a penumbra: blockers at depths [minDepth, maxDepth] above a receiver
// at receiverDepth estimate penumbra widths (d - z) / z (PCSS Eq. 1, similar triangles) whose largest over smallest
// is zmax (d - zmin) / (zmin (d - zmax)) >= 1; 1 for one depth.
double blockerDepthRatio(double minDepth, double maxDepth, double receiverDepth);

// Marks with `code` every pixel whose caster texels (ShadowMapFootprint::casterRange) lie at depths whose
// blockerDepthRatio exceeds 1 + `tolerance`: an average blocker depth (PCSS, VSSM Eq. 4) or back-projected
// micro-occluders of one depth layer (occluder fusion) then scale the penumbra, hence the visible fraction along a
// shadow edge crossing the light, by more than the tolerance. Keeps codes already set.
void markMultipleBlockerDepths(const ShadowMapFootprint& footprint, ImageF& codes, float code, double tolerance);

// Marks with `code` every pixel where ShadowMapFootprint::depthTestMixed holds with the pixel's depth_bias (buffer)
// and radius 1 texel, or kernel_texels / 2 + 1 with `kernelTexels` (a filter's footprint): shadow-map sampling.
void markShadowMapSampling(const ShadowMapFootprint& footprint, const FrameResult& frame, ImageF& codes, float code,
  const ImageF* kernelTexels);
// The same on the frame's own map, or with views that partition the pixels (survey §4.3) on each view's map for the
// pixels that read it (the primary and, where they blend, the secondary of selectView).
void markShadowMapSampling(const ApproximationContext& context, ImageF& codes, float code, const ImageF* kernelTexels);
// depth_layer = polygon_id (survey §5, Hourcade & Nicolas 1985): `code` where a receiver that reaches the id test finds
// more than one id (0, no caster, counts as one) among the 3 x 3 texels of the map around its own; 0 elsewhere left.
void markSeveralPolygonIds(const ApproximationContext& context, ImageF& codes, float code);
// depth_layer = midpoint or dual (survey §5): `code` where a receiver that reaches the depth test, within
// `kernelTexels` / 2 + 1 texels of its own (1 without a kernel), finds a texel whose nearest caster (layer 1) lies in
// front of its depth less depth_bias while the combined depth compared lies behind it: lit only by the gap to the
// second layer, where a light leak and removed acne look alike. Pixels already coded are left.
void markDepthLayerGap(const ApproximationContext& context, ImageF& codes, float code, const ImageF* kernelTexels);

// Marks with `code` every pixel whose segment to the light's centre crosses a caster with an alpha texture (double
// precision, RayTriangle.h), wherever the texture is: for techniques that shadow such casters as solid.
void markCentreRayThroughPerforatedCaster(const ApproximationContext& context, ImageF& codes, float code);
// The same for the segments to the light's centre and to its four corners (square) or the four ends of its
// right/up diameters (disk): a caster with an alpha texture lies between the point and the light, and a shadow map
// samples its holes at texel centres only (alpha texture detail finer than a texel is lost or aliased).
void markLightRaysThroughPerforatedCaster(const ApproximationContext& context, ImageF& codes, float code);
Approximation perforatedCasterInMapApproximation();

// The declarations several techniques share: PCSS's average blocker depth (also VSSM Eq. 4) and back-projection's
// occluder fusion (GBP06, GBP07, Yang et al. 2009, SS08), both marked by markMultipleBlockerDepths.
Approximation averageBlockerDepthApproximation();
Approximation occluderFusionApproximation();

// Marks with `code` every pixel where the map's resolution, not the technique, decides the value by more than
// `tolerance`: the receiver's texel is so wide that its margin (about the depth bias) exceeds 5% of the distance to
// the light and either the pixel's light footprint holds casters (CasterRange::found: one layer of texels this wide
// loses whatever lies behind them) or the casters the margin hides cover more than `tolerance` of the light
// (ShadowMapFootprint::hiddenByMargin); or the pixel's light footprint holds both casters and uncovered texels (an
// edge of the shadow runs through it) and a caster texel back-projects onto more than `tolerance` of the light's
// size (CasterRange::texelOnLight: an edge crossing the light, misplaced by one texel, changes that much of it).
// Typical where a caster nearly touches the light (the focus window then spans a wide angle, survey §4.1) or the
// light is small against the texels. Keeps codes already set.
void markCoarseShadowMap(const ShadowMapFootprint& footprint, ImageF& codes, float code, double tolerance);
Approximation coarseShadowMapApproximation();

// The accuracy contract of a shadow-map soft-shadow technique that reads one depth layer of blockers (PCSS, VSSM,
// GBP06, GBP07, Yang et al. 2009): the whole light as reference, `tolerance`, and three declared approximations,
// codes 1-3: its blocker depths (BlockerDepthModel, markMultipleBlockerDepths), "coarse shadow map"
// (markCoarseShadowMap) and "perforated caster in the map" (markLightRaysThroughPerforatedCaster), all held to
// `tolerance`.
enum class BlockerDepthModel
{
  Average,       // one average blocker depth: averageBlockerDepthApproximation
  OccluderFusion // back-projected micro-occluders: occluderFusionApproximation
};
AccuracyContract oneLayerSoftShadowContract(BlockerDepthModel model, double tolerance);
// The contract of PCSS's average blocker depth followed by a moment bound over the penumbra kernel in place of its PCF
// (savsm: Chebyshev; msmsoft: Hamburger 4MSM): against the area light within `tolerance`, approximations 1 average
// blocker depth, 2 `bound` (marked where |light_leak| > 0.01), 3 coarse shadow map, 4 perforated caster in the map,
// 5 blocker search beyond the light.
AccuracyContract momentBoundSoftShadowContract(Approximation bound, double tolerance);

// Marks with `code` every pixel whose value lies strictly inside (epsilon, 1 - epsilon): a filtered (partial) value.
void markPartialVisibility(const FrameResult& frame, ImageF& codes, float code, double epsilon = 1e-3);

// Marks with `code` every pixel where `buffer` (component 0) satisfies `predicate`; nothing when the frame has no
// such buffer.
void markWhere(const FrameResult& frame, const std::string& buffer, const std::function<bool(float)>& predicate,
  ImageF& codes, float code);

} // namespace sl

namespace sl
{

// Marks with `code` every pixel whose blocker search region (PCSS step 1, VSSM Alg. 1 L7: the light's footprint at
// the near plane, the square of side w) holds casters that cannot hide the light, at depths more than 1% of the
// receiver's outside the range of those that can (ShadowMapFootprint::casterRange), and whose `visibility` lies more
// than `visibilityChange` outside what the penumbra kernel gives at the latter's depths counting only them (1 where
// none can): the search and the filter counted casters that hide nothing. Kernels are read on at most 32 x 32 taps.
// Keeps codes already set.
void markBlockerSearchBeyondTheLight(const ShadowMapFootprint& footprint, const FrameResult& frame, ImageF& codes,
  float code, double visibilityChange = 0.1);
Approximation blockerSearchBeyondTheLightApproximation();

} // namespace sl

namespace sl
{

// Marks with `code` every covered pixel whose segment to one of `samples` (points on the light) crosses a caster with
// an alpha texture: for techniques that render one shadow map per light sample (each samples the holes at texel
// centres). Keeps codes already set.
void markSampleRaysThroughPerforatedCaster(const ApproximationContext& context, const std::vector<glm::dvec3>& samples,
  ImageF& codes, float code);

} // namespace sl
