// Technique `pcf`: percentage-closer filtering (Reeves, Salesin & Cook 1987; survey §6, Fig. 23).
//
// Parameters: the shadow-map ones, its warp, warp_n (ShadowMapParameters.h; survey §4.2), its cascades (survey
// §4.3.1), cube_map (survey §2) and
//   kernel_texels    [texels]  grid: kernel_texels x kernel_texels taps one texel apart, centred on the
//                              receiver's exact shadow-map position; poisson: disk diameter
//   pattern          grid | poisson (rotated per pixel by common/SamplingPatterns.glsl)
//   poisson_samples  taps of the Poisson disk (poisson only)
//   filter           nearest: each tap is one texel comparison; hardware_bilinear: each tap is the
//                    hardware's bilinearly weighted 2x2 comparison (sampler2DShadow, GL_LINEAR)
// Buffers: kernel_texels (footprint width, +1 for the bilinear taps), taps (depth comparisons per pixel),
// texel_ratio (survey Eq. 2), depth_bias.
#pragma once

#include "techniques/SamplingPatterns.h"
#include "techniques/ShadowMapReference.h"
#include "frame/TechniqueDescriptor.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace sl
{

TechniqueDescriptor pcfTechnique();

enum class PcfPattern
{
  Grid,
  Poisson
};

enum class PcfFilter
{
  Nearest,
  HardwareBilinear
};

// pcf's parameters, typed (parsed once, by from()).
struct PcfSettings
{
  BiasSettings bias;
  int kernelTexels{};
  PcfPattern pattern{};
  int poissonSamples{};
  PcfFilter filter{};

  static PcfSettings from(const ParameterValues& values);
};

// CPU reference (double precision) of PcfVisibility.glsl at pixel (x, y). `recorder` (optional, `shadowlab
// probe`): the receiver, the kernel (texels and world units, as a ProbeKernel), every texel compared with its
// weight in the result (nearest: 1 / taps per tap; hardware_bilinear: the 2x2 texels of each tap with their
// bilinear weights / taps), so the occluding texels' weights sum to 1 - visibility.
ReferenceSample pcfReference(const ShadowMapInputs& inputs, const ParameterValues& values, int x, int y,
  ProbeRecorder* recorder = nullptr);

} // namespace sl
