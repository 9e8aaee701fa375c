// The layered moment map of layered variance shadow maps (Lauritzen & McCool 2008; survey §6): for each of
// `layers` depth layers (structures/layeredmoments/LayeredMoments.h), the moments (phi_i(z), phi_i(z)^2) of the
// shadow map's depths warped into that layer, box-blurred over prefilter_texels like the VSM moment map. One RG32F
// slice per layer of a 3D texture (VTK 9.1's vtkTextureObject allocates no 2D array texture; texelFetch with
// nearest filtering reads a slice as an array layer would). Built by vtkSLLayeredMomentsPass (stage
// layered_moments).
#pragma once

#include "structures/LightSpaceStructure.h"

namespace sl
{

const LightSpaceStructure& layeredMomentsStructure();

// The parameters its build reads, typed: `layers`, which it declares, and `prefilter_texels`, the box width the moment
// map (structures/moments) declares with the same meaning (a parameter name belongs to one structure), which a
// technique reading the layered moments declares with it.
struct LayeredMomentsSettings
{
  int layers = 1;     // layers
  int blurTexels = 1; // prefilter_texels

  static LayeredMomentsSettings from(const ParameterValues& values);
};

// What the build leaves in the frame (FrameResources::structureData<LayeredMomentsData>("layered_moments")).
struct LayeredMomentsData : LightSpaceData
{
  vtkSmartPointer<vtkTextureObject> moments; // RG32F, size x size x layers
  int layers = 1;
};

} // namespace sl
