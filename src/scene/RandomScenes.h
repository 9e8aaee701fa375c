// Random scenes for the differential test (issue 27): configurations nobody tuned for, made deterministically from
// a seed, as scene.json text that loadScene/parseScene read like any other scene.
//
// Every scene is a ground quad (8 x 8 at y = 0, receiving) under one area light, square or disk, of size 0.01 to 3
// (log-uniform) at height 1.5 to 4, pointing straight down or at the origin, with 1 to 5 occluders: horizontal or
// tilted quads, boxes floating or standing on the ground (in contact with the receiver), and perforated quads
// (alpha texture `fence` or `leaves`), placed within 0.7 of the axis so that they overlap or not. The highest
// occluder is sometimes (30%) 1e-3 to 0.1 below the light (log-uniform; the light is then vertical and that occluder
// horizontal, so neither crosses the other's plane). The camera looks at the origin from 4.5 to 6.5 away, at an image
// of 64 to 128 pixels a side, mostly non-square (`maxSide` scales it down for tests).
//
// Random numbers are drawn from splitmix64 in a fixed order and mapped to [0, 1) by their top 53 bits, so a seed
// gives the same scene with any compiler and standard library.
#pragma once

#include <cstdint>
#include <string>

namespace sl
{

struct RandomScene
{
  std::string json;     // the scene file's text
  std::string summary;  // one line: light, occluders, image size
  // A draw for the technique's shadow-map size, taken from the same seed: the map is its default divided by
  // 2^mapSizeHalvings (0..3), never below the parameter's minimum (the differential applies it).
  int mapSizeHalvings = 0;
};

// `maxSide` (>= 16): the image's longer side is at most this (the drawn size scaled down, aspect kept).
RandomScene randomScene(std::uint64_t seed, int maxSide = 128);

} // namespace sl
