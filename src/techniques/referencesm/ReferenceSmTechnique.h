// Technique `reference-sm`: the GPU accumulation reference the soft-shadow papers compare against
// (e.g. VSSM, Yang et al. 2010 §7: 1024 shadow maps): K hard shadow maps rendered from K points spread
// over the area light (Hammersley, lightspace/LightSamples.h), each focused on the visible receivers, and
// the hard test of each averaged. It converges to the unweighted visible fraction of the light as K grows,
// up to shadow-map discretisation and bias.
//
// Parameters: samples (K), seed (rotation of the sample set), and the shadow-map ones
// (ShadowMapParameters.h; shadow_map_size defaults to 1024 here, K maps are rendered per frame).
// Buffers: visibility_stderr (Bernoulli bound over the K samples), sample_count.
// Point and spot lights have one sample (their centre): the result is `hard`. Directional lights: one map.
#pragma once

#include "frame/TechniqueDescriptor.h"

namespace sl
{

TechniqueDescriptor referenceSmTechnique();

} // namespace sl
