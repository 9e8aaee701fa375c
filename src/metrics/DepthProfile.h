// A buffer's distribution over the eye's depth (`shadowlab bench --depth-profile`, the warping lesson): the covered
// pixels binned by their `depth` (linear view depth along the camera axis) into bins of equal ratio, the median and
// quartiles of the buffer in each. For a shadow map warped with a view perpendicular to the light, each bin also
// carries the survey's Fig. 12 closed form of the error along the map's t axis (Eq. 1 with cos α / cos β = 1, the
// warp's z_n, z_f and n; PerspectiveWarp.h closedFormWarpAliasing), converted to pixels per texel with the frame's
// own scales, and the median over the bin's pixels of buffer / closed form at each pixel's depth.
#pragma once

#include <nlohmann/json.hpp>

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace sl
{

struct FrameResult;

struct DepthProfileSettings
{
  std::string buffer;      // a one-component buffer of the frame
  int bins = 16;           // equal ratios of depth between nearDepth and farDepth
  double nearDepth = 0.0;  // both 0: the binned pixels' own depth range
  double farDepth = 0.0;
};

// Fig. 12's closed form for the frame's map (survey §4.2, view ⟂ light): dp/ds = (z - z_n + n)^2 / (C n z),
// C = (z_f - z_n + n) / (z_f - z_n), s running over [0, 1] across the focused body and p over the screen at unit
// distance; n = infinity is the uniform map, (z_f - z_n) / z. In pixels per texel: times pixelsPerUnit (screen
// pixels per unit of p, vertically) over texelsAcrossBody (the map's t texels from z_n to z_f).
struct Fig12ClosedForm
{
  double zNear = 0.0;
  double zFar = 0.0;
  double n = 0.0;                 // infinity for the uniform limit
  double pixelsPerUnit = 0.0;
  double texelsAcrossBody = 0.0;
  double at(double depth) const;  // pixels per texel at eye depth `depth`
  // Logarithmic warping's (§4.2.1, s = ln(z / z_n) / ln(z_f / z_n)): dp/ds = ln(z_f / z_n) at every depth.
  double logarithmic() const;
};

// The closed form for `frame`'s light view: a perspective warp (PerspectiveWarp) with the view within half a degree
// of perpendicular to the light, and `buffer` one that measures the t axis's error (texel_ratio_t,
// perspective_factor). Otherwise none.
std::optional<Fig12ClosedForm> fig12ClosedForm(const FrameResult& frame, const std::string& buffer);

struct DepthBin
{
  double nearDepth = 0.0;       // the bin's edges
  double farDepth = 0.0;
  std::size_t pixels = 0;       // the statistics below are 0 when the bin is empty
  double depthMedian = 0.0;
  double lowerQuartile = 0.0;
  double median = 0.0;
  double upperQuartile = 0.0;
  std::optional<double> closedForm;        // at depthMedian
  std::optional<double> medianOverClosedForm; // median of value / closed form at the pixel's depth
};

struct DepthProfile
{
  std::string buffer;
  std::vector<DepthBin> bins;
  std::optional<Fig12ClosedForm> closedForm;
};

// Bins the covered pixels (coverage > 0.5) whose value is finite and not 0 (the sampling-error buffers' 0 marks a
// pixel the map does not test) and whose depth lies in the range. Throws InputError naming `buffer` when the frame
// has no such one-component buffer, `bins` when it is below 1, the range when it is not 0 < near < far.
DepthProfile depthProfile(const FrameResult& frame, const DepthProfileSettings& settings);

// The settings from the command line's --depth-profile, --depth-bins and --depth-range ("near,far" or ""). Throws
// InputError naming the option for bins below 1 or a range that is not two numbers 0 < near < far.
DepthProfileSettings depthProfileSettings(const std::string& buffer, int bins, const std::string& range);

nlohmann::json depthProfileJson(const DepthProfile& profile);

} // namespace sl
