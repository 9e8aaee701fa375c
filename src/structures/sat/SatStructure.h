// The summed-area table of the shadow map's (z, z^2) (Crow 1984; survey §6.4; SAVSM, VSSM): RG32F of the
// centred depth, or RG32UI of 16-bit fixed-point z_n, z_n^2 whose wrapping sums give exact box sums
// (structures/sat/shaders/SatBuild.glsl). Built by vtkSLSatPass (stage summed_area_table); CPU mirror: SummedAreaTable.h.
#pragma once

#include "structures/LightSpaceStructure.h"

namespace sl
{

const LightSpaceStructure& summedAreaTableStructure();

// The parameters its build reads, typed.
struct SummedAreaTableSettings
{
  bool integer = true; // sat_precision = int32 (else float_centred)
};
SummedAreaTableSettings summedAreaTableSettings(const ParameterValues& values);

// What the build leaves in the frame.
struct SummedAreaTableData : LightSpaceData
{
  vtkSmartPointer<vtkTextureObject> table;
  bool integer = false;
  double fixedPointScale = 0.0; // int32: 2^b - 1 (satFixedPointScale)
  std::size_t bandBytes = 0;    // the build's band and carry buffers, kept with the table (gl/BandedPrefixSums.h)
};
const SummedAreaTableData& summedAreaTableData(const FrameResources& frame);

} // namespace sl
