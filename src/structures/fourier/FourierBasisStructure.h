// The Fourier basis images of convolution shadow maps (Annen et al. 2007, survey §6): per shadow-map texel,
// sin(c_k s z_n) and cos(c_k s z_n) for k = 1..terms, c_k = pi (2k - 1), z_n the linear depth normalised to the
// light's [near, far] (clamped to [0, 1]), s = depth_range (so gaps s (z_n - d_n) stay inside (-1, 1), the series'
// period, away from its jump back at +-1); four terms per RGBA32F texture (sine textures, then cosine textures), each
// prefiltered like the moment map: a separable box blur of prefilter_texels, or mip-mapped. Its own parameter is
// `terms` and `depth_range`; the prefilter's (prefilter, prefilter_texels, prefilter_region) are the moment map's, declared once by momentMapStructure()
// and by each technique listing this structure. Built by vtkSLFourierBasisPass (stage fourier_basis).
#pragma once

#include "structures/LightSpaceStructure.h"
#include "structures/moments/ReceiverTiles.h"

#include <optional>

#include <vector>

namespace sl
{

const LightSpaceStructure& fourierBasisStructure();

// The basis terms of one texture (RGBA): terms 4 i + 1 .. 4 i + 4 of texture i.
inline constexpr int fourierTermsPerTexture = 4;

// The parameters its build reads, typed.
struct FourierBasisSettings
{
  int terms = 16;     // M, a multiple of 4 in [4, 16]
  double depthRange = 0.5; // s: the series reads s z_n, s in (0, 1]
  bool mipmap = false; // prefilter = mipmap
  int blurTexels = 1; // prefilter_texels for prefilter = blur; 1 = no blur
  bool receiversOnly = false; // prefilter_region = receivers with prefilter = blur

  // Throws InputError naming `terms` when it is not a multiple of 4.
  static FourierBasisSettings from(const ParameterValues& values);
};

// Whether the sparse blur of prefilter_region = receivers costs less than the basis pass and the blur over the plan's
// tiles. Unlike the moment map's rule (sparseBlurIsCheaper, fetches alone) it counts the basis: the sparse blur forms
// every texture's terms at each of the w^2 taps of each listed texel (one fetch, then per texture a rotation to its
// four terms and their sums: fourierSparseTermCost fetches), while the basis pass forms them once per texel of its
// tiles (taken as a fetch per texture written) and each texture's two blur passes then read w texels per texel.
// Calibrated on llvmpipe with each path forced (docs/bench/fourier-terms), before the sparse blur shared its taps
// across each pixel's footprint (docs/bench/footprint-blur): the rule now underrates the sparse path.
inline constexpr double fourierSparseTermCost = 0.8;
bool fourierSparseBlurIsCheaper(const ReceiverPrefilterPlan& plan, int blurTexels, int textures);

// What the build leaves in the frame (FrameResources::structureData<FourierBasisData>("fourier_basis")).
struct FourierBasisData : LightSpaceData
{
  std::vector<vtkSmartPointer<vtkTextureObject>> sine;   // terms / 4 RGBA32F textures: prefiltered sin(c_k z_n)
  std::vector<vtkSmartPointer<vtkTextureObject>> cosine; // the same for cos(c_k z_n)
  int terms = 0;
  bool mipmapped = false;
  // prefilter_region = receivers: the moment map's plan; the texels it did not build are not data. None: all built.
  std::optional<ReceiverPrefilterPlan> region;
};

} // namespace sl
