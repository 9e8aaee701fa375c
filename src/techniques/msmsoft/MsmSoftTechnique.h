// Technique `msmsoft`: moment soft shadow mapping (Peters, Münstermann, Wetzstein & Klein 2016; JCGT 2017). From the
// moment summed-area table (structures/momentsat): the blocker intensity and average blocker depth from the four
// moments over PCSS's search region (the canonical representation at the receiver's depth), the penumbra kernel by
// similar triangles, and Hamburger 4MSM over the kernel's moments with fractional edges.
// Math: msmsoft/shaders/MsmSoftVisibility.glsl.
// Parameters: the shadow-map ones, the moment SAT's (moment_sat_precision, moment_sat_max_kernel_texels),
// moment_bias (msm's), fully_lit_bias, min_kernel_texels, max_grid_taps and receiver_plane_bias (the light_leak
// buffer's PCF only).
// Buffers: light_leak, blocker_kernel_texels, blocker_intensity, avg_blocker_depth, penumbra_kernel_texels, depth_bias,
// moment_sat_overflow, and from the pass support_depth_near/far, hankel_pivot.
#pragma once

#include "core/Image.h"
#include "frame/TechniqueDescriptor.h"
#include "lightspace/MomentHamburger.h"
#include "lightspace/MomentSummedAreaTable.h"
#include "techniques/ShadowMapReference.h"
#include "techniques/SoftShadowSupport.h"

#include <cstdint>

namespace sl
{

TechniqueDescriptor msmSoftTechnique();

// The GPU's visibility lies within this of the twin's (MsmSoftTest; README.md, Precision) where no search kernel edge
// lies within 1e-4 texel of a texel centre and the rounding sensitivity is at most msmSoftSensitivityLimit.
inline constexpr double msmSoftTwinTolerance = 5e-4;

// msmsoft's parameters, typed (parsed once, by from()).
struct MsmSoftSettings
{
  BiasSettings bias;
  double momentBias{};      // alpha of MSM Alg. 3 (msm's moment_bias)
  double fullyLitBias{};    // epsilon of the average blocker depth
  double minKernelTexels{}; // the penumbra kernel's smallest width
  int maxGridTaps{};        // the light-leak PCF's grid
  bool receiverPlaneBias{}; // the light-leak PCF's comparisons
  MomentSatFormat satFormat; // moment_sat_precision, moment_sat_max_kernel_texels (structures/momentsat)

  static MsmSoftSettings from(const ParameterValues& values);
};

// Step 4: the blocker estimate from the search region's moments at z_f.
struct MsmSoftBlockers
{
  MsmReconstruction canonical; // Hamburger 4MSM at z_f on the search moments: its support z_1, z_2
  glm::dvec2 weights{ 0.0 };   // of z_1 and z_2 in the three-point distribution with z_f (floored at 0)
  double intensity = 0.0;      // G_b: the weights of the z_i < z_f (unclamped; the buffer clamps at 1)
  double averageDepth = 0.0;   // z_avg, moment depth
};
MsmSoftBlockers msmSoftBlockers(const glm::dvec4& searchMoments, double momentBias, double fullyLitBias, double zf);

// How far float rounding moves steps 4-6: the sum over the four search moments, the four filter moments and z_f of the
// largest change when one moves by +-msmSoftMomentRounding.
inline constexpr double msmSoftMomentRounding = 1e-6; // the absolute rounding of a float moment in [0, 1] (as msm's)
struct MsmSoftSensitivity
{
  double visibility = 0.0;
  double blockerIntensity = 0.0; // G_b (clamped at 1 as the buffer)
  double averageDepth = 0.0;     // relative change of the linear average blocker depth
  double kernel = 0.0;           // relative change of penumbra_kernel_texels
  double supportDepth = 0.0;     // change of the filter's support depths (MSM Alg. 3's roots), relative beyond 1
};
// Above this a quantity is ill-conditioned (a near-singular Hankel matrix): tests and the probe count it instead of
// comparing it (msm's msmSensitivityLimit).
inline constexpr double msmSoftSensitivityLimit = 1e-3;

struct MsmSoftSample
{
  ReferenceSample sample;
  double fragmentDepth = 0.0;      // z_f
  glm::dvec2 searchHalfTexels{ 0.0 };
  glm::ivec2 searchLo{ 0 };        // the search rectangle, inclusive texels
  glm::ivec2 searchHi{ 0 };
  double searchEdgeMargin = 1e300; // the search kernel's edges' distance to texel centres (texels)
  glm::dvec4 searchMoments{ 0.0 };
  MsmSoftBlockers blockers;
  double averageBlockerDepth = 0.0; // linear depth
  glm::dvec2 filterHalfTexels{ 0.0 };
  glm::dvec2 filterMin{ 0.0 };      // the fractional filter rectangle, texels
  glm::dvec2 filterMax{ 0.0 };
  glm::dvec4 filterMoments{ 0.0 };
  MsmReconstruction filter;         // Hamburger 4MSM over the filter rectangle
  glm::ivec2 coverLo{ 0 };          // the filter rectangle's integer cover (the light-leak PCF)
  glm::ivec2 coverHi{ 0 };
  double lightLeak = 0.0;
  MsmSoftSensitivity sensitivity;
  // int32 table: the search box or the filter's integer cover holds more texels than the table sums exactly (the
  // GPU's sums wrapped; the moment_sat_overflow buffer). The twin's sums are exact regardless.
  bool satOverflow = false;
};

// CPU twin (double precision) of MsmSoftVisibility.glsl at pixel (x, y). `momentTable` is the moment SAT of
// inputs.shadowMapLinear in settings.satFormat (momentSummedAreaTable, lightspace/MomentSummedAreaTable.h): its box
// sums are exact, so the twin's box means are the quantised moments' (2^-bits) in double. `recorder` (optional, `shadowlab probe`): the
// receiver, the search box and its moments, the canonical representation with its weights, G_b and z_avg, the
// penumbra kernel and the filter box, the filter's Hamburger 4MSM (pivots, support points, weights), the visibility
// and the light leak against the PCF over the filter rectangle's integer cover.
MsmSoftSample msmSoftReference(const ShadowMapInputs& inputs, const MsmSoftSettings& settings,
  const MomentSatTable& momentTable, int x, int y, ProbeRecorder* recorder = nullptr);

} // namespace sl
