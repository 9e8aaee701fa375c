// CPU mirror of the moment map (prefilter = blur) and of common/MomentLookup.glsl, in double precision.
#pragma once

#include "techniques/ShadowMapReference.h"

namespace sl
{

struct FilteredMoments
{
  double mean = 0.0;        // E[z]
  double second = 0.0;      // E[z^2]
  double exponential = 0.0; // E[exp(c z_n)]
};

// The box of `width` texels around the texel containing uvTexels (clamp to edge), as the blur computes it.
FilteredMoments boxMoments(const ShadowMapInputs& inputs, const glm::dvec2& uvTexels, int width, double exponent);
// Fraction of that box's texels passing the depth test (the light-leak reference).
double boxPcf(const ShadowMapInputs& inputs, const glm::dvec2& uvTexels, double comparisonDepth, int width);

} // namespace sl
