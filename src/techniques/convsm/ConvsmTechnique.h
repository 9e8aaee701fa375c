// Technique `convsm`: convolution shadow maps (Annen, Mertens, Bekaert, Seidel & Kautz 2007; survey §6). The shadow
// test H(z_n - d_n) expanded in an M-term Fourier series whose basis images sin(c_k z_n), cos(c_k z_n) are
// prefiltered (structures/fourier), with the per-term damping sigma_k = exp(-alpha (k / M)^2) against ringing (its
// form not verified against the paper; README.md).
// Math: convsm/shaders/ConvsmVisibility.glsl. Parameters: the shadow-map ones, terms, prefilter, prefilter_texels,
// ringing_alpha. Buffers: reconstruction (before clamping), overshoot (its part outside [0, 1]), light_leak
// (visibility - pcf over the same box, pcf's default bias), kernel_texels, depth_bias.
#pragma once

#include "frame/TechniqueDescriptor.h"
#include "structures/fourier/FourierBasisStructure.h"
#include "techniques/MomentReference.h"
#include "techniques/ShadowMapReference.h"

#include <vector>

namespace sl
{

TechniqueDescriptor convsmTechnique();

// convsm's parameters, typed (parsed once, by from()).
struct ConvsmSettings
{
  BiasSettings bias;
  MomentPrefilterSettings prefilter;
  int terms = 16;            // M
  double ringingAlpha = 0.0; // alpha of sigma_k = exp(-alpha (k / M)^2); 0: the plain truncated series

  static ConvsmSettings from(const ParameterValues& values);
};

// c_k = pi (2k - 1), k >= 1: the frequencies of the step's Fourier series on [-1, 1].
double convsmFrequency(int k);
// sigma_k = exp(-alpha (k / M)^2), the damping of term k of M.
double convsmDamping(int k, int terms, double alpha);
// The damped M-term series of the step at one pair of normalised depths (d, z in [0, 1]):
// 1/2 + 2 sum_k sigma_k / c_k sin(c_k (z - d)).
double convsmStepSeries(double dNormalized, double zNormalized, int terms, double alpha);

// The basis images averaged over a box, per term (index k - 1): E[sin(c_k z_n)], E[cos(c_k z_n)].
struct FourierCoefficients
{
  std::vector<double> sine;
  std::vector<double> cosine;
};
// The box of `width` texels around the texel containing uvTexels (clamp to edge), as the blur computes it.
// `recorder` (optional): the box's texels (role "fourier box", read only, weight 1 / width^2).
FourierCoefficients convsmBasisAverage(const ShadowMapInputs& inputs, const glm::dvec2& uvTexels, int width, int terms,
  ProbeRecorder* recorder = nullptr);
// The reconstruction from prefiltered coefficients at the receiver's normalised depth:
// 1/2 + 2 sum_k sigma_k / c_k [cos(c_k d) E[sin(c_k z)] - sin(c_k d) E[cos(c_k z)]].
double convsmReconstruct(double dNormalized, const FourierCoefficients& coefficients, int terms, double alpha);
// (d - near) / (far - near) clamped to [0, 1]: the depth normalisation of the basis images and the receiver.
double convsmNormalizedDepth(const ShadowMapInputs& inputs, double depthLin);

struct ConvsmSample
{
  ReferenceSample sample; // visibility: the reconstruction clamped to [0, 1]
  double reconstruction = 0.0;
  double lightLeak = 0.0; // visibility - box PCF (pcf's default bias)
  double boxPcf = 0.0;
  double dNormalized = 0.0;
  FourierCoefficients coefficients;
};

// CPU reference (double precision) of ConvsmVisibility.glsl for prefilter = blur. `recorder` (optional,
// `shadowlab probe`): the receiver, the box, each term's prefiltered coefficients and damping, the reconstructed
// step around the receiver's depth, the reconstruction, visibility and the light leak against the box PCF.
ConvsmSample convsmReference(const ShadowMapInputs& inputs, const ConvsmSettings& settings, int x, int y,
  ProbeRecorder* recorder = nullptr);

} // namespace sl
