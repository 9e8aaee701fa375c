// A prefiltered map's separable box blur (moments/BoxBlur.glsl, x then y, over the values a fragment pass forms from
// each shadow-map depth) evaluated only at the texels the receivers read (ReceiverTiles.h), one invocation per
// pixel's footprint of listed texels (up to 2 x 2, whose boxes share all but one row and column of taps: (w + 1)^2
// fetches instead of 4 w^2): for each of the vertical pass's rows it forms the horizontal pass's value there for
// each texel as that pass does (the same taps, clamped alike, summed in the same order, divided by the width), then
// sums them as the vertical pass does, each texel in its own sums, so every texel holds the whole map's bits. The
// values of each tap are formed inline by `vec4 momentsOfDepth(float depth)`, which the including shader defines
// with the code its fragment pass uses (moments/SparseMomentsBlur.glsl: vsm's and esm's moments; the power moments'),
// so that pass is skipped. A shader whose pass writes several RGBA textures (the Fourier basis) defines
// SPARSE_BLUR_IMAGES and `void momentsOfDepthImages(float depth, out vec4 values[SPARSE_BLUR_IMAGES])` instead, and
// every texture is blurred from one fetch of each tap into images 0 .. SPARSE_BLUR_IMAGES - 1. The list is
// shaders/ReceiverTiles.glsl's: word 0 the count, then x | y << 16, four entries per pixel, its footprint's corners
// (0, 0), (1, 0), (0, 1), (1, 1), repeated where the footprint is narrower.
layout(local_size_x = 64) in;

#ifndef SPARSE_BLUR_IMAGES
#define SPARSE_BLUR_IMAGES 1
void momentsOfDepthImages(float depth, out vec4 values[SPARSE_BLUR_IMAGES])
{
  values[0] = momentsOfDepth(depth);
}
#endif

layout(std430, binding = 0) readonly buffer ReceiverReadTexels
{
  uint receiverReadTexels[];
};
uniform sampler2D source; // the shadow map's linear depth
uniform int blurWidth;
uniform int readTexelCount;
layout(rgba32f, binding = 0) uniform writeonly image2D blurred[SPARSE_BLUR_IMAGES];

ivec2 listedTexel(int entry)
{
  uint packedTexel = receiverReadTexels[1 + entry];
  return ivec2(int(packedTexel & 0xFFFFu), int(packedTexel >> 16));
}

void main()
{
  int footprint = int(gl_GlobalInvocationID.y * gl_NumWorkGroups.x * gl_WorkGroupSize.x + gl_GlobalInvocationID.x);
  if (4 * footprint + 3 >= readTexelCount)
  {
    return;
  }
  // Texel (0, 0) of the footprint and its extent, 0 or 1 along each axis: (1, 1) is its last entry.
  ivec2 pixel = listedTexel(4 * footprint);
  ivec2 extent = listedTexel(4 * footprint + 3) - pixel;
  ivec2 size = textureSize(source, 0);
  int first = -(blurWidth - 1) / 2;
  // Index 2 dy + dx: the sums of texel pixel + (dx, dy).
  vec4 sums[4 * SPARSE_BLUR_IMAGES];
  for (int image = 0; image < 4 * SPARSE_BLUR_IMAGES; ++image)
  {
    sums[image] = vec4(0.0);
  }
  for (int row = 0; row < blurWidth + extent.y; ++row)
  {
    ivec2 rowTexel = clamp(pixel + (first + row) * ivec2(0, 1), ivec2(0), size - 1);
    // Index dx: the horizontal sums of texel column pixel.x + dx in this row.
    vec4 rowSums[2 * SPARSE_BLUR_IMAGES];
    for (int image = 0; image < 2 * SPARSE_BLUR_IMAGES; ++image)
    {
      rowSums[image] = vec4(0.0);
    }
    for (int k = 0; k < blurWidth + extent.x; ++k)
    {
      // The values the fragment pass would have stored there (the same function, so that pass is skipped).
      ivec2 tap = clamp(rowTexel + (first + k) * ivec2(1, 0), ivec2(0), size - 1);
      vec4 values[SPARSE_BLUR_IMAGES];
      momentsOfDepthImages(texelFetch(source, tap, 0).r, values);
      for (int image = 0; image < SPARSE_BLUR_IMAGES; ++image)
      {
        if (k < blurWidth)
        {
          rowSums[image] += values[image];
        }
        if (k >= extent.x)
        {
          rowSums[SPARSE_BLUR_IMAGES + image] += values[image];
        }
      }
    }
    for (int image = 0; image < SPARSE_BLUR_IMAGES; ++image)
    {
      for (int dx = 0; dx < 2; ++dx)
      {
        vec4 rowValue = rowSums[dx * SPARSE_BLUR_IMAGES + image] / float(blurWidth);
        if (row < blurWidth)
        {
          sums[dx * SPARSE_BLUR_IMAGES + image] += rowValue;
        }
        if (row >= extent.y)
        {
          sums[(2 + dx) * SPARSE_BLUR_IMAGES + image] += rowValue;
        }
      }
    }
  }
  for (int corner = 0; corner < 4; ++corner)
  {
    ivec2 offset = ivec2(corner & 1, corner >> 1);
    if (all(lessThanEqual(offset, extent)))
    {
      for (int image = 0; image < SPARSE_BLUR_IMAGES; ++image)
      {
        imageStore(blurred[image], pixel + offset, sums[corner * SPARSE_BLUR_IMAGES + image] / float(blurWidth));
      }
    }
  }
}
