// The moment summed-area table (moment soft shadow mapping: Peters, Münstermann, Wetzstein & Klein 2016; JCGT 2017):
// the summed-area table of the shadow map's four power moments b = (z, z^2, z^3, z^4) (z normalised to the light's
// range, as structures/powermoments). moment_sat_precision = int64: each texel's moment in 32-bit fixed point and the
// sums in 64-bit integers (two RGBA32UI images, low and high words), exact box sums for every box of every map size
// allowed; int32 (the authors' form): fewer bits per texel and 32-bit sums that wrap (one RGBA32UI image), exact for
// boxes up to moment_sat_max_kernel_texels squared (shaders/MomentSatBuild.glsl). Built by vtkSLMomentSatPass (stage
// moment_sat); CPU mirror: lightspace/MomentSummedAreaTable.h; lookup: momentsat/MomentSatLookup.glsl.
#pragma once

#include "lightspace/MomentSummedAreaTable.h"
#include "structures/LightSpaceStructure.h"

namespace sl
{

const LightSpaceStructure& momentSatStructure();

// The parameters its build reads (moment_sat_precision, moment_sat_max_kernel_texels), typed.
MomentSatFormat momentSatFormat(const ParameterValues& values);

// What the build leaves in the frame.
struct MomentSatData : LightSpaceData
{
  vtkSmartPointer<vtkTextureObject> low;  // RGBA32UI: the low 32 bits of the four prefix sums
  vtkSmartPointer<vtkTextureObject> high; // RGBA32UI: the high 32 bits (int64 only)
  MomentSatFormat format;
  std::size_t bandBytes = 0; // the build's band and carry buffers, kept with the tables (gl/BandedPrefixSums.h)
};
const MomentSatData& momentSatData(const FrameResources& frame);

} // namespace sl
