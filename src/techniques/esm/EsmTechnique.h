// Technique `esm`: exponential shadow maps (Annen et al. 2008), prefiltered like vsm. Math:
// esm/shaders/EsmVisibility.glsl. Parameters: the shadow-map ones and prefilter, prefilter_texels,
// esm_exponent (c). Buffers: light_leak (visibility - pcf, at pcf's default bias, over the same
// box), kernel_texels, depth_bias, bias_gain (exp(c bias_n); pixels at 2 or more are flagged and warned about).
#pragma once

#include "techniques/MomentReference.h"
#include "techniques/ShadowMapReference.h"
#include "frame/TechniqueDescriptor.h"

namespace sl
{

TechniqueDescriptor esmTechnique();
// The bias_gain buffer: exp(c bias_n) per pixel, flagged (BufferSpec::flagAtOrAbove) at 2.
BufferSpec esmBiasGainBuffer();

// esm's parameters, typed (parsed once, by from()).
struct EsmSettings
{
  BiasSettings bias;
  MomentPrefilterSettings prefilter;
  double exponent{}; // esm_exponent: c in exp(c (z_n - t_n))

  static EsmSettings from(const ParameterValues& values);
};

// CPU reference (double precision) of EsmVisibility.glsl for prefilter = blur. `recorder` (optional, `shadowlab
// probe`): the receiver, the moment box (kernel_texels, its texels), E[exp(c z_n)], the exponential test, and the
// light leak against the true PCF over the same box (its comparisons).
ReferenceSample esmReference(const ShadowMapInputs& inputs, const EsmSettings& settings, int x, int y,
  ProbeRecorder* recorder = nullptr);

} // namespace sl
