// Technique `savsm`: SAT-based variance soft shadow mapping (Lauritzen 2007, GPU Gems 3 ch. 8), the
// baseline of the VSSM paper: PCSS's blocker search and penumbra kernel, then the kernel's moments from a
// summed-area table and the Chebyshev bound. Math: savsm/shaders/SavsmVisibility.glsl.
// Parameters: the shadow-map ones (the bias applies to the blocker search; Chebyshev compares the receiver's
// own depth), the PCSS-family ones (SoftShadowSupport.h),
// sat_precision (float_centred | int32, survey §6.4), light_bleeding_reduction, min_variance.
// Buffers: p_max, light_leak (p_max - PCF over w_p, compared as pcss's filter compares), blocker_kernel_texels,
// blocker_samples,
// avg_blocker_depth, penumbra_kernel_texels, depth_bias.
#pragma once

#include "structures/sat/SatStructure.h"
#include "techniques/PcssReference.h"
#include "techniques/ShadowMapReference.h"
#include "frame/TechniqueDescriptor.h"

namespace sl
{

TechniqueDescriptor savsmTechnique();

// savsm's parameters, typed (parsed once, by from()).
struct SavsmSettings
{
  PcssSettings pcss;           // the blocker search and penumbra estimate (and the bias)
  SummedAreaTableSettings sat; // sat_precision
  double lightBleedingReduction{};
  double minVariance{};        // relative to d^2

  static SavsmSettings from(const ParameterValues& values);
};

struct SavsmSample
{
  ReferenceSample sample;
  double pMax = 0.0;
  double lightLeak = 0.0; // the light_leak buffer: p_max - PCF over w_p with pcss's comparison (0 without blockers)
  double variance = 0.0;
  double kernelEdgeMargin = 1e300; // as PcssSample
  glm::ivec2 lo{ 0 };              // the penumbra rectangle, inclusive texels
  glm::ivec2 hi{ 0 };
  bool foundBlockers = false;
};

// CPU reference (double precision, exact box moments of the encoded depths) of SavsmVisibility.glsl.
// `recorder` (optional, `shadowlab probe`): PCSS's blocker search and penumbra estimate (pcssReference), the SAT
// box (w_p's texel rectangle) with its moments, p_max and the light-bleeding reduction, and the light leak against
// the PCF over the same rectangle, each tap compared as pcss's filter compares it (as the shader's light_leak
// buffer computes it).
SavsmSample savsmReference(const ShadowMapInputs& inputs, const SavsmSettings& settings, int x, int y,
  ProbeRecorder* recorder = nullptr);

} // namespace sl
