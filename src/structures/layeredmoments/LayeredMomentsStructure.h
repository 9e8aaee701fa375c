// The layered moment map of layered variance shadow maps (Lauritzen & McCool 2008; survey §6): for each of
// `layers` depth layers (lightspace/LayeredMoments.h), the moments (phi_i(z), phi_i(z)^2) of the
// shadow map's depths warped into that layer, box-blurred over prefilter_texels like the VSM moment map. One RG32F
// slice per layer of a 3D texture (VTK 9.1's vtkTextureObject allocates no 2D array texture; texelFetch with
// nearest filtering reads a slice as an array layer would). Built by vtkSLLayeredMomentsPass (stage
// layered_moments).
#pragma once

#include "structures/LightSpaceStructure.h"
#include "structures/moments/ReceiverTiles.h"
#include "lightspace/LayeredMoments.h"

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace sl
{

const LightSpaceStructure& layeredMomentsStructure();

// The parameters its build reads, typed: `layers` and `layer_placement`, which it declares, and `prefilter_texels` and
// `prefilter_region`, which the moment map (structures/moments) declares with the same meaning (a parameter name
// belongs to one structure) and a technique reading the layered moments declares with them.
struct LayeredMomentsSettings
{
  int layers = 1;     // layers
  int blurTexels = 1; // prefilter_texels
  LayerPlacement placement = LayerPlacement::Uniform; // layer_placement
  bool receiversOnly = false; // prefilter_region = receivers (absent: whole_map)

  static LayeredMomentsSettings from(const ParameterValues& values);
};

// What the build leaves in the frame (FrameResources::structureData<LayeredMomentsData>("layered_moments")).
struct LayeredMomentsData : LightSpaceData
{
  vtkSmartPointer<vtkTextureObject> moments; // RG32F, size x size x layers
  int layers = 1;
  std::vector<double> ends; // the layers' ends, layers + 1 linear depths (float-rounded, as the shaders get them)
  std::vector<std::uint32_t> histogram; // layer_placement=gaps: the depth histogram they were placed from (else empty)
  // prefilter_region = receivers, where marking could pay: the moment map's plan (structures/moments/ReceiverTiles.h),
  // whose built texels (ReceiverPrefilterPlan::builtMask) are the only ones built, in every layer; the x pass warps
  // the depths itself (sourceTiles 0). None: every texel built.
  std::optional<ReceiverPrefilterPlan> region;
};

// Whether the sparse blur (shaders/LayeredMomentsSparseBlur.glsl: per listed texel, w^2 taps, each warped into every
// layer) stays within the loop iterations llvmpipe allows one invocation (65535); where not, the blur runs over tiles.
bool layeredSparseBlurFits(int blurTexels, int layers);

// The layers' ends of a rendered frame (FrameResult::techniqueStatistics layer_end_<i>, which a technique reading
// the layered moments publishes with layeredEndStatistics); empty where the frame has none.
std::vector<double> layeredEndsOf(const std::map<std::string, double>& statistics);
void layeredEndStatistics(const std::vector<double>& ends, std::map<std::string, double>& statistics);

} // namespace sl
