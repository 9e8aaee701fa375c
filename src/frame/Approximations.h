// The common buffer `approximation` (issue 27): per pixel, which of the technique's declared approximations
// (TechniqueDescriptor::accuracy, AccuracyContract) applies, so that a value a technique is allowed to get wrong by
// design is marked where it is, like a value cut short (FrameResult.h, cutShortPixels).
#pragma once

#include "core/NamedImage.h"
#include "frame/FrameResult.h"
#include "scene/Scene.h"

#include <cstddef>
#include <string>
#include <vector>

namespace sl
{

// The buffer's name and the label of code 0.
inline constexpr const char* kApproximationBuffer = "approximation";
inline constexpr const char* kNoApproximation = "none";

// Runs the technique's marking rule on a rendered frame: a categorical W x H buffer, code 0 "none" and code
// 1 + i the frame technique's approximations[i].name (every technique publishes it; one that declares no
// approximation has only code 0). Codes are kept only on covered pixels that receive shadows.
NamedImage approximationBuffer(const FrameResult& frame, const Scene& scene, int lightIndex);

// The frame's marked pixels: their count and, per declared approximation that marks any, its name and count.
struct ApproximatePixels
{
  std::size_t count = 0;
  std::vector<std::pair<std::string, std::size_t>> byApproximation;
};
ApproximatePixels approximatePixels(const FrameResult& frame);

} // namespace sl
