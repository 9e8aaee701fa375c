// Technique `convsm`: convolution shadow maps (Annen, Mertens, Bekaert, Seidel & Kautz 2007; survey §6). The shadow
// test H(z_n - d_n) expanded in an M-term Fourier series whose basis images sin(c_k s z_n), cos(c_k s z_n) are
// prefiltered (structures/fourier), s = depth_range keeping every gap inside the series' period, with the per-term
// damping sigma_k = exp(-alpha (k / M)^2) against ringing (its form not verified against the paper; README.md), and
// visibility = clamp(reconstruction_scale f, 0, 1), which maps the series' 1/2 at z = d to lit.
// Math: convsm/shaders/ConvsmVisibility.glsl. Parameters: the shadow-map ones, terms, depth_range, prefilter,
// prefilter_texels, ringing_alpha, reconstruction_scale. Buffers: reconstruction (the series f before scaling and
// clamping), overshoot (f's part outside [0, 1]), light_leak (visibility - pcf over the same box, pcf's default
// bias), kernel_texels, depth_bias.
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
  double depthRange = 0.5;   // s: normalised depths enter the series as s z_n (structures/fourier)
  double ringingAlpha = 0.0; // alpha of sigma_k = exp(-alpha (k / M)^2); 0: the plain truncated series
  double reconstructionScale = 2.0; // visibility = clamp(scale f, 0, 1); 1: the raw series

  static ConvsmSettings from(const ParameterValues& values);
};

// c_k = pi (2k - 1), k >= 1: the frequencies of the step's Fourier series on [-1, 1].
double convsmFrequency(int k);
// sigma_k = exp(-alpha (k / M)^2), the damping of term k of M.
double convsmDamping(int k, int terms, double alpha);
// The damped M-term series of the step at one pair of series depths (d_s, z_s in [0, s], s = depth_range):
// 1/2 + 2 sum_k sigma_k / c_k sin(c_k (z_s - d_s)).
double convsmStepSeries(double dSeries, double zSeries, int terms, double alpha);
// visibility from the series f: clamp(scale f, 0, 1) (reconstruction_scale).
double convsmVisibility(double reconstruction, double reconstructionScale);

// The basis images averaged over a box, per term (index k - 1): E[sin(c_k z_s)], E[cos(c_k z_s)], z_s = s z_n.
struct FourierCoefficients
{
  std::vector<double> sine;
  std::vector<double> cosine;
};
// The box of `width` texels around the texel containing uvTexels (clamp to edge), as the blur computes it.
// `recorder` (optional): the box's texels (role "fourier box", read only, weight 1 / width^2).
FourierCoefficients convsmBasisAverage(const ShadowMapInputs& inputs, const glm::dvec2& uvTexels, int width, int terms,
  double depthRange, ProbeRecorder* recorder = nullptr);
// The reconstruction from prefiltered coefficients at the receiver's series depth d_s:
// 1/2 + 2 sum_k sigma_k / c_k [cos(c_k d_s) E[sin(c_k z_s)] - sin(c_k d_s) E[cos(c_k z_s)]].
double convsmReconstruct(double dSeries, const FourierCoefficients& coefficients, int terms, double alpha);
// (d - near) / (far - near) clamped to [0, 1]: the depth normalisation of the basis images and the receiver.
double convsmNormalizedDepth(const ShadowMapInputs& inputs, double depthLin);
// s (d - near) / (far - near), the normalised depth mapped into [0, s] (s = depth_range): the series' depth.
double convsmSeriesDepth(const ShadowMapInputs& inputs, double depthLin, double depthRange);

struct ConvsmSample
{
  ReferenceSample sample; // visibility: clamp(reconstruction_scale reconstruction, 0, 1)
  double reconstruction = 0.0; // the series f, before scaling and clamping
  double lightLeak = 0.0; // visibility - box PCF (pcf's default bias)
  double boxPcf = 0.0;
  double dNormalized = 0.0; // d_n in [0, 1]
  double dSeries = 0.0;     // s d_n
  FourierCoefficients coefficients;
};

// CPU reference (double precision) of ConvsmVisibility.glsl for prefilter = blur. `recorder` (optional,
// `shadowlab probe`): the receiver, the box, each term's prefiltered coefficients and damping, the reconstructed
// step around the receiver's depth, the reconstruction, visibility and the light leak against the box PCF.
ConvsmSample convsmReference(const ShadowMapInputs& inputs, const ConvsmSettings& settings, int x, int y,
  ProbeRecorder* recorder = nullptr);

} // namespace sl
