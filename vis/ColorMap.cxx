#include "vis/ColorMap.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <iterator>

namespace sl
{

namespace
{

constexpr RgbColor fromHex(std::uint32_t rgbHex)
{
  return { ((rgbHex >> 16) & 0xffu) / 255.0, ((rgbHex >> 8) & 0xffu) / 255.0, (rgbHex & 0xffu) / 255.0 };
}

// matplotlib's viridis (Nathaniel J. Smith, Stefan van der Walt, Eric Firing; CC0 public domain dedication,
// https://github.com/BIDS/colormap): every 5th entry of its 256-entry table `_viridis_data`
// (matplotlib/_cm_listed.py), i.e. entries 0, 5, ..., 255, evenly spaced in t. Linear interpolation between
// them stays within 0.0025 of the full table (less than one 8-bit step).
// clang-format off
constexpr RgbColor kViridis[] = {
  { 0.267004, 0.004874, 0.329415 }, { 0.273809, 0.031497, 0.358853 },
  { 0.278791, 0.062145, 0.386592 }, { 0.281924, 0.089666, 0.412415 },
  { 0.283197, 0.115680, 0.436115 }, { 0.282623, 0.140926, 0.457517 },
  { 0.280255, 0.165693, 0.476498 }, { 0.276194, 0.190074, 0.493001 },
  { 0.270595, 0.214069, 0.507052 }, { 0.263663, 0.237631, 0.518762 },
  { 0.255645, 0.260703, 0.528312 }, { 0.246811, 0.283237, 0.535941 },
  { 0.237441, 0.305202, 0.541921 }, { 0.227802, 0.326594, 0.546532 },
  { 0.218130, 0.347432, 0.550038 }, { 0.208623, 0.367752, 0.552675 },
  { 0.199430, 0.387607, 0.554642 }, { 0.190631, 0.407061, 0.556089 },
  { 0.182256, 0.426184, 0.557120 }, { 0.174274, 0.445044, 0.557792 },
  { 0.166617, 0.463708, 0.558119 }, { 0.159194, 0.482237, 0.558073 },
  { 0.151918, 0.500685, 0.557587 }, { 0.144759, 0.519093, 0.556572 },
  { 0.137770, 0.537492, 0.554906 }, { 0.131172, 0.555899, 0.552459 },
  { 0.125394, 0.574318, 0.549086 }, { 0.121148, 0.592739, 0.544641 },
  { 0.119423, 0.611141, 0.538982 }, { 0.121380, 0.629492, 0.531973 },
  { 0.128087, 0.647749, 0.523491 }, { 0.140210, 0.665859, 0.513427 },
  { 0.157851, 0.683765, 0.501686 }, { 0.180653, 0.701402, 0.488189 },
  { 0.208030, 0.718701, 0.472873 }, { 0.239374, 0.735588, 0.455688 },
  { 0.274149, 0.751988, 0.436601 }, { 0.311925, 0.767822, 0.415586 },
  { 0.352360, 0.783011, 0.392636 }, { 0.395174, 0.797475, 0.367757 },
  { 0.440137, 0.811138, 0.340967 }, { 0.487026, 0.823929, 0.312321 },
  { 0.535621, 0.835785, 0.281908 }, { 0.585678, 0.846661, 0.249897 },
  { 0.636902, 0.856542, 0.216620 }, { 0.688944, 0.865448, 0.182725 },
  { 0.741388, 0.873449, 0.149561 }, { 0.793760, 0.880678, 0.120005 },
  { 0.845561, 0.887322, 0.099702 }, { 0.896320, 0.893616, 0.096335 },
  { 0.945636, 0.899815, 0.112838 }, { 0.993248, 0.906157, 0.143936 }};
// clang-format on

// ColorBrewer RdBu, 11 classes (Cynthia A. Brewer, colorbrewer2.org, Apache-2.0), reversed so that low values
// are blue, with the centre class #f7f7f7 replaced by pure white. Its CIELAB lightness is symmetric about the
// centre (mirrored entries differ by at most ~4 L*), so equal distances from 0 look equally strong.
constexpr RgbColor kDiverging[] = { fromHex(0x053061), fromHex(0x2166ac), fromHex(0x4393c3), fromHex(0x92c5de),
  fromHex(0xd1e5f0), fromHex(0xffffff), fromHex(0xfddbc7), fromHex(0xf4a582), fromHex(0xd6604d),
  fromHex(0xb2182b), fromHex(0x67001f) };

// Tableau 10 (matplotlib's "tab10", d3's schemeCategory10).
constexpr RgbColor kCategories[] = { fromHex(0x1f77b4), fromHex(0xff7f0e), fromHex(0x2ca02c), fromHex(0xd62728),
  fromHex(0x9467bd), fromHex(0x8c564b), fromHex(0xe377c2), fromHex(0x7f7f7f), fromHex(0xbcbd22),
  fromHex(0x17becf) };

template <std::size_t Count>
RgbColor interpolate(const RgbColor (&controlPoints)[Count], double t)
{
  static_assert(Count >= 2);
  const double position = t * static_cast<double>(Count - 1);
  const std::size_t lower = std::min(static_cast<std::size_t>(position), Count - 2);
  const double fraction = position - static_cast<double>(lower);
  RgbColor color{};
  for (std::size_t c = 0; c < 3; ++c)
    color[c] = (1.0 - fraction) * controlPoints[lower][c] + fraction * controlPoints[lower + 1][c];
  return color;
}

} // namespace

RgbColor ColorMap::map(double t) const
{
  t = t > 0.0 ? std::min(t, 1.0) : 0.0; // also maps NaN to 0
  switch (kind_)
  {
    case ColorMapKind::Viridis:
      return interpolate(kViridis, t);
    case ColorMapKind::Diverging:
      return interpolate(kDiverging, t);
    case ColorMapKind::Categorical:
    {
      const auto lastIndex = static_cast<double>(std::size(kCategories) - 1);
      return kCategories[static_cast<std::size_t>(t * lastIndex + 0.5)];
    }
  }
  return kViridis[0];
}

RgbColor ColorMap::categoryColor(long long categoryId)
{
  const auto paletteSize = static_cast<long long>(std::size(kCategories));
  return kCategories[static_cast<std::size_t>(((categoryId % paletteSize) + paletteSize) % paletteSize)];
}

} // namespace sl
