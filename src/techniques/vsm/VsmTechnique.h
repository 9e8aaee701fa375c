// Technique `vsm`: variance shadow maps (Donnelly & Lauritzen 2006), prefiltered by a box blur or by
// mip-mapping, with light-bleeding reduction (Lauritzen 2007). Math: vsm/shaders/VsmVisibility.glsl.
// Parameters: the shadow-map ones and prefilter (blur|mipmap), prefilter_texels, light_bleeding_reduction,
// min_variance. Buffers: p_max (Chebyshev bound), light_leak (p_max - pcf, at pcf's default bias, over the same box),
// kernel_texels, depth_bias.
#pragma once

#include "techniques/MomentReference.h"
#include "techniques/ShadowMapReference.h"
#include "frame/TechniqueDescriptor.h"

namespace sl
{

TechniqueDescriptor vsmTechnique();

// vsm's parameters, typed (parsed once, by from()).
struct VsmSettings
{
  BiasSettings bias;
  MomentPrefilterSettings prefilter;
  double lightBleedingReduction{};
  double minVariance{}; // relative to d^2

  static VsmSettings from(const ParameterValues& values);
};

struct VsmSample
{
  ReferenceSample sample;
  double pMax = 0.0;
  double lightLeak = 0.0;
  double variance = 0.0;
};

// CPU reference (double precision) of VsmVisibility.glsl for prefilter = blur. `recorder` (optional, `shadowlab
// probe`): the receiver, the moment box (kernel_texels, its texels), the moments, p_max and the light-bleeding
// reduction, and the light leak against the true PCF over the same box (its comparisons).
VsmSample vsmReference(const ShadowMapInputs& inputs, const VsmSettings& settings, int x, int y,
  ProbeRecorder* recorder = nullptr);

} // namespace sl
