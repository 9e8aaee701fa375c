// A prefiltered map's separable box blur (moments/BoxBlur.glsl, x then y, over the values a fragment pass forms from
// each shadow-map depth) evaluated only at the texels the receivers read (ReceiverTiles.h), one invocation per listed
// texel: for each of the vertical pass's rows it forms the horizontal pass's value there as that pass does (the same
// taps, clamped alike, summed in the same order, divided by the width), then sums them as the vertical pass does. The
// values of each tap are formed inline by `vec4 momentsOfDepth(float depth)`, which the including shader defines
// with the code its fragment pass uses (moments/SparseMomentsBlur.glsl: vsm's and esm's moments; the power moments'),
// so that pass is skipped. A shader whose pass writes several RGBA textures (the Fourier basis) defines
// SPARSE_BLUR_IMAGES and `void momentsOfDepthImages(float depth, out vec4 values[SPARSE_BLUR_IMAGES])` instead, and
// every texture is blurred from one fetch of each tap into images 0 .. SPARSE_BLUR_IMAGES - 1. The list is
// shaders/ReceiverTiles.glsl's: word 0 the count, then x | y << 16 (repeats write the same value twice).
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

void main()
{
  int entry = int(gl_GlobalInvocationID.y * gl_NumWorkGroups.x * gl_WorkGroupSize.x + gl_GlobalInvocationID.x);
  if (entry >= readTexelCount)
  {
    return;
  }
  uint packedTexel = receiverReadTexels[1 + entry];
  ivec2 pixel = ivec2(int(packedTexel & 0xFFFFu), int(packedTexel >> 16));
  ivec2 size = textureSize(source, 0);
  int first = -(blurWidth - 1) / 2;
  vec4 sums[SPARSE_BLUR_IMAGES];
  for (int image = 0; image < SPARSE_BLUR_IMAGES; ++image)
  {
    sums[image] = vec4(0.0);
  }
  for (int row = 0; row < blurWidth; ++row)
  {
    ivec2 rowTexel = clamp(pixel + (first + row) * ivec2(0, 1), ivec2(0), size - 1);
    vec4 rowSums[SPARSE_BLUR_IMAGES];
    for (int image = 0; image < SPARSE_BLUR_IMAGES; ++image)
    {
      rowSums[image] = vec4(0.0);
    }
    for (int k = 0; k < blurWidth; ++k)
    {
      // The values the fragment pass would have stored there (the same function, so that pass is skipped).
      ivec2 tap = clamp(rowTexel + (first + k) * ivec2(1, 0), ivec2(0), size - 1);
      vec4 values[SPARSE_BLUR_IMAGES];
      momentsOfDepthImages(texelFetch(source, tap, 0).r, values);
      for (int image = 0; image < SPARSE_BLUR_IMAGES; ++image)
      {
        rowSums[image] += values[image];
      }
    }
    for (int image = 0; image < SPARSE_BLUR_IMAGES; ++image)
    {
      sums[image] += rowSums[image] / float(blurWidth);
    }
  }
  for (int image = 0; image < SPARSE_BLUR_IMAGES; ++image)
  {
    imageStore(blurred[image], pixel, sums[image] / float(blurWidth));
  }
}
