// shadow_map_size = auto: the map sized to the view (resolution matching, the survey's §4.3.3 idea applied to one
// map). Survey Eq. 2 per axis gives, at each visible receiver, how many pixels one texel of a fitted map spans
// (texel_ratio_s, texel_ratio_t); a map of N texels per side spans N - 2 margin of them over the receivers, so the
// pixel gets at least one texel per pixel along both axes iff N - 2 margin >= max(r_s, r_t) (N0 - 2 margin) for the
// ratios measured in a map of N0, and gets d texels per pixel iff d times that (auto_texels_per_pixel, 2 by default,
// under an area light; auto_texels_per_pixel_hard, 4, under the others: the shadow map's page says why). The chosen size meets that at kAutomaticMapQuantile of the receivers, rounded up to
// a power of two and bounded by kAutomaticMapMinSize and kAutomaticMapMaxSize (and the GL's limits); receivers the eye or the light
// grazes (ratio 0: unbounded, no size serves them) do not count. With several views that partition the pixels
// (cascades, cube faces) a receiver counts in the finest view that holds it, and all views share the size.
#pragma once

#include "core/Image.h"
#include "lightspace/LightView.h"

#include <vector>

namespace sl
{

struct CameraView;

// The share of visible receivers that get at least the texels per pixel asked for: 0.9, so most of the image is served at
// the size while the few grazing pixels whose need grows without bound (projection aliasing, survey §3) do not
// decide it. The shadow map's page (src/structures/shadowmap/README.md) measures the choice on the datasets.
constexpr double kAutomaticMapQuantile = 0.9;
// The smallest automatic size: below it the focus pass and the structures cost more than the map saves.
constexpr int kAutomaticMapMinSize = 64;
// The largest automatic size, the fixed default before `auto`: where the view asks for more (a receiver close to a
// wide perspective light, a deep view), the need comes from perspective aliasing, which the survey answers with
// warping and partitioning (§4.2-4.3: warp, cascades, fvsm), not with one map's size; an automatic map is never
// larger, so never slower, than the fixed default was (a technique may lower it to its own former default,
// TechniqueDescriptor::largestAutomaticMapSize). `capped` says the view asked for more.
constexpr int kAutomaticMapMaxSize = 2048;
// Receivers measured at most (every k-th pixel in x and y beyond it): a 0.9 quantile of 4096 samples is within about
// half a percent of its rank, and the rule rounds to a power of two.
constexpr int kAutomaticMapMaxSamples = 1 << 12;

struct AutomaticMapSize
{
  int size = 0;               // texels per side, a power of two
  double texelsPerPixel = 1;  // the density asked for (auto_texels_per_pixel or auto_texels_per_pixel_hard)
  double requiredTexels = 0;  // texels across the receivers at the quantile (before margin and rounding)
  int samples = 0;            // receivers measured
  int pixelStride = 1;        // every pixelStride-th pixel in x and y was measured
  bool capped = false;        // the quantile needed more than maxSize
};

// `views`: the map (or the views that partition the pixels) as fitted at any resolution (each view's `resolution`);
// `marginTexels`: the filter margin the fit keeps outside the receivers; position and normal as the G-buffer (xyz,
// w = coverage / receives shadows); `maxSize`: the largest size the GL and the parameter allow; `texelsPerPixel`: the
// texels per pixel along each axis to serve (1: one texel per pixel).
AutomaticMapSize automaticMapSize(const CameraView& camera, const Light& light, const std::vector<LightView>& views,
  double marginTexels, const ImageF& position, const ImageF& normal, int maxSize, double texelsPerPixel = 1.0);

// The smallest power of two >= value (at least 1); the largest <= value (at least 1).
int powerOfTwoAtLeast(double value);
int powerOfTwoAtMost(double value);

} // namespace sl
