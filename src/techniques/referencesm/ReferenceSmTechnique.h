// Technique `reference-sm`: the GPU accumulation reference the soft-shadow papers compare against
// (e.g. VSSM, Yang et al. 2010 §7: 1024 shadow maps): K hard shadow maps rendered from K points spread
// over the area light (Hammersley, lightspace/LightSamples.h), each focused on the visible receivers, and
// the hard test of each averaged. It converges to the unweighted visible fraction of the light as K grows,
// up to shadow-map discretisation and bias.
//
// Parameters: samples (K), seed (rotation of the sample set), and the shadow-map ones
// (ShadowMapParameters.h; K maps are rendered per frame).
// Buffers: visibility_stderr (Bernoulli bound over the K samples), sample_count.
// Point and spot lights have one sample (their centre): the result is `hard`. Directional lights: one map.
#pragma once

#include "frame/FrameResult.h"
#include "frame/ProbeRecord.h"
#include "frame/TechniqueDescriptor.h"
#include "lightspace/LightView.h"
#include "scene/Scene.h"
#include "structures/shadowmap/ShadowMapStructure.h"
#include "techniques/ShadowMapReference.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace sl
{

TechniqueDescriptor referenceSmTechnique();

// reference-sm's parameters, typed (parsed once, by from()).
struct ReferenceSmSettings
{
  ShadowMapSettings shadowMap; // resolution and caster faces of each of the K maps; a one-texel margin (no filter)
  BiasSettings bias;
  int samples{};               // K
  std::uint64_t seed{};        // rotation of the Hammersley light samples

  static ReferenceSmSettings from(const ParameterValues& values);
};

// The probe's twin of the pass (no whole-image twin exists: the K maps stay on the GPU). For a pixel it replays
// the K hard shadow tests exactly as the pass makes them, one shadow-map texel each:
//  - the same K light samples (lightSamplePoints with `samples` and `seed`), each a light of the area light's
//    orientation at the sample;
//  - each sample's light view fitted on the CPU from the frame's G-buffer (fitLightView on ImageReceivers, the
//    reference of the GPU's focus reduction: GpuCpuTest holds them equal to 1e-5 of the window);
//  - the receiver's texel, bias and comparison depth as `hard` computes them (prepareShadowLookup);
//  - the depth that texel stores: the nearest caster along the ray through the texel's centre (a rasteriser
//    covers a texel exactly where its centre lies in the triangle), alpha-tested as AlphaMask.glsl, front or
//    back faces as caster_faces, within the view's depth range, else the clear value 2 far; Moller-Trumbore in
//    double over every caster triangle.
// A sample is uncertain when float rounding or the fit may decide it the other way: its comparison within 2e-6
// (relative) of the stored depth, a ray within kTexelMargin of the texel centre that stores a depth deciding
// otherwise (rasterisation's sub-texel precision, the fitted window's rounding), the receiver within kTexelMargin
// of a texel edge whose neighbour decides otherwise, or a light-reach cosine under 1e-5.
class ReferenceSmReplay
{
public:
  // How far (texels) the GPU's coverage decision at a texel centre, or its receiver position, may lie from the
  // replay's: rasterisation snaps to 1/256 texel (llvmpipe's 8 sub-pixel bits), the float focus reduction and
  // projection add ~1e-4 at 1024^2; twice the snapping for headroom. Without a margin ReferenceSmTest finds 3
  // pixels of stacked-occluders beyond tolerance; with 1/256 or more, none.
  static constexpr double kTexelMargin = 1.0 / 128.0;

  ReferenceSmReplay(const FrameResult& frame, const Scene& scene, int lightIndex = 0);

  struct Pixel
  {
    bool evaluated = false;   // covered and receiving: the K tests ran
    double visibility = 0.0;  // lit samples / K (or 1 for a pixel that receives no shadows, 0 uncovered)
    int lit = 0;
    int unreachable = 0;      // the receiver faces away from the sample or lies behind the light's plane
    int uncertain = 0;        // samples float rounding may decide the other way
    int edge = 0;             // edge_samples: samples whose test a texel next to the receiver's decides otherwise
    int edgeUncertain = 0;    // samples whose edge decision float rounding or rasterisation may flip
    // The largest |GPU - replay| this pixel allows: float accumulation of K weights 1/K (K 2^-24) plus one 1/K per
    // uncertain sample.
    double tolerance = 0.0;
  };
  // `recorder` (optional): the receiver, each light sample (light coordinates, blocked, as a ProbeLightSample),
  // the counts and the visibility.
  Pixel replay(glm::ivec2 pixel, ProbeRecorder* recorder = nullptr);

  int sampleCount() const { return static_cast<int>(lights_.size()); }
  const LightView& sampleView(int k) const { return views_.at(static_cast<std::size_t>(k)); }

private:
  struct Triangle
  {
    glm::dvec3 a{ 0.0 }, edge1{ 0.0 }, edge2{ 0.0 }, normal{ 0.0 };
    glm::dvec2 uvA{ 0.0 }, uvB{ 0.0 }, uvC{ 0.0 };
    const ImageF* alpha = nullptr; // the object's alpha texture, or null
  };
  // The depth the map of sample `k` stores at continuous texel position `texelPosition` (the ray through it).
  double storedDepth(std::size_t k, const glm::dvec2& texelPosition) const;

  const Light& light_;
  ShadowMapInputs inputs_;        // the G-buffer; light and light view set per sample
  BiasSettings bias_;
  std::vector<Light> lights_;     // one per sample: the light moved to the sample
  std::vector<LightView> views_;
  std::vector<glm::dmat4> worldFromClip_;
  std::vector<Triangle> casters_;
  bool backFaces_ = false;
};

// The technique's probe (TechniqueDescriptor::probe): ReferenceSmReplay at one pixel.
ProbeOutcome probeReferenceSm(const FrameResult& frame, const Scene& scene, int lightIndex, glm::ivec2 pixel,
  ProbeRecorder& recorder);

} // namespace sl
