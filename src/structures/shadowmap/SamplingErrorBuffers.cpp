#include "structures/shadowmap/SamplingErrorBuffers.h"

#include "core/Error.h"
#include "frame/FrameResult.h"
#include "lightspace/ShadowMapMath.h"
#include "passes/FrameResources.h"

#include <algorithm>
#include <thread>

namespace sl
{

const std::vector<BufferSpec>& samplingErrorBufferSpecs()
{
  static const std::vector<BufferSpec> specs = {
    { "texel_ratio_s", "pixels/texel",
      "aliasing error m along the shadow map's s axis (survey Eq. 2 per axis): screen pixels one s-texel step on the "
      "surface spans; > 1 means undersampling" },
    { "texel_ratio_t", "pixels/texel", "the same along the map's t axis (the axis a perspective warp acts on)" },
    { "perspective_factor", "pixels/texel",
      "survey Eq. 1's (1/z)(dz/ds): one t-texel's width across the light ray, in pixels across the eye ray at the "
      "receiver's distance (the error of a surface facing both the eye and the light)" },
    { "projection_factor", "",
      "survey Eq. 1's cos(alpha)/cos(beta): the surface's cosine to the eye over its cosine to the light (> 1 where the "
      "light grazes the surface)" },
  };
  return specs;
}

std::vector<NamedImage> samplingErrorBuffers(
  const FrameResources& frame, const FrameResult& result, const ImageF* viewIndex)
{
  const NamedImage* position = result.find("position");
  const NamedImage* normal = result.find("normal");
  const NamedImage* coverage = result.find("coverage");
  const NamedImage* receives = result.find("receives_shadows");
  if (frame.technique == nullptr || frame.light == nullptr || !position || !normal || !coverage || !receives ||
    frame.technique->subLightsPerSide(frame.parameters) > 1)
  {
    return {};
  }
  // Views that partition the pixels (survey §4.3): each pixel's error is its own view's map's.
  SL_CHECK_MSG(frame.partitions.has_value() == (viewIndex != nullptr), "a partitioned frame names each pixel's view");
  const int width = position->image.width;
  const int height = position->image.height;
  std::vector<ImageF> images(4, ImageF(width, height, 1));
  const auto evaluateRows = [&](int firstRow, int rowStep) {
    for (int y = firstRow; y < height; y += rowStep)
    {
      for (int x = 0; x < width; ++x)
      {
        const glm::dvec3 pWs(position->image.at(x, y, 0), position->image.at(x, y, 1), position->image.at(x, y, 2));
        const glm::dvec3 nWs(normal->image.at(x, y, 0), normal->image.at(x, y, 1), normal->image.at(x, y, 2));
        if (coverage->image.at(x, y, 0) <= 0.5f || receives->image.at(x, y, 0) <= 0.5f ||
          !lightCanReach(*frame.light, pWs, nWs))
        {
          continue;
        }
        const LightView& view = viewIndex
          ? frame.partitions->views.at(static_cast<std::size_t>(viewIndex->at(x, y, 0)))
          : frame.lightView;
        const SamplingError error = samplingError(frame.camera, view, x + 0.5, y + 0.5, pWs, nWs);
        images[0].at(x, y, 0) = static_cast<float>(error.texelRatioS);
        images[1].at(x, y, 0) = static_cast<float>(error.texelRatioT);
        images[2].at(x, y, 0) = static_cast<float>(error.perspectiveFactor);
        images[3].at(x, y, 0) = static_cast<float>(error.projectionFactor);
      }
    }
  };
  // Interleaved rows on every core: each pixel is written by one worker (about 0.1 s per million pixels on one).
  const int workers = static_cast<int>(std::max(1u, std::min(8u, std::thread::hardware_concurrency())));
  std::vector<std::thread> threads;
  for (int worker = 1; worker < workers; ++worker)
  {
    threads.emplace_back(evaluateRows, worker, workers);
  }
  evaluateRows(0, workers);
  for (std::thread& thread : threads)
  {
    thread.join();
  }
  std::vector<NamedImage> buffers;
  const std::vector<BufferSpec>& specs = samplingErrorBufferSpecs();
  for (std::size_t i = 0; i < specs.size(); ++i)
  {
    buffers.push_back({ specs[i].name, std::move(images[i]), specs[i].unit, specs[i].doc, specs[i].kind, {} });
  }
  return buffers;
}

} // namespace sl
