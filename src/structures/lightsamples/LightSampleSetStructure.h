// The light-sample set of a frame (lightspace/LightSampleSet.h; Forest et al. 2009 = Forest et al. 2009 §4.1,
// Fig. 5): the N base points of a named pattern in an N x 1 RG32F texture, and, as uniforms, what
// shaders/common/LightSampleSet.glsl needs to give each pixel its N shifted samples on the light
// (lightSampleShift, lightSampleUnit, lightSampleOffset, lightSamplePoint). Object-space techniques (dcs) and the
// Embree reference draw the very same points. Built from nothing: no shadow map, light view or focus (the
// samples live on the light, not in its view). Built by vtkSLLightSamplePass (stage light_samples), which
// uploads the points only when the settings change. Parameters: light_samples, samples, sample_seed.
#pragma once

#include "lightspace/LightSampleSet.h"
#include "structures/LightSpaceStructure.h"

#include <memory>

namespace sl
{

const LightSpaceStructure& lightSampleSetStructure();

// The parameters its build reads, typed: light_samples (a name of lightSamplePatternNames()), samples ("16",
// "64" or "256") and sample_seed.
LightSampleSetSettings lightSampleSetSettings(const ParameterValues& values);

// What the build leaves in the frame.
struct LightSampleSetData : LightSpaceData
{
  std::shared_ptr<const LightSampleSet> samples; // the CPU set the texture holds
  vtkSmartPointer<vtkTextureObject> baseTexture; // RG32F N x 1: samples->basePoints()
};
const LightSampleSetData& lightSampleSetData(const FrameResources& frame);

} // namespace sl
