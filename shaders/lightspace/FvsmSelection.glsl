// Adaptive partitioning (survey §4.3.3, fitted virtual shadow maps): which quadtree tile's map each covered pixel
// reads. The tile whose rectangle holds the pixel's light xy (containment): its cell of the finest level's grid
// (2^fvsm_max_level per side over the root rectangle), looked up in the tile-of-cell texture. Writes (tile, tile, 1, 0)
// per pixel, (0, 0, 1, 0) where no tile holds it (uncovered, or a cell no receiver of the pre-pass fell in).
// The CPU twin is sl::FvsmQuadtree::tileAt on sl::lightXYOf (src/lightspace/FittedVirtualShadowMap.cpp).
// Driver: vtkSLFocusPass (src/structures/shadowmap/vtkSLFocusPass.cxx).
layout(local_size_x = 8, local_size_y = 8) in;

#include "common/GBufferInputs.glsl"

layout(rgba32f, binding = 0) uniform writeonly image2D selection;
uniform sampler2D tileOfCell; // R32F, gridSize^2: the leaf's index, -1 where none
uniform int gridSize;
uniform mat4 rootViewFromWorld;
uniform int lightIsPerspective;
uniform vec4 rootRect; // xMin, xMax, yMin, yMax in light xy

void main()
{
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = imageSize(selection);
  if (pixel.x >= size.x || pixel.y >= size.y)
  {
    return;
  }
  Surface surface = readSurface(pixel);
  vec4 result = vec4(0.0, 0.0, 1.0, 0.0);
  if (surface.covered)
  {
    vec4 pLs = rootViewFromWorld * vec4(surface.pWs, 1.0);
    vec2 lightXY = lightIsPerspective != 0 ? pLs.xy / -pLs.z : pLs.xy;
    vec2 scaled = floor((lightXY - rootRect.xz) / (rootRect.yw - rootRect.xz) * float(gridSize));
    ivec2 cell = ivec2(clamp(scaled, vec2(0.0), vec2(float(gridSize - 1))));
    float tile = texelFetch(tileOfCell, cell, 0).r;
    if (tile >= 0.0)
    {
      result = vec4(tile, tile, 1.0, 0.0);
    }
  }
  imageStore(selection, pixel, result);
}
