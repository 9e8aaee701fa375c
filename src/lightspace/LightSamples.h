// Points on a light's surface, for techniques that sample the light (reference-sm), and the sub-lights of
// multi-view shadow maps.
#pragma once

#include "scene/Scene.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace sl
{

// splitmix64's finaliser: well-mixed bits from a counter or a seed (Steele, Lea & Flood 2014).
std::uint64_t mix64(std::uint64_t value);

// Radical inverse of `index` in `base` (van der Corput), in [0, 1).
double radicalInverse(unsigned base, std::uint64_t index);
// Shirley and Chiu's concentric map of [0, 1)^2 onto the unit disk (area-preserving and continuous, so a
// stratified square stays stratified).
glm::dvec2 concentricDiskMap(const glm::dvec2& unit);

// The point of an area light at unit-square coordinates (u, v) in [0, 1)^2: the square spanned by
// light.right() and light.up with side light.size, or, for a disk of diameter light.size, Shirley and
// Chiu's concentric map of the square onto the disk (area-preserving, so uniform stays uniform).
glm::dvec3 pointOnAreaLight(const Light& light, const glm::dvec2& unitSquare);

// `count` well-spread points on an area light: the Hammersley set ((k + 1/2)/count, radical inverse of k)
// rotated toroidally by an offset drawn from `seed` (Cranley-Patterson), so any count is stratified and
// unbiased. Other light types have one point, their centre (a directional light has none: empty).
std::vector<glm::dvec3> lightSamplePoints(const Light& light, int count, std::uint64_t seed);

// The S x S sub-lights of a square area light (Yang et al. 2009 §5, multi-view shadow maps): centres on the light's (right, up) grid, size / S each,
// row by row from the (-right, -up) corner.
std::vector<Light> splitIntoSubLights(const Light& light, int perSide);

} // namespace sl
