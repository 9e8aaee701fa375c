// A prefiltered map's separable box blur (moments/BoxBlur.glsl, x then y, over the values a fragment pass forms from
// each shadow-map depth) evaluated only at the texels the receivers read (ReceiverTiles.h), one invocation per listed
// texel: for each of the vertical pass's rows it forms the horizontal pass's value there as that pass does (the same
// taps, clamped alike, summed in the same order, divided by the width), then sums them as the vertical pass does. The
// values of each tap are formed inline by `vec4 momentsOfDepth(float depth)`, which the including shader defines
// with the code its fragment pass uses (moments/SparseMomentsBlur.glsl: vsm's and esm's moments; the power moments';
// the Fourier basis'), so that pass is skipped. The list is shaders/ReceiverTiles.glsl's: word 0 the count, then
// x | y << 16 (repeats write the same value twice).
layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer ReceiverReadTexels
{
  uint receiverReadTexels[];
};
uniform sampler2D source; // the shadow map's linear depth
uniform int blurWidth;
uniform int readTexelCount;
layout(rgba32f, binding = 0) uniform writeonly image2D blurred;

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
  vec4 sum = vec4(0.0);
  for (int row = 0; row < blurWidth; ++row)
  {
    ivec2 rowTexel = clamp(pixel + (first + row) * ivec2(0, 1), ivec2(0), size - 1);
    vec4 rowSum = vec4(0.0);
    for (int k = 0; k < blurWidth; ++k)
    {
      // The moments the moments pass would have stored there (the same function, so that pass is skipped).
      ivec2 tap = clamp(rowTexel + (first + k) * ivec2(1, 0), ivec2(0), size - 1);
      rowSum += momentsOfDepth(texelFetch(source, tap, 0).r);
    }
    sum += rowSum / float(blurWidth);
  }
  imageStore(blurred, pixel, sum / float(blurWidth));
}
