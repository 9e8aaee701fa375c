// PCSS's CPU twin (Fernando 2005; double precision), shared by pcss and by savsm, which builds on its blocker search
// and penumbra estimate. Its GLSL: pcss/shaders/PcssVisibility.glsl.
#pragma once

#include "techniques/ShadowMapReference.h"
#include "techniques/SoftShadowSupport.h"
#include "frame/TechniqueDescriptor.h"

namespace sl
{

struct PcssSample
{
  ReferenceSample sample;   // visibility, bias, margins
  double blockerKernelTexels = 0.0;
  double averageBlockerDepth = 0.0;
  double penumbraWidth = 0.0;
  double penumbraKernelTexels = 0.0;
  glm::dvec2 filterHalfTexels{ 0.0 }; // half extents of w_p in texels (x, y)
  glm::dvec2 uvTexels{ 0.0 };         // the receiver's shadow-map position
  bool foundBlockers = false;
  // Smallest distance (texels) of a grid kernel's edge to the texel-centre lattice: below ~1e-4 float
  // rounding on the GPU may include or exclude a row of texels.
  double kernelEdgeMargin = 1e300;
};

// pcss's parameters, typed (parsed once, by from()); savsm's blocker search and penumbra estimate read the same.
struct PcssSettings
{
  BiasSettings bias;
  SoftShadowSettings soft;
  TapPattern filter{}; // the PCF step; a technique without `filter` (savsm): the grid

  static PcssSettings from(const ParameterValues& values);
};

// CPU reference (double precision) of PcssVisibility.glsl at pixel (x, y). Techniques built on PCSS's first
// two steps (savsm) call it too; without a `filter` parameter the PCF step uses the grid.
// `recorder` (optional, `shadowlab probe`): the receiver; the blocker search (its kernel w_i in texels and world
// units, every tap with its comparison, blocker_samples, the blockers found); the penumbra estimate
// (avg_blocker_depth, penumbra_width, penumbra_kernel_texels, the kernel w_p); and, when `recordFilter`, the PCF
// step's taps (weight 1 / taps each) and visibility. savsm records the first two steps only (its filter is
// Chebyshev's), while the PCF step still runs so the sample's margins stay those of the whole twin.
PcssSample pcssReference(const ShadowMapInputs& inputs, const PcssSettings& settings, int x, int y,
  ProbeRecorder* recorder = nullptr, bool recordFilter = true);

} // namespace sl
