// CPU mirror of the moment map (prefilter = blur) and of common/MomentLookup.glsl, in double precision.
#pragma once

#include "core/Parameters.h"
#include "frame/TechniqueDescriptor.h"
#include "techniques/ShadowMapReference.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace sl
{

struct FilteredMoments
{
  double mean = 0.0;        // E[z]
  double second = 0.0;      // E[z^2]
  double exponential = 0.0; // E[exp(c z_n)]
};

// Calls visit(z, texel) for the width x width texels of the prefilter's box around the receiver's texel (clamp to
// edge), z the map's linear depth: the texels the prefiltered maps average and the light-leak PCF compares, so that
// every technique's twin walks the same box.
template <typename Visit>
void visitPrefilterBox(const ShadowMapInputs& inputs, const glm::dvec2& uvTexels, int width, Visit visit)
{
  const int size = inputs.shadowMapLinear.width;
  const int centerX = std::clamp(static_cast<int>(std::floor(uvTexels.x)), 0, size - 1);
  const int centerY = std::clamp(static_cast<int>(std::floor(uvTexels.y)), 0, size - 1);
  const int first = -(width - 1) / 2;
  for (int j = 0; j < width; ++j)
  {
    for (int i = 0; i < width; ++i)
    {
      const glm::ivec2 texel(std::clamp(centerX + first + i, 0, size - 1), std::clamp(centerY + first + j, 0, size - 1));
      visit(static_cast<double>(inputs.shadowMapLinear.at(texel.x, texel.y)), texel);
    }
  }
}

// The box of `width` texels around the texel containing uvTexels (clamp to edge), as the blur computes it.
// `recorder` (optional, `shadowlab probe`): the box's texels (role "moment box", read only, weight 1 / width^2).
FilteredMoments boxMoments(const ShadowMapInputs& inputs, const glm::dvec2& uvTexels, int width, double exponent,
  ProbeRecorder* recorder = nullptr);
// Fraction of that box's texels passing the depth test (the light-leak reference). `recorder` (optional): each
// texel's comparison (role "light-leak pcf", weight 1 / width^2).
double boxPcf(const ShadowMapInputs& inputs, const glm::dvec2& uvTexels, double comparisonDepth, int width,
  ProbeRecorder* recorder = nullptr);
// The PCF over a set of comparisons when those within float rounding of their boundary (depths within `relative`
// of the compared depth) go either way on the GPU: vsm and savsm compare the receiver's own depth, so a receiver
// facing the light ties with its own texels.
struct PcfRange
{
  double lowest = 0.0;  // every tie unlit
  double highest = 0.0; // every tie lit
  int ties = 0;
};
PcfRange boxPcfRange(const ShadowMapInputs& inputs, const glm::dvec2& uvTexels, double comparisonDepth, int width,
  double relative);
// Group "light leak" of the probes: box_pcf, light_leak_tied_comparisons, and `value` - PCF as light_leak (the
// buffer's name) when no comparison ties, else as light_leak_range (lowest, highest): the GPU's buffer lies there.
void recordLightLeak(ProbeRecorder& recorder, double value, double pcf, const PcfRange& range, const std::string& source);

// `moment_bias`, alpha of MSM Alg. 3, declared alike by msm and msmsoft (Hamburger 4MSM, common/MomentHamburger.glsl).
// 3e-5: the value public ports of the authors' code use for 16-bit storage in their optimised basis (msm's page says
// what was and was not found); minimum 1e-6: below it the bias vanishes in float moments.
ParameterSpec momentBiasParameter();

struct SoftShadowGeometry;
// CPU mirror of common/RectanglePcf.glsl: the PCF over the texels [lo, hi] (every texel up to maxGridTaps per axis, a
// regular sub-grid beyond), each tap compared as PCSS's filter step compares it (`geometry`: the bias and the
// receiver's tangent plane), the light_leak reference of savsm and msmsoft. `range` (optional): the same PCF with
// the comparisons within rounding of their boundary counted both ways; `recorder` (optional): every tap (role
// "light-leak pcf").
double rectanglePcf(const ShadowMapInputs& inputs, const SoftShadowGeometry& geometry, int maxGridTaps, double bias,
  glm::ivec2 lo, glm::ivec2 hi, PcfRange* range = nullptr, ProbeRecorder* recorder = nullptr);

enum class MomentPrefilter
{
  Blur,
  Mipmap
};

// The moment map's prefilter as the moment techniques (vsm, esm) read it: part of their typed settings.
struct MomentPrefilterSettings
{
  MomentPrefilter prefilter{};
  int texels{}; // prefilter_texels: the box width (blur), or 2^lod (mipmap)

  static MomentPrefilterSettings from(const ParameterValues& values);
};

// What the moment techniques' probes (vsm, esm) share.
// Throws InputError for prefilter = mipmap: the twins mirror the box blur only (a trilinear lookup between mip
// levels has no twin).
void requireBlurPrefilter(const MomentPrefilterSettings& settings);
// Group "moments": kernel_texels (the buffer's name: the box width), its world size at the receiver, and the box
// as a ProbeKernel (the texels boxMoments averages, before clamping to the map's edge).
void recordMomentBox(ProbeRecorder& recorder, const ShadowMapInputs& inputs, const ShadowLookup& lookup, int width);
// Notes (ProbeSupport.h noteAmbiguity) a receiver within 1e-4 texel of a texel edge: the GPU may fetch the
// neighbouring texel of the moment map, whose box average differs.
void noteMomentTexelEdge(std::string& ambiguity, const glm::dvec2& uvTexels);

// vsm's and esm's accuracy contract: a prefiltered hard shadow of the light's centre. The filter blurs its edges and
// the moment bound bleeds light where the filtered depths are not two-valued (survey §6); held to the centre's ray
// where the value is 0 or 1, flagged "filtered edge" or, from the pass's light_leak buffer, "light bleeding".
AccuracyContract prefilteredCentreShadowAccuracy();

} // namespace sl
