// Sampling patterns shared by filtering techniques (pcf, pcss): a fixed Poisson disk and the per-pixel
// rotation hash, with their GLSL twins in shaders (uniform poissonDisk[], common/SamplingPatterns.glsl).
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace sl
{

constexpr int maxPoissonSamples = 64;
// A fixed Poisson-disk pattern in the unit disk (best-candidate sampling, fixed seed), maxPoissonSamples
// points; any prefix of it is well distributed.
const std::vector<glm::dvec2>& poissonDisk();
// The same as interleaved floats, for the `uniform vec2 poissonDisk[MAX_POISSON_SAMPLES]` of the shaders.
const std::vector<float>& poissonDiskFloats();

// The per-pixel hash of shaders/common/SamplingPatterns.glsl, bit for bit.
std::uint32_t pixelHash(std::uint32_t x, std::uint32_t y);
double pixelHashAngle(std::uint32_t x, std::uint32_t y);
// pixelRotation(uvec2) of the same file: rotation * p turns p by pixelHashAngle(x, y) counter-clockwise.
glm::dmat2 pixelRotation(int x, int y);

} // namespace sl
