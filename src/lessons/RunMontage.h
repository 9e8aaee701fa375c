// Montage panels made from runs (a run = a stats.json document and the buffers of buffers.vti): how a run's buffer
// is drawn and which of its pixels hold data. `shadowlab montage` and the lessons both go through these.
#pragma once

#include "core/Image.h"
#include "core/NamedImage.h"
#include "frame/TechniqueDescriptor.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace sl
{

// `buffer`'s declaration in the run's technique (stats "technique") or among the buffers every frame has; a
// reference run's buffers and unknown ones are continuous, with the unit stats.json gives.
BufferSpec runBufferSpec(const nlohmann::json& stats, const std::string& buffer);

// 1 where the run's "coverage" buffer is > 0.5; empty (every pixel valid) when the run has no coverage buffer.
ImageU8 coverageMask(const std::vector<NamedImage>& buffers);

// The montage mask of the run's buffer `values` as `spec` declares it: coverage, and kNotApplicablePixel where a
// buffer on BufferDomain::ShadowTested had no shadow test (vis/BufferHeatMap.h bufferValueMask).
ImageU8 runValueMask(const std::vector<NamedImage>& buffers, const NamedImage& values, const BufferSpec& spec);

} // namespace sl
