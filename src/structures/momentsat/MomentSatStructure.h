// The moment summed-area table (moment soft shadow mapping: Peters, Münstermann, Wetzstein & Klein 2016; JCGT 2017):
// the summed-area table of the shadow map's four power moments b = (z, z^2, z^3, z^4) (z normalised to the light's
// range, as structures/powermoments), each texel's moment in 32-bit fixed point and the sums in 64-bit integers (two
// RGBA32UI images, low and high words): exact box sums for every box of every map size allowed
// (shaders/MomentSatBuild.glsl). Built by vtkSLMomentSatPass (stage moment_sat); CPU mirror:
// lightspace/MomentSummedAreaTable.h; lookup: momentsat/MomentSatLookup.glsl.
#pragma once

#include "structures/LightSpaceStructure.h"

namespace sl
{

const LightSpaceStructure& momentSatStructure();

// What the build leaves in the frame.
struct MomentSatData : LightSpaceData
{
  vtkSmartPointer<vtkTextureObject> low;  // RGBA32UI: the low 32 bits of the four prefix sums
  vtkSmartPointer<vtkTextureObject> high; // RGBA32UI: the high 32 bits
};
const MomentSatData& momentSatData(const FrameResources& frame);

} // namespace sl
