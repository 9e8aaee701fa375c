// Technique `pcss`: percentage-closer soft shadows (Fernando 2005), the brute-force baseline the VSSM
// paper (Yang et al. 2010) compares against. Steps and kernels: pcss/shaders/PcssVisibility.glsl.
//
// Parameters: the shadow-map ones (ShadowMapParameters.h) and
//   blocker_search   grid (every texel of w_i, the default) | poisson
//   filter           grid (every texel of w_p, the default) | poisson
//   max_grid_taps    [taps per axis] grid kernels wider than this are sampled on a regular sub-grid
//   poisson_samples  [taps] for the poisson variants (rotated per pixel)
// Buffers: blocker_kernel_texels (w_i), blocker_samples, avg_blocker_depth, penumbra_width (w_p at the
// receiver, world units), penumbra_kernel_texels, pcf_samples, depth_bias.
// Lights: area (square or disk; the kernels are the bounding squares), point and spot (size 0: hard).
#pragma once

#include "frame/TechniqueDescriptor.h"

namespace sl
{

TechniqueDescriptor pcssTechnique();

} // namespace sl
